//! One grader per assignment, in course order. Each takes the grading's
//! `seed` (its random inputs come from it) and the student's function.
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
//! | [`precession_tilt`] | (4.11), corrected | the constant tilt θ, for either sign of Ω₃ |
//! | [`reduced_ale_rhs`] | (4.12)–(4.14) | Ω̇ of the reduced model |
//! | [`reduced_decay_time`] | (4.16) | σ |
//! | [`reduced_closed_form`] | (4.15)–(4.16) | Ω(t) for any Ω₀ |
//! | [`rk4_step`] | – | one classical RK4 step |
//! | [`dp5_step`] | – | one Dormand–Prince 5(4) step and its error estimate |
//! | [`reduced_rk4`] | (4.12)–(4.14) | a whole RK4 run: N classical steps, to rounding |
//! | [`shell_masses`] | (A.1) | m₀ and m_em |
//! | [`shell_acceleration`] | (A.1) | the method-of-steps update Z'' |
//! | [`characteristic_root`] | (A.1), Z ∝ e^{st} | the oscillation's root s |

use super::{Again, Answer, Grade, Grader, Passed, Rng, call, close, mistake, panic_diagnosis};
use super::{CASES, diagnosis};
use spintop::assignment::DynField;
use spintop::integrate::{dopri5::dopri5_step, rk4::rk4_step as reference_rk4_step};
use spintop::math::{Mat3, Real, State, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use spintop_runner::fields::Field;
use std::fmt;

const OMEGA: [&str; 3] = ["Ω₁", "Ω₂", "Ω₃"];

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

fn jets(seed: u64) -> Vec<JetInput> {
    let mut rng = Rng::new(seed);
    let mut out: Vec<JetInput> = (0..CASES)
        .map(|_| JetInput([rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0)]))
        .collect();
    // A precessing dipole, the Section 2 example, at a few times.
    let (theta, omega) = (rng.uniform(0.2, 2.9), rng.sign() * rng.uniform(0.3, 2.0));
    if let Ok(p) = balance::PrecessingDipole::new(theta, omega) {
        out.extend([0.0, rng.uniform(0.1, 1.0), rng.uniform(1.0, 5.0)].map(|t| JetInput(p.jet(t))));
    }
    out
}

const JET_NAMES: [&str; 4] = ["d", "d'", "d''", "d'''"];

/// Every cross product of two derivatives of the dipole, with either sign, as
/// a plausible wrong answer, except `right` (and the pairs `special` names):
/// "you crossed d' with d''': …".
fn crossings<'a>(
    right: (usize, usize, Real),
    special: &[((usize, usize, Real), &'static str)],
) -> Vec<super::Mistake<'a, JetInput, Vec3>> {
    let mut out = Vec::new();
    for &(pair, text) in special {
        let (i, j, s) = pair;
        out.push(mistake(text, move |x: &JetInput| s * x.0[i].cross(&x.0[j])));
    }
    for (i, a) in JET_NAMES.iter().enumerate() {
        for (j, b) in JET_NAMES.iter().enumerate() {
            if i == j || (i, j) == (right.0, right.1) || (j, i) == (right.0, right.1) {
                continue; // the right pair: a sign or the order, said by the shape
            }
            for s in [1.0, -1.0] {
                // A special pair has its own words; with the other sign (or
                // the factors the other way round) it is a wrong pair.
                let said = special.iter().any(|((p, q, t), _)| {
                    ((*p, *q) == (i, j) && *t == s) || ((*p, *q) == (j, i) && *t == -s)
                });
                if said {
                    continue;
                }
                let text = format!(
                    "you crossed {a} with {b}: the law involves another pair of the dipole's derivatives (count the derivatives)"
                );
                out.push(mistake(text, move |x: &JetInput| s * x.0[i].cross(&x.0[j])));
            }
        }
    }
    out
}

fn tight(a: &Vec3, b: &Vec3) -> bool {
    close(a, b, 1e-12)
}

/// Grade the Larmor-like loss rate.
///
/// Paper: Eq. (2.1).
pub fn larmor_rate(seed: u64, student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "larmor_rate",
        "Eq. (2.1)",
        seed,
        jets(seed),
        |j: &JetInput| balance::larmor_rate(&j.0),
        tight,
    )
    .mistakes(crossings(
        (1, 2, -1.0),
        &[
            (
                (0, 2, 1.0),
                "that is the Schott angular momentum L_S of (2.4), an angular momentum, not a rate of loss",
            ),
            (
                (0, 3, 1.0),
                "that is the torque law (2.2), not the Larmor-like law (2.1): the two differ by the Schott term",
            ),
        ],
    ))
    .labels(&["x", "y", "z"])
    .run(|j| student(&j.0))
}

/// Grade the Schott angular momentum.
///
/// Paper: Eq. (2.4).
pub fn schott_angular_momentum(seed: u64, student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "schott_angular_momentum",
        "Eq. (2.4)",
        seed,
        jets(seed),
        |j: &JetInput| balance::schott_angular_momentum(&j.0),
        tight,
    )
    .mistakes(crossings(
        (0, 2, 1.0),
        &[
            (
                (0, 1, 1.0),
                "one derivative short: you crossed d with its first derivative; L_S involves the second",
            ),
            (
                (0, 3, 1.0),
                "that is the torque law (2.2), a rate; L_S is the angular momentum whose rate is the difference of the two laws",
            ),
            (
                (1, 2, 1.0),
                "that is (minus) the Larmor-like rate (2.1), a rate of loss; L_S is an angular momentum",
            ),
        ],
    ))
    .labels(&["x", "y", "z"])
    .run(|j| student(&j.0))
}

/// Grade the Abraham–Lorentz torque.
///
/// Paper: Eq. (2.2).
pub fn torque_rate(seed: u64, student: impl Fn(&Jet) -> Vec3) -> Grade {
    let mut mistakes = vec![
        mistake(
            "that is the Larmor-like law (2.1): the Schott term (2.3) is missing",
            |j: &JetInput| balance::larmor_rate(&j.0),
        ),
        mistake(
            "that is dL_S/dt of (2.3), the difference of the two laws, not the torque",
            |j: &JetInput| balance::schott_rate(&j.0),
        ),
    ];
    mistakes.extend(crossings(
        (0, 3, 1.0),
        &[(
            (0, 2, 1.0),
            "that is L_S of (2.4), one derivative too few on the second factor",
        )],
    ));
    Grader::new(
        "torque_rate",
        "Eq. (2.2)",
        seed,
        jets(seed),
        |j: &JetInput| balance::torque_rate(&j.0),
        tight,
    )
    .mistakes(mistakes)
    .labels(&["x", "y", "z"])
    .run(|j| student(&j.0))
}

/// Grade the rate of the Schott angular momentum, the difference of the laws.
///
/// Paper: Eq. (2.3).
pub fn schott_rate(seed: u64, student: impl Fn(&Jet) -> Vec3) -> Grade {
    Grader::new(
        "schott_rate",
        "Eq. (2.3)",
        seed,
        jets(seed),
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
        mistake(
            "the two terms of the product rule have opposite signs in your answer: both come with +",
            |j: &JetInput| j.0[1].cross(&j.0[2]) - j.0[0].cross(&j.0[3]),
        ),
        mistake(
            "that is L_S of (2.4) itself, not its rate: differentiate it in time (product rule)",
            |j: &JetInput| j.0[0].cross(&j.0[2]),
        ),
        mistake(
            "the product rule applied with a derivative too many: differentiate each factor of L_S once",
            |j: &JetInput| j.0[1].cross(&j.0[3]) + j.0[0].cross(&j.0[3]),
        ),
        mistake(
            "a factor 2 on one term of the product rule: each factor is differentiated once, with weight 1",
            |j: &JetInput| 2.0 * j.0[1].cross(&j.0[2]) + j.0[0].cross(&j.0[3]),
        ),
        mistake(
            "a factor 2 on one term of the product rule: each factor is differentiated once, with weight 1",
            |j: &JetInput| j.0[1].cross(&j.0[2]) + 2.0 * j.0[0].cross(&j.0[3]),
        ),
    ])
    .labels(&["x", "y", "z"])
    .run(|j| student(&j.0))
}

