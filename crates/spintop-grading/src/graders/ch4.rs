//! Section 4: the symmetric top, the truncated model (4.2)–(4.11) and the
//! reduced one (4.12)–(4.18).

use super::OMEGA;
use crate::parts::{named, part};
use crate::{Again, Answer, Grade, Grader, Rng, close, mistake};
use crate::{CASES, diagnosis};
use spintop::math::{Real, Vec3};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use std::fmt;

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
            return Some(phase_words(x, again, &reference).unwrap_or_else(|| {
                "Omega_perp has the right size but has turned by the wrong angle: the precession rate (which spin, which moment ratio) or the clock it runs on is wrong".into()
            }));
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

/// How far the student's Ω⊥ has turned from a start (u, 0), as a multiple
/// of the right angle, at the time the free precession turns it by about
/// `target` radians (small, so that no turn is lost to 2π).
fn turn_ratio(
    x: &TopTime,
    target: Real,
    again: &Again<'_, TopTime, Vec3>,
    reference: &impl Fn(&TopTime) -> Vec3,
) -> Option<Real> {
    let rate = (1.0 - x.ratio) * x.omega0.z;
    if rate.abs() < 1e-6 {
        return None;
    }
    let start = TopTime {
        omega0: Vec3::new(x.omega0.x.hypot(x.omega0.y), 0.0, x.omega0.z),
        t: target / rate.abs(),
        ..*x
    };
    let angle = |p: Vec3| -p.y.atan2(p.x);
    let right = angle(reference(&start));
    (right.abs() > 1e-3).then_some(angle(again(&start)?) / right)
}

/// What a phase that is off by the same factor at two times says: degrees
/// for radians, a factor 2, or a rate off by some other factor.
fn phase_words(
    x: &TopTime,
    again: &Again<'_, TopTime, Vec3>,
    reference: &impl Fn(&TopTime) -> Vec3,
) -> Option<String> {
    let (k1, k2) = (
        turn_ratio(x, 0.5, again, reference)?,
        turn_ratio(x, 0.3, again, reference)?,
    );
    if (k1 - k2).abs() > 1e-6 * k1.abs().max(1e-3) {
        return None;
    }
    let is = |f: Real| (k1 / f - 1.0).abs() < 1e-6;
    let radians = std::f64::consts::PI / 180.0;
    Some(if is(radians) {
        "the phase (the precession angle) went through a conversion from degrees to radians, but it is in radians already: sin and cos take it as it is".into()
    } else if is(0.5) {
        "the phase runs at half speed: Omega_perp turns by half the right angle at every time, a factor 2 missing in the precession angle (in its rate, or in the clock it runs on)".into()
    } else if is(2.0) {
        "the phase runs twice too fast: Omega_perp turns by twice the right angle at every time, a factor 2 too many in the precession angle (in its rate, or in the clock it runs on)".into()
    } else {
        format!(
            "the phase is off: Omega_perp turns {} times as far as it should at every time, so the precession rate (which spin, which moment ratio) is wrong",
            diagnosis::factor_words(k1)
        )
    })
}

