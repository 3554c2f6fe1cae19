//! The secular model of a top whose radiation is weak: the slow drift of its
//! two free invariants, 2E = Ω·IΩ and L² = |IΩ|², averaged over the free
//! motion round the polhode.
//!
//! For a real molecule or nanoparticle, τ_f|Ω| (the radiation's effect per
//! radian, τ_f = |d|²/min I) is 10⁻¹⁷ or less: its energy drains over some
//! 10¹⁷ turns, which no integrator can step one by one, and the asymmetric
//! top has no closed form to jump with. But within one turn the torque
//! changes Ω by a part in 10¹⁷, so the motion is the free one (a closed form,
//! [`crate::physics::free_top`]) with invariants that drift at their
//! period-averaged rates:
//!
//! ```text
//! d(2E)/dt = ⟨2 Ω·T(Ω)⟩,   d(L²)/dt = ⟨2 IΩ·T(Ω)⟩,   T(Ω) = I Ω̇(Ω) + Ω × IΩ
//! ```
//!
//! where T is the radiation torque of the model ((3.3) or the reduced (3.4))
//! and ⟨·⟩ the average over the polhode with the current invariants. Only this
//! 2-dimensional system is integrated (DOP853), with steps as long as the
//! slow drift allows. Its error is of the order of τ_f|Ω| (first-order
//! averaging), far below any tolerance for the particles it is used on; the
//! phase along the polhode and the orientation are not followed.
//!
//! Beyond the paper: the paper solves only the symmetric top, where closed
//! forms make this unnecessary (tests check the secular model against them).

use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Stats, Stepper, solve};
use crate::math::{Real, State, Vec3};
use crate::physics::free_top::Polhode;
use crate::physics::full_ale::{slow_manifold_second_order, slow_manifold_third_order};
use crate::physics::general_top::GeneralTop;
use serde::Serialize;

/// Which torque law drifts the invariants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// The truncated ALE (3.3), the law (2.1) without the Schott term.
    Truncated,
    /// The reduced ALE, (3.4) with Ω̇, Ω̈ of the free motion in its small terms.
    Reduced,
    /// The slow manifold of (3.4) to third order: the reduced ALE's torque
    /// plus I(G₂ + G₃) ([`slow_manifold_second_order`],
    /// [`slow_manifold_third_order`]). It stands in for the physical solution
    /// where the errors of the other two are estimated: G₂ only turns the
    /// symmetric top's precession (it drains neither E nor |L|), and G₃
    /// carries the first drift of the invariants that the reduced ALE gets
    /// wrong (with G₂ alone the reduced model's error in E was claimed
    /// 4.6e-14 where it was 3e-10).
    Manifold,
}

/// The state of the secular model at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SecularSample {
    /// Time (κ = 1 units, as the model's).
    pub t: Real,
    /// E = ½ Ω·IΩ.
    pub energy: Real,
    /// |L| = |IΩ|.
    pub l_norm: Real,
    /// The body axis the polhode circles, 1, 2 or 3.
    pub axis: usize,
    /// The period of the free motion round the polhode; `None` (absent in
    /// JSON) for a rotation about a principal axis, which has none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<Real>,
}

/// A secular run.
#[derive(Clone, Debug, PartialEq)]
pub struct SecularRun {
    /// One sample per output time.
    pub samples: Vec<SecularSample>,
    /// Work of the slow integration (each evaluation is one period average).
    pub stats: Stats,
    /// The most quadrature points one period average needed.
    pub max_points: usize,
}

/// At most this many slow steps: the drift is smooth, so a run that needs
/// more is outside what the model is for (it is then reported, not run on).
pub const MAX_SLOW_STEPS: u64 = 20_000;

/// The radiation torque of `law` at Ω, computed on its own (never as
/// IΩ̇ + Ω × IΩ, which rounding would swamp for a real particle).
fn torque(top: &GeneralTop, law: Law, omega: &Vec3) -> Vec3 {
    match law {
        Law::Truncated => top.truncated_torque(omega),
        Law::Reduced => top.reduced_torque(omega),
        Law::Manifold => {
            top.reduced_torque(omega)
                + top.inertia().component_mul(
                    &(slow_manifold_second_order(top, omega)
                        + slow_manifold_third_order(top, omega)),
                )
        }
    }
}