/// Grade the axial projection n·dL_S/dt, n = d/|d|.
///
/// Paper: Eq. (2.3), Eq. (2.4).
pub fn axial_schott_rate(seed: u64, student: impl Fn(&Jet) -> Real) -> Grade {
    let rate = |j: &JetInput| j.0[0].dot(&balance::schott_rate(&j.0));
    Grader::new(
        "axial_schott_rate",
        "Eqs. (2.3)-(2.4)",
        seed,
        jets(seed),
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
        mistake(
            "that is the size of dL_S/dt, not its part along d: project it on the unit vector along d",
            |j: &JetInput| balance::schott_rate(&j.0).norm(),
        ),
        mistake(
            "projected on the wrong vector: the projection is along d itself, not along one of its derivatives",
            |j: &JetInput| balance::axial(&j.0[1], &balance::schott_rate(&j.0)),
        ),
        mistake(
            "projected on the wrong vector: the projection is along d itself, not along one of its derivatives",
            |j: &JetInput| balance::axial(&j.0[2], &balance::schott_rate(&j.0)),
        ),
        mistake(
            "your answer is zero: d x (anything), the torque term or L_S itself, has no part along d; the part of dL_S/dt along d comes from its other term",
            |_: &JetInput| 0.0,
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
pub fn precessing_dipole_jet(seed: u64, student: impl Fn(Real, Real, Real) -> Jet) -> Grade {
    let mut rng = Rng::new(seed);
    let mut inputs: Vec<ConeInput> = (0..CASES)
        .map(|_| ConeInput {
            theta: rng.uniform(0.05, 3.1),
            omega: rng.sign() * rng.uniform(0.2, 3.0),
            t: rng.uniform(0.0, 10.0),
        })
        .collect();
    // The start (t = 0) and a cone wider than a hemisphere, turning backwards.
    inputs.insert(
        0,
        ConeInput {
            theta: rng.uniform(0.3, 1.2),
            omega: rng.uniform(0.5, 2.0),
            t: 0.0,
        },
    );
    inputs.push(ConeInput {
        theta: rng.uniform(2.0, 3.0),
        omega: -rng.uniform(0.5, 2.0),
        t: rng.uniform(1.0, 5.0),
    });
    let reference = |x: &ConeInput| match balance::PrecessingDipole::new(x.theta, x.omega) {
        Ok(p) => p.jet(x.t),
        Err(_) => [Vec3::repeat(Real::NAN); 4],
    };
    Grader::new(
        "precessing_dipole_jet",
        "Section 2, the precessing dipole",
        seed,
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
            "d' has a factor omega too many: each time derivative brings exactly one factor omega (d' has one)",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[1] *= x.omega;
                j
            },
        ),
        mistake(
            "d'' has the wrong power of omega (one): each time derivative brings one factor omega, so d'' has two",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[2] /= x.omega;
                j
            },
        ),
        mistake(
            "d'' has the wrong power of omega (three): each time derivative brings one factor omega, so d'' has two",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[2] *= x.omega;
                j
            },
        ),
        mistake(
            "d''' has the wrong power of omega (two): each time derivative brings one factor omega, so d''' has three",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[3] /= x.omega;
                j
            },
        ),
        mistake(
            "d''' has the wrong power of omega (four): each time derivative brings one factor omega, so d''' has three",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[3] *= x.omega;
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
        mistake(
            "d' has the wrong sign: the derivative of cos is minus sin",
            move |x: &ConeInput| {
                let mut j = reference(x);
                j[1] = -j[1];
                j[3] = -j[3];
                j
            },
        ),
    ])
    .probe(move |x: &ConeInput, again: &Again<'_, ConeInput, Jet>| {
        // Where the dipole starts: in the x-z plane, at x = sin(theta).
        let at0 = ConeInput { t: 0.0, ..*x };
        let (theirs, right) = (again(&at0)?[0], reference(&at0)[0]);
        let same_cone = (theirs.z - right.z).abs() < 1e-12 && (theirs.norm() - 1.0).abs() < 1e-12;
        (same_cone && (theirs - right).norm() > 1e-9).then(|| {
            "the start is wrong: at t = 0 the dipole lies in the x-z plane (y = 0, x > 0); yours starts elsewhere on the cone (a sine where a cosine belongs?)".to_string()
        })
    })
    .variant(
        "the dipole turns the wrong way about z: a positive omega turns it counter-clockwise seen from +z (x toward y)",
        |x: &ConeInput| ConeInput { omega: -x.omega, ..*x },
    )
    .variant(
        "theta measured from the x-y plane: the cone's half-angle is measured from the z axis",
        |x: &ConeInput| ConeInput { theta: std::f64::consts::FRAC_PI_2 - x.theta, ..*x },
    )
    .variant(
        "the start is wrong: at t = 0 the dipole lies in the x-z plane (a quarter turn off?)",
        |x: &ConeInput| ConeInput { t: x.t + std::f64::consts::FRAC_PI_2 / x.omega, ..*x },
    )
    .variant(
        "the start is wrong: at t = 0 the dipole lies in the x-z plane (a quarter turn off?)",
        |x: &ConeInput| ConeInput { t: x.t - std::f64::consts::FRAC_PI_2 / x.omega, ..*x },
    )
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
            "the damping term that contains the angular acceleration itself is missing: it is on both sides, so the equation must be solved for it",
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
            "the damping's size is |d|^2 |Omega|^2: it is the square of d x Omega, which vanishes when the rotation is along the dipole",
            move |x: &TopInput| {
                // (3.3) with the damping's coefficient |d x Omega|^2 replaced.
                let damp = dw(x).norm_squared();
                let s = x.dipole.norm_squared() * x.omega.norm_squared() / damp;
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
            "only the first damping term: the term with the angular acceleration inside also does work",
            |x: &TopInput| -x.dipole.cross(&x.omega).norm_squared() * x.omega.norm_squared(),
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
                    return Err(g.fail(
                        format!("{input:?}"),
                        "finite angles, theta in [0, pi], rebuilding the matrix to 1e-12".into(),
                        format!("({phi}, {theta:e}, {psi}), rebuilding it to {err:.1e}"),
                        euler_diagnosis(&m, (phi, theta, psi)).into(),
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

/// Random tops, starts and times: prolate and oblate, either sign of the spin.
fn top_times(seed: u64, omega: Real, t_max: Real) -> Vec<TopTime> {
    let mut rng = Rng::new(seed);
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

/// "Right at t = 0 but drifting": the probe of the graders of Ω(t).
fn drift_probe<T: Answer>(
    reference: impl Fn(&TopTime) -> T,
) -> impl Fn(&TopTime, &Again<'_, TopTime, T>) -> Option<String> {
    move |x, again| {
        let at0 = TopTime { t: 0.0, ..*x };
        let theirs = again(&at0)?;
        close(&theirs, &reference(&at0), 1e-10).then(|| {
            "right at t = 0, but it drifts away from the right answer: a rate (of decay or of precession) is wrong".to_string()
        })
    }
}

/// How Ω⊥ turns and shrinks, for the graders of Ω(t): the student's answer
/// for two starts of the same size, (u, 0) and (0, u), is the image of the
/// start under a map that must be a rotation scaled by the decay. A mirror
/// image means a sign in one component; the right size at the wrong angle a
/// wrong precession; the right angle at the wrong size a wrong decay.
fn perp_probe(
    reference: impl Fn(&TopTime) -> Vec3,
) -> impl Fn(&TopTime, &Again<'_, TopTime, Vec3>) -> Option<String> {
    move |x, again| {
        let u = x.omega0.x.hypot(x.omega0.y);
        if u < 1e-3 || x.t == 0.0 {
            return None;
        }
        let a_in = TopTime {
            omega0: Vec3::new(u, 0.0, x.omega0.z),
            ..*x
        };
        let b_in = TopTime {
            omega0: Vec3::new(0.0, u, x.omega0.z),
            ..*x
        };
        let (a, b) = (again(&a_in)?, again(&b_in)?);
        let ra = reference(&a_in);
        // A scaled rotation maps (u, 0) and (0, u) to two perpendicular
        // vectors of one length, turned the same way.
        let (na, nb) = (a.x.hypot(a.y), b.x.hypot(b.y));
        let near = |p: Real, q: Real| (p - q).abs() <= 1e-8 * (p.abs() + q.abs()).max(1e-300);
        let rotation = near(na, nb)
            && (a.x * b.x + a.y * b.y).abs() <= 1e-8 * na * nb
            && a.x * b.y - a.y * b.x > 0.0;
        if !rotation && na + nb > 1e-12 * u {
            return Some(
                "Omega_1 and Omega_2 do not turn together as a rotation of the start: one of the two components has a sign wrong in one of its terms (or a sine where a cosine belongs)".into(),
            );
        }
        let (size, rsize) = (a.x.hypot(a.y), ra.x.hypot(ra.y));
        let turn = |p: Vec3| p.y.atan2(p.x);
        let same_turn = (turn(a) - turn(ra)).sin().abs() < 1e-8 && (turn(a) - turn(ra)).cos() > 0.0;
        let mirrored_turn =
            (turn(a) + turn(ra)).sin().abs() < 1e-8 && (turn(a) + turn(ra)).cos() > 0.0;
        if near(size, rsize) && !same_turn && mirrored_turn {
            return Some(
                "the precession turns the wrong way: in the body frame Omega_perp turns clockwise (seen from the tip of the symmetry axis) when the top is prolate and Omega_3 > 0, counter-clockwise when it is oblate: check the sign of the phase against the rate equations".into(),
            );
        }
        if near(size, rsize) && !same_turn {
            return Some(
                "Omega_perp has the right size but has turned by the wrong angle: the precession rate (which spin, which moment ratio) or the clock it runs on is wrong".into(),
            );
        }
        if same_turn && !near(size, rsize) {
            return Some(format!(
                "Omega_perp turns by the right angle but its size is {} times the right one: the decay factor is wrong",
                diagnosis::factor_words(size / rsize)
            ));
        }
        None
    }
}

/// Grade Ω⊥(t) of the truncated model.
///
/// Paper: Eq. (4.5), Eq. (4.6).
pub fn truncated_omega_perp(seed: u64, student: impl Fn(Real, Real, Real, Real) -> Real) -> Grade {
    let inputs: Vec<TopTime> = top_times(seed, 1.0, 40.0)
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
        seed,
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
            "an exponential decay: the loss of the truncated model grows with the cube of the rate, so the rate falls like a power of t, not exponentially",
            |x: &TopTime| x.omega0.x * (-2.0 * x.tau * x.omega0.x * x.omega0.x * x.t).exp(),
        ),
        mistake(
            "the square root is missing: separating the variables gives 1/Omega_perp^2, so the rate falls like 1/sqrt(t) at late times",
            |x: &TopTime| x.omega0.x / (1.0 + 2.0 * x.tau * x.omega0.x * x.omega0.x * x.t),
        ),
        mistake(
            "the start rate enters the slowing once, not squared: 1/Omega_perp^2 grows at a rate proportional to tau alone",
            |x: &TopTime| x.omega0.x / (1.0 + 2.0 * x.tau * x.omega0.x * x.t).sqrt(),
        ),
    ])
    .variant(
        "the right shape, the wrong speed: a factor 2 inside the square root is missing",
        |x: &TopTime| TopTime { tau: x.tau / 2.0, ..*x },
    )
    .variant(
        "the truncated model's slowing does not involve the moment ratio: Omega_perp's loss depends on tau and Omega_perp alone",
        |x: &TopTime| TopTime { tau: x.tau * x.ratio, ..*x },
    )
    .variant(
        "the truncated model's slowing does not involve the moment ratio: Omega_perp's loss depends on tau and Omega_perp alone",
        |x: &TopTime| TopTime { tau: x.tau / x.ratio, ..*x },
    )
    .variant(
        "the right shape, the wrong speed: the slowing runs twice too fast (a factor 2 too many inside the square root)",
        |x: &TopTime| TopTime { tau: 2.0 * x.tau, ..*x },
    )
    .probe(drift_probe(reference))
    .run(|x| student(x.ratio, x.tau, x.omega0.x, x.t))
}

/// Grade Ω(t) of the truncated model, for any start.
///
/// Paper: Eq. (4.7).
pub fn truncated_closed_form(seed: u64, student: impl Fn(Real, Real, Vec3, Real) -> Vec3) -> Grade {
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
        seed,
        top_times(seed, 1.0, 20.0),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the precession turns the wrong way: in the body frame Omega_perp turns clockwise (seen from the tip of the symmetry axis) when the top is prolate and Omega_3 > 0, counter-clockwise when it is oblate: check the sign of the phase against the rate equations",
            move |x: &TopTime| with_phase(x, -(1.0 - x.ratio) * x.omega0.z * vartheta(x)),
        ),
        mistake(
            "the phase runs on the ordinary clock t: as the rates fall the precession slows, so it runs on the slowed time of (4.9)",
            move |x: &TopTime| with_phase(x, (1.0 - x.ratio) * x.omega0.z * x.t),
        ),
        mistake(
            "the precession rate is the spin itself: in the body frame Omega_perp turns at the spin times (1 - the moment ratio)",
            move |x: &TopTime| with_phase(x, x.omega0.z * vartheta(x)),
        ),
        mistake(
            "the moment ratio is upside down in the precession rate: the ratio is I3/I1",
            move |x: &TopTime| with_phase(x, (1.0 - 1.0 / x.ratio) * x.omega0.z * vartheta(x)),
        ),
        mistake(
            "the slowing factor R is built from the whole |Omega0|^2: only the perpendicular rate Omega_perp0 enters it (a spin along the dipole radiates nothing)",
            |x: &TopTime| {
                let w = x.omega0.z;
                let r = (1.0 + 2.0 * x.tau * x.omega0.norm_squared() * x.t).sqrt();
                let alpha = (1.0 - x.ratio) * w * 2.0 * x.t / (1.0 + r);
                let (s, c) = alpha.sin_cos();
                Vec3::new(
                    (x.omega0.x * c + x.omega0.y * s) / r,
                    (x.omega0.y * c - x.omega0.x * s) / r,
                    w / r,
                )
            },
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
    .variant(
        "the start was taken with Omega_10 = 0, as the paper prints it: keep both components of Omega_perp0",
        |x: &TopTime| TopTime { omega0: Vec3::new(0.0, x.omega0.x.hypot(x.omega0.y), x.omega0.z), ..*x },
    )
    .variant(
        "every rate falls too slowly: a factor 2 is missing in the slowing factor R",
        |x: &TopTime| TopTime { tau: x.tau / 2.0, ..*x },
    )
    .probe(perp_probe(reference))
    .probe(drift_probe(reference))
    .labels(&OMEGA)
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
pub fn truncated_time_to_factor(
    seed: u64,
    student: impl Fn(Real, Real, Real, Real) -> Real,
) -> Grade {
    let mut rng = Rng::new(seed);
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
        seed,
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
            "the factor is upside down: the rates fall as 1/R, so R must reach 1/p, not p",
            move |x: &FactorInput| (1.0 - x.p * x.p) / rate(x),
        ),
        mistake(
            "R was not squared: R is a square root, so undo it before solving for t",
            move |x: &FactorInput| (1.0 / x.p - 1.0) / rate(x),
        ),
        mistake(
            "the start rate enters once, not squared, in the slowing factor",
            move |x: &FactorInput| (1.0 / (x.p * x.p) - 1.0) / (2.0 * x.tau * x.omega_perp0),
        ),
        mistake(
            "the truncated model's slowing does not involve the moment ratio: Omega_perp's loss depends on tau and Omega_perp alone",
            move |x: &FactorInput| (1.0 / (x.p * x.p) - 1.0) / (rate(x) * x.ratio),
        ),
        mistake(
            "the truncated model's slowing does not involve the moment ratio: Omega_perp's loss depends on tau and Omega_perp alone",
            move |x: &FactorInput| (1.0 / (x.p * x.p) - 1.0) * x.ratio / rate(x),
        ),
    ])
    .run(|x| student(x.ratio, x.tau, x.omega_perp0, x.p))
}

