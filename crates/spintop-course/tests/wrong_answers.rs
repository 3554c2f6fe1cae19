//! The plausible wrong answers the graders must reject, each with the words
//! its diagnosis must contain: at least two per assignment, written by the
//! graders' author (the independent sets are in `lessons/wrong/`).

use spintop::integrate::dopri5::dopri5_step;
use spintop::integrate::rk4::rk4_step;
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet, PrecessingDipole};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use spintop_grading::{self as grading, DynField, Grade};

fn top(r: f64, tau: f64) -> SymmetricTop {
    SymmetricTop::new(r, tau).unwrap()
}

/// A plausible wrong answer: which assignment, what is wrong, and the words
/// its diagnosis must contain.
pub(crate) struct Wrong {
    pub(crate) assignment: &'static str,
    pub(crate) what: &'static str,
    pub(crate) grade: Grade,
    pub(crate) says: &'static str,
}

fn w(assignment: &'static str, what: &'static str, grade: Grade, says: &'static str) -> Wrong {
    Wrong {
        assignment,
        what,
        grade,
        says,
    }
}

fn rk4_variant(
    weights: [f64; 4],
    k4_at_end: bool,
) -> impl Fn(DynField, f64, &State<3>, f64) -> State<3> {
    move |f: DynField, t, y: &State<3>, h| {
        let k1 = f(t, y);
        let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
        let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
        let k4 = f(if k4_at_end { t + h } else { t }, &(y + k3 * h));
        y + (k1 * weights[0] + k2 * weights[1] + k3 * weights[2] + k4 * weights[3]) * (h / 6.0)
    }
}

/// The plausible wrong answers, at least two per assignment.
pub(crate) fn wrong_answers(seed: u64) -> Vec<Wrong> {
    [
        section_2,
        section_2_schott,
        section_3,
        section_4_1,
        section_4_2,
        appendix,
        numerics,
    ]
    .iter()
    .flat_map(|part| part(seed))
    .collect()
}

/// Section 2: the laws (2.1)-(2.4) and the precessing dipole.
fn section_2(seed: u64) -> Vec<Wrong> {
    vec![
        // (2.1)
        w(
            "larmor_rate",
            "the sign flipped",
            grading::larmor_rate(seed, |j: &Jet| j[1].cross(&j[2])),
            "sign flip",
        ),
        w(
            "larmor_rate",
            "L_S handed in",
            grading::larmor_rate(seed, balance::schott_angular_momentum),
            "Schott angular momentum",
        ),
        w(
            "larmor_rate",
            "the torque handed in",
            grading::larmor_rate(seed, balance::torque_rate),
            "torque law (2.2)",
        ),
        w(
            "larmor_rate",
            "twice the rate",
            grading::larmor_rate(seed, |j: &Jet| 2.0 * balance::larmor_rate(j)),
            "factor 2",
        ),
        // (2.4)
        w(
            "schott_angular_momentum",
            "one derivative short",
            grading::schott_angular_momentum(seed, |j: &Jet| j[0].cross(&j[1])),
            "one derivative short",
        ),
        w(
            "schott_angular_momentum",
            "the sign flipped",
            grading::schott_angular_momentum(seed, |j: &Jet| j[2].cross(&j[0])),
            "sign flip",
        ),
        w(
            "schott_angular_momentum",
            "the torque handed in",
            grading::schott_angular_momentum(seed, balance::torque_rate),
            "torque law (2.2)",
        ),
        // (2.2)
        w(
            "torque_rate",
            "the Larmor-like law",
            grading::torque_rate(seed, balance::larmor_rate),
            "Schott term (2.3) is missing",
        ),
        w(
            "torque_rate",
            "L_S handed in",
            grading::torque_rate(seed, balance::schott_angular_momentum),
            "one derivative too few",
        ),
        w(
            "torque_rate",
            "the sign flipped",
            grading::torque_rate(seed, |j: &Jet| j[3].cross(&j[0])),
            "sign flip",
        ),
    ]
}

