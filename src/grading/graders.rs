//! One grader per assignment, in course order.
//!
//! | grader | equation | the student writes |
//! |---|---|---|
//! | [`larmor_rate`] | (2.1) | the Larmor-like loss rate |
//! | [`schott_angular_momentum`] | (2.4) | L_S |
//! | [`torque_rate`] | (2.2) | the radiation-reaction torque |
//! | [`schott_rate`] | (2.3) | dL_S/dt, the difference of the two laws |
//! | [`axial_schott_rate`] | (2.3)–(2.4) | n · dL_S/dt |
//! | [`precessing_dipole_jet`] | Section 2 | the jet of a precessing dipole |
//! | [`truncated_ale_rhs`] | (3.3) | Ω̇ of a general top |
//! | [`energy_rate`] | (3.3) | dE/dt of a general top |
//! | [`euler_from_rotation`] | (3.5) | Euler angles of a rotation, pole included |
//! | [`truncated_omega_perp`] | (4.5)–(4.6) | Ω⊥(t) of the truncated top |
//! | [`truncated_closed_form`] | (4.7) | Ω(t) of the truncated top |
//! | [`truncated_time_to_factor`] | (4.6) inverted | when Ω has fallen by p |
//! | [`precession_tilt`] | (4.11), corrected | the constant tilt θ |
//! | [`reduced_ale_rhs`] | (4.12)–(4.14) | Ω̇ of the reduced model |
//! | [`reduced_decay_time`] | (4.16) | σ |
//! | [`reduced_closed_form`] | (4.15)–(4.16) | Ω(t) for any Ω₀ |
//! | [`rk4_step`] | – | one classical RK4 step |
//! | [`dp5_step`] | – | one Dormand–Prince 5(4) step and its error estimate |
//! | [`reduced_rk4`] | (4.12)–(4.14) | a whole RK4 run, converging at order 4 |
//! | [`shell_masses`] | (A.1) | m₀ and m_em |
//! | [`shell_acceleration`] | (A.1) | the method-of-steps update Z'' |
//! | [`characteristic_root`] | (A.1), Z ∝ e^{st} | the oscillation's root s |

use super::{Answer, Grade, Grader, Passed, Rng, call, close, mistake, panic_diagnosis};
use super::{CASES, SEED, shape_diagnosis};
use crate::assignment::DynField;
use crate::integrate::{dopri5::dopri5_step, rk4::rk4_step as reference_rk4_step};
use crate::math::{Mat3, Real, State, Vec3};
use crate::physics::balance::{self, DipoleTrajectory, Jet};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::shell::{C, ShellModel};
use crate::physics::symmetric_top::{self as sym, SymmetricTop};
use std::fmt;

// ---------------------------------------------------------------- Section 2

/// A readable jet for reports.
#[derive(Clone, Copy)]
struct JetInput(Jet);

impl fmt::Debug for JetInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [d, d1, d2, d3] = self.0;
        write!(
            f,
            "d = {:?}, d' = {:?}, d'' = {:?}, d''' = {:?}",
            d.as_slice(),
            d1.as_slice(),
            d2.as_slice(),
            d3.as_slice()
        )
    }
}

fn jets() -> Vec<JetInput> {
    let mut rng = Rng::new(SEED);
    let mut out: Vec<JetInput> = (0..CASES)
        .map(|_| JetInput([rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0)]))
        .collect();
    // A precessing dipole, the Section 2 example, at a few times.
    if let Ok(p) = balance::PrecessingDipole::new(0.7, 1.3) {
        out.extend([0.0, 0.4, 2.0].map(|t| JetInput(p.jet(t))));
    }
    out
}

fn tight(a: &Vec3, b: &Vec3) -> bool {
    close(a, b, 1e-12)
}

/// Grade the Larmor-like loss rate.
///
/// Paper: Eq. (2.1).
pub fn larmor_rate(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "larmor_rate",
        "Eq. (2.1)",
        jets(),
        |j: &JetInput| balance::larmor_rate(&j.0),
        tight,
    )
    .mistakes(vec![
        mistake(
            "that is the Schott angular momentum L_S of (2.4), an angular momentum, not a rate of loss",
            |j: &JetInput| j.0[0].cross(&j.0[2]),
        ),
        mistake(
            "that is the torque law (2.2), not the Larmor-like law (2.1): the two differ by the Schott term",
            |j: &JetInput| j.0[0].cross(&j.0[3]),
        ),
    ])
    .run(|j| student(&j.0))
}

/// Grade the Schott angular momentum.
///
/// Paper: Eq. (2.4).
pub fn schott_angular_momentum(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "schott_angular_momentum",
        "Eq. (2.4)",
        jets(),
        |j: &JetInput| balance::schott_angular_momentum(&j.0),
        tight,
    )
    .mistakes(vec![
        mistake(
            "one derivative short: you crossed d with its first derivative; L_S involves the second",
            |j: &JetInput| j.0[0].cross(&j.0[1]),
        ),
        mistake(
            "that is the torque law (2.2), a rate; L_S is the angular momentum whose rate is the difference of the two laws",
            |j: &JetInput| j.0[0].cross(&j.0[3]),
        ),
    ])
    .run(|j| student(&j.0))
}

/// Grade the Abraham–Lorentz torque.
///
/// Paper: Eq. (2.2).
pub fn torque_rate(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "torque_rate",
        "Eq. (2.2)",
        jets(),
        |j: &JetInput| balance::torque_rate(&j.0),
        tight,
    )
    .mistakes(vec![
        mistake(
            "that is the Larmor-like law (2.1): the Schott term (2.3) is missing",
            |j: &JetInput| balance::larmor_rate(&j.0),
        ),
        mistake(
            "that is L_S of (2.4), one derivative too few on the second factor",
            |j: &JetInput| j.0[0].cross(&j.0[2]),
        ),
    ])
    .run(|j| student(&j.0))
}

