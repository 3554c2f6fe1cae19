//! The graders of the course assignments really grade. For every assignment
//! of the course: spintop's own implementation passes; a `todo!()` stub fails
//! and says it is a stub; at least two plausible wrong answers fail, each
//! with its own diagnosis; the failure never prints the formula (the last
//! hint rung does); and a file that takes a shortcut through spintop's own
//! function fails with the "no shortcut" message.

use spintop::course::{COURSE, find};
use spintop::grading::{
    self, DynField, Failed, Grade, NO_SHORTCUT, no_shortcut, shape_diagnosis, without_shortcut,
};
use spintop::integrate::dopri5::dopri5_step;
use spintop::integrate::rk4::rk4_step;
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet, PrecessingDipole};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use std::collections::BTreeSet;

fn top(r: f64, tau: f64) -> SymmetricTop {
    SymmetricTop::new(r, tau).unwrap()
}

/// spintop's own answer to every assignment, graded, by function name.
fn references() -> Vec<(&'static str, Grade)> {
    let top_rhs = |i: Vec3, d: Vec3, w: Vec3| GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w);
    let reduced_rhs = |r: f64, tau: f64, w: Vec3| sym::reduced_ale_rhs(&top(r, tau), &w);
    vec![
        ("larmor_rate", grading::larmor_rate(balance::larmor_rate)),
        (
            "schott_angular_momentum",
            grading::schott_angular_momentum(balance::schott_angular_momentum),
        ),
        ("torque_rate", grading::torque_rate(balance::torque_rate)),
        ("schott_rate", grading::schott_rate(balance::schott_rate)),
        (
            "axial_schott_rate",
            grading::axial_schott_rate(|j: &Jet| balance::axial(&j[0], &balance::schott_rate(j))),
        ),
        (
            "precessing_dipole_jet",
            grading::precessing_dipole_jet(|th, w, t| PrecessingDipole::new(th, w).unwrap().jet(t)),
        ),
        ("truncated_ale_rhs", grading::truncated_ale_rhs(top_rhs)),
        (
            "energy_rate",
            grading::energy_rate(move |i, d, w| w.dot(&i.component_mul(&top_rhs(i, d, w)))),
        ),
        (
            "euler_from_rotation",
            grading::euler_from_rotation(|m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.phi, a.theta, a.psi)
            }),
        ),
        (
            "truncated_omega_perp",
            grading::truncated_omega_perp(|r, tau, w, t| {
                sym::truncated_omega_perp(&top(r, tau), w, t)
            }),
        ),
        (
            "truncated_closed_form",
            grading::truncated_closed_form(|r, tau, w0, t| {
                sym::truncated_closed_form(&top(r, tau), &w0, t)
            }),
        ),
        (
            "truncated_time_to_factor",
            grading::truncated_time_to_factor(|r, tau, w, p| {
                sym::truncated_time_to_factor(&top(r, tau), w, p)
            }),
        ),
        (
            "precession_tilt",
            grading::precession_tilt(|r, w0| sym::precession_tilt(&top(r, 1.0), &w0)),
        ),
        ("reduced_ale_rhs", grading::reduced_ale_rhs(reduced_rhs)),
        (
            "reduced_decay_time",
            grading::reduced_decay_time(|r, tau, w3| sym::reduced_decay_time(&top(r, tau), w3)),
        ),
        (
            "reduced_closed_form",
            grading::reduced_closed_form(|r, tau, w0, t| {
                sym::reduced_closed_form(&top(r, tau), &w0, t)
            }),
        ),
        (
            "shell_masses",
            grading::shell_masses(|tau0, delta| {
                let m = ShellModel::new(tau0, delta).unwrap();
                (m.m0(), m.m_em())
            }),
        ),
        (
            "shell_acceleration",
            grading::shell_acceleration(|tau0, delta, z, zr| {
                ShellModel::new(tau0, delta).unwrap().acceleration(z, zr)
            }),
        ),
        (
            "characteristic_root",
            grading::characteristic_root(|tau0, delta| {
                ShellModel::new(tau0, delta)
                    .unwrap()
                    .root_near_al()
                    .unwrap()
            }),
        ),
        (
            "rk4_step",
            grading::rk4_step(|f: DynField, t, y: &State<3>, h| rk4_step(&f, t, y, h)),
        ),
        (
            "dp5_step",
            grading::dp5_step(|f: DynField, t, y: &State<3>, h| dopri5_step(&f, t, y, h)),
        ),
        (
            "reduced_rk4",
            grading::reduced_rk4(move |r, tau, w0, t_end, n| {
                let h = t_end / n as f64;
                let f = |_t: f64, y: &State<3>| reduced_rhs(r, tau, *y);
                (0..n).fold(w0, |y, i| rk4_step(&f, i as f64 * h, &y, h))
            }),
        ),
    ]
}