/// Section 2: the Schott rate (2.3), its axial part, and the precessing dipole.
fn section_2_schott(seed: u64) -> Vec<Wrong> {
    let cone = |th: f64, w: f64, t: f64| PrecessingDipole::new(th, w).unwrap().jet(t);
    vec![
        // (2.3)
        w(
            "schott_rate",
            "first factor only",
            grading::schott_rate(seed, |j: &Jet| j[1].cross(&j[2])),
            "differentiated the first factor",
        ),
        w(
            "schott_rate",
            "second factor only",
            grading::schott_rate(seed, |j: &Jet| j[0].cross(&j[3])),
            "differentiated the second factor",
        ),
        w(
            "schott_rate",
            "a minus between the terms",
            grading::schott_rate(seed, |j: &Jet| j[0].cross(&j[3]) - j[1].cross(&j[2])),
            "opposite signs",
        ),
        // (2.3)-(2.4) axial
        w(
            "axial_schott_rate",
            "not normalised",
            grading::axial_schott_rate(seed, |j: &Jet| j[0].dot(&balance::schott_rate(j))),
            "not normalised",
        ),
        w(
            "axial_schott_rate",
            "normalised twice",
            grading::axial_schott_rate(seed, |j: &Jet| {
                j[0].dot(&balance::schott_rate(j)) / j[0].norm_squared()
            }),
            "normalised twice",
        ),
        w(
            "axial_schott_rate",
            "the sign flipped",
            grading::axial_schott_rate(seed, |j: &Jet| {
                -balance::axial(&j[0], &balance::schott_rate(j))
            }),
            "sign flip",
        ),
        // the precessing dipole
        w(
            "precessing_dipole_jet",
            "no chain-rule factors",
            grading::precessing_dipole_jet(seed, move |th, om, t| {
                let mut j = cone(th, om, t);
                j[1] /= om;
                j[2] /= om * om;
                j[3] /= om.powi(3);
                j
            }),
            "chain rule",
        ),
        w(
            "precessing_dipole_jet",
            "d'' outward",
            grading::precessing_dipole_jet(seed, move |th, om, t| {
                let mut j = cone(th, om, t);
                j[2] = -j[2];
                j
            }),
            "toward its axis",
        ),
        w(
            "precessing_dipole_jet",
            "d''' flipped",
            grading::precessing_dipole_jet(seed, move |th, om, t| {
                let mut j = cone(th, om, t);
                j[3] = -j[3];
                j
            }),
            "d''' has the wrong sign",
        ),
    ]
}

/// Section 3: (3.3), its energy, and the Euler angles of (3.5).
fn section_3(seed: u64) -> Vec<Wrong> {
    let top_rhs = |i: Vec3, d: Vec3, w: Vec3| GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w);
    vec![
        // (3.3)
        w(
            "truncated_ale_rhs",
            "I1 and I3 swapped",
            grading::truncated_ale_rhs(seed, move |i: Vec3, d, om| {
                top_rhs(Vec3::new(i.z, i.y, i.x), d, om)
            }),
            "wrong axes",
        ),
        w(
            "truncated_ale_rhs",
            "Omega' only on the left",
            grading::truncated_ale_rhs(seed, |i: Vec3, d: Vec3, om: Vec3| {
                let b = -om.cross(&i.component_mul(&om)) - d.cross(&om).norm_squared() * om;
                b.component_div(&i)
            }),
            "on both sides",
        ),
        w(
            "truncated_ale_rhs",
            "the gyroscopic sign",
            grading::truncated_ale_rhs(seed, |i: Vec3, d: Vec3, om: Vec3| {
                // (I + d (d x W)^T) W' = +W x I W - |d x W|^2 W, solved.
                let w = d.cross(&om);
                let b = om.cross(&i.component_mul(&om)) - w.norm_squared() * om;
                let (ib, id) = (b.component_div(&i), d.component_div(&i));
                ib - id * (w.dot(&ib) / (1.0 + w.dot(&id)))
            }),
            "gyroscopic term",
        ),
        // (3.3) energy
        w(
            "energy_rate",
            "no inertia",
            grading::energy_rate(seed, move |i, d, om: Vec3| om.dot(&top_rhs(i, d, om))),
            "moments of inertia are missing",
        ),
        w(
            "energy_rate",
            "first term only",
            grading::energy_rate(seed, |_, d: Vec3, om: Vec3| {
                -d.cross(&om).norm_squared() * om.norm_squared()
            }),
            "only the first damping term",
        ),
        w(
            "energy_rate",
            "the 1/2 kept",
            grading::energy_rate(seed, move |i: Vec3, d, om: Vec3| {
                0.5 * om.dot(&i.component_mul(&top_rhs(i, d, om)))
            }),
            "factor 1/2",
        ),
        // (3.5)
        w(
            "euler_from_rotation",
            "no pole handling",
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let theta = m[(0, 2)].hypot(m[(1, 2)]).atan2(m[(2, 2)]);
                let phi = m[(0, 2)].atan2(-m[(1, 2)]);
                let psi = m[(2, 0)].atan2(m[(2, 1)]);
                let s = m[(0, 2)].hypot(m[(1, 2)]);
                // Divides by sin(theta) on the way, as a hand derivation might.
                (phi * s / s, theta, psi)
            }),
            "not finite on or near a pole",
        ),
        w(
            "euler_from_rotation",
            "acos for theta",
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.phi, m[(2, 2)].clamp(-1.0, 1.0).acos(), a.psi)
            }),
            "inverse cosine",
        ),
        w(
            "euler_from_rotation",
            "phi and psi swapped",
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.psi, a.theta, a.phi)
            }),
            "phi and psi are swapped",
        ),
    ]
}