/// Grade the rate of the Schott angular momentum, the difference of the laws.
///
/// Paper: Eq. (2.3).
pub fn schott_rate(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "schott_rate",
        "Eq. (2.3)",
        jets(),
        |j: &JetInput| balance::schott_rate(&j.0),
        tight,
    )
    .mistakes(vec![
        mistake(
            "only half of the product rule: you differentiated the first factor of L_S and not the second",
            |j: &JetInput| j.0[1].cross(&j.0[2]),
        ),
        mistake(
            "only half of the product rule: you differentiated the second factor of L_S and not the first",
            |j: &JetInput| j.0[0].cross(&j.0[3]),
        ),
        mistake(
            "the two terms of the product rule have opposite signs in your answer: both come with +",
            |j: &JetInput| j.0[0].cross(&j.0[3]) - j.0[1].cross(&j.0[2]),
        ),
    ])
    .run(|j| student(&j.0))
}

/// Grade the axial projection n·dL_S/dt, n = d/|d|.
///
/// Paper: Eq. (2.3), Eq. (2.4).
pub fn axial_schott_rate(student: impl Fn(&Jet) -> Real) -> Grade {
    let rate = |j: &JetInput| j.0[0].dot(&balance::schott_rate(&j.0));
    Grader::new(
        "axial_schott_rate",
        "Eqs. (2.3)-(2.4)",
        jets(),
        |j: &JetInput| balance::axial(&j.0[0], &balance::schott_rate(&j.0)),
        |a: &Real, b: &Real| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "not normalised: you projected on d itself, not on the unit vector along d",
            rate,
        ),
        mistake(
            "normalised twice: you divided by the square of |d|; the unit vector needs one |d|",
            move |j: &JetInput| rate(j) / j.0[0].norm_squared(),
        ),
    ])
    .run(|j| student(&j.0))
}

/// The precessing dipole's parameters.
#[derive(Clone, Copy)]
struct ConeInput {
    theta: Real,
    omega: Real,
    t: Real,
}

impl fmt::Debug for ConeInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "theta = {}, omega = {}, t = {}",
            self.theta, self.omega, self.t
        )
    }
}

/// Grade the jet of a dipole precessing uniformly on a cone about z.
///
/// Paper: Section 2 (the example of Eqs. (2.1)–(2.4)).
pub fn precessing_dipole_jet(student: impl Fn(Real, Real, Real) -> Jet) -> Grade {
    let mut rng = Rng::new(SEED);
    let inputs: Vec<ConeInput> = (0..CASES)
        .map(|_| {
            let sign = if rng.uniform(0.0, 1.0) < 0.5 {
                -1.0
            } else {
                1.0
            };
            ConeInput {
                theta: rng.uniform(0.05, 3.1),
                omega: sign * rng.uniform(0.2, 3.0),
                t: rng.uniform(0.0, 10.0),
            }
        })
        .collect();
    let reference = |x: &ConeInput| match balance::PrecessingDipole::new(x.theta, x.omega) {
        Ok(p) => p.jet(x.t),
        Err(_) => [Vec3::repeat(Real::NAN); 4],
    };
    Grader::new(
        "precessing_dipole_jet",
        "Section 2, the precessing dipole",
        inputs,
        reference,
        |a: &Jet, b: &Jet| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "the chain rule's factors of omega are missing: each time derivative of cos(omega t) brings one",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[1] /= x.omega;
                j[2] /= x.omega * x.omega;
                j[3] /= x.omega.powi(3);
                j
            },
        ),
        mistake(
            "d'' points the wrong way: a uniform circular motion accelerates toward its axis",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[2] = -j[2];
                j
            },
        ),
        mistake(
            "d''' has the wrong sign: differentiate d'' once more, carefully",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[3] = -j[3];
                j
            },
        ),
    ])
    .run(|x| student(x.theta, x.omega, x.t))
}

// ---------------------------------------------------------------- Section 3

/// A general top and a rate, for (3.3).
#[derive(Clone, Copy)]
struct TopInput {
    inertia: Vec3,
    dipole: Vec3,
    omega: Vec3,
}

impl fmt::Debug for TopInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "inertia = {:?}, dipole = {:?}, omega = {:?}",
            self.inertia.as_slice(),
            self.dipole.as_slice(),
            self.omega.as_slice()
        )
    }
}

fn top_inputs() -> Vec<TopInput> {
    let mut rng = Rng::new(SEED);
    let mut inputs = Vec::new();
    while inputs.len() < CASES {
        let inertia = Vec3::new(
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
        );
        // Small dipoles keep I + d(d x Omega)^T far from singular; every tenth
        // case is nearly free (Euler's equations).
        let dipole = if inputs.len() % 10 == 0 {
            rng.vec3(1e-6)
        } else {
            rng.vec3(0.6)
        };
        let input = TopInput {
            inertia,
            dipole,
            omega: rng.vec3(1.0),
        };
        if GeneralTop::new(inertia, dipole).is_ok() {
            inputs.push(input);
        }
    }
    inputs
}

fn top_rhs(x: &TopInput) -> Vec3 {
    match GeneralTop::new(x.inertia, x.dipole) {
        Ok(top) => top.truncated_ale_rhs(&x.omega),
        Err(_) => Vec3::repeat(Real::NAN),
    }
}