/// Every todo!() stub, graded, by function name.
fn stubs() -> Vec<(&'static str, Grade)> {
    let v = |_: &Jet| -> Vec3 { todo!("stub") };
    vec![
        ("larmor_rate", grading::larmor_rate(v)),
        (
            "schott_angular_momentum",
            grading::schott_angular_momentum(v),
        ),
        ("torque_rate", grading::torque_rate(v)),
        ("schott_rate", grading::schott_rate(v)),
        (
            "axial_schott_rate",
            grading::axial_schott_rate(|_: &Jet| -> f64 { todo!() }),
        ),
        (
            "precessing_dipole_jet",
            grading::precessing_dipole_jet(|_, _, _| -> Jet { todo!() }),
        ),
        (
            "truncated_ale_rhs",
            grading::truncated_ale_rhs(|_, _, _| -> Vec3 { todo!() }),
        ),
        (
            "energy_rate",
            grading::energy_rate(|_, _, _| -> f64 { todo!() }),
        ),
        (
            "euler_from_rotation",
            grading::euler_from_rotation(|_: &Mat3| -> (f64, f64, f64) { todo!() }),
        ),
        (
            "truncated_omega_perp",
            grading::truncated_omega_perp(|_, _, _, _| -> f64 { todo!() }),
        ),
        (
            "truncated_closed_form",
            grading::truncated_closed_form(|_, _, _, _| -> Vec3 { todo!() }),
        ),
        (
            "truncated_time_to_factor",
            grading::truncated_time_to_factor(|_, _, _, _| -> f64 { todo!() }),
        ),
        (
            "precession_tilt",
            grading::precession_tilt(|_, _| -> f64 { todo!() }),
        ),
        (
            "reduced_ale_rhs",
            grading::reduced_ale_rhs(|_, _, _| -> Vec3 { todo!() }),
        ),
        (
            "reduced_decay_time",
            grading::reduced_decay_time(|_, _, _| -> f64 { todo!() }),
        ),
        (
            "reduced_closed_form",
            grading::reduced_closed_form(|_, _, _, _| -> Vec3 { todo!() }),
        ),
        (
            "shell_masses",
            grading::shell_masses(|_, _| -> (f64, f64) { todo!() }),
        ),
        (
            "shell_acceleration",
            grading::shell_acceleration(|_, _, _, _| -> C { todo!() }),
        ),
        (
            "characteristic_root",
            grading::characteristic_root(|_, _| -> C { todo!() }),
        ),
        (
            "rk4_step",
            grading::rk4_step(|_: DynField, _, _: &State<3>, _| -> State<3> { todo!() }),
        ),
        (
            "dp5_step",
            grading::dp5_step(|_: DynField, _, _: &State<3>, _| -> (State<3>, State<3>) {
                todo!()
            }),
        ),
        (
            "reduced_rk4",
            grading::reduced_rk4(|_, _, _, _, _| -> Vec3 { todo!() }),
        ),
    ]
}