/// Grade the constant tilt between the symmetry axis and L.
///
/// Paper: Eq. (4.11) (corrected: erratum 4).
pub fn precession_tilt(seed: u64, student: impl Fn(Real, Vec3) -> Real) -> Grade {
    let mut rng = Rng::new(seed);
    let mut inputs: Vec<(Real, Vec3)> = (0..CASES)
        .map(|_| {
            let ratio = rng.uniform(0.1, 2.0);
            let w = rng.vec3(0.5);
            // Either sign of the spin: with Omega_3 < 0 the tilt passes pi/2.
            (ratio, Vec3::new(w.x, w.y, rng.sign() * (w.z.abs() + 0.05)))
        })
        .collect();
    // The book's top; the same spinning backwards; a spin that is zero
    // (tilt pi/2); no perpendicular rate with a negative spin (tilt pi).
    inputs.insert(0, (0.4, Vec3::new(0.0, 0.1, 0.2)));
    inputs.push((0.4, Vec3::new(0.0, 0.1, -0.2)));
    inputs.push((
        rng.uniform(0.2, 1.8),
        Vec3::new(rng.uniform(0.1, 0.5), rng.uniform(-0.5, 0.5), 0.0),
    ));
    inputs.push((
        rng.uniform(0.2, 1.8),
        Vec3::new(0.0, 0.0, -rng.uniform(0.1, 0.5)),
    ));
    let tilt = |(ratio, w): &(Real, Vec3)| match SymmetricTop::new(*ratio, 1.0) {
        Ok(top) => sym::precession_tilt(&top, w),
        Err(_) => Real::NAN,
    };
    Grader::new(
        "precession_tilt",
        "Eq. (4.11), corrected",
        seed,
        inputs,
        tilt,
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
        mistake(
            "wrong by pi when Omega_3 < 0: a one-argument arctangent cannot tell an axis along L from one against it, and the tilt runs from 0 to pi; use a two-argument arctangent",
            move |x: &(Real, Vec3)| tilt(x).tan().atan(),
        ),
        mistake(
            "wrong when Omega_3 < 0: the tilt is not symmetric in the sign of the spin (a spin against L tilts the axis past pi/2); an absolute value or a square lost the sign",
            move |(ratio, w): &(Real, Vec3)| tilt(&(*ratio, Vec3::new(w.x, w.y, w.z.abs()))),
        ),
        mistake(
            "that is the angle from the equator: the tilt is measured from the symmetry axis (pi/2 minus your angle)",
            move |x: &(Real, Vec3)| std::f64::consts::FRAC_PI_2 - tilt(x),
        ),
        mistake(
            "Omega_perp is the size of both perpendicular components: Omega_2 is left out",
            move |(ratio, w): &(Real, Vec3)| tilt(&(*ratio, Vec3::new(w.x, 0.0, w.z))),
        ),
        mistake(
            "Omega_perp is the size of both perpendicular components: Omega_1 is left out",
            move |(ratio, w): &(Real, Vec3)| tilt(&(*ratio, Vec3::new(0.0, w.y, w.z))),
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

fn sym_inputs(seed: u64) -> Vec<SymInput> {
    let mut rng = Rng::new(seed);
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

/// (4.12)–(4.14) with its pieces changed: the precession rate `wt3` and the
/// squared rate `k2` in the damping, from the input.
fn reduced_rhs_with(x: &SymInput, wt3: Real, k2: Real) -> Vec3 {
    let w = x.omega;
    let damp = x.tau * (w.x * w.x + w.y * w.y + k2);
    Vec3::new(wt3 * w.y - damp * w.x, -wt3 * w.x - damp * w.y, 0.0)
}

/// Grade the reduced model's right-hand side.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_ale_rhs(seed: u64, student: impl Fn(Real, Real, Vec3) -> Vec3) -> Grade {
    let reference = |x: &SymInput| match sym_top(x) {
        Some(top) => sym::reduced_ale_rhs(&top, &x.omega),
        None => Vec3::repeat(Real::NAN),
    };
    let wt3 = |x: &SymInput| (1.0 - x.ratio) * x.omega.z;
    let k2 = |x: &SymInput| (x.ratio * x.omega.z).powi(2);
    Grader::new(
        "reduced_ale_rhs",
        "Eqs. (4.12)-(4.14)",
        seed,
        sym_inputs(seed),
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
                w.z = -x.tau * (x.omega.x.powi(2) + x.omega.y.powi(2) + k2(x)) * x.omega.z;
                w
            },
        ),
        mistake(
            "the damping's Schott part uses the rate about the axis without its moment ratio: it is the axial angular momentum over I1 that enters",
            move |x: &SymInput| reduced_rhs_with(x, wt3(x), x.omega.z.powi(2)),
        ),
        mistake(
            "the damping's Schott part is missing: Omega_perp is damped by more than its own square in the reduced model",
            move |x: &SymInput| reduced_rhs_with(x, wt3(x), 0.0),
        ),
        mistake(
            "the damping rate lacks Omega_perp's own square: Omega_perp is damped by its own square and the axial part together",
            move |x: &SymInput| {
                let w = x.omega;
                let damp = x.tau * k2(x);
                Vec3::new(wt3(x) * w.y - damp * w.x, -wt3(x) * w.x - damp * w.y, 0.0)
            },
        ),
        mistake(
            "the free precession turns the wrong way: check the signs of the two precession terms against (4.12)-(4.13)",
            move |x: &SymInput| reduced_rhs_with(x, -wt3(x), k2(x)),
        ),
        mistake(
            "the precession rate is the spin itself: in the body frame Omega_perp turns at the spin times (1 - the moment ratio)",
            move |x: &SymInput| reduced_rhs_with(x, x.omega.z, k2(x)),
        ),
        mistake(
            "the moment ratio is upside down in the precession rate: the ratio is I3/I1",
            move |x: &SymInput| reduced_rhs_with(x, (1.0 - 1.0 / x.ratio) * x.omega.z, k2(x)),
        ),
        mistake(
            "the moment ratio enters the damping once, not squared: it is the square of the axial angular momentum over I1",
            move |x: &SymInput| reduced_rhs_with(x, wt3(x), x.ratio * x.omega.z.powi(2)),
        ),
        mistake(
            "the damping has the wrong sign: radiation slows Omega_perp",
            move |x: &SymInput| {
                let mut w = reduced_rhs_with(x, wt3(x), k2(x));
                let undamped = reduced_rhs_with(&SymInput { tau: 0.0, ..*x }, wt3(x), k2(x));
                w = undamped - (w - undamped);
                w
            },
        ),
    ])
    .variant(
        "the damping is twice too strong: a factor 2 on tau",
        |x: &SymInput| SymInput { tau: 2.0 * x.tau, ..*x },
    )
    .variant(
        "the damping is half as strong as it should be: a factor 2 missing on tau",
        |x: &SymInput| SymInput { tau: x.tau / 2.0, ..*x },
    )
    .labels(&["Ω̇₁", "Ω̇₂", "Ω̇₃"])
    .run(|x| student(x.ratio, x.tau, x.omega))
}