/// Grade the body-frame right-hand side of the truncated ALE of a general top.
///
/// Paper: Eq. (3.3).
pub fn truncated_ale_rhs(student: impl Fn(Vec3, Vec3, Vec3) -> Vec3) -> Grade {
    Grader::new(
        "truncated_ale_rhs",
        "Eq. (3.3)",
        top_inputs(),
        top_rhs,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the moments of inertia are attached to the wrong axes (I1 and I3 swapped?): check with a zero dipole, where Euler's equations must come out",
            |x: &TopInput| {
                top_rhs(&TopInput {
                    inertia: Vec3::new(x.inertia.z, x.inertia.y, x.inertia.x),
                    ..*x
                })
            },
        ),
        mistake(
            "the damping term that contains the angular acceleration itself is missing: it is on both sides, so the equation must be solved for it",
            |x: &TopInput| {
                let w = x.omega;
                let b = -w.cross(&x.inertia.component_mul(&w)) - x.dipole.cross(&w).norm_squared() * w;
                b.component_div(&x.inertia)
            },
        ),
        mistake(
            "the gyroscopic term has the wrong sign: with a zero dipole, compare with Euler's equations",
            |x: &TopInput| {
                let flipped = top_rhs(x);
                let w = x.omega;
                let gyro = w.cross(&x.inertia.component_mul(&w));
                // Exact only for a vanishing dipole; elsewhere it is simply another answer.
                flipped + 2.0 * gyro.component_div(&x.inertia)
            },
        ),
    ])
    .run(|x| student(x.inertia, x.dipole, x.omega))
}

/// Grade the rate of change of the kinetic energy under (3.3).
///
/// Paper: Eq. (3.3) (the energy balance it implies).
pub fn energy_rate(student: impl Fn(Vec3, Vec3, Vec3) -> Real) -> Grade {
    Grader::new(
        "energy_rate",
        "Eq. (3.3), the energy balance",
        top_inputs(),
        |x: &TopInput| x.omega.dot(&x.inertia.component_mul(&top_rhs(x))),
        |a: &Real, b: &Real| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the moments of inertia are missing: the kinetic energy weighs each component of the rate by its moment",
            |x: &TopInput| x.omega.dot(&top_rhs(x)),
        ),
        mistake(
            "only the first damping term: the term with the angular acceleration inside also does work",
            |x: &TopInput| -x.dipole.cross(&x.omega).norm_squared() * x.omega.norm_squared(),
        ),
    ])
    .run(|x| student(x.inertia, x.dipole, x.omega))
}

#[derive(Clone, Copy)]
struct RotationInput(Mat3);

impl fmt::Debug for RotationInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = EulerAngles::from_rotation(&self.0);
        write!(
            f,
            "the rotation with (phi, theta, psi) = ({}, {:e}, {})",
            a.phi, a.theta, a.psi
        )
    }
}

/// Grade Euler angles from a rotation matrix, z-x-z, pole included.
///
/// Paper: Eq. (3.5) (its angle convention).
pub fn euler_from_rotation(student: impl Fn(&Mat3) -> (Real, Real, Real)) -> Grade {
    let mut rng = Rng::new(SEED);
    let pi = std::f64::consts::PI;
    let mut inputs: Vec<RotationInput> = (0..CASES)
        .map(|_| {
            let e = EulerAngles::new(
                rng.uniform(-pi, pi),
                rng.uniform(0.0, pi),
                rng.uniform(-pi, pi),
            );
            RotationInput(e.to_rotation())
        })
        .collect();
    for theta in [0.0, pi, 1e-9, 1e-13, pi - 1e-9] {
        let e = EulerAngles::new(rng.uniform(-pi, pi), theta, rng.uniform(-pi, pi));
        inputs.push(RotationInput(e.to_rotation()));
    }
    // The engine is used for its report only; the check is by rebuilding.
    let g: Grader<'_, RotationInput, Real> = Grader::new(
        "euler_from_rotation",
        "Eq. (3.5), z-x-z angles",
        Vec::new(),
        |_| 0.0,
        |_, _| true,
    );
    for input in &inputs {
        let m = input.0;
        let true_theta = EulerAngles::from_rotation(&m).theta;
        let near_pole = true_theta < 1e-6 || true_theta > pi - 1e-6;
        match call(|| student(&m)) {
            Ok((phi, theta, psi)) => {
                let finite = phi.is_finite() && theta.is_finite() && psi.is_finite();
                let rebuilt = EulerAngles::new(phi, theta, psi).to_rotation();
                let err = (rebuilt - m).norm();
                if !finite || !(0.0..=pi).contains(&theta) || err > 1e-12 {
                    let diagnosis = if !finite && near_pole {
                        "not finite on a pole: where theta is 0 or pi only one combination of phi and psi is defined; choose psi = 0 there"
                    } else if !finite {
                        "not finite: a division or an inverse trigonometric function out of its range?"
                    } else if !(0.0..=pi).contains(&theta) {
                        "theta is outside [0, pi]: the z-x-z convention keeps the nutation angle there"
                    } else if near_pole {
                        "right away from the poles, but digits are lost near theta = 0 or pi: an inverse cosine is ill-conditioned there"
                    } else {
                        "the angles rebuild a different rotation: check which matrix entries give phi and psi in the z-x-z convention"
                    };
                    return Err(g.fail(
                        format!("{input:?}"),
                        "finite angles, theta in [0, pi], rebuilding the matrix to 1e-12".into(),
                        format!("({phi}, {theta:e}, {psi}), rebuilding it to {err:.1e}"),
                        diagnosis.into(),
                    ));
                }
            }
            Err(msg) => {
                let d = panic_diagnosis(&msg);
                return Err(g.fail(format!("{input:?}"), "three angles".into(), msg, d));
            }
        }
    }
    Ok(Passed {
        assignment: g.name,
        equation: g.equation,
        cases: inputs.len(),
    })
}