/// Section 4.1: the truncated model.
fn section_4_1(seed: u64) -> Vec<Wrong> {
    vec![
        // (4.5)-(4.6)
        w(
            "truncated_omega_perp",
            "exponential decay",
            grading::truncated_omega_perp(seed, |_, tau, om: f64, t| {
                om * (-tau * om * om * t).exp()
            }),
            "exponential decay",
        ),
        w(
            "truncated_omega_perp",
            "no 2 under the root",
            grading::truncated_omega_perp(seed, |_, tau, om: f64, t| {
                om / (1.0 + tau * om * om * t).sqrt()
            }),
            "factor 2 inside the square root",
        ),
        w(
            "truncated_omega_perp",
            "a cube root",
            grading::truncated_omega_perp(seed, |_, tau, om: f64, t| {
                om / (1.0 + 2.0 * tau * om * om * t).cbrt()
            }),
            "right at t = 0",
        ),
        // (4.7)
        w(
            "truncated_closed_form",
            "turning the wrong way",
            grading::truncated_closed_form(seed, |r, tau, w0: Vec3, t| {
                let m = sym::truncated_closed_form(&top(r, tau), &Vec3::new(w0.x, -w0.y, w0.z), t);
                Vec3::new(m.x, -m.y, m.z)
            }),
            "turns the wrong way",
        ),
        w(
            "truncated_closed_form",
            "the phase on t",
            grading::truncated_closed_form(seed, |r, tau, w0: Vec3, t| {
                let u0 = w0.x * w0.x + w0.y * w0.y;
                let big_r = (1.0 + 2.0 * tau * u0 * t).sqrt();
                let (s, c) = ((1.0 - r) * w0.z * t).sin_cos();
                Vec3::new(w0.x * c + w0.y * s, w0.y * c - w0.x * s, w0.z) / big_r
            }),
            "ordinary clock",
        ),
        w(
            "truncated_closed_form",
            "Omega_3 constant",
            grading::truncated_closed_form(seed, |r, tau, w0: Vec3, t| {
                let mut m = sym::truncated_closed_form(&top(r, tau), &w0, t);
                m.z = w0.z;
                m
            }),
            "held constant",
        ),
        // (4.6) inverted
        w(
            "truncated_time_to_factor",
            "R = p",
            grading::truncated_time_to_factor(seed, |_, tau, om: f64, p: f64| {
                (p * p - 1.0) / (2.0 * tau * om * om)
            }),
            "negative time",
        ),
        w(
            "truncated_time_to_factor",
            "R not squared",
            grading::truncated_time_to_factor(seed, |_, tau, om: f64, p: f64| {
                (1.0 / p - 1.0) / (2.0 * tau * om * om)
            }),
            "not squared",
        ),
        w(
            "truncated_time_to_factor",
            "the 2 dropped",
            grading::truncated_time_to_factor(seed, |_, tau, om: f64, p: f64| {
                (1.0 / (p * p) - 1.0) / (tau * om * om)
            }),
            "factor 2",
        ),
        // (4.11)
        w(
            "precession_tilt",
            "the printed (4.11)",
            grading::precession_tilt(seed, |r, w0| sym::printed_tilt_4_11(&top(r, 1.0), &w0)),
            "erratum 4",
        ),
        w(
            "precession_tilt",
            "the angle to Omega",
            grading::precession_tilt(seed, |_, w0: Vec3| w0.x.hypot(w0.y).atan2(w0.z)),
            "not L",
        ),
        w(
            "precession_tilt",
            "moments swapped",
            grading::precession_tilt(seed, |r: f64, w0: Vec3| (r * w0.x.hypot(w0.y)).atan2(w0.z)),
            "swapped",
        ),
    ]
}