/// The period-averaged drift of (2E, L²), each relative to its start
/// (2E₀, L₀²), at the invariants `y` (in the same units), under `law`; and
/// the quadrature points the average took.
fn drift_and_points(
    top: &GeneralTop,
    law: Law,
    inertia: &Vec3,
    two_e0: Real,
    l2_0: Real,
    y: &State<2>,
    quadrature_tol: Real,
) -> (State<2>, usize) {
    let p = Polhode::of(inertia, y[0] * two_e0, y[1] * l2_0);
    let (rates, n) = p.average(
        |w| {
            let t = torque(top, law, w);
            [
                2.0 * w.dot(&t) / two_e0,
                2.0 * inertia.component_mul(w).dot(&t) / l2_0,
            ]
        },
        quadrature_tol,
    );
    (State::<2>::new(rates[0], rates[1]), n)
}

/// The invariants the secular model follows at Ω: (E, |L|) = (½Ω·IΩ, |IΩ|).
pub fn invariants(inertia: &Vec3, omega: &Vec3) -> (Real, Real) {
    let l = inertia.component_mul(omega);
    (0.5 * omega.dot(&l), l.norm())
}

/// The secular model from Ω(0) = `omega0`, sampled at `times` (increasing,
/// from 0), to relative tolerance `rtol`.
///
/// Beyond the paper (the slow drift of (3.3) or the reduced (3.4), averaged).
pub fn secular(
    top: &GeneralTop,
    law: Law,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<SecularRun, IntegrateError> {
    // NOTE: scale-free. (3.3) and (3.4) keep their form under Ω → Ω/s,
    // t → ts, d → d√s, so a slow top (s = |Ω₀| < 1) is run as the top of
    // unit |Ω₀|: below |Ω₀| ~ 1e-154, 2E = Ω·IΩ underflows, and a moving top
    // was taken for one at rest (|L| printed 0).
    let Some((unit_top, s)) = unit_scaled(top, omega0) else {
        return secular_as_given(top, law, omega0, times, rtol);
    };
    let unit_times: Vec<Real> = times.iter().map(|t| t * s).collect();
    let mut run = secular_as_given(&unit_top, law, &(omega0 / s), &unit_times, rtol)?;
    for (sample, &t) in run.samples.iter_mut().zip(times) {
        sample.t = t;
        sample.energy = sample.energy * s * s;
        sample.l_norm *= s;
        sample.period = sample.period.map(|p| p / s).filter(|p| p.is_finite());
    }
    Ok(run)
}

/// The top of unit |Ω₀| with the same motion, and the scale s = |Ω₀|, for
/// a top slower than 1: (3.3) and (3.4) keep their form under Ω → Ω/s,
/// t → ts, d → d√s (see [`secular`]). `None` where the top is run as given.
pub(crate) fn unit_scaled(top: &GeneralTop, omega0: &Vec3) -> Option<(GeneralTop, Real)> {
    let s = omega0.norm();
    (s > 0.0 && s < 1.0)
        .then(|| GeneralTop::new(top.inertia(), top.dipole() * s.sqrt()).ok())
        .flatten()
        .map(|unit| (unit, s))
}

/// [`secular`] in the units it is given.
fn secular_as_given(
    top: &GeneralTop,
    law: Law,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<SecularRun, IntegrateError> {
    let inertia = top.inertia();
    let two_e0 = omega0.dot(&inertia.component_mul(omega0));
    let l2_0 = inertia.component_mul(omega0).norm_squared();
    if !(two_e0 > 0.0 && l2_0 > 0.0) {
        // A top at rest stays at rest.
        return Ok(SecularRun {
            samples: times
                .iter()
                .map(|&t| SecularSample {
                    t,
                    energy: 0.0,
                    l_norm: 0.0,
                    axis: 3,
                    period: None,
                })
                .collect(),
            stats: Stats::default(),
            max_points: 0,
        });
    }
    let quadrature_tol = (rtol * 1e-2).max(1e-14);
    let max_points = std::cell::Cell::new(0usize);
    // The state is (2E, L²) relative to their initial values.
    let rhs = |_t: Real, y: &State<2>| -> State<2> {
        let (rates, n) = drift_and_points(top, law, &inertia, two_e0, l2_0, y, quadrature_tol);
        max_points.set(max_points.get().max(n));
        rates
    };
    let mut options = AdaptiveOptions::new(rtol, rtol * 1e-3)?;
    options.max_steps = MAX_SLOW_STEPS;
    // The first step: a thousandth of the time the invariants take to change
    // by their own size (the integrator's guess starts far too small when
    // that time is 10³⁰ of the model's units).
    let f0 = rhs(0.0, &State::<2>::new(1.0, 1.0));
    let rate = f0.amax();
    if rate > 0.0 && rate.is_finite() {
        options.h_init = Some(1e-3 / rate);
    }
    let mut stepper = Dop853::new(0.0, State::<2>::new(1.0, 1.0), options)?;
    let ys = solve(&mut stepper, &rhs, times)?;
    let stats = stepper.stats();
    let samples = times
        .iter()
        .zip(&ys)
        .map(|(&t, y)| {
            let (two_e, l2) = (y[0] * two_e0, y[1] * l2_0);
            let p = Polhode::of(&inertia, two_e, l2);
            SecularSample {
                t,
                energy: 0.5 * two_e,
                l_norm: l2.max(0.0).sqrt(),
                axis: p.axis() + 1,
                period: Some(p.period()).filter(|p| p.is_finite()),
            }
        })
        .collect();
    Ok(SecularRun {
        samples,
        stats,
        max_points: max_points.get(),
    })
}

/// Points per period at which [`averaging_error`] follows the free motion.
const WIGGLE_POINTS: usize = 512;

// ANCHOR: averaging_error
/// The secular model's own error in E and |L|, relative: within each turn
/// round the polhode the true invariants swing about their averaged drift,
/// and the secular model, which follows the drift alone, misses the swing.
///
/// Beyond the paper (first-order averaging).
///
/// ```text
/// w(t) = ∫₀ᵗ (P(Ω(t′)) − ⟨P⟩) dt′      over one period of the free motion,
/// error ≈ max w − min w                 (P = d(2E)/dt / 2E, or d(L²)/dt / 2L²)
/// ```
///
/// taken at the start, where the swing is largest relative to the invariants
/// (it scales as τ_f|Ω|, which falls as the top slows down). Zero for a
/// rotation about one axis, where nothing swings.
pub fn averaging_error(top: &GeneralTop, law: Law, omega0: &Vec3) -> Real {
    swing(&top.inertia(), omega0, |w| torque(top, law, w))
}
// ANCHOR_END: averaging_error

/// The largest swing over one period of the free motion through Ω₀ of the
/// invariants (2E and |L|, relative) that the torque `torque` drives, about
/// its period average (see [`averaging_error`]).
pub fn swing(inertia: &Vec3, omega0: &Vec3, torque: impl Fn(&Vec3) -> Vec3) -> Real {
    let inertia = *inertia;
    let two_e = omega0.dot(&inertia.component_mul(omega0));
    let l2 = inertia.component_mul(omega0).norm_squared();
    let p = Polhode::through(&inertia, omega0);
    let period = p.period();
    if !(period.is_finite() && two_e > 0.0 && l2 > 0.0) {
        return 0.0;
    }
    let dt = period / WIGGLE_POINTS as Real;
    let rates: Vec<[Real; 2]> = (0..=WIGGLE_POINTS)
        .map(|j| {
            let w = p.omega_at(j as Real * dt);
            let t = torque(&w);
            [
                2.0 * w.dot(&t) / two_e,
                inertia.component_mul(&w).dot(&t) / l2,
            ]
        })
        .collect();
    let mut widest: Real = 0.0;
    for c in 0..2 {
        let mean =
            rates[..WIGGLE_POINTS].iter().map(|r| r[c]).sum::<Real>() / WIGGLE_POINTS as Real;
        let (mut w, mut lo, mut hi) = (0.0 as Real, 0.0 as Real, 0.0 as Real);
        for pair in rates.windows(2) {
            w += 0.5 * dt * (pair[0][c] + pair[1][c] - 2.0 * mean);
            lo = lo.min(w);
            hi = hi.max(w);
        }
        widest = widest.max(hi - lo);
    }
    widest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::symmetric_top::{SymmetricTop, reduced_closed_form, truncated_closed_form};

    /// I₁ = I₂, d ∥ e₃: the secular drift of E and |L| against the closed
    /// forms (4.7) and (4.15)–(4.16), over three decay times. For this top
    /// the rates of E and L² are constant round the (circular) polhode, so
    /// averaging loses nothing and only the tolerance is left.
    #[test]
    fn the_secular_model_of_a_symmetric_top_follows_eq_4_7_and_4_15() {
        let sym = SymmetricTop::new(0.4, 1e-4).unwrap();
        let top = GeneralTop::new(sym.inertia(), Vec3::new(0.0, 0.0, 1e-2)).unwrap();
        let omega0 = Vec3::new(0.0, 0.6, 0.8);
        // The decay times are about 1/(τ|Ω|²) = 10⁴ here.
        let times: Vec<Real> = (0..=6).map(|k| k as Real * 5e3).collect();
        let i = sym.inertia();
        for (law, closed) in [
            (
                Law::Reduced,
                reduced_closed_form as fn(&SymmetricTop, &Vec3, Real) -> Vec3,
            ),
            (Law::Truncated, truncated_closed_form),
        ] {
            let run = secular(&top, law, &omega0, &times, 1e-11).unwrap();
            let mut worst: Real = 0.0;
            for s in &run.samples {
                let w = closed(&sym, &omega0, s.t);
                let e = 0.5 * w.dot(&i.component_mul(&w));
                let l = i.component_mul(&w).norm();
                worst = worst
                    .max((s.energy / e - 1.0).abs())
                    .max((s.l_norm / l - 1.0).abs());
            }
            let last = run.samples.last().unwrap();
            assert!(
                last.energy < 0.9 * run.samples[0].energy,
                "{law:?} must drain: {last:?}"
            );
            // The book's claim: agreement with the closed forms to 1e-11
            // (at rtol 1e-11; at rtol 1e-10 the gap is 1.5e-11).
            assert!(worst < 1e-11, "{law:?}: worst relative gap {worst:e}");
            assert!(
                run.stats.steps < 200,
                "{law:?}: {} slow steps",
                run.stats.steps
            );
        }
    }

    /// An asymmetric top with weak radiation: the secular model against
    /// DOP853 stepping the ALE itself through about two decay times (300 and
    /// 3000 turns). First-order averaging leaves a gap of the order of
    /// ε = τ_f|Ω₀|, and it shrinks with ε.
    #[test]
    fn the_secular_model_of_an_asymmetric_top_follows_the_stepped_ale() {
        let inertia = Vec3::new(1.0, 1.5, 2.0);
        let omega0 = Vec3::new(0.5, 0.3, 0.8);
        let e0 = 0.5 * omega0.dot(&inertia.component_mul(&omega0));
        for eps in [1e-3, 1e-4_f64] {
            // τ_f = |d|²/min I = eps, and |Ω₀| ≈ 1.
            let dipole = Vec3::new(0.3, 0.2, 1.0) * (eps / 1.13).sqrt();
            let top = GeneralTop::new(inertia, dipole).unwrap();
            let t_end = 2.0 / eps;
            let times: Vec<Real> = (0..=5).map(|k| k as Real * t_end / 5.0).collect();
            for law in [Law::Reduced, Law::Truncated] {
                let run = secular(&top, law, &omega0, &times, 1e-10).unwrap();
                let rhs = |_t: Real, y: &State<3>| -> State<3> {
                    let w = Vec3::new(y[0], y[1], y[2]);
                    match law {
                        Law::Reduced => top.reduced_ale_rhs(&w),
                        Law::Truncated => top.truncated_ale_rhs(&w),
                        Law::Manifold => {
                            top.reduced_ale_rhs(&w)
                                + slow_manifold_second_order(&top, &w)
                                + slow_manifold_third_order(&top, &w)
                        }
                    }
                };
                let opts = AdaptiveOptions::new(1e-11, 1e-14).unwrap();
                let mut s = Dop853::new(0.0, omega0, opts).unwrap();
                let ys = solve(&mut s, &rhs, &times).unwrap();
                let mut worst: Real = 0.0;
                for (smp, y) in run.samples.iter().zip(&ys) {
                    let w = Vec3::new(y[0], y[1], y[2]);
                    let e = 0.5 * w.dot(&inertia.component_mul(&w));
                    let l = inertia.component_mul(&w).norm();
                    worst = worst
                        .max((smp.energy - e).abs() / e0)
                        .max((smp.l_norm / l - 1.0).abs());
                }
                let drop = 1.0 - run.samples.last().unwrap().energy / e0;
                assert!(drop > 0.05, "{law:?}: E fell by only {drop}");
                assert!(
                    worst < 1.5 * eps,
                    "{law:?}, eps = {eps:e}: worst gap {worst:e}"
                );
                assert!(run.stats.steps < 200, "{} slow steps", run.stats.steps);
            }
        }
    }
}