// ---------------------------------------------------------------- Section 4.1

/// A symmetric top, a start and a time, for the closed forms of Section 4.
#[derive(Clone, Copy)]
struct TopTime {
    ratio: Real,
    tau: Real,
    omega0: Vec3,
    t: Real,
}

impl fmt::Debug for TopTime {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega0 = {:?}, t = {}",
            self.ratio,
            self.tau,
            self.omega0.as_slice(),
            self.t
        )
    }
}

fn top_times(omega: Real, t_max: Real) -> Vec<TopTime> {
    let mut rng = Rng::new(SEED);
    (0..CASES)
        .map(|_| TopTime {
            ratio: rng.uniform(0.1, 2.0),
            tau: rng.uniform(0.2, 2.0),
            omega0: rng.vec3(omega),
            t: rng.uniform(0.1, t_max),
        })
        .collect()
}

fn top_of(x: &TopTime) -> Option<SymmetricTop> {
    SymmetricTop::new(x.ratio, x.tau).ok()
}

/// The student's function called again on another input.
type Again<'a, T> = dyn Fn(&TopTime) -> Option<T> + 'a;

/// "Right at t = 0 but drifting": the probe of the graders of Ω(t).
fn drift_probe<T: Answer>(
    reference: impl Fn(&TopTime) -> T,
) -> impl Fn(&TopTime, &Again<'_, T>) -> Option<String> {
    move |x, again| {
        let at0 = TopTime { t: 0.0, ..*x };
        let theirs = again(&at0)?;
        close(&theirs, &reference(&at0), 1e-10).then(|| {
            "right at t = 0, but it drifts away from the right answer: a rate (of decay or of precession) is wrong".to_string()
        })
    }
}

/// Grade Ω⊥(t) of the truncated model.
///
/// Paper: Eq. (4.5), Eq. (4.6).
pub fn truncated_omega_perp(student: impl Fn(Real, Real, Real, Real) -> Real) -> Grade {
    let inputs: Vec<TopTime> = top_times(1.0, 40.0)
        .into_iter()
        .map(|x| TopTime {
            omega0: Vec3::new(x.omega0.x.abs() + 0.05, 0.0, 0.0),
            ..x
        })
        .collect();
    let reference = |x: &TopTime| match top_of(x) {
        Some(top) => sym::truncated_omega_perp(&top, x.omega0.x, x.t),
        None => Real::NAN,
    };
    Grader::new(
        "truncated_omega_perp",
        "Eqs. (4.5)-(4.6)",
        inputs,
        reference,
        |a: &Real, b: &Real| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "an exponential decay: the loss of the truncated model grows with the cube of the rate, so the rate falls like a power of t, not exponentially",
            |x: &TopTime| x.omega0.x * (-x.tau * x.omega0.x * x.omega0.x * x.t).exp(),
        ),
        mistake(
            "the right shape, the wrong speed: a factor 2 inside the square root is missing",
            |x: &TopTime| x.omega0.x / (1.0 + x.tau * x.omega0.x * x.omega0.x * x.t).sqrt(),
        ),
    ])
    .probe(drift_probe(reference))
    .run(|x| student(x.ratio, x.tau, x.omega0.x, x.t))
}

/// Grade Ω(t) of the truncated model, for any start.
///
/// Paper: Eq. (4.7).
pub fn truncated_closed_form(student: impl Fn(Real, Real, Vec3, Real) -> Vec3) -> Grade {
    let reference = |x: &TopTime| match top_of(x) {
        Some(top) => sym::truncated_closed_form(&top, &x.omega0, x.t),
        None => Vec3::repeat(Real::NAN),
    };
    // The same model with the phase alpha replaced.
    let with_phase = |x: &TopTime, alpha: Real| {
        let u0 = x.omega0.x.hypot(x.omega0.y);
        let r = (1.0 + 2.0 * x.tau * u0 * u0 * x.t).sqrt();
        let (s, c) = alpha.sin_cos();
        Vec3::new(
            (x.omega0.x * c + x.omega0.y * s) / r,
            (x.omega0.y * c - x.omega0.x * s) / r,
            x.omega0.z / r,
        )
    };
    let vartheta = |x: &TopTime| {
        let u0 = x.omega0.x.hypot(x.omega0.y);
        2.0 * x.t / (1.0 + (1.0 + 2.0 * x.tau * u0 * u0 * x.t).sqrt())
    };
    Grader::new(
        "truncated_closed_form",
        "Eq. (4.7)",
        top_times(1.0, 20.0),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the precession turns the wrong way: in the body frame Omega_perp turns clockwise when the top is oblate... check the sign of the phase against the rate equations",
            move |x: &TopTime| with_phase(x, -(1.0 - x.ratio) * x.omega0.z * vartheta(x)),
        ),
        mistake(
            "the phase runs on the ordinary clock t: as the rates fall the precession slows, so it runs on the slowed time of (4.9)",
            move |x: &TopTime| with_phase(x, (1.0 - x.ratio) * x.omega0.z * x.t),
        ),
        mistake(
            "Omega_3 is held constant: in the truncated model the spin slows together with Omega_perp",
            move |x: &TopTime| {
                let mut w = reference(x);
                w.z = x.omega0.z;
                w
            },
        ),
    ])
    .probe(drift_probe(reference))
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t))
}