/// A plausible wrong answer: which assignment, what is wrong, and the words
/// its diagnosis must contain.
struct Wrong {
    assignment: &'static str,
    what: &'static str,
    grade: Grade,
    says: &'static str,
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
fn wrong_answers() -> Vec<Wrong> {
    let top_rhs = |i: Vec3, d: Vec3, w: Vec3| GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w);
    let cone = |th: f64, w: f64, t: f64| PrecessingDipole::new(th, w).unwrap().jet(t);
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
        // (2.1)
        w(
            "larmor_rate",
            "the sign flipped",
            grading::larmor_rate(|j: &Jet| j[1].cross(&j[2])),
            "sign flip",
        ),
        w(
            "larmor_rate",
            "L_S handed in",
            grading::larmor_rate(balance::schott_angular_momentum),
            "Schott angular momentum",
        ),
        w(
            "larmor_rate",
            "the torque handed in",
            grading::larmor_rate(balance::torque_rate),
            "torque law (2.2)",
        ),
        w(
            "larmor_rate",
            "twice the rate",
            grading::larmor_rate(|j: &Jet| 2.0 * balance::larmor_rate(j)),
            "factor 2",
        ),
        // (2.4)
        w(
            "schott_angular_momentum",
            "one derivative short",
            grading::schott_angular_momentum(|j: &Jet| j[0].cross(&j[1])),
            "one derivative short",
        ),
        w(
            "schott_angular_momentum",
            "the sign flipped",
            grading::schott_angular_momentum(|j: &Jet| j[2].cross(&j[0])),
            "sign flip",
        ),
        w(
            "schott_angular_momentum",
            "the torque handed in",
            grading::schott_angular_momentum(balance::torque_rate),
            "torque law (2.2)",
        ),
        // (2.2)
        w(
            "torque_rate",
            "the Larmor-like law",
            grading::torque_rate(balance::larmor_rate),
            "Schott term (2.3) is missing",
        ),
        w(
            "torque_rate",
            "L_S handed in",
            grading::torque_rate(balance::schott_angular_momentum),
            "one derivative too few",
        ),
        w(
            "torque_rate",
            "the sign flipped",
            grading::torque_rate(|j: &Jet| j[3].cross(&j[0])),
            "sign flip",
        ),
        // (2.3)
        w(
            "schott_rate",
            "first factor only",
            grading::schott_rate(|j: &Jet| j[1].cross(&j[2])),
            "differentiated the first factor",
        ),
        w(
            "schott_rate",
            "second factor only",
            grading::schott_rate(|j: &Jet| j[0].cross(&j[3])),
            "differentiated the second factor",
        ),
        w(
            "schott_rate",
            "a minus between the terms",
            grading::schott_rate(|j: &Jet| j[0].cross(&j[3]) - j[1].cross(&j[2])),
            "opposite signs",
        ),
        // (2.3)-(2.4) axial
        w(
            "axial_schott_rate",
            "not normalised",
            grading::axial_schott_rate(|j: &Jet| j[0].dot(&balance::schott_rate(j))),
            "not normalised",
        ),
        w(
            "axial_schott_rate",
            "normalised twice",
            grading::axial_schott_rate(|j: &Jet| {
                j[0].dot(&balance::schott_rate(j)) / j[0].norm_squared()
            }),
            "normalised twice",
        ),
        w(
            "axial_schott_rate",
            "the sign flipped",
            grading::axial_schott_rate(|j: &Jet| -balance::axial(&j[0], &balance::schott_rate(j))),
            "sign flip",
        ),
        // the precessing dipole
        w(
            "precessing_dipole_jet",
            "no chain-rule factors",
            grading::precessing_dipole_jet(move |th, om, t| {
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
            grading::precessing_dipole_jet(move |th, om, t| {
                let mut j = cone(th, om, t);
                j[2] = -j[2];
                j
            }),
            "toward its axis",
        ),
        w(
            "precessing_dipole_jet",
            "d''' flipped",
            grading::precessing_dipole_jet(move |th, om, t| {
                let mut j = cone(th, om, t);
                j[3] = -j[3];
                j
            }),
            "d''' has the wrong sign",
        ),
        // (3.3)
        w(
            "truncated_ale_rhs",
            "I1 and I3 swapped",
            grading::truncated_ale_rhs(move |i: Vec3, d, om| {
                top_rhs(Vec3::new(i.z, i.y, i.x), d, om)
            }),
            "wrong axes",
        ),
        w(
            "truncated_ale_rhs",
            "Omega' only on the left",
            grading::truncated_ale_rhs(|i: Vec3, d: Vec3, om: Vec3| {
                let b = -om.cross(&i.component_mul(&om)) - d.cross(&om).norm_squared() * om;
                b.component_div(&i)
            }),
            "on both sides",
        ),
        w(
            "truncated_ale_rhs",
            "the gyroscopic sign",
            grading::truncated_ale_rhs(move |i: Vec3, d, om: Vec3| {
                top_rhs(i, d, om) + 2.0 * om.cross(&i.component_mul(&om)).component_div(&i)
            }),
            "gyroscopic term",
        ),
        // (3.3) energy
        w(
            "energy_rate",
            "no inertia",
            grading::energy_rate(move |i, d, om: Vec3| om.dot(&top_rhs(i, d, om))),
            "moments of inertia are missing",
        ),
        w(
            "energy_rate",
            "first term only",
            grading::energy_rate(|_, d: Vec3, om: Vec3| {
                -d.cross(&om).norm_squared() * om.norm_squared()
            }),
            "only the first damping term",
        ),
        w(
            "energy_rate",
            "the 1/2 kept",
            grading::energy_rate(move |i: Vec3, d, om: Vec3| {
                0.5 * om.dot(&i.component_mul(&top_rhs(i, d, om)))
            }),
            "factor 1/2",
        ),
        // (3.5)
        w(
            "euler_from_rotation",
            "no pole handling",
            grading::euler_from_rotation(|m: &Mat3| {
                let theta = m[(0, 2)].hypot(m[(1, 2)]).atan2(m[(2, 2)]);
                let phi = m[(0, 2)].atan2(-m[(1, 2)]);
                let psi = m[(2, 0)].atan2(m[(2, 1)]);
                let s = m[(0, 2)].hypot(m[(1, 2)]);
                // Divides by sin(theta) on the way, as a hand derivation might.
                (phi * s / s, theta, psi)
            }),
            "not finite on a pole",
        ),
        w(
            "euler_from_rotation",
            "acos for theta",
            grading::euler_from_rotation(|m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.phi, m[(2, 2)].clamp(-1.0, 1.0).acos(), a.psi)
            }),
            "digits are lost near theta",
        ),
        w(
            "euler_from_rotation",
            "phi and psi swapped",
            grading::euler_from_rotation(|m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.psi, a.theta, a.phi)
            }),
            "rebuild a different rotation",
        ),
        // (4.5)-(4.6)
        w(
            "truncated_omega_perp",
            "exponential decay",
            grading::truncated_omega_perp(|_, tau, om: f64, t| om * (-tau * om * om * t).exp()),
            "exponential decay",
        ),
        w(
            "truncated_omega_perp",
            "no 2 under the root",
            grading::truncated_omega_perp(|_, tau, om: f64, t| {
                om / (1.0 + tau * om * om * t).sqrt()
            }),
            "factor 2 inside the square root",
        ),
        w(
            "truncated_omega_perp",
            "a cube root",
            grading::truncated_omega_perp(|_, tau, om: f64, t| {
                om / (1.0 + 2.0 * tau * om * om * t).cbrt()
            }),
            "right at t = 0",
        ),
        // (4.7)
        w(
            "truncated_closed_form",
            "turning the wrong way",
            grading::truncated_closed_form(|r, tau, w0: Vec3, t| {
                let m = sym::truncated_closed_form(&top(r, tau), &Vec3::new(w0.x, -w0.y, w0.z), t);
                Vec3::new(m.x, -m.y, m.z)
            }),
            "turns the wrong way",
        ),
        w(
            "truncated_closed_form",
            "the phase on t",
            grading::truncated_closed_form(|r, tau, w0: Vec3, t| {
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
            grading::truncated_closed_form(|r, tau, w0: Vec3, t| {
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
            grading::truncated_time_to_factor(|_, tau, om: f64, p: f64| {
                (p * p - 1.0) / (2.0 * tau * om * om)
            }),
            "negative time",
        ),
        w(
            "truncated_time_to_factor",
            "R not squared",
            grading::truncated_time_to_factor(|_, tau, om: f64, p: f64| {
                (1.0 / p - 1.0) / (2.0 * tau * om * om)
            }),
            "not squared",
        ),
        w(
            "truncated_time_to_factor",
            "the 2 dropped",
            grading::truncated_time_to_factor(|_, tau, om: f64, p: f64| {
                (1.0 / (p * p) - 1.0) / (tau * om * om)
            }),
            "factor 2",
        ),
        // (4.11)
        w(
            "precession_tilt",
            "the printed (4.11)",
            grading::precession_tilt(|r, w0| sym::printed_tilt_4_11(&top(r, 1.0), &w0)),
            "erratum 4",
        ),
        w(
            "precession_tilt",
            "the angle to Omega",
            grading::precession_tilt(|_, w0: Vec3| w0.x.hypot(w0.y).atan2(w0.z)),
            "not L",
        ),
        w(
            "precession_tilt",
            "moments swapped",
            grading::precession_tilt(|r: f64, w0: Vec3| (r * w0.x.hypot(w0.y)).atan2(w0.z)),
            "swapped",
        ),
        // (4.12)-(4.14)
        w(
            "reduced_ale_rhs",
            "the truncated model",
            grading::reduced_ale_rhs(|r, tau, om| sym::truncated_ale_rhs(&top(r, tau), &om)),
            "truncated model",
        ),
        w(
            "reduced_ale_rhs",
            "the spin damped",
            grading::reduced_ale_rhs(|r, tau, om: Vec3| {
                let mut d = sym::reduced_ale_rhs(&top(r, tau), &om);
                d.z = -tau * (om.x * om.x + om.y * om.y + (r * om.z).powi(2)) * om.z;
                d
            }),
            "the spin is damped",
        ),
        w(
            "reduced_ale_rhs",
            "the spin in the damping without its moment ratio",
            grading::reduced_ale_rhs(|r: f64, tau, om: Vec3| {
                let extra = tau * ((r * om.z).powi(2) - om.z.powi(2));
                sym::reduced_ale_rhs(&top(r, tau), &om) + extra * Vec3::new(om.x, om.y, 0.0)
            }),
            "moment ratio",
        ),
        // (4.16) sigma
        w(
            "reduced_decay_time",
            "ratio not squared",
            grading::reduced_decay_time(|r, tau, w3: f64| 1.0 / (r * w3 * w3 * tau)),
            "enters squared",
        ),
        w(
            "reduced_decay_time",
            "ratio upside down",
            grading::reduced_decay_time(|r: f64, tau, w3: f64| 1.0 / ((w3 / r).powi(2) * tau)),
            "upside down",
        ),
        w(
            "reduced_decay_time",
            "sigma/2",
            grading::reduced_decay_time(|r, tau, w3| {
                0.5 * sym::reduced_decay_time(&top(r, tau), w3)
            }),
            "factor 1/2",
        ),
        // (4.15)-(4.16)
        w(
            "reduced_closed_form",
            "Omega_10 = 0",
            grading::reduced_closed_form(|r, tau, w0: Vec3, t| {
                sym::reduced_closed_form(&top(r, tau), &Vec3::new(0.0, w0.x.hypot(w0.y), w0.z), t)
            }),
            "Omega_10 = 0",
        ),
        w(
            "reduced_closed_form",
            "half the exponent",
            grading::reduced_closed_form(|r, tau: f64, w0: Vec3, t| {
                // Phi decaying at half the rate is Phi of tau/2; the phase does not involve tau.
                sym::reduced_closed_form(&top(r, tau / 2.0), &w0, t)
            }),
            "factor 2",
        ),
        w(
            "reduced_closed_form",
            "turning the wrong way",
            grading::reduced_closed_form(|r, tau, w0: Vec3, t| {
                let m = sym::reduced_closed_form(&top(r, tau), &Vec3::new(w0.x, -w0.y, w0.z), t);
                Vec3::new(m.x, -m.y, m.z)
            }),
            "turns the wrong way",
        ),
        // (A.1) masses
        w(
            "shell_masses",
            "swapped",
            grading::shell_masses(|tau0, delta| (tau0 / delta, 1.0 - tau0 / delta)),
            "swapped",
        ),
        w(
            "shell_masses",
            "upside down",
            grading::shell_masses(|tau0, delta| (1.0 - delta / tau0, delta / tau0)),
            "upside down",
        ),
        // (A.1)
        w(
            "shell_acceleration",
            "the retarded sign",
            grading::shell_acceleration(|tau0, delta, z: C, zr: C| {
                let m_em = tau0 / delta;
                (-z + zr * m_em) / (1.0 - m_em)
            }),
            "retarded term has the wrong sign",
        ),
        w(
            "shell_acceleration",
            "the whole mass",
            grading::shell_acceleration(|tau0, delta, z: C, zr: C| -z - zr * (tau0 / delta)),
            "whole mass",
        ),
        w(
            "shell_acceleration",
            "the sign flipped",
            grading::shell_acceleration(|tau0, delta, z, zr| {
                -ShellModel::new(tau0, delta).unwrap().acceleration(z, zr)
            }),
            "sign flip",
        ),
        // (A.1) root
        w(
            "characteristic_root",
            "the start",
            grading::characteristic_root(|_, _| C::new(0.0, 1.0)),
            "where the search starts",
        ),
        w(
            "characteristic_root",
            "e^{+s delta}",
            grading::characteristic_root(|tau0: f64, delta: f64| {
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
        // RK4
        w(
            "rk4_step",
            "wrong weights",
            grading::rk4_step(rk4_variant([1.0, 1.0, 2.0, 2.0], true)),
            "weights",
        ),
        w(
            "rk4_step",
            "k4 at the old time",
            grading::rk4_step(rk4_variant([1.0, 2.0, 2.0, 1.0], false)),
            "wrong time",
        ),
        w(
            "rk4_step",
            "Euler's method",
            grading::rk4_step(|f: DynField, t, y: &State<3>, h| y + f(t, y) * h),
            "Euler's method",
        ),
        // DP5
        w(
            "dp5_step",
            "the estimate's sign",
            grading::dp5_step(|f: DynField, t, y: &State<3>, h| {
                let (y5, e) = dopri5_step(&f, t, y, h);
                (y5, -e)
            }),
            "wrong sign",
        ),
        w(
            "dp5_step",
            "the fourth-order step",
            grading::dp5_step(|f: DynField, t, y: &State<3>, h| {
                let (y5, e) = dopri5_step(&f, t, y, h);
                (y5 - e, e)
            }),
            "fourth-order solution",
        ),
        // a whole RK4 run
        w(
            "reduced_rk4",
            "Euler steps",
            grading::reduced_rk4(reduced_run(true)),
            "not 4",
        ),
        w(
            "reduced_rk4",
            "midpoint steps",
            grading::reduced_rk4(reduced_run(false)),
            "not 4",
        ),
        w(
            "reduced_rk4",
            "the truncated model integrated",
            grading::reduced_rk4(|r, tau, w0, t_end, n: usize| {
                let h = t_end / n as f64;
                let f = |_t: f64, y: &State<3>| sym::truncated_ale_rhs(&top(r, tau), y);
                (0..n).fold(w0, |y, i| rk4_step(&f, i as f64 * h, &y, h))
            }),
            "does not shrink",
        ),
    ]
}

#[test]
fn every_reference_implementation_passes_its_grader() {
    let refs = references();
    let names: BTreeSet<_> = refs.iter().map(|(n, _)| *n).collect();
    let course: BTreeSet<_> = COURSE.iter().map(|a| a.function).collect();
    assert_eq!(names, course, "one reference per assignment of the course");
    for (name, grade) in refs {
        let passed = grade.unwrap_or_else(|f| panic!("{name}: {f}"));
        assert!(passed.cases >= 20, "{passed:?}");
    }
}

#[test]
fn every_stub_fails_and_says_it_is_a_stub() {
    let stubs = stubs();
    assert_eq!(stubs.len(), COURSE.len());
    for (name, grade) in stubs {
        let failed = grade.expect_err(name);
        assert_eq!(failed.assignment, name);
        assert!(
            failed.diagnosis.starts_with("the stub is still a todo!()"),
            "{failed}"
        );
        assert!(
            failed
                .to_string()
                .contains(&format!("spintop course hint {name}"))
        );
    }
}

fn report(failed: &Failed) -> String {
    let text = failed.to_string();
    for part in ["input:", "expected:", "got:", "diagnosis:"] {
        assert!(text.contains(part), "{text}");
    }
    text
}

#[test]
fn every_plausible_wrong_answer_fails_with_its_own_diagnosis() {
    let wrong = wrong_answers();
    for a in COURSE {
        let mine: Vec<&Wrong> = wrong
            .iter()
            .filter(|x| x.assignment == a.function)
            .collect();
        assert!(
            mine.len() >= 2,
            "{}: fewer than two wrong answers",
            a.function
        );
        let diagnoses: BTreeSet<String> = mine
            .iter()
            .map(|x| match &x.grade {
                Ok(p) => panic!("{} ({}) passed: {p:?}", a.function, x.what),
                Err(f) => {
                    assert_eq!(f.assignment, a.function);
                    report(f);
                    assert!(
                        f.diagnosis.contains(x.says),
                        "{} ({}): the diagnosis should say '{}':\n{f}",
                        a.function,
                        x.what,
                        x.says
                    );
                    f.diagnosis.clone()
                }
            })
            .collect();
        assert!(
            diagnoses.len() >= 2,
            "{}: the wrong answers share one diagnosis: {diagnoses:?}",
            a.function
        );
    }
}

/// The pieces of a formula rung worth looking for in a report.
fn formula_pieces(formula: &str) -> Vec<&str> {
    let mut pieces: Vec<&str> = formula
        .split([';', ','])
        .map(str::trim)
        .filter(|p| p.len() >= 12)
        .collect();
    pieces.push(formula);
    pieces
}

#[test]
fn no_failure_prints_the_formula_and_the_last_hint_does() {
    let mut failures: Vec<(&str, String)> = Vec::new();
    for (name, grade) in stubs() {
        failures.push((name, grade.unwrap_err().to_string()));
    }
    for x in wrong_answers() {
        failures.push((x.assignment, x.grade.unwrap_err().to_string()));
    }
    for a in COURSE {
        let formula = a.hints[2];
        assert!(
            formula.contains('='),
            "{}: the last rung is a formula",
            a.function
        );
        for rung in &a.hints[..2] {
            for piece in formula_pieces(formula) {
                assert!(
                    !rung.contains(piece),
                    "{}: an early rung gives the formula: {rung}",
                    a.function
                );
            }
        }
        for (name, text) in failures.iter().filter(|(n, _)| *n == a.function) {
            for piece in formula_pieces(formula) {
                assert!(
                    !text.contains(piece),
                    "{name}: the report prints the formula '{piece}':\n{text}"
                );
            }
        }
    }
}

#[test]
fn a_shortcut_through_spintop_fails_with_the_no_shortcut_message() {
    for (name, grade) in references() {
        assert!(grade.is_ok());
        let a = find(name).unwrap();
        // The reference passes numerically; the file that calls it must not.
        let source = format!(
            "use spintop::assignment::Vec3;\n\npub fn {name}(x: Vec3) -> Vec3 {{\n    spintop::physics::{module}::{name}(x)\n}}\n",
            module = a.binary
        );
        let failed = without_shortcut(grade, &[(a.file, &source)]).expect_err(name);
        assert!(failed.diagnosis.starts_with(NO_SHORTCUT), "{failed}");
        assert!(failed.actual.contains("line 4"), "{failed}");
        assert_eq!(failed.assignment, name);
    }
}

#[test]
fn the_shortcut_check_allows_math_and_assignment_and_nothing_else() {
    let allowed = [
        "use spintop::assignment::{Jet, Vec3};",
        "use spintop::math::{Mat3, State};",
        "let v = spintop::math::Vec3::zeros();",
        "use spintop :: assignment :: C;",
        "// spintop::physics::balance::larmor_rate is the reference; not used",
        "/* spintop::sim */ use spintop::math::Vec3;",
        "use spintop_lessons::ch2;",
        "let s = crate::ch4::reduced_ale_rhs(r, t, w);",
    ];
    for line in allowed {
        assert_eq!(no_shortcut(line), Ok(()), "{line}");
    }
    let rejected = [
        "use spintop::physics::balance;",
        "spintop::physics::balance::larmor_rate(jet)",
        "use spintop as s;",
        "use spintop::{math, physics};",
        "let x = ::spintop::sim::simulate;",
        "use spintop::grading::DynField;",
        "use spintop::integrate::rk4::rk4_step;",
        "use spintop::mathx::Vec3;",
        "include!(\"../../src/physics/balance.rs\");",
        "#[path = \"../../src/physics/balance.rs\"] mod b;",
        "extern crate spintop as reference;",
    ];
    for line in rejected {
        assert!(no_shortcut(line).is_err(), "{line}");
    }
}

#[test]
fn the_course_files_and_the_reference_solutions_take_no_shortcut() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/src");
    for dir in [root.clone(), root.join("solutions")] {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|x| x == "rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                assert_eq!(no_shortcut(&text), Ok(()), "{}", path.display());
            }
        }
    }
}

#[test]
fn the_shape_of_a_wrong_answer_is_named() {
    let e = [1.0, -2.0, 0.5];
    assert!(shape_diagnosis(&[-1.0, 2.0, -0.5], &e).contains("sign flip"));
    assert!(shape_diagnosis(&[2.0, -4.0, 1.0], &e).contains("factor 2"));
    assert!(shape_diagnosis(&[0.5, -1.0, 0.25], &e).contains("factor 1/2"));
    assert!(shape_diagnosis(&[0.0, 0.0, 0.0], &e).contains("zero"));
    assert!(shape_diagnosis(&[f64::NAN, 0.0, 0.0], &e).contains("not finite"));
    assert!(shape_diagnosis(&[-2.0, 1.0, 0.5], &e).contains("right size, wrong direction"));
    assert!(shape_diagnosis(&[1.7, -3.4, 0.85], &e).contains("1.7000 times"));
    assert!(shape_diagnosis(&[5.0, 1.0, 0.0], &e).contains("wrong in size and direction"));
}