/// The reduced model's decay factor Φ with a tiny Ω⊥₀ is its exponential
/// alone: how fast the student's falls, as a multiple of the right rate,
/// at two times (a factor the same at both names the slip).
fn decay_probe(
    reference: impl Fn(&TopTime) -> Vec3,
) -> impl Fn(&TopTime, &Again<'_, TopTime, Vec3>) -> Option<String> {
    move |x, again| {
        let k = x.ratio * x.omega0.z;
        if k.abs() < 1e-3 || x.tau <= 0.0 {
            return None;
        }
        let u = 1e-6;
        let rate_at = |t: Real| -> Option<Real> {
            let input = TopTime {
                omega0: Vec3::new(u, 0.0, x.omega0.z),
                t,
                ..*x
            };
            let (theirs, right) = (again(&input)?, reference(&input));
            let (phi, want) = (theirs.x.hypot(theirs.y) / u, right.x.hypot(right.y) / u);
            (phi > 0.0 && want < 1.0 - 1e-6).then(|| phi.ln() / want.ln())
        };
        // Where the exponential has fallen to 1/e, and half as far.
        let t1 = (1.0 / (x.tau * k * k)).min(100.0);
        let (q1, q2) = (rate_at(t1)?, rate_at(t1 / 2.0)?);
        if (q1 - q2).abs() > 1e-6 * q1.abs().max(1e-3) || (q1 - 1.0).abs() < 1e-6 {
            return None;
        }
        let is = |f: Real| (q1 - f).abs() < 1e-6;
        let tiny = "with a tiny Omega_perp0 the decay is the exponential factor of Phi alone";
        Some(if is(0.0) {
            format!(
                "a missing factor: the exponential factor of Phi is missing; {tiny}, and yours does not decay"
            )
        } else if is(0.5) {
            format!(
                "Omega_perp decays at half the rate: {tiny}, and yours falls half as fast (a factor 2 missing in its exponent s)"
            )
        } else if is(2.0) {
            format!(
                "Omega_perp decays twice too fast: {tiny}, and yours falls twice as fast (a factor 2 too many in its exponent s)"
            )
        } else {
            format!(
                "{tiny}, and yours decays {} times as fast: its exponent is wrong",
                diagnosis::factor_words(q1)
            )
        })
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
        "the start was taken with Omega_10 = 0, as the paper prints it, so the initial phase of Omega_perp is wrong: keep both components of Omega_perp0",

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
            "the factor is upside down (inverted): the rates fall as 1/R, so R must reach 1/p, not p",
            move |x: &FactorInput| (1.0 - x.p * x.p) / rate(x),
        ),
        mistake(
            "R was not squared: the rates fall as 1/R, so R reaches 1/p at the time asked, and R is a square root: square it before solving for t",
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
    let book = Vec3::from(sym::FIGURE_OMEGA0);
    inputs.insert(0, (sym::FIGURE_RATIO, book));
    inputs.push((sym::FIGURE_RATIO, Vec3::new(book.x, book.y, -book.z)));
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
            "the angle between the axis and the rotation rate, not L: the moment ratio is missing, and the angular momentum weighs each component by its moment of inertia",
            |(_, w): &(Real, Vec3)| w.x.hypot(w.y).atan2(w.z),
        ),
        mistake(
            "the ratio of the moments is inverted: the moments of inertia are swapped, and the perpendicular part of L carries I1, the axial part I3",
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
/// squared rate `k2` in the damping.
fn reduced_rhs_with(tau: Real, w: &Vec3, wt3: Real, k2: Real) -> Vec3 {
    let damp = tau * (w.x * w.x + w.y * w.y + k2);
    Vec3::new(wt3 * w.y - damp * w.x, -wt3 * w.x - damp * w.y, 0.0)
}

/// A slip in (4.12)–(4.14): what it says, and Ω̇ with it from the moment
/// ratio, τ and Ω.
pub(super) type RhsSlip = (&'static str, fn(Real, Real, &Vec3) -> Vec3);

/// The plausible slips in the reduced model's right-hand side (the graders
/// of the model and of an RK4 run of it share them).
pub(super) fn reduced_rhs_slips() -> Vec<RhsSlip> {
    let slips: Vec<RhsSlip> = vec![
        (
            "that is the truncated model (4.2)-(4.4): the Schott term's contribution to the damping is missing, and the spin is damped",
            |r, tau, w| match SymmetricTop::new(r, tau) {
                Ok(top) => sym::truncated_ale_rhs(&top, w),
                Err(_) => Vec3::repeat(Real::NAN),
            },
        ),
        (
            "the spin is damped: in the reduced model the axial rate is constant",
            |r, tau, w| {
                let mut out = reduced_rhs_with(tau, w, (1.0 - r) * w.z, (r * w.z).powi(2));
                out.z = -tau * (w.x * w.x + w.y * w.y + (r * w.z).powi(2)) * w.z;
                out
            },
        ),
        (
            "the damping's Schott part uses the rate about the axis without its moment ratio: it is the axial angular momentum over I1 that enters",
            |r, tau, w| reduced_rhs_with(tau, w, (1.0 - r) * w.z, w.z * w.z),
        ),
        (
            "the damping's Schott part is missing: Omega_perp is damped by more than its own square in the reduced model",
            |r, tau, w| reduced_rhs_with(tau, w, (1.0 - r) * w.z, 0.0),
        ),
        (
            "a missing term: the damping rate lacks Omega_perp's own square (the perpendicular rate squared); Omega_perp is damped by its own square and the axial part together",
            |r, tau, w| {
                let (wt, damp) = ((1.0 - r) * w.z, tau * (r * w.z).powi(2));
                Vec3::new(wt * w.y - damp * w.x, -wt * w.x - damp * w.y, 0.0)
            },
        ),
        (
            "the free precession turns the wrong way: check the signs of the two precession terms against (4.12)-(4.13)",
            |r, tau, w| reduced_rhs_with(tau, w, -(1.0 - r) * w.z, (r * w.z).powi(2)),
        ),
        (
            "the precession rate is the spin itself: in the body frame Omega_perp turns at the spin times (1 - the moment ratio)",
            |r, tau, w| reduced_rhs_with(tau, w, w.z, (r * w.z).powi(2)),
        ),
        (
            "the moment ratio is upside down in the precession rate: the ratio is I3/I1",
            |r, tau, w| reduced_rhs_with(tau, w, (1.0 - 1.0 / r) * w.z, (r * w.z).powi(2)),
        ),
        (
            "the moment ratio enters the damping once, not squared: it is the square of the axial angular momentum over I1",
            |r, tau, w| reduced_rhs_with(tau, w, (1.0 - r) * w.z, r * w.z * w.z),
        ),
        (
            "the damping has the wrong sign: radiation slows Omega_perp",
            |r, tau, w| reduced_rhs_with(-tau, w, (1.0 - r) * w.z, (r * w.z).powi(2)),
        ),
        (
            "the damping is twice too strong: a factor 2 on tau",
            |r, tau, w| reduced_rhs_with(2.0 * tau, w, (1.0 - r) * w.z, (r * w.z).powi(2)),
        ),
        (
            "the damping is half as strong as it should be: a factor 2 missing on tau",
            |r, tau, w| reduced_rhs_with(tau / 2.0, w, (1.0 - r) * w.z, (r * w.z).powi(2)),
        ),
        (
            "the precession rate is the moment ratio times the spin: in the body frame Omega_perp turns at the spin times (1 - the moment ratio)",
            |r, tau, w| reduced_rhs_with(tau, w, r * w.z, (r * w.z).powi(2)),
        ),
    ];
    slips
}

/// Grade the reduced model's right-hand side.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_ale_rhs(seed: u64, student: impl Fn(Real, Real, Vec3) -> Vec3) -> Grade {
    let reference = |x: &SymInput| match sym_top(x) {
        Some(top) => sym::reduced_ale_rhs(&top, &x.omega),
        None => Vec3::repeat(Real::NAN),
    };
    let mistakes = reduced_rhs_slips()
        .into_iter()
        .map(|(text, f)| mistake(text, move |x: &SymInput| f(x.ratio, x.tau, &x.omega)))
        .collect();
    Grader::new(
        "reduced_ale_rhs",
        "Eqs. (4.12)-(4.14)",
        seed,
        sym_inputs(seed),
        reference,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-12),
    )
    .mistakes(mistakes)
    .parts(
        vec![
            part(
                "with tau = 0 (no radiation)",
                "the free precession",
                "the precession rate (which spin, which moment ratio)",
                |x: &SymInput| SymInput { tau: 0.0, ..*x },
            ),
            part(
                "with no spin (Omega_3 = 0)",
                "Omega_perp's damping by its own square",
                "the damping rate",
                |x: &SymInput| SymInput {
                    omega: Vec3::new(x.omega.x, x.omega.y, 0.0),
                    ..*x
                },
            ),
        ],
        vec![
            named("tau", |x: &SymInput| x.tau),
            named("the moment ratio", |x: &SymInput| x.ratio),
        ],
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
            "the moment ratio is inverted (upside down): the axial angular momentum is I3 times the spin, divided by I1",
            |x: &SymInput| 1.0 / ((x.omega.z / x.ratio).powi(2) * x.tau),
        ),
        mistake(
            "the moment ratio is missing: it is the axial angular momentum over I1, I3/I1 times the spin, that sets the decay",
            |x: &SymInput| 1.0 / (x.omega.z * x.omega.z * x.tau),
        ),
        mistake(
            "half the decay time (a factor 1/2): that is the decay time of Omega_perp squared, which decays twice as fast as Omega_perp itself (a factor 2 missing)",

            |x: &SymInput| 0.5 / ((x.ratio * x.omega.z).powi(2) * x.tau),
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
            "a wrong term under the square root of Phi: that is the truncated model's; in the reduced model its growth slows as the exponential decays, it does not grow linearly in t",
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
        "the start was taken with Omega_10 = 0, as the paper prints it, so the initial phase of Omega_perp is wrong: keep both components of Omega_perp0",

        |x: &TopTime| TopTime { omega0: Vec3::new(0.0, x.omega0.x.hypot(x.omega0.y), x.omega0.z), ..*x },
    )
    .variant(
        "the moment ratio is upside down: the ratio is I3/I1, in the precession rate and in sigma",
        |x: &TopTime| TopTime { ratio: 1.0 / x.ratio, ..*x },
    )
    .probe(decay_probe(reference))
    .probe(perp_probe(reference))
    .probe(drift_probe(reference))
    .labels(&OMEGA)
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t))
}