/// A top, a perpendicular rate and a factor p, for the inverted (4.6).
#[derive(Clone, Copy)]
struct FactorInput {
    ratio: Real,
    tau: Real,
    omega_perp0: Real,
    p: Real,
}

impl fmt::Debug for FactorInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega_perp0 = {}, p = {}",
            self.ratio, self.tau, self.omega_perp0, self.p
        )
    }
}

/// Grade the time the truncated model takes to slow every rate by p.
///
/// Paper: Eq. (4.6) (inverted).
pub fn truncated_time_to_factor(student: impl Fn(Real, Real, Real, Real) -> Real) -> Grade {
    let mut rng = Rng::new(SEED);
    let inputs: Vec<FactorInput> = (0..CASES)
        .map(|_| FactorInput {
            ratio: rng.uniform(0.1, 2.0),
            tau: rng.uniform(0.01, 2.0),
            omega_perp0: rng.uniform(0.05, 2.0),
            p: rng.uniform(0.01, 0.99),
        })
        .collect();
    let rate = |x: &FactorInput| 2.0 * x.tau * x.omega_perp0 * x.omega_perp0;
    Grader::new(
        "truncated_time_to_factor",
        "Eq. (4.6), inverted",
        inputs,
        |x: &FactorInput| match SymmetricTop::new(x.ratio, x.tau) {
            Ok(top) => sym::truncated_time_to_factor(&top, x.omega_perp0, x.p),
            Err(_) => Real::NAN,
        },
        |a: &Real, b: &Real| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "a negative time: you solved for the wrong end; the rates fall, so their factor R grows past 1",
            move |x: &FactorInput| (x.p * x.p - 1.0) / rate(x),
        ),
        mistake(
            "R was not squared: R is a square root, so undo it before solving for t",
            move |x: &FactorInput| (1.0 / x.p - 1.0) / rate(x),
        ),
    ])
    .run(|x| student(x.ratio, x.tau, x.omega_perp0, x.p))
}

/// Grade the constant tilt between the symmetry axis and L.
///
/// Paper: Eq. (4.11) (corrected: erratum 4).
pub fn precession_tilt(student: impl Fn(Real, Vec3) -> Real) -> Grade {
    let mut rng = Rng::new(SEED);
    let mut inputs: Vec<(Real, Vec3)> = (0..CASES)
        .map(|_| {
            let ratio = rng.uniform(0.1, 2.0);
            let w = rng.vec3(0.5);
            (ratio, Vec3::new(w.x, w.y, w.z.abs() + 0.05))
        })
        .collect();
    inputs.push((0.4, Vec3::new(0.0, 0.1, 0.2)));
    Grader::new(
        "precession_tilt",
        "Eq. (4.11), corrected",
        inputs,
        |(ratio, w): &(Real, Vec3)| match SymmetricTop::new(*ratio, 1.0) {
            Ok(top) => sym::precession_tilt(&top, w),
            Err(_) => Real::NAN,
        },
        |a: &Real, b: &Real| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "that is the angle printed in (4.11): it is erratum 4 (see the Errata page)",
            |(ratio, w): &(Real, Vec3)| match SymmetricTop::new(*ratio, 1.0) {
                Ok(top) => sym::printed_tilt_4_11(&top, w),
                Err(_) => Real::NAN,
            },
        ),
        mistake(
            "the angle between the axis and the rotation rate, not L: the angular momentum weighs each component by its moment of inertia",
            |(_, w): &(Real, Vec3)| w.x.hypot(w.y).atan2(w.z),
        ),
        mistake(
            "the moments of inertia are swapped: the perpendicular part of L carries I1, the axial part I3",
            |(ratio, w): &(Real, Vec3)| (ratio * w.x.hypot(w.y)).atan2(w.z),
        ),
    ])
    .run(|(ratio, w)| student(*ratio, *w))
}

// ---------------------------------------------------------------- Section 4.2

/// A symmetric top and a rate, for (4.12)–(4.14).
#[derive(Clone, Copy)]
struct SymInput {
    ratio: Real,
    tau: Real,
    omega: Vec3,
}

impl fmt::Debug for SymInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega = {:?}",
            self.ratio,
            self.tau,
            self.omega.as_slice()
        )
    }
}

fn sym_inputs() -> Vec<SymInput> {
    let mut rng = Rng::new(SEED);
    (0..CASES)
        .map(|_| SymInput {
            ratio: rng.uniform(0.1, 2.0),
            tau: rng.uniform(0.05, 2.0),
            omega: rng.vec3(1.0),
        })
        .collect()
}

fn sym_top(x: &SymInput) -> Option<SymmetricTop> {
    SymmetricTop::new(x.ratio, x.tau).ok()
}

/// Grade the reduced model's right-hand side.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_ale_rhs(student: impl Fn(Real, Real, Vec3) -> Vec3) -> Grade {
    let reference = |x: &SymInput| match sym_top(x) {
        Some(top) => sym::reduced_ale_rhs(&top, &x.omega),
        None => Vec3::repeat(Real::NAN),
    };
    Grader::new(
        "reduced_ale_rhs",
        "Eqs. (4.12)-(4.14)",
        sym_inputs(),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "that is the truncated model (4.2)-(4.4): the Schott term's contribution to the damping is missing, and the spin is damped",
            |x: &SymInput| match sym_top(x) {
                Some(top) => sym::truncated_ale_rhs(&top, &x.omega),
                None => Vec3::repeat(Real::NAN),
            },
        ),
        mistake(
            "the spin is damped: in the reduced model the axial rate is constant",
            move |x: &SymInput| {
                let mut w = reference(x);
                let k = x.ratio * x.omega.z;
                w.z = -x.tau * (x.omega.x.powi(2) + x.omega.y.powi(2) + k * k) * x.omega.z;
                w
            },
        ),
        mistake(
            "the damping's Schott part uses the rate about the axis without its moment ratio: it is the axial angular momentum over I1 that enters",
            move |x: &SymInput| {
                let mut w = reference(x);
                let extra = x.tau * ((x.ratio * x.omega.z).powi(2) - x.omega.z.powi(2));
                w.x += extra * x.omega.x;
                w.y += extra * x.omega.y;
                w
            },
        ),
    ])
    .run(|x| student(x.ratio, x.tau, x.omega))
}