/// Grade σ, the late-time decay time of Ω⊥ in the reduced model.
///
/// Paper: Eq. (4.16).
pub fn reduced_decay_time(seed: u64, student: impl Fn(Real, Real, Real) -> Real) -> Grade {
    let mut rng = Rng::new(seed ^ 0x5157);
    let inputs: Vec<SymInput> = sym_inputs(seed)
        .into_iter()
        .map(|x| SymInput {
            // Either sign of the spin: sigma depends on its square.
            omega: Vec3::new(0.0, 0.0, rng.sign() * (x.omega.z.abs() + 0.05)),
            ..x
        })
        .collect();
    Grader::new(
        "reduced_decay_time",
        "Eq. (4.16), sigma",
        seed,
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
        mistake(
            "the moment ratio is missing: it is the axial angular momentum over I1, I3/I1 times the spin, that sets the decay",
            |x: &SymInput| 1.0 / (x.omega.z * x.omega.z * x.tau),
        ),
        mistake(
            "that is a rate, not a time: sigma is the inverse of the decay rate",
            |x: &SymInput| (x.ratio * x.omega.z).powi(2) * x.tau,
        ),
        mistake(
            "the spin enters once, not squared: the decay rate is tau times the square of the axial angular momentum over I1",
            |x: &SymInput| 1.0 / (x.ratio * x.ratio * x.omega.z * x.tau),
        ),
    ])
    .run(|x| student(x.ratio, x.tau, x.omega.z))
}