/// Section 4.2: the reduced model.
fn section_4_2(seed: u64) -> Vec<Wrong> {
    vec![
        // (4.12)-(4.14)
        w(
            "reduced_ale_rhs",
            "the truncated model",
            grading::reduced_ale_rhs(seed, |r, tau, om| sym::truncated_ale_rhs(&top(r, tau), &om)),
            "truncated model",
        ),
        w(
            "reduced_ale_rhs",
            "the spin damped",
            grading::reduced_ale_rhs(seed, |r, tau, om: Vec3| {
                let mut d = sym::reduced_ale_rhs(&top(r, tau), &om);
                d.z = -tau * (om.x * om.x + om.y * om.y + (r * om.z).powi(2)) * om.z;
                d
            }),
            "the spin is damped",
        ),
        w(
            "reduced_ale_rhs",
            "the spin in the damping without its moment ratio",
            grading::reduced_ale_rhs(seed, |r: f64, tau, om: Vec3| {
                let extra = tau * ((r * om.z).powi(2) - om.z.powi(2));
                sym::reduced_ale_rhs(&top(r, tau), &om) + extra * Vec3::new(om.x, om.y, 0.0)
            }),
            "moment ratio",
        ),
        // (4.16) sigma
        w(
            "reduced_decay_time",
            "ratio not squared",
            grading::reduced_decay_time(seed, |r, tau, w3: f64| 1.0 / (r * w3 * w3 * tau)),
            "enters squared",
        ),
        w(
            "reduced_decay_time",
            "ratio upside down",
            grading::reduced_decay_time(seed, |r: f64, tau, w3: f64| {
                1.0 / ((w3 / r).powi(2) * tau)
            }),
            "upside down",
        ),
        w(
            "reduced_decay_time",
            "sigma/2",
            grading::reduced_decay_time(seed, |r, tau, w3| {
                0.5 * sym::reduced_decay_time(&top(r, tau), w3)
            }),
            "factor 1/2",
        ),
        // (4.15)-(4.16)
        w(
            "reduced_closed_form",
            "Omega_10 = 0",
            grading::reduced_closed_form(seed, |r, tau, w0: Vec3, t| {
                sym::reduced_closed_form(&top(r, tau), &Vec3::new(0.0, w0.x.hypot(w0.y), w0.z), t)
            }),
            "Omega_10 = 0",
        ),
        w(
            "reduced_closed_form",
            "half the exponent",
            grading::reduced_closed_form(seed, |r, tau: f64, w0: Vec3, t| {
                // Phi decaying at half the rate is Phi of tau/2; the phase does not involve tau.
                sym::reduced_closed_form(&top(r, tau / 2.0), &w0, t)
            }),
            "factor 2",
        ),
        w(
            "reduced_closed_form",
            "turning the wrong way",
            grading::reduced_closed_form(seed, |r, tau, w0: Vec3, t| {
                let m = sym::reduced_closed_form(&top(r, tau), &Vec3::new(w0.x, -w0.y, w0.z), t);
                Vec3::new(m.x, -m.y, m.z)
            }),
            "turns the wrong way",
        ),
    ]
}