/// Grade σ, the late-time decay time of Ω⊥ in the reduced model.
///
/// Paper: Eq. (4.16).
pub fn reduced_decay_time(student: impl Fn(Real, Real, Real) -> Real) -> Grade {
    let inputs: Vec<SymInput> = sym_inputs()
        .into_iter()
        .map(|x| SymInput {
            omega: Vec3::new(0.0, 0.0, x.omega.z.abs() + 0.05),
            ..x
        })
        .collect();
    Grader::new(
        "reduced_decay_time",
        "Eq. (4.16), sigma",
        inputs,
        |x: &SymInput| match sym_top(x) {
            Some(top) => sym::reduced_decay_time(&top, x.omega.z),
            None => Real::NAN,
        },
        |a: &Real, b: &Real| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "the moment ratio enters squared, as the spin does: it comes from the square of the axial angular momentum",
            |x: &SymInput| 1.0 / (x.ratio * x.omega.z * x.omega.z * x.tau),
        ),
        mistake(
            "the moment ratio is upside down: the axial angular momentum is I3 times the spin, divided by I1",
            |x: &SymInput| 1.0 / ((x.omega.z / x.ratio).powi(2) * x.tau),
        ),
    ])
    .run(|x| student(x.ratio, x.tau, x.omega.z))
}

/// Grade the reduced model's closed form, with Ω₁₀ ≠ 0.
///
/// Paper: Eq. (4.15), Eq. (4.16).
pub fn reduced_closed_form(student: impl Fn(Real, Real, Vec3, Real) -> Vec3) -> Grade {
    let reference = |x: &TopTime| match top_of(x) {
        Some(top) => sym::reduced_closed_form(&top, &x.omega0, x.t),
        None => Vec3::repeat(Real::NAN),
    };
    // Φ with the exponent scaled by `f`, and the phase by `turn`.
    let variant = |x: &TopTime, f: Real, turn: Real| {
        let u0 = x.omega0.x * x.omega0.x + x.omega0.y * x.omega0.y;
        let k = x.ratio * x.omega0.z;
        let s = f * 2.0 * x.tau * k * k * x.t;
        let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
        let phi = (-0.5 * s).exp() / (1.0 + f * 2.0 * x.tau * u0 * x.t * g).sqrt();
        let alpha = turn * (1.0 - x.ratio) * x.omega0.z * x.t;
        let (sa, ca) = alpha.sin_cos();
        Vec3::new(
            phi * (x.omega0.x * ca + x.omega0.y * sa),
            phi * (x.omega0.y * ca - x.omega0.x * sa),
            x.omega0.z,
        )
    };
    Grader::new(
        "reduced_closed_form",
        "Eqs. (4.15)-(4.16)",
        top_times(0.5, 40.0),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the start was taken with Omega_10 = 0, as the paper prints it: keep both components of Omega_perp0",
            move |x: &TopTime| {
                reference(&TopTime {
                    omega0: Vec3::new(0.0, x.omega0.x.hypot(x.omega0.y), x.omega0.z),
                    ..*x
                })
            },
        ),
        mistake(
            "the amplitude decays at half the rate: the exponent in Phi carries a factor 2",
            move |x: &TopTime| variant(x, 0.5, 1.0),
        ),
        mistake(
            "the precession turns the wrong way: check the sign of the phase against (4.12)-(4.13)",
            move |x: &TopTime| variant(x, 1.0, -1.0),
        ),
    ])
    .probe(drift_probe(reference))
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t))
}

// ---------------------------------------------------------------- numerical methods

/// The test problems of the step graders: a non-autonomous linear system and
/// the reduced ALE (4.12), as `(name, f)`.
type Field = fn(Real, &State<3>) -> State<3>;

fn fields() -> [(&'static str, Field); 2] {
    fn linear(t: Real, y: &State<3>) -> State<3> {
        State::<3>::new(
            -0.5 * y[0] + 2.0 * y[1] + t.sin(),
            -2.0 * y[0] - 0.5 * y[1],
            -y[2] + t * t,
        )
    }
    fn reduced(_t: Real, y: &State<3>) -> State<3> {
        let top = SymmetricTop::figure();
        sym::reduced_ale_rhs(&top, &Vec3::new(y[0], y[1], y[2]))
    }
    [("linear", linear), ("reduced ALE (4.12), tau = 1", reduced)]
}

#[derive(Clone, Copy)]
struct StepInput {
    field: usize,
    t: Real,
    y: State<3>,
    h: Real,
}

impl fmt::Debug for StepInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "f = {}, t = {}, y = {:?}, h = {}",
            fields()[self.field].0,
            self.t,
            self.y.as_slice(),
            self.h
        )
    }
}

fn step_inputs() -> Vec<StepInput> {
    let mut rng = Rng::new(SEED);
    (0..CASES)
        .map(|i| StepInput {
            field: i % 2,
            t: rng.uniform(-1.0, 3.0),
            y: State::<3>::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            ),
            h: rng.uniform(0.01, 0.4),
        })
        .collect()
}