/// Grade the reduced model's closed form, with Ω₁₀ ≠ 0.
///
/// Paper: Eq. (4.15), Eq. (4.16).
pub fn reduced_closed_form(seed: u64, student: impl Fn(Real, Real, Vec3, Real) -> Vec3) -> Grade {
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
        seed,
        top_times(seed, 0.5, 40.0),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "the amplitude decays at half the rate: the exponent in Phi carries a factor 2",
            move |x: &TopTime| variant(x, 0.5, 1.0),
        ),
        mistake(
            "the precession turns the wrong way: in the body frame Omega_perp turns clockwise (seen from the tip of the symmetry axis) when the top is prolate and Omega_3 > 0, counter-clockwise when it is oblate: check the sign of the phase against (4.12)-(4.13)",
            move |x: &TopTime| variant(x, 1.0, -1.0),
        ),
        mistake(
            "Omega_perp decays twice too fast at late times: the exponential in Phi falls at half the rate of its exponent's argument s (it is Omega_perp squared that falls at the rate s)",
            move |x: &TopTime| {
                let late = variant(x, 1.0, 1.0);
                let k = x.ratio * x.omega0.z;
                let s = 2.0 * x.tau * k * k * x.t;
                Vec3::new(late.x * (-0.5 * s).exp(), late.y * (-0.5 * s).exp(), late.z)
            },
        ),
        mistake(
            "the square root in Phi is the truncated model's: in the reduced model its growth slows as the exponential decays, it does not grow linearly in t",
            move |x: &TopTime| {
                let u0 = x.omega0.x * x.omega0.x + x.omega0.y * x.omega0.y;
                let k = x.ratio * x.omega0.z;
                let s = 2.0 * x.tau * k * k * x.t;
                let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
                let fix = ((1.0 + 2.0 * x.tau * u0 * x.t * g) / (1.0 + 2.0 * x.tau * u0 * x.t)).sqrt();
                let w = variant(x, 1.0, 1.0);
                Vec3::new(w.x * fix, w.y * fix, w.z)
            },
        ),
        mistake(
            "the spin decays: in the reduced model Omega_3 is constant",
            move |x: &TopTime| {
                let mut w = reference(x);
                let r = (1.0 + 2.0 * x.tau * (x.omega0.x.powi(2) + x.omega0.y.powi(2)) * x.t).sqrt();
                w.z = x.omega0.z / r;
                w
            },
        ),
        mistake(
            "that is the truncated model's Omega(t) (4.7): the reduced model keeps the spin and damps Omega_perp exponentially at late times",
            move |x: &TopTime| match top_of(x) {
                Some(top) => sym::truncated_closed_form(&top, &x.omega0, x.t),
                None => Vec3::repeat(Real::NAN),
            },
        ),
    ])
    .variant(
        "the start was taken with Omega_10 = 0, as the paper prints it: keep both components of Omega_perp0",
        |x: &TopTime| TopTime { omega0: Vec3::new(0.0, x.omega0.x.hypot(x.omega0.y), x.omega0.z), ..*x },
    )
    .variant(
        "the moment ratio is upside down: the ratio is I3/I1, in the precession rate and in sigma",
        |x: &TopTime| TopTime { ratio: 1.0 / x.ratio, ..*x },
    )
    .probe(perp_probe(reference))
    .probe(drift_probe(reference))
    .labels(&OMEGA)
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t))
}

// ---------------------------------------------------------------- numerical methods

/// The test problems of the step graders: named fields of
/// [`spintop_runner::fields`], which a student's runner builds on its side
/// (a function cannot cross the pipe, and no field is an assignment's answer).
fn fields() -> [Field; 2] {
    Field::TESTS
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
            fields()[self.field].describe(),
            self.t,
            self.y.as_slice(),
            self.h
        )
    }
}

