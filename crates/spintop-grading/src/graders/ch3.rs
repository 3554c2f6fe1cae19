//! Section 3: the truncated ALE (3.3) of a general top, its energy balance,
//! and the Euler angles of (3.5).

use super::OMEGA;
use crate::CASES;
use crate::parts::{named, part};
use crate::{Grade, Grader, Passed, Rng, call, close, mistake, panic_diagnosis};
use spintop::math::{Mat3, Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use std::fmt;

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

fn top_inputs(seed: u64) -> Vec<TopInput> {
    let mut rng = Rng::new(seed);
    let mut inputs = Vec::new();
    while inputs.len() < CASES {
        let inertia = Vec3::new(
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
        );
        // Small dipoles keep I + d(d x Omega)^T far from singular; every tenth
        // case is nearly free (Euler's equations).
        let dipole = if inputs.len() % 10 == 9 {
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

/// (diag(I) + a cᵀ)⁻¹ b, by Sherman–Morrison.
fn solve_rank_one(i: &Vec3, a: &Vec3, c: &Vec3, b: &Vec3) -> Vec3 {
    let (ib, ia) = (b.component_div(i), a.component_div(i));
    ib - ia * (c.dot(&ib) / (1.0 + c.dot(&ia)))
}

/// (3.3) with its pieces changed: the gyroscopic sign `g`, the damping's
/// sign `s`, and the rank-one term `(a, c)` (`None`: left out).
fn top_rhs_with(x: &TopInput, g: Real, s: Real, rank_one: Option<(Vec3, Vec3)>) -> Vec3 {
    let (i, w) = (x.inertia, x.omega);
    let b = -g * w.cross(&i.component_mul(&w)) - s * x.dipole.cross(&w).norm_squared() * w;
    match rank_one {
        Some((a, c)) => solve_rank_one(&i, &a, &c, &b),
        None => b.component_div(&i),
    }
}

/// Grade the body-frame right-hand side of the truncated ALE of a general top.
///
/// Paper: Eq. (3.3).
pub fn truncated_ale_rhs(seed: u64, student: impl Fn(Vec3, Vec3, Vec3) -> Vec3) -> Grade {
    let dw = |x: &TopInput| x.dipole.cross(&x.omega);
    Grader::new(
        "truncated_ale_rhs",
        "Eq. (3.3)",
        seed,
        top_inputs(seed),
        top_rhs,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "a missing term: the damping term of the left-hand side that contains the angular acceleration itself (the rank-one matrix times it) is missing: it is on both sides, so the equation must be solved for it",
            |x: &TopInput| top_rhs_with(x, 1.0, 1.0, None),
        ),
        mistake(
            "the gyroscopic term has the wrong sign: with a zero dipole, compare with Euler's equations",
            move |x: &TopInput| top_rhs_with(x, -1.0, 1.0, Some((x.dipole, dw(x)))),
        ),
        mistake(
            "the damping has the wrong sign: radiation takes energy away, so the |d x Omega|^2 term must slow the top",
            move |x: &TopInput| top_rhs_with(x, 1.0, -1.0, Some((x.dipole, dw(x)))),
        ),
        mistake(
            "the rank-one matrix is transposed: the column is the dipole, the row comes from d x Omega",
            move |x: &TopInput| top_rhs_with(x, 1.0, 1.0, Some((dw(x), x.dipole))),
        ),
        mistake(
            "the term with the angular acceleration has the wrong sign once moved to the left-hand side",
            move |x: &TopInput| top_rhs_with(x, 1.0, 1.0, Some((-x.dipole, dw(x)))),
        ),
        mistake(
            "the radiation damping is missing altogether: that is Euler's equations of a free top",
            |x: &TopInput| top_rhs_with(x, 1.0, 0.0, None),
        ),
        mistake(
            "the damping's size is |d|^2 |Omega|^2: it is the square of the cross product d x Omega, which vanishes when the rotation is along the dipole",
            move |x: &TopInput| {
                // (3.3) with the damping's coefficient |d x Omega|^2 replaced.
                let damp = dw(x).norm_squared();
                let s = x.dipole.norm_squared() * x.omega.norm_squared() / damp;
                top_rhs_with(x, 1.0, s, Some((x.dipole, dw(x))))
            },
        ),
        mistake(
            "the damping is not squared: its coefficient is the square of the size of d x Omega, and yours has the size alone",
            move |x: &TopInput| {
                let s = 1.0 / dw(x).norm();
                top_rhs_with(x, 1.0, s, Some((x.dipole, dw(x))))
            },
        ),
    ])
    .variant(
        "the moments of inertia are attached to the wrong axes (I1 and I3 swapped?): check with a zero dipole, where Euler's equations must come out",
        |x: &TopInput| TopInput { inertia: Vec3::new(x.inertia.z, x.inertia.y, x.inertia.x), ..*x },
    )
    .variant(
        "the moments of inertia are attached to the wrong axes (I1 and I2 swapped?): check with a zero dipole, where Euler's equations must come out",
        |x: &TopInput| TopInput { inertia: Vec3::new(x.inertia.y, x.inertia.x, x.inertia.z), ..*x },
    )
    .variant(
        "the moments of inertia are attached to the wrong axes (I2 and I3 swapped?): check with a zero dipole, where Euler's equations must come out",
        |x: &TopInput| TopInput { inertia: Vec3::new(x.inertia.x, x.inertia.z, x.inertia.y), ..*x },
    )
    .parts(
        vec![
            part(
                "with no dipole",
                "Euler's equations of a free top",
                "the gyroscopic term or the moments of inertia",
                |x: &TopInput| TopInput { dipole: Vec3::zeros(), ..*x },
            ),
            part(
                "with equal moments of inertia (no gyroscopic term)",
                "radiation's terms",
                "the damping, or the term with the angular acceleration on the left-hand side",
                |x: &TopInput| TopInput { inertia: Vec3::repeat(x.inertia.x), ..*x },
            ),
        ],
        vec![named("the moment of inertia", |x: &TopInput| x.inertia.x)],
    )
    .labels(&OMEGA.map(|w| match w {
        "Ω₁" => "Ω̇₁",
        "Ω₂" => "Ω̇₂",
        _ => "Ω̇₃",
    }))
    .run(|x| student(x.inertia, x.dipole, x.omega))
}

/// Grade the rate of change of the kinetic energy under (3.3).
///
/// Paper: Eq. (3.3) (the energy balance it implies).
pub fn energy_rate(seed: u64, student: impl Fn(Vec3, Vec3, Vec3) -> Real) -> Grade {
    Grader::new(
        "energy_rate",
        "Eq. (3.3), the energy balance",
        seed,
        top_inputs(seed),
        |x: &TopInput| x.omega.dot(&x.inertia.component_mul(&top_rhs(x))),
        |a: &Real, b: &Real| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the moments of inertia are missing: the kinetic energy weighs each component of the rate by its moment",
            |x: &TopInput| x.omega.dot(&top_rhs(x)),
        ),
        mistake(
            "a missing term: only the first damping term is there; the term from the matrix on the left-hand side, with the angular acceleration inside, also does work",
            |x: &TopInput| -x.dipole.cross(&x.omega).norm_squared() * x.omega.norm_squared(),
        ),
        mistake(
            "the moment of inertia is applied twice: that is the rate of |L|^2/2, half the squared angular momentum L = I Omega, not of the kinetic energy",
            |x: &TopInput| {
                let l = x.inertia.component_mul(&x.omega);
                l.dot(&x.inertia.component_mul(&top_rhs(x)))
            },
        ),
        mistake(
            "half of the product rule: your value is half the right one; differentiating Omega . I Omega gives two equal terms, so the energy's factor 1/2 cancels (a factor 2 missing)",
            |x: &TopInput| 0.5 * x.omega.dot(&x.inertia.component_mul(&top_rhs(x))),
        ),
        mistake(
            "the angular acceleration used is not solved from (3.3): the term with it inside was left out",
            |x: &TopInput| {
                x.omega
                    .dot(&x.inertia.component_mul(&top_rhs_with(x, 1.0, 1.0, None)))
            },
        ),
        mistake(
            "the energy uses the squared rate with its moments, but Omega was dotted into the rate of Omega without them: dE/dt = Omega . (I dOmega/dt)",
            |x: &TopInput| x.omega.component_mul(&x.inertia).dot(&x.omega),
        ),
    ])
    .parts(
        vec![
            part(
                "with no dipole",
                "a free top, whose energy is constant",
                "a term that should vanish without radiation",
                |x: &TopInput| TopInput { dipole: Vec3::zeros(), ..*x },
            ),
        ],
        vec![],
    )
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

/// What is wrong with Euler angles that do not rebuild `m`.
fn euler_diagnosis(m: &Mat3, (phi, theta, psi): (Real, Real, Real)) -> &'static str {
    let pi = std::f64::consts::PI;
    let truth = EulerAngles::from_rotation(m);
    let sin_true = m[(0, 2)].hypot(m[(1, 2)]);
    let on_pole = sin_true == 0.0;
    let near_pole = truth.theta < 1e-4 || truth.theta > pi - 1e-4;
    let finite = phi.is_finite() && theta.is_finite() && psi.is_finite();
    if !finite && (on_pole || near_pole) {
        return "not finite on or near a pole: where theta is 0 or pi only one combination of phi and psi is defined; choose psi = 0 there, and test for the pole before dividing or taking atan2 of two zeros";
    }
    if !finite {
        return "not finite: a division or an inverse trigonometric function out of its range?";
    }
    let r = pi / 180.0;
    if (EulerAngles::new(phi * r, theta * r, psi * r).to_rotation() - m).norm() < 1e-9 {
        return "the angles are in degrees: a rotation is built from radians (Rust's atan2, acos and asin return radians)";
    }
    if !(0.0..=pi).contains(&theta) {
        return "theta is outside [0, pi]: the z-x-z convention keeps the nutation angle there";
    }
    let theta_off = (theta - truth.theta).abs() > 1e-13 * (1.0 + truth.theta);
    if theta_off && truth.theta > pi / 2.0 && (theta - sin_true.min(1.0).asin()).abs() <= 1e-12 {
        return "theta comes from an inverse sine, which never exceeds pi/2: the axis's tilt from z runs from 0 to pi, so it needs the cosine too (a two-argument arctangent)";
    }
    if theta_off && (theta - m[(2, 2)].clamp(-1.0, 1.0).acos()).abs() <= 1e-15 {
        return "theta comes from an inverse cosine of the (3,3) entry, which loses digits near theta = 0 and pi: a two-argument arctangent keeps them";
    }
    if theta_off {
        return "theta is wrong: the nutation angle comes from the third column and row (the axis's tilt from z)";
    }
    if psi == 0.0 && !on_pole && sin_true >= 1e-12 {
        return "you treated a rotation near (not on) a pole as on the pole: away from the poles psi is defined and must not be set to 0 (your pole test is too wide)";
    }
    if on_pole || sin_true < 1e-12 {
        return "on the pole, the angles you set do not rebuild the rotation: with psi = 0, all of the turn about z goes into phi (read it from the first column)";
    }
    let swapped = EulerAngles::new(psi, theta, phi).to_rotation();
    if (swapped - m).norm() < 1e-10 {
        return "phi and psi are swapped: phi comes from the third column, psi from the third row";
    }
    "the angles rebuild a different rotation: check which matrix entries give phi and psi in the z-x-z convention, and the signs inside each atan2"
}