/// Grade one classical RK4 step.
pub fn rk4_step(student: impl Fn(DynField, Real, &State<3>, Real) -> State<3>) -> Grade {
    let f = |x: &StepInput| fields()[x.field].1;
    Grader::new(
        "rk4_step",
        "classical RK4, Hairer-Norsett-Wanner I, Table II.1.2",
        step_inputs(),
        move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h),
        |a: &State<3>, b: &State<3>| close(a, b, 1e-13),
    )
    .mistakes(vec![
        mistake(
            "the weights of the four stages are not the classical ones: the two middle stages count twice, the ends once",
            move |x: &StepInput| {
                let (f, t, y, h) = (f(x), x.t, x.y, x.h);
                let k1 = f(t, &y);
                let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
                let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
                let k4 = f(t + h, &(y + k3 * h));
                y + (k1 + k2 + k3 * 2.0 + k4 * 2.0) * (h / 6.0)
            },
        ),
        mistake(
            "right when f does not depend on t, wrong when it does: a stage evaluates f at the wrong time",
            move |x: &StepInput| {
                let (f, t, y, h) = (f(x), x.t, x.y, x.h);
                let k1 = f(t, &y);
                let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
                let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
                let k4 = f(t, &(y + k3 * h));
                y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
            },
        ),
        mistake(
            "that is one step of Euler's method: only the first stage is used",
            move |x: &StepInput| x.y + f(x)(x.t, &x.y) * x.h,
        ),
    ])
    .run(|x| student(&fields()[x.field].1, x.t, &x.y, x.h))
}

/// Grade one Dormand–Prince 5(4) step: (y₅, y₅ − ŷ₄).
pub fn dp5_step(
    student: impl Fn(DynField, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    let f = |x: &StepInput| fields()[x.field].1;
    let reference = move |x: &StepInput| dopri5_step(&f(x), x.t, &x.y, x.h);
    Grader::new(
        "dp5_step",
        "Dormand-Prince 5(4), Hairer-Norsett-Wanner I, Table II.5.2",
        step_inputs(),
        reference,
        |a: &(State<3>, State<3>), b: &(State<3>, State<3>)| {
            close(&a.0, &b.0, 1e-13) && (a.1 - b.1).norm() <= 1e-13 + 1e-9 * b.1.norm()
        },
    )
    .mistakes(vec![
        mistake(
            "the step is right, the error estimate has the wrong sign: it is the fifth-order result minus the fourth",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5, -e)
            },
        ),
        mistake(
            "the fourth-order solution was returned as the step: the step is the fifth-order one (local extrapolation)",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5 - e, e)
            },
        ),
    ])
    .run(|x| student(&fields()[x.field].1, x.t, &x.y, x.h))
}

/// A start and an end for [`reduced_rk4`].
#[derive(Clone, Copy)]
struct RunInput {
    ratio: Real,
    tau: Real,
    omega0: Vec3,
    t_end: Real,
}

impl fmt::Debug for RunInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega0 = {:?}, t_end = {}",
            self.ratio,
            self.tau,
            self.omega0.as_slice(),
            self.t_end
        )
    }
}

/// The step counts a run is graded with, coarse to fine.
pub const RK4_STEPS: [usize; 3] = [40, 80, 160];

/// Grade a whole RK4 run of the reduced model, `steps` equal steps to
/// `t_end`: the answer must be close to the closed form (4.15)–(4.16), and
/// its error must fall like h⁴ (observed order in [3.5, 4.6] between 80 and
/// 160 steps).
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_rk4(student: impl Fn(Real, Real, Vec3, Real, usize) -> Vec3) -> Grade {
    let mut rng = Rng::new(SEED);
    let inputs: Vec<RunInput> = (0..20)
        .map(|_| {
            let pick = |rng: &mut Rng| {
                let s = if rng.uniform(0.0, 1.0) < 0.5 {
                    -1.0
                } else {
                    1.0
                };
                s * rng.uniform(0.5, 1.5)
            };
            RunInput {
                ratio: rng.uniform(0.2, 0.8),
                tau: rng.uniform(0.1, 0.5),
                omega0: Vec3::new(pick(&mut rng), pick(&mut rng), pick(&mut rng)),
                t_end: rng.uniform(2.0, 4.0),
            }
        })
        .collect();
    let g: Grader<'_, RunInput, Real> = Grader::new(
        "reduced_rk4",
        "Eqs. (4.12)-(4.14), integrated by RK4",
        Vec::new(),
        |_| 0.0,
        |_, _| true,
    );
    for x in &inputs {
        let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
            continue;
        };
        let exact = sym::reduced_closed_form(&top, &x.omega0, x.t_end);
        let mut errors = Vec::new();
        for n in RK4_STEPS {
            match call(|| student(x.ratio, x.tau, x.omega0, x.t_end, n)) {
                Ok(w) if w.iter().all(|c| c.is_finite()) => errors.push((w - exact).norm()),
                Ok(w) => {
                    return Err(g.fail(
                        format!("{x:?}, steps = {n}"),
                        exact.show(),
                        w.show(),
                        shape_diagnosis(&w.parts(), &exact.parts()),
                    ));
                }
                Err(msg) => {
                    let d = panic_diagnosis(&msg);
                    return Err(g.fail(format!("{x:?}, steps = {n}"), exact.show(), msg, d));
                }
            }
        }
        let order = (errors[1] / errors[2]).log2();
        let finest = errors[2];
        let scale = 1.0 + exact.norm();
        if finest > 1e-5 * scale || !(3.5..=4.6).contains(&order) {
            let coarse_order = (errors[0] / errors[1]).log2();
            let diagnosis = if finest > 1e-5 * scale
                && order.abs() < 0.3
                && coarse_order.abs() < 0.3
            {
                "the error does not shrink as the steps get smaller: the run converges to a wrong answer (the step size, the number of steps, or the right-hand side)".to_string()
            } else if order < 3.5 {
                format!(
                    "your run converges at order {order:.2}, not 4: a stage of the step is wrong, or it is a lower-order method"
                )
            } else {
                format!(
                    "the error falls at order {order:.2}, faster than RK4 can: are you returning something other than the RK4 result?"
                )
            };
            return Err(g.fail(
                format!("{x:?}, steps = {:?}", RK4_STEPS),
                format!("{} at the end, with errors falling like h^4", exact.show()),
                format!(
                    "errors {:.2e}, {:.2e}, {:.2e} (observed order {order:.2})",
                    errors[0], errors[1], errors[2]
                ),
                diagnosis,
            ));
        }
    }
    Ok(Passed {
        assignment: g.name,
        equation: g.equation,
        cases: inputs.len(),
    })
}