/// The appendix: the shell's masses, its update and its root.
fn appendix(seed: u64) -> Vec<Wrong> {
    vec![
        // (A.1) masses
        w(
            "shell_masses",
            "swapped",
            grading::shell_masses(seed, |tau0, delta| (tau0 / delta, 1.0 - tau0 / delta)),
            "swapped",
        ),
        w(
            "shell_masses",
            "upside down",
            grading::shell_masses(seed, |tau0, delta| (1.0 - delta / tau0, delta / tau0)),
            "upside down",
        ),
        // (A.1)
        w(
            "shell_acceleration",
            "the retarded sign",
            grading::shell_acceleration(seed, |tau0, delta, z: C, zr: C| {
                let m_em = tau0 / delta;
                (-z + zr * m_em) / (1.0 - m_em)
            }),
            "retarded term has the wrong sign",
        ),
        w(
            "shell_acceleration",
            "the whole mass",
            grading::shell_acceleration(seed, |tau0, delta, z: C, zr: C| -z - zr * (tau0 / delta)),
            "whole mass",
        ),
        w(
            "shell_acceleration",
            "the sign flipped",
            grading::shell_acceleration(seed, |tau0, delta, z, zr| {
                -ShellModel::new(tau0, delta).unwrap().acceleration(z, zr)
            }),
            "sign flip",
        ),
        // (A.1) root
        w(
            "characteristic_root",
            "the start",
            grading::characteristic_root(seed, |_, _| C::new(0.0, 1.0)),
            "where the search starts",
        ),
        w(
            "characteristic_root",
            "e^{+s delta}",
            grading::characteristic_root(seed, |tau0: f64, delta: f64| {
                let m_em = tau0 / delta;
                let m0 = 1.0 - m_em;
                let mut s = C::new(0.0, 1.0);
                for _ in 0..100 {
                    let e = (s * delta).exp() * m_em;
                    let step = (s * s * (m0 + e) + 1.0) / (s * 2.0 * (e + m0) + s * s * e * delta);
                    s -= step;
                }
                s
            }),
            "wrong sign in the exponent",
        ),
    ]
}

/// The numerical methods: a step of RK4 and of DP5, a whole run.
fn numerics(seed: u64) -> Vec<Wrong> {
    let reduced_run = |euler: bool| {
        move |r: f64, tau: f64, w0: Vec3, t_end: f64, n: usize| {
            let h = t_end / n as f64;
            let f = |_t: f64, y: &State<3>| sym::reduced_ale_rhs(&top(r, tau), y);
            (0..n).fold(w0, |y, i| {
                if euler {
                    y + f(0.0, &y) * h
                } else {
                    // The midpoint method: order 2.
                    let _ = i;
                    let k1 = f(0.0, &y);
                    y + f(0.0, &(y + k1 * (h / 2.0))) * h
                }
            })
        }
    };
    vec![
        // RK4
        w(
            "rk4_step",
            "wrong weights",
            grading::rk4_step(seed, rk4_variant([1.0, 1.0, 2.0, 2.0], true)),
            "weights",
        ),
        w(
            "rk4_step",
            "k4 at the old time",
            grading::rk4_step(seed, rk4_variant([1.0, 2.0, 2.0, 1.0], false)),
            "the fourth stage evaluates f at the start time",
        ),
        w(
            "rk4_step",
            "Euler's method",
            grading::rk4_step(seed, |f: DynField, t, y: &State<3>, h| y + f(t, y) * h),
            "Euler's method",
        ),
        // DP5
        w(
            "dp5_step",
            "the estimate's sign",
            grading::dp5_step(seed, |f: DynField, t, y: &State<3>, h| {
                let (y5, e) = dopri5_step(&f, t, y, h);
                (y5, -e)
            }),
            "wrong sign",
        ),
        w(
            "dp5_step",
            "the fourth-order step",
            grading::dp5_step(seed, |f: DynField, t, y: &State<3>, h| {
                let (y5, e) = dopri5_step(&f, t, y, h);
                (y5 - e, e)
            }),
            "fourth-order solution",
        ),
        // a whole RK4 run
        w(
            "reduced_rk4",
            "Euler steps",
            grading::reduced_rk4(seed, reduced_run(true)),
            "Euler's method",
        ),
        w(
            "reduced_rk4",
            "midpoint steps",
            grading::reduced_rk4(seed, reduced_run(false)),
            "not 4",
        ),
        w(
            "reduced_rk4",
            "the truncated model integrated",
            grading::reduced_rk4(seed, |r, tau, w0, t_end, n: usize| {
                let h = t_end / n as f64;
                let f = |_t: f64, y: &State<3>| sym::truncated_ale_rhs(&top(r, tau), y);
                (0..n).fold(w0, |y, i| rk4_step(&f, i as f64 * h, &y, h))
            }),
            "truncated model",
        ),
    ]
}