fn step_inputs(seed: u64) -> Vec<StepInput> {
    let mut rng = Rng::new(seed);
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

/// An RK4 step with one thing changed: `weights` of the four slopes (over
/// 6), the time of each stage after the first as a fraction of h (`c`), and
/// for each stage after the first, which slope it steps from and how far
/// (`from`, as (stage, fraction of h)).
#[derive(Clone, Copy)]
struct Rk4Shape {
    weights: [Real; 4],
    c: [Real; 3],
    from: [(usize, Real); 3],
}

const RK4: Rk4Shape = Rk4Shape {
    weights: [1.0, 2.0, 2.0, 1.0],
    c: [0.5, 0.5, 1.0],
    from: [(0, 0.5), (1, 0.5), (2, 1.0)],
};

fn rk4_shaped(
    shape: Rk4Shape,
    f: &dyn Fn(Real, &State<3>) -> State<3>,
    t: Real,
    y: &State<3>,
    h: Real,
) -> State<3> {
    let mut k = [State::<3>::zeros(); 4];
    k[0] = f(t, y);
    for s in 1..4 {
        let (j, a) = shape.from[s - 1];
        k[s] = f(t + shape.c[s - 1] * h, &(y + k[j] * (a * h)));
    }
    y + (k[0] * shape.weights[0]
        + k[1] * shape.weights[1]
        + k[2] * shape.weights[2]
        + k[3] * shape.weights[3])
        * (h / 6.0)
}

/// The plausible slips in an RK4 step, each with what it says.
fn rk4_slips() -> Vec<(Rk4Shape, &'static str)> {
    vec![
        (
            Rk4Shape {
                weights: [1.0, 1.0, 2.0, 2.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones: the two middle stages count twice, the ends once",
        ),
        (
            Rk4Shape {
                weights: [2.0, 1.0, 1.0, 2.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones: the two middle stages count twice, the ends once",
        ),
        (
            Rk4Shape {
                weights: [1.0, 1.0, 1.0, 1.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones (they must add up to 6 with the middle ones doubled)",
        ),
        (
            Rk4Shape {
                c: [0.5, 0.5, 0.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the fourth stage evaluates f at the start time, not at the end of the step",
        ),
        (
            Rk4Shape {
                c: [0.0, 0.0, 0.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the stages evaluate f at the start time, not at the midpoint and the end",
        ),
        (
            Rk4Shape {
                c: [1.0, 1.0, 1.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the middle stages evaluate f at the end of the step, not at the midpoint",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (0, 0.5), (2, 1.0)],
                ..RK4
            },
            "the third stage steps from the wrong slope: it must step from the second slope, and yours steps from the first",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (1, 1.0)],
                ..RK4
            },
            "the fourth stage steps from the wrong slope: it must step from the third slope, and yours steps from the second",
        ),
        (
            Rk4Shape {
                from: [(0, 1.0), (1, 0.5), (2, 1.0)],
                ..RK4
            },
            "the second stage steps too far: the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 1.0), (2, 1.0)],
                ..RK4
            },
            "the third stage steps too far: the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (2, 0.5)],
                ..RK4
            },
            "the fourth stage steps only half a step: it goes the whole step, to the end",
        ),
    ]
}

/// Grade one classical RK4 step.
pub fn rk4_step(seed: u64, student: impl Fn(DynField, Real, &State<3>, Real) -> State<3>) -> Grade {
    rk4_step_on(seed, |f: &Field, t, y: &State<3>, h| {
        student(&|t: Real, y: &State<3>| f.eval(t, y), t, y, h)
    })
}

/// [`rk4_step`], with the right-hand side given by name: how a runner in
/// another process is graded (it builds the named field on its side).
pub fn rk4_step_on(
    seed: u64,
    student: impl Fn(&Field, Real, &State<3>, Real) -> State<3>,
) -> Grade {
    let f = |x: &StepInput| {
        let field = fields()[x.field];
        move |t: Real, y: &State<3>| field.eval(t, y)
    };
    let mut mistakes: Vec<_> = rk4_slips()
        .into_iter()
        .map(|(shape, text)| {
            mistake(text, move |x: &StepInput| {
                rk4_shaped(shape, &f(x), x.t, &x.y, x.h)
            })
        })
        .collect();
    mistakes.extend([
        mistake(
            "your step returns the increment alone: the new state is the old one plus it",
            move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h) - x.y,
        ),
        mistake(
            "that is one step of Euler's method: only the first stage is used",
            move |x: &StepInput| x.y + f(x)(x.t, &x.y) * x.h,
        ),
        mistake(
            "the slopes were not multiplied by the step size h",
            move |x: &StepInput| x.y + (reference_rk4_step(&f(x), x.t, &x.y, x.h) - x.y) / x.h,
        ),
    ]);
    Grader::new(
        "rk4_step",
        "classical RK4, Hairer-Norsett-Wanner I, Table II.1.2",
        seed,
        step_inputs(seed),
        move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h),
        |a: &State<3>, b: &State<3>| close(a, b, 1e-13),
    )
    .mistakes(mistakes)
    .probe(rk4_weights_probe)
    .probe(step_order_probe(
        "classical RK4",
        move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h),
        |y: &State<3>| *y,
    ))
    .labels(&["y₁", "y₂", "y₃"])
    .run(|x| student(&fields()[x.field], x.t, &x.y, x.h))
}

/// The inputs a step probe tries beside `x`: the same field, nearby starts.
fn nearby_steps(x: &StepInput) -> [StepInput; 3] {
    [
        *x,
        StepInput {
            t: x.t + 0.37,
            y: x.y * 0.8 + State::<3>::repeat(0.1),
            ..*x
        },
        StepInput {
            t: x.t - 0.21,
            y: x.y.map(|v| -v) + State::<3>::new(0.2, -0.1, 0.05),
            ..*x
        },
    ]
}

/// The weights the student's RK4 step gives its four stages, fitted on
/// three inputs: when the stages are the classical ones and only their
/// weights differ, it says so (and what the weights look like).
fn rk4_weights_probe(x: &StepInput, again: &Again<'_, StepInput, State<3>>) -> Option<String> {
    let mut rows = Vec::new();
    let mut rhs = Vec::new();
    for s in nearby_steps(x) {
        let theirs = again(&s)?;
        let field = fields()[s.field];
        let f = |t: Real, y: &State<3>| field.eval(t, y);
        let k1 = f(s.t, &s.y);
        let k2 = f(s.t + s.h / 2.0, &(s.y + k1 * (s.h / 2.0)));
        let k3 = f(s.t + s.h / 2.0, &(s.y + k2 * (s.h / 2.0)));
        let k4 = f(s.t + s.h, &(s.y + k3 * s.h));
        for c in 0..3 {
            rows.extend([k1[c], k2[c], k3[c], k4[c]].map(|k| k * s.h));
            rhs.push(theirs[c] - s.y[c]);
        }
    }
    let a = nalgebra::DMatrix::from_row_slice(rhs.len(), 4, &rows);
    let b = nalgebra::DVector::from_vec(rhs);
    let w = a.clone().svd(true, true).solve(&b, 1e-14).ok()?;
    let fits = (&a * &w - &b).norm() <= 1e-10 * (1.0 + b.norm());
    let classical = nalgebra::DVector::from_vec(vec![1.0, 2.0, 2.0, 1.0]) / 6.0;
    (fits && (&w - classical).norm() > 1e-8).then(|| {
        let w6: Vec<String> = w.iter().map(|v| format!("{:.3}", 6.0 * v)).collect();
        format!(
            "your four stages are right, but you combine them with other weights: about ({}) over 6; the classical step counts the middle two twice and the ends once",
            w6.join(", ")
        )
    })
}

/// How the student's step approaches the right one as h shrinks: a step
/// that gets closer like a power of h is a consistent method with a
/// coefficient or a node wrong; `part` picks the state out of an answer.
fn step_order_probe<'a, T: 'a>(
    method: &'static str,
    reference: impl Fn(&StepInput) -> T + 'a,
    part: impl Fn(&T) -> State<3> + 'a,
) -> impl Fn(&StepInput, &Again<'_, StepInput, T>) -> Option<String> + 'a {
    move |x, again| {
        let dev = |h: Real| -> Option<Real> {
            let s = StepInput { h, ..*x };
            Some((part(&again(&s)?) - part(&reference(&s))).norm())
        };
        let (d1, d2, d3) = (dev(x.h)?, dev(x.h / 2.0)?, dev(x.h / 4.0)?);
        if !(d1 > 0.0 && d2 > 0.0 && d3 > 0.0) {
            return None;
        }
        let p = (d2 / d3).log2();
        (p >= 1.5 && (d1 / d2).log2() >= 1.0).then(|| {
            format!(
                "your step is not {method}, but close to it, and closer as h shrinks (the difference falls like h^{p:.1}): a coefficient, a weight or the time of a stage is wrong; check each against the method's table"
            )
        })
    }
}

/// Grade one Dormand–Prince 5(4) step: (y₅, y₅ − ŷ₄).
pub fn dp5_step(
    seed: u64,
    student: impl Fn(DynField, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    dp5_step_on(seed, |f: &Field, t, y: &State<3>, h| {
        student(&|t: Real, y: &State<3>| f.eval(t, y), t, y, h)
    })
}

/// [`dp5_step`], with the right-hand side given by name (see [`rk4_step_on`]).
pub fn dp5_step_on(
    seed: u64,
    student: impl Fn(&Field, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    let f = |x: &StepInput| {
        let field = fields()[x.field];
        move |t: Real, y: &State<3>| field.eval(t, y)
    };
    let reference = move |x: &StepInput| dopri5_step(&f(x), x.t, &x.y, x.h);
    Grader::new(
        "dp5_step",
        "Dormand-Prince 5(4), Hairer-Norsett-Wanner I, Table II.5.2",
        seed,
        step_inputs(seed),
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
        mistake(
            "the error estimate is the whole new state, not the difference of the two solutions",
            move |x: &StepInput| {
                let (y5, _) = reference(x);
                (y5, y5)
            },
        ),
        mistake(
            "the error estimate is the difference of the two increments divided by h: both solutions already carry the factor h",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5, e / x.h)
            },
        ),
        mistake(
            "your step returns the increment alone: the new state is the old one plus it",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5 - x.y, e)
            },
        ),
    ])
    .probe(move |x: &StepInput, again: &Again<'_, StepInput, (State<3>, State<3>)>| {
        // The step right, the estimate not: the fourth-order solution. (An
        // estimate right but for signs is left to the shape, which names them.)
        let (theirs, right) = (again(x)?, reference(x));
        let signs_only = theirs
            .1
            .iter()
            .zip(right.1.iter())
            .all(|(a, b)| (a.abs() - b.abs()).abs() <= 1e-9 * (1e-300 + b.abs()));
        (close(&theirs.0, &right.0, 1e-13) && !signs_only).then(|| {
            "the step is right, the error estimate is not: it is the fifth-order result minus the embedded fourth-order one, which has weights of its own and uses a seventh stage, f at the end of the step from the fifth-order result".to_string()
        })
    })
    .probe(step_order_probe("Dormand-Prince 5(4)", reference, |a: &(State<3>, State<3>)| a.0))
    .labels(&[
        "the step's y₁",
        "the step's y₂",
        "the step's y₃",
        "the estimate's y₁",
        "the estimate's y₂",
        "the estimate's y₃",
    ])
    .run(|x| student(&fields()[x.field], x.t, &x.y, x.h))
}

/// A start, an end and a number of steps for [`reduced_rk4`].
#[derive(Clone, Copy)]
struct RunInput {
    ratio: Real,
    tau: Real,
    omega0: Vec3,
    t_end: Real,
    steps: usize,
}

impl fmt::Debug for RunInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega0 = {:?}, t_end = {}, steps = {}",
            self.ratio,
            self.tau,
            self.omega0.as_slice(),
            self.t_end,
            self.steps
        )
    }
}