// ---------------------------------------------------------------- appendix

#[derive(Clone, Copy)]
struct ShellInput {
    tau0: Real,
    delta: Real,
    z: C,
    z_ddot_ret: C,
}

impl fmt::Debug for ShellInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "tau0 = {}, delta = {}, Z = {}, Z''(t - delta) = {}",
            self.tau0, self.delta, self.z, self.z_ddot_ret
        )
    }
}

fn shell_inputs(delta_max: Real) -> Vec<ShellInput> {
    let mut rng = Rng::new(SEED);
    (0..CASES)
        .map(|_| {
            let tau0 = rng.uniform(1e-3, 0.05);
            ShellInput {
                tau0,
                delta: rng.uniform(2.5 * tau0, delta_max),
                z: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
                z_ddot_ret: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
            }
        })
        .collect()
}

/// Grade the split of the mass into the bare and the electromagnetic part.
///
/// Paper: Eq. (A.1).
pub fn shell_masses(student: impl Fn(Real, Real) -> (Real, Real)) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => (m.m0(), m.m_em()),
        Err(_) => (Real::NAN, Real::NAN),
    };
    Grader::new(
        "shell_masses",
        "Eq. (A.1), the masses",
        shell_inputs(1.0),
        reference,
        |a: &(Real, Real), b: &(Real, Real)| close(a, b, 1e-13),
    )
    .mistakes(vec![
        mistake(
            "the two masses are swapped: the field's share is the small one when the shell is large",
            move |x: &ShellInput| {
                let (a, b) = reference(x);
                (b, a)
            },
        ),
        mistake(
            "the field's mass is upside down: it grows as the shell shrinks",
            |x: &ShellInput| (1.0 - x.delta / x.tau0, x.delta / x.tau0),
        ),
    ])
    .run(|x| student(x.tau0, x.delta))
}

/// Grade the method-of-steps update of the shell model: Z''(t) from Z(t) and
/// the retarded Z''(t − δ).
///
/// Paper: Eq. (A.1).
pub fn shell_acceleration(student: impl Fn(Real, Real, C, C) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.acceleration(x.z, x.z_ddot_ret),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    Grader::new(
        "shell_acceleration",
        "Eq. (A.1)",
        shell_inputs(1.0),
        reference,
        |a: &C, b: &C| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "the retarded term has the wrong sign: move it to the other side of the equation with care",
            |x: &ShellInput| {
                let m_em = x.tau0 / x.delta;
                (-x.z + x.z_ddot_ret * m_em) / (1.0 - m_em)
            },
        ),
        mistake(
            "divided by the whole mass: the acceleration now is multiplied by the bare mass only, the rest acts one delay later",
            |x: &ShellInput| -x.z - x.z_ddot_ret * (x.tau0 / x.delta),
        ),
    ])
    .run(|x| student(x.tau0, x.delta, x.z, x.z_ddot_ret))
}

/// Newton's method on `p` (with derivative `dp`) from `start`.
fn newton(p: impl Fn(C) -> C, dp: impl Fn(C) -> C, start: C) -> C {
    let mut s = start;
    for _ in 0..100 {
        let step = p(s) / dp(s);
        s -= step;
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    s
}

/// Grade the root of the characteristic function of (A.1) that continues
/// the undamped oscillation s = i.
///
/// Paper: Eq. (A.1) with Z ∝ e^{st}.
pub fn characteristic_root(student: impl Fn(Real, Real) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.root_near_al().unwrap_or(C::new(Real::NAN, Real::NAN)),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    Grader::new(
        "characteristic_root",
        "Eq. (A.1) with Z ~ e^{st}",
        shell_inputs(0.3),
        reference,
        |a: &C, b: &C| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "that is where the search starts, the oscillation without radiation: the root itself is shifted by the radiation (iterate)",
            |_: &ShellInput| C::new(0.0, 1.0),
        ),
        mistake(
            "the retarded factor has the wrong sign in the exponent: a delay brings a decaying exponential of s times delta",
            |x: &ShellInput| {
                let m_em = x.tau0 / x.delta;
                let m0 = 1.0 - m_em;
                let d = x.delta;
                newton(
                    |s| s * s * (m0 + (s * d).exp() * m_em) + 1.0,
                    |s| {
                        let e = (s * d).exp() * m_em;
                        s * 2.0 * (e + m0) + s * s * e * d
                    },
                    C::new(0.0, 1.0),
                )
            },
        ),
    ])
    .run(|x| student(x.tau0, x.delta))
}
