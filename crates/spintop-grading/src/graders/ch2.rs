//! Section 2: the two laws of the angular momentum a radiating dipole loses,
//! the Schott term, and the precessing dipole of the example.

use crate::{Again, Grade, Grader, Rng, close, mistake};
use crate::{CASES, diagnosis};
use spintop::math::{Real, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet};
use std::fmt;

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
) -> Vec<crate::Mistake<'a, JetInput, Vec3>> {
    let (ri, rj, rs) = right;
    let mut out = vec![mistake(
        "a sign flip: your answer is exactly −1 times the right one (the cross product's factors in the wrong order, or a minus sign lost)",
        move |x: &JetInput| -rs * x.0[ri].cross(&x.0[rj]),
    )];
    for &(pair, text) in special {
        let (i, j, s) = pair;
        out.push(mistake(text, move |x: &JetInput| s * x.0[i].cross(&x.0[j])));
    }
    for i in 0..JET_NAMES.len() {
        for j in 0..JET_NAMES.len() {
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
                let text = wrong_pair_words((i, j), (right.0, right.1));
                out.push(mistake(text, move |x: &JetInput| s * x.0[i].cross(&x.0[j])));
            }
        }
    }
    out
}

/// "you crossed d with d'': d'' is right, but d is the wrong factor, one
/// derivative too few": which factor of a wrong pair is wrong, and by how
/// many derivatives, when one of the two is right.
fn wrong_pair_words((i, j): (usize, usize), (ri, rj): (usize, usize)) -> String {
    let (a, b) = (JET_NAMES[i], JET_NAMES[j]);
    let shared = [i, j].into_iter().find(|k| *k == ri || *k == rj);
    let Some(k) = shared else {
        return format!(
            "you crossed {a} with {b}: neither factor is the right derivative of the dipole (count the derivatives)"
        );
    };
    let wrong = if k == i { j } else { i };
    let want = if k == ri { rj } else { ri };
    let n = wrong.abs_diff(want);
    let how = match (n, wrong > want) {
        (1, true) => "one derivative too many".to_string(),
        (1, false) => "one derivative too few".to_string(),
        (n, true) => format!("{n} derivatives too many"),
        (n, false) => format!("{n} derivatives too few"),
    };
    format!(
        "you crossed {a} with {b}: {} is right, but {} is the wrong factor, {how}",
        JET_NAMES[k], JET_NAMES[wrong]
    )
}

/// The cross products of two derivatives of the dipole, d_i × d_j (i < j).
const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// The student's answer as a sum of cross products of the dipole's
/// derivatives: its coefficient on each pair, read from jets with two
/// derivatives only (d_i along x and d_j along y give the coefficient along
/// z), checked on a second such jet for each pair and on the failing input
/// `x`; `None` if the answer is not such a sum.
fn jet_terms(x: &JetInput, again: &Again<'_, JetInput, Vec3>) -> Option<[Real; 6]> {
    let mut c = [0.0; 6];
    for (n, &(i, j)) in PAIRS.iter().enumerate() {
        let mut jet = [Vec3::zeros(); 4];
        (jet[i], jet[j]) = (Vec3::x(), Vec3::y());
        let a = again(&JetInput(jet))?;
        c[n] = a.z;
        (jet[i], jet[j]) = (2.0 * Vec3::y(), -0.5 * Vec3::z());
        let b = again(&JetInput(jet))?;
        let tol = 1e-12 * (1.0 + a.z.abs());
        if a.x.abs() + a.y.abs() > tol || (b + Vec3::x() * a.z).norm() > tol {
            return None;
        }
    }
    let sum = PAIRS.iter().zip(c).fold(Vec3::zeros(), |s, (&(i, j), k)| {
        s + k * x.0[i].cross(&x.0[j])
    });
    close(&again(x)?, &sum, 1e-10).then_some(c)
}

/// What a term the student added is, when it is a law of Section 2.
fn known_term(n: usize, k: Real) -> &'static str {
    match (PAIRS[n], k) {
        ((1, 2), -1.0) => " (the Larmor-like law (2.1))",
        ((0, 2), 1.0) => " (L_S of (2.4))",
        ((0, 3), 1.0) => " (the torque law (2.2))",
        _ => "",
    }
}