/// `steps` RK4 steps (of the given shape) of size `h` on the right-hand side
/// `rhs` of the reduced model.
fn run_with(
    x: &RunInput,
    shape: Rk4Shape,
    rhs: fn(&SymmetricTop, &Vec3) -> Vec3,
    steps: usize,
    h: Real,
) -> Vec3 {
    let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
        return Vec3::repeat(Real::NAN);
    };
    let f = |_t: Real, y: &State<3>| rhs(&top, y);
    (0..steps).fold(x.omega0, |y, i| rk4_shaped(shape, &f, i as Real * h, &y, h))
}

/// The reference: `steps` classical RK4 steps of size t_end/steps.
fn reference_run(x: &RunInput) -> Vec3 {
    let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
        return Vec3::repeat(Real::NAN);
    };
    let h = x.t_end / x.steps as Real;
    let f = |_t: Real, y: &State<3>| sym::reduced_ale_rhs(&top, y);
    (0..x.steps).fold(x.omega0, |y, i| {
        reference_rk4_step(&f, i as Real * h, &y, h)
    })
}

/// The order at which the student's run converges, from three step counts.
fn observed_order(x: &RunInput, again: &Again<'_, RunInput, Vec3>) -> Option<(Real, Real)> {
    let top = SymmetricTop::new(x.ratio, x.tau).ok()?;
    let exact = sym::reduced_closed_form(&top, &x.omega0, x.t_end);
    let n = 40;
    let err = |steps: usize| again(&RunInput { steps, ..*x }).map(|w| (w - exact).norm());
    let (e2, e3) = (err(2 * n)?, err(4 * n)?);
    Some(((e2 / e3).log2(), e3 / (1.0 + exact.norm())))
}

/// Grade a whole RK4 run of the reduced model: `steps` equal classical RK4
/// steps from 0 to `t_end` must give the same Ω(t_end) as spintop's, to
/// rounding; a wrong run is told apart by its step count, its end time, its
/// stages, its model or its order of convergence.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_rk4(seed: u64, student: impl Fn(Real, Real, Vec3, Real, usize) -> Vec3) -> Grade {
    let mut rng = Rng::new(seed);
    let inputs: Vec<RunInput> = (0..20)
        .map(|_| {
            let mut pick = || rng.sign() * rng.uniform(0.5, 1.5);
            let omega0 = Vec3::new(pick(), pick(), pick());
            RunInput {
                ratio: rng.uniform(0.2, 0.8),
                tau: rng.uniform(0.1, 0.5),
                omega0,
                t_end: rng.uniform(2.0, 4.0),
                steps: 20 + (rng.next_u64() % 181) as usize,
            }
        })
        .collect();
    let mut mistakes: Vec<_> = rk4_slips()
        .into_iter()
        .filter(|(s, _)| s.from != RK4.from || s.weights != RK4.weights)
        .map(|(shape, text)| {
            let text = format!("your RK4 step is wrong: {text}");
            mistake(text, move |x: &RunInput| {
                run_with(
                    x,
                    shape,
                    sym::reduced_ale_rhs,
                    x.steps,
                    x.t_end / x.steps as Real,
                )
            })
        })
        .collect();
    mistakes.extend([
        mistake(
            "you integrated the truncated model (4.2)-(4.4), not the reduced one (4.12)-(4.14)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::truncated_ale_rhs, x.steps, x.t_end / x.steps as Real),
        ),
        mistake(
            "one step too many: your run takes steps + 1 steps of size t_end/steps and ends past t_end (count the loop's steps)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps + 1, x.t_end / x.steps as Real),
        ),
        mistake(
            "one step too few: your run takes steps - 1 steps of size t_end/steps and stops short of t_end (count the loop's steps)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps - 1, x.t_end / x.steps as Real),
        ),
        mistake(
            "the step size is t_end/(steps + 1): with `steps` steps the run stops short of t_end".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end / (x.steps + 1) as Real),
        ),
        mistake(
            "the step size is t_end/(steps - 1): with `steps` steps the run ends past t_end".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end / (x.steps - 1) as Real),
        ),
        mistake(
            "your run returns the start: no step was taken (is the loop empty, or is the state never updated?)".to_string(),
            |x: &RunInput| x.omega0,
        ),
        mistake(
            "that is the exact Ω(t_end) of the closed form (4.15)-(4.16), not `steps` RK4 steps: the assignment asks for the numerical run, whose error the book measures against the closed form".to_string(),
            |x: &RunInput| match SymmetricTop::new(x.ratio, x.tau) {
                Ok(top) => sym::reduced_closed_form(&top, &x.omega0, x.t_end),
                Err(_) => Vec3::repeat(Real::NAN),
            },
        ),
        mistake(
            "the run ends at the wrong time: each step is t_end long (h = t_end/steps was not divided)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end),
        ),
        mistake(
            "that is Euler's method, not RK4: only the first slope of each step is used".to_string(),
            |x: &RunInput| {
                let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
                    return Vec3::repeat(Real::NAN);
                };
                let h = x.t_end / x.steps as Real;
                (0..x.steps).fold(x.omega0, |y, _| y + sym::reduced_ale_rhs(&top, &y) * h)
            },
        ),
    ]);
    // The end: a run that does not move with t_end, or that stops (or goes
    // on) after another number of the right steps.
    let end_probe = |x: &RunInput, again: &Again<'_, RunInput, Vec3>| {
        let theirs = again(x)?;
        let later = again(&RunInput {
            t_end: 1.37 * x.t_end,
            ..*x
        })?;
        if close(&theirs, &later, 1e-11) {
            return Some(
                "your answer does not change with t_end: the run must end at t_end, so the step size is t_end over the number of steps".to_string(),
            );
        }
        let top = SymmetricTop::new(x.ratio, x.tau).ok()?;
        let h = x.t_end / x.steps as Real;
        let f = |_t: Real, y: &State<3>| sym::reduced_ale_rhs(&top, y);
        let mut y = x.omega0;
        for k in 1..=3 * x.steps {
            y = reference_rk4_step(&f, (k - 1) as Real * h, &y, h);
            if k != x.steps && close(&theirs, &y, 1e-11) {
                return Some(format!(
                    "your run takes {k} steps of size t_end/steps, not steps = {}: it ends at t = {}, not at t_end = {} (count the loop's steps)",
                    x.steps,
                    spintop::numbers::fmt_time(k as Real * h),
                    spintop::numbers::fmt_time(x.t_end)
                ));
            }
        }
        None
    };
    let order_probe = |x: &RunInput, again: &Again<'_, RunInput, Vec3>| {
        let (order, finest) = observed_order(x, again)?;
        Some(if !order.is_finite() {
            "your answer does not change with the number of steps: it is not a run of `steps` RK4 steps".to_string()
        } else if (3.5..=4.6).contains(&order) && finest > 1e-7 {
            "your run converges at order 4, but to a wrong answer: the right-hand side it integrates is not (4.12)-(4.14), or the start or the end is wrong".to_string()
        } else if order.abs() < 0.3 {
            "the error does not shrink as the steps get smaller: the run converges to a wrong answer (the step size, the number of steps, or the right-hand side)".to_string()
        } else if order < 3.5 {
            format!(
                "your run converges at order {order:.2}, not 4: it is not the classical RK4 (a stage of your step, or a lower-order method)"
            )
        } else {
            format!(
                "your run's error falls at order {order:.2} but it is not N classical RK4 steps: did you take more steps than asked, or a method other than RK4?"
            )
        })
    };
    Grader::new(
        "reduced_rk4",
        "Eqs. (4.12)-(4.14), integrated by RK4",
        seed,
        inputs,
        reference_run,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-11),
    )
    .mistakes(mistakes)
    .probe(end_probe)
    .probe(order_probe)
    .labels(&OMEGA)
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t_end, x.steps))
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