/// The slip behind angles that rebuild another rotation, away from the
/// poles: the transpose read for the matrix, or one of phi and psi wrong
/// (the other two right) in a way an atan2 makes it: its two arguments
/// swapped, or one of them with the wrong sign.
fn euler_slip(m: &Mat3, (phi, theta, psi): (Real, Real, Real)) -> Option<String> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let truth = EulerAngles::from_rotation(m);
    if truth.theta < 1e-3 || truth.theta > PI - 1e-3 {
        return None;
    }
    let rebuilt = EulerAngles::new(phi, theta, psi).to_rotation();
    if (rebuilt - m.transpose()).norm() < 1e-9 {
        return Some("those are the angles of the transpose: rows and columns of the matrix swapped when reading it (the transpose is the inverse rotation)".into());
    }
    let same = |a: Real, b: Real| (a - b).sin().abs() < 1e-9 && (a - b).cos() > 0.0;
    if !same(theta, truth.theta) {
        return None;
    }
    let slips = [
        (
            FRAC_PI_2,
            -1.0,
            "the two arguments of its atan2 are swapped",
        ),
        (0.0, -1.0, "one argument of its atan2 has the wrong sign"),
        (PI, -1.0, "one argument of its atan2 has the wrong sign"),
        (PI, 1.0, "both arguments of its atan2 have the wrong sign"),
        (
            FRAC_PI_2,
            1.0,
            "the arguments of its atan2 are swapped, and one has the wrong sign",
        ),
        (
            -FRAC_PI_2,
            1.0,
            "the arguments of its atan2 are swapped, and one has the wrong sign",
        ),
        (
            -FRAC_PI_2,
            -1.0,
            "the arguments of its atan2 are swapped, and both have the wrong sign",
        ),
    ];
    for (name, theirs, right, other, other_right, others) in [
        ("phi", phi, truth.phi, psi, truth.psi, "theta and psi"),
        ("psi", psi, truth.psi, phi, truth.phi, "phi and theta"),
    ] {
        if !same(other, other_right) || same(theirs, right) {
            continue;
        }
        let how = slips
            .iter()
            .find(|(shift, sign, _)| same(theirs, shift + sign * right))
            .map_or("check which matrix entries give it", |(_, _, words)| words);
        return Some(format!(
            "{name} is wrong ({others} are right): {how} (check the signs inside each atan2)"
        ));
    }
    None
}