/// Which term of a sum of cross products is wrong: the student's answer is
/// decomposed on the six pairs of derivatives (see [`jet_terms`]) and
/// compared with `right`, the law's terms as (i, j, coefficient, name).
fn jet_terms_probe(
    right: &[(usize, usize, Real, &'static str)],
) -> impl Fn(&JetInput, &Again<'_, JetInput, Vec3>) -> Option<String> + use<> {
    let right: Vec<(usize, usize, Real, &'static str)> = right.to_vec();
    move |x, again| {
        let theirs = jet_terms(x, again)?;
        // An answer proportional to the law's is a factor, which the shape
        // of the answer names better.
        let scale = right.iter().find_map(|r| {
            PAIRS
                .iter()
                .position(|p| *p == (r.0, r.1))
                .map(|n| theirs[n] / r.2)
        })?;
        let proportional = PAIRS.iter().enumerate().all(|(n, &(i, j))| {
            let want = right
                .iter()
                .find(|r| (r.0, r.1) == (i, j))
                .map_or(0.0, |r| r.2);
            (theirs[n] - scale * want).abs() <= 1e-12 * (1.0 + want.abs())
        });
        if proportional {
            return None;
        }
        let mut words = Vec::new();

        for (n, &(i, j)) in PAIRS.iter().enumerate() {
            let (want, name) = right
                .iter()
                .find(|r| (r.0, r.1) == (i, j))
                .map_or((0.0, ""), |r| (r.2, r.3));
            let k = theirs[n];
            if (k - want).abs() <= 1e-12 * (1.0 + want.abs()) {
                continue;
            }
            words.push(if want == 0.0 {
                let sign = if k < 0.0 { "−" } else { "" };
                let times = if k.abs() == 1.0 {
                    String::new()
                } else {
                    format!("{} ", diagnosis::factor_words(k.abs()))
                };
                format!(
                    "a term too many: {sign}{times}{} × {}{}",
                    JET_NAMES[i],
                    JET_NAMES[j],
                    known_term(n, k)
                )
            } else if k == 0.0 {
                format!("{name} is missing")
            } else if k == -want {
                format!("{name} has the wrong sign")
            } else {
                format!(
                    "{name} is {} times the right one",
                    diagnosis::factor_words(k / want)
                )
            });
        }
        (!words.is_empty()).then(|| {
            format!(
                "your answer is a sum of cross products of the dipole's derivatives, but not the law's: {}",
                words.join("; ")
            )
        })
    }
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
    .probe(jet_terms_probe(&[(1, 2, -1.0, "the law's own term")]))
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
                "that is the torque law (2.2), a rate: its second factor d''' is one derivative too many; L_S is the angular momentum whose rate is the difference of the two laws",
            ),
            (
                (1, 2, 1.0),
                "that is (minus) the Larmor-like rate (2.1), a rate of loss; L_S is an angular momentum",
            ),
        ],
    ))
    .probe(jet_terms_probe(&[(0, 2, 1.0, "the law's own term")]))
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
        mistake(
            "that is the Larmor-like law (2.1) plus only half of dL_S/dt: its product rule has two terms, and the one from differentiating the first factor, d' × d'', which cancels the Larmor-like term, is missing",
            |j: &JetInput| balance::larmor_rate(&j.0) + j.0[0].cross(&j.0[3]),
        ),
    ];
    mistakes.extend(crossings(
        (0, 3, 1.0),
        &[(
            (0, 2, 1.0),
            "that is the Schott angular momentum L_S of (2.4): its second factor d'' is one derivative too few",
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
    .probe(jet_terms_probe(&[(0, 3, 1.0, "the law's own term")]))
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
            "only half of the product rule (a missing term): you differentiated the first factor of L_S and not the second",
            |j: &JetInput| j.0[1].cross(&j.0[2]),
        ),
        mistake(
            "only half of the product rule (a missing term): you differentiated the second factor of L_S and not the first",
            |j: &JetInput| j.0[0].cross(&j.0[3]),
        ),
        mistake(
            "the first term of the product rule (from differentiating the first factor of L_S) has the wrong sign: the two terms have opposite signs in your answer, and both come with +",
            |j: &JetInput| j.0[0].cross(&j.0[3]) - j.0[1].cross(&j.0[2]),
        ),
        mistake(
            "the second term of the product rule (from differentiating the second factor of L_S) has the wrong sign: the two terms have opposite signs in your answer, and both come with +",
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
    .probe(jet_terms_probe(&[
        (1, 2, 1.0, "the product rule's first term (from differentiating the first factor of L_S)"),
        (0, 3, 1.0, "its second term (from differentiating the second factor)"),
    ]))
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
            "that is the size of dL_S/dt, its magnitude (norm), not its projection on d: project it on the unit vector along d",
            |j: &JetInput| balance::schott_rate(&j.0).norm(),
        ),
        mistake(
            "projected on the wrong vector (the wrong direction): the projection is along d itself, not along one of its derivatives",
            |j: &JetInput| balance::axial(&j.0[1], &balance::schott_rate(&j.0)),
        ),
        mistake(
            "projected on the wrong vector (the wrong direction): the projection is along d itself, not along one of its derivatives",
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

/// The cone's inputs: random ones, the start (t = 0), and a cone wider than
/// a hemisphere turning backwards.
fn cone_inputs(seed: u64) -> Vec<ConeInput> {
    let mut rng = Rng::new(seed);
    let mut inputs: Vec<ConeInput> = (0..CASES)
        .map(|_| ConeInput {
            theta: rng.uniform(0.05, 3.1),
            omega: rng.sign() * rng.uniform(0.2, 3.0),
            t: rng.uniform(0.0, 10.0),
        })
        .collect();
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
    inputs
}

/// The right jet (not finite for a cone spintop refuses).
fn cone_jet(x: &ConeInput) -> Jet {
    match balance::PrecessingDipole::new(x.theta, x.omega) {
        Ok(p) => p.jet(x.t),
        Err(_) => [Vec3::repeat(Real::NAN); 4],
    }
}

/// The right jet with each derivative scaled by its own factor.
fn cone_scaled(x: &ConeInput, scale: [Real; 4]) -> Jet {
    let mut j = cone_jet(x);
    for (v, s) in j.iter_mut().zip(scale) {
        *v *= s;
    }
    j
}

/// The slips of the chain rule (a power of omega too few or too many on one
/// derivative, all of them missing) and the signs of the derivatives.
fn cone_mistakes<'a>() -> Vec<crate::Mistake<'a, ConeInput, Jet>> {
    let mut out = vec![mistake(
        "the chain rule's factors of omega are missing: each time derivative of cos(omega t) brings one",
        |x: &ConeInput| cone_scaled(x, [1.0, 1.0 / x.omega, x.omega.powi(-2), x.omega.powi(-3)]),
    )];
    for (k, name, right) in [(1, "d'", "one"), (2, "d''", "two"), (3, "d'''", "three")] {
        for (power, words) in [(1, "too many"), (-1, "too few")] {
            let text = format!(
                "{name} has a power of omega {words}: each time derivative brings exactly one factor omega, so {name} has {right}"
            );
            out.push(mistake(text, move |x: &ConeInput| {
                let mut scale = [1.0; 4];
                scale[k] = x.omega.powi(power);
                cone_scaled(x, scale)
            }));
        }
    }
    out.extend([
        mistake(
            "d'' points the wrong way: a uniform circular motion accelerates toward its axis",
            |x: &ConeInput| cone_scaled(x, [1.0, 1.0, -1.0, 1.0]),
        ),
        mistake(
            "the third derivative d''' has the wrong sign: differentiate d'' once more, carefully",
            |x: &ConeInput| cone_scaled(x, [1.0, 1.0, 1.0, -1.0]),
        ),
        mistake(
            "d' has the wrong sign: the derivative of cos is minus sin",
            |x: &ConeInput| cone_scaled(x, [1.0, -1.0, 1.0, -1.0]),
        ),
    ]);
    out
}

/// Where the dipole starts: in the x-z plane, at x = sin(theta).
fn cone_start_probe(x: &ConeInput, again: &Again<'_, ConeInput, Jet>) -> Option<String> {
    let at0 = ConeInput { t: 0.0, ..*x };
    let (theirs, right) = (again(&at0)?[0], cone_jet(&at0)[0]);
    let same_cone = (theirs.z - right.z).abs() < 1e-12 && (theirs.norm() - 1.0).abs() < 1e-12;
    (same_cone && (theirs - right).norm() > 1e-9).then(|| {
        "the start is wrong: at t = 0 the dipole lies in the x-z plane (y = 0, x > 0); yours starts elsewhere on the cone (a sine where a cosine belongs?)".to_string()
    })
}

/// Grade the jet of a dipole precessing uniformly on a cone about z.
///
/// Paper: Section 2 (the example of Eqs. (2.1)–(2.4)).
pub fn precessing_dipole_jet(seed: u64, student: impl Fn(Real, Real, Real) -> Jet) -> Grade {
    use std::f64::consts::FRAC_PI_2;
    let radians = std::f64::consts::PI / 180.0;
    Grader::new(
        "precessing_dipole_jet",
        "Section 2, the precessing dipole",
        seed,
        cone_inputs(seed),
        cone_jet,
        |a: &Jet, b: &Jet| close(a, b, 1e-12),
    )
    .mistakes(cone_mistakes())
    .probe(cone_start_probe)
    .variant(
        "the dipole turns the wrong way about z: a positive omega turns it counter-clockwise seen from +z (x toward y)",
        |x: &ConeInput| ConeInput { omega: -x.omega, ..*x },
    )
    .variant(
        "theta measured from the x-y plane (sin and cos of theta swapped): the cone's half-angle is measured from the z axis",

        |x: &ConeInput| ConeInput { theta: FRAC_PI_2 - x.theta, ..*x },
    )
    .variant(
        "theta treated as degrees and converted to radians, but it is given in radians already: sin and cos take it as it is",
        move |x: &ConeInput| ConeInput { theta: x.theta * radians, ..*x },
    )
    .variant(
        "theta converted from radians to degrees before sin and cos: they take radians, as theta is given",
        move |x: &ConeInput| ConeInput { theta: x.theta / radians, ..*x },
    )
    .variant(
        "the angle omega t treated as degrees and converted to radians, but it is in radians already: sin and cos take it as it is",
        move |x: &ConeInput| ConeInput { t: x.t * radians, ..*x },
    )
    .variant(
        "the start is wrong: at t = 0 the dipole lies in the x-z plane (a quarter turn off?)",
        |x: &ConeInput| ConeInput { t: x.t + FRAC_PI_2 / x.omega, ..*x },
    )
    .variant(
        "the start is wrong: at t = 0 the dipole lies in the x-z plane (a quarter turn off?)",
        |x: &ConeInput| ConeInput { t: x.t - FRAC_PI_2 / x.omega, ..*x },
    )
    .run(|x| student(x.theta, x.omega, x.t))
}