fn shell_inputs(seed: u64, delta_max: Real) -> Vec<ShellInput> {
    let mut rng = Rng::new(seed);
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
pub fn shell_masses(seed: u64, student: impl Fn(Real, Real) -> (Real, Real)) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => (m.m0(), m.m_em()),
        Err(_) => (Real::NAN, Real::NAN),
    };
    Grader::new(
        "shell_masses",
        "Eq. (A.1), the masses",
        seed,
        shell_inputs(seed, 1.0),
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
        mistake(
            "the bare mass is not the rest of the whole mass: the two add up to m = 1",
            |x: &ShellInput| (1.0, x.tau0 / x.delta),
        ),
        mistake(
            "the bare mass is not the rest of the whole mass: the two add up to m = 1",
            |x: &ShellInput| (1.0 + x.tau0 / x.delta, x.tau0 / x.delta),
        ),
    ])
    .labels(&["m₀", "m_em"])
    .run(|x| student(x.tau0, x.delta))
}

/// Grade the method-of-steps update of the shell model: Z''(t) from Z(t) and
/// the retarded Z''(t − δ).
///
/// Paper: Eq. (A.1).
pub fn shell_acceleration(seed: u64, student: impl Fn(Real, Real, C, C) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.acceleration(x.z, x.z_ddot_ret),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    let masses = |x: &ShellInput| {
        let m_em = x.tau0 / x.delta;
        (1.0 - m_em, m_em)
    };
    Grader::new(
        "shell_acceleration",
        "Eq. (A.1)",
        seed,
        shell_inputs(seed, 1.0),
        reference,
        |a: &C, b: &C| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "the retarded term has the wrong sign: move it to the other side of the equation with care",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (-x.z + x.z_ddot_ret * m_em) / m0
            },
        ),
        mistake(
            "divided by the whole mass: the acceleration now is multiplied by the bare mass only, the rest acts one delay later",
            move |x: &ShellInput| -x.z - x.z_ddot_ret * masses(x).1,
        ),
        mistake(
            "the two masses are swapped: the bare mass multiplies the acceleration now, the field's mass the retarded one",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (-x.z - x.z_ddot_ret * m0) / m_em
            },
        ),
        mistake(
            "the restoring force has the wrong sign: the spring pulls Z back toward 0",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (x.z - x.z_ddot_ret * m_em) / m0
            },
        ),
        mistake(
            "the retarded acceleration is missing: the field's mass acts with the acceleration one delay earlier",
            move |x: &ShellInput| -x.z / masses(x).0,
        ),
        mistake(
            "divided by the field's mass: the acceleration now is multiplied by the bare mass m0, so solve for it by dividing by m0",
            move |x: &ShellInput| {
                let (_, m_em) = masses(x);
                (-x.z - x.z_ddot_ret * m_em) / m_em
            },
        ),
        mistake(
            "the retarded term is not divided by the bare mass: solving for Z''(t) divides everything on the other side by m0",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                -x.z / m0 - x.z_ddot_ret * m_em
            },
        ),
    ])
    .run(|x| student(x.tau0, x.delta, x.z, x.z_ddot_ret))
}

/// Newton's method on `p` (with derivative `dp`) from `start`, `steps` at
/// most; every iterate.
fn newton_iterates(p: impl Fn(C) -> C, dp: impl Fn(C) -> C, start: C, steps: usize) -> Vec<C> {
    let mut s = start;
    let mut out = vec![s];
    for _ in 0..steps {
        let step = p(s) / dp(s);
        s -= step;
        out.push(s);
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    out
}

/// The characteristic function of (A.1) with the delay factor e^{sign·sδ}
/// and the masses given, and its derivative.
fn characteristic(m0: Real, m_em: Real, d: Real, sign: Real) -> (impl Fn(C) -> C, impl Fn(C) -> C) {
    (
        move |s: C| s * s * (m0 + (s * (sign * d)).exp() * m_em) + 1.0,
        move |s: C| {
            let e = (s * (sign * d)).exp() * m_em;
            s * 2.0 * (e + m0) + s * s * e * (sign * d)
        },
    )
}

/// Grade the root of the characteristic function of (A.1) that continues
/// the undamped oscillation s = i.
///
/// Paper: Eq. (A.1) with Z ∝ e^{st}.
pub fn characteristic_root(seed: u64, student: impl Fn(Real, Real) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.root_near_al().unwrap_or(C::new(Real::NAN, Real::NAN)),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    let masses = |x: &ShellInput| {
        let m_em = x.tau0 / x.delta;
        (1.0 - m_em, m_em)
    };
    let root_of = move |x: &ShellInput, swap: bool, sign: Real| {
        let (m0, m_em) = masses(x);
        let (m0, m_em) = if swap { (m_em, m0) } else { (m0, m_em) };
        let (p, dp) = characteristic(m0, m_em, x.delta, sign);
        *newton_iterates(p, dp, C::new(0.0, 1.0), 100)
            .last()
            .unwrap_or(&C::new(0.0, 1.0))
    };
    // Newton stopped after a fixed number of iterations.
    let stopped_early = move |x: &ShellInput, again: &Again<'_, ShellInput, C>| {
        let theirs = again(x)?;
        let (m0, m_em) = masses(x);
        let (p, dp) = characteristic(m0, m_em, x.delta, -1.0);
        let iterates = newton_iterates(p, dp, C::new(0.0, 1.0), 12);
        let last = *iterates.last()?;
        iterates
            .iter()
            .enumerate()
            .skip(1)
            .find(|(_, s)| (**s - theirs).norm() <= 1e-13 * s.norm() && (**s - last).norm() > 1e-10)
            .map(|(k, _)| {
                format!(
                    "you stopped Newton's method after {k} step{}: it has not converged yet. Iterate until the Newton step is below rounding (a fixed number of steps, or a test of |P(s)| against a tolerance far above rounding, stops too early)",
                    if k == 1 { "" } else { "s" }
                )
            })
    };
    let not_converged = move |x: &ShellInput, again: &Again<'_, ShellInput, C>| {
        let theirs = again(x)?;
        let (m0, m_em) = masses(x);
        let (p, _) = characteristic(m0, m_em, x.delta, -1.0);
        let right = reference(x);
        let residual = p(theirs).norm();
        let near = (theirs - right).norm() < 1e-3;
        (near && residual > 1e-12).then(|| {
            format!(
                "close to the root but not on it (P(s) is {residual:.1e} there, not zero to rounding): iterate until the Newton step is below rounding; is the derivative P'(s) right?"
            )
        })
    };
    Grader::new(
        "characteristic_root",
        "Eq. (A.1) with Z ~ e^{st}",
        seed,
        shell_inputs(seed, 0.3),
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
            move |x: &ShellInput| root_of(x, false, 1.0),
        ),
        mistake(
            "the two masses are swapped in the characteristic function: the bare mass goes with s^2 alone, the field's mass with the delay factor",
            move |x: &ShellInput| root_of(x, true, -1.0),
        ),
        mistake(
            "that is the complex conjugate of the root: the oscillation's root continues s = +i, with a positive imaginary part",
            move |x: &ShellInput| reference(x).conj(),
        ),
    ])
    .probe(stopped_early)
    .probe(not_converged)
    .run(|x| student(x.tau0, x.delta))
}