/// Grade Euler angles from a rotation matrix, z-x-z, pole included.
///
/// Paper: Eq. (3.5) (its angle convention).
pub fn euler_from_rotation(seed: u64, student: impl Fn(&Mat3) -> (Real, Real, Real)) -> Grade {
    let mut rng = Rng::new(seed);
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
    // The poles, and their neighbourhood on both sides of any sensible test.
    for theta in [
        0.0,
        pi,
        1e-13,
        1e-9,
        1e-7,
        1e-5,
        1e-3,
        pi - 1e-9,
        pi - 1e-7,
        pi - 1e-5,
    ] {
        let e = EulerAngles::new(rng.uniform(-pi, pi), theta, rng.uniform(-pi, pi));
        inputs.push(RotationInput(e.to_rotation()));
    }
    // The engine is used for its report only; the check is by rebuilding.
    let g: Grader<'_, RotationInput, Real> = Grader::new(
        "euler_from_rotation",
        "Eq. (3.5), z-x-z angles",
        seed,
        Vec::new(),
        |_| 0.0,
        |_, _| true,
    );
    for input in &inputs {
        let m = input.0;
        match call(|| student(&m)) {
            Ok((phi, theta, psi)) => {
                let finite = phi.is_finite() && theta.is_finite() && psi.is_finite();
                let rebuilt = EulerAngles::new(phi, theta, psi).to_rotation();
                let err = (rebuilt - m).norm();
                // NOTE: a NaN error (from non-finite angles) fails too.
                if !finite || !(0.0..=pi).contains(&theta) || err.is_nan() || err > 1e-12 {
                    // A slip is named only when a second rotation shows it too.
                    let slip = euler_slip(&m, (phi, theta, psi)).filter(|s| {
                        let other = inputs[inputs.len() / 2..]
                            .iter()
                            .map(|r| r.0)
                            .find(|o| *o != m)
                            .unwrap_or(m);

                        call(|| student(&other))
                            .ok()
                            .and_then(|a| euler_slip(&other, a))
                            .is_some_and(|t| t == *s)
                    });
                    return Err(g.fail(
                        format!("{input:?}"),
                        "finite angles, theta in [0, pi], rebuilding the matrix to 1e-12".into(),
                        format!("({phi}, {theta:e}, {psi}), rebuilding it to {err:.1e}"),
                        slip.unwrap_or_else(|| euler_diagnosis(&m, (phi, theta, psi)).into()),
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
