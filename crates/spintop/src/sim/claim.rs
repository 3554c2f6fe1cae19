//! How far what a run printed may be from the truth, over the whole run.
//!
//! An integrator's tolerance bounds the error of each step, not of the run:
//! over many turns every step's error in the invariants shifts the frequency,
//! and the phase error is the integral of that shift. So the error a run
//! reports is measured, not assumed: the same run again at a hundredth of
//! the tolerance (half the step for RK4), and the largest distance between
//! the two over the samples, in Ω and in the orientation. With tolerance
//! proportionality the tighter run's own error is a small part of the
//! looser one's (a hundredth for a method whose error follows its tolerance,
//! a sixteenth for RK4 at half the step), so the distance is the looser
//! run's error to within that part; the claim is twice it, plus what
//! rounding alone leaves ([`rounding`]).
//!
//! | quantity | unit |
//! |---|---|
//! | Ω's error | relative to \|Ω₀\| |
//! | the orientation's error | radians: the angle of the rotation between the printed O(t) and the true one |

use super::cost::turning_angle;
use super::method::{MIN_RTOL, Method, MethodOptions};
use super::model::Model;
use super::physical::internal_rtol;
use super::secular::{Law, SecularRun, averaging_error, invariants, secular, unit_scaled};
use super::simulation::Simulation;
use super::state::{InitialState, Sample, SimError};
use crate::integrate::IntegrateError;
use crate::math::{Mat3, Real, Vec3};
use crate::physics::free_top::Polhode;
use crate::physics::general_top::GeneralTop;
use crate::sim::accuracy::secular_gap;
use serde::Serialize;

/// The factor between the run's tolerance and the second run's.
pub const TIGHTER: Real = 100.0;

/// The claim is this many times the distance between the two runs.
pub const SAFETY: Real = 2.0;

/// A model's estimated error against the physical solution of (3.4), over
/// a run ([`crate::sim::accuracy`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TierEstimate {
    /// In Ω (relative to |Ω₀|), or in E and |L| (relative) where the
    /// secular model answers.
    pub omega: Real,
    /// In the orientation, radians, where the run reports it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Real>,
}

/// What `model = "auto"` estimated of the two lighter models before it chose.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ModelEstimates {
    /// The truncated ALE (3.3).
    pub truncated: TierEstimate,
    /// The reduced ALE.
    pub reduced: TierEstimate,
    /// What `omega` measures: "Omega" or "E and |L|".
    pub measured: &'static str,
}

/// The estimated error of a run's samples, over the run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ErrorEstimate {
    /// The largest error of Ω over the samples, relative to |Ω₀|.
    pub omega: Real,
    /// The largest error of the orientation over the samples, in radians
    /// (`None` where the run reports no orientation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Real>,
    /// What rounding alone may leave in Ω (a part of `omega`; relative to
    /// |Ω₀|, or of E and |L| where those are measured).
    pub rounding: Real,
    /// What rounding alone may leave in the orientation, in radians (a part
    /// of `orientation`, present with it): the phase rounds as the body
    /// turns, while Ω's share stops where Ω⊥ has decayed.
    ///
    /// NOTE: one field held the orientation's floor for both, and Figure 2's
    /// reduced run printed a rounding of 2.1e-13 inside an Ω total of
    /// 1.3e-14 (issue 46, review).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation_rounding: Option<Real>,
    /// What `omega` measures where it is not Ω: "E and |L|" (each relative
    /// to its value at the start) where the secular model answers.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured: Option<&'static str>,
    /// Against what: the model's own exact solution, or the physical
    /// solution of (3.4).
    pub against: String,
    /// How it was estimated, in one sentence.
    pub how: String,
}

impl ErrorEstimate {
    /// One line for a table's header.
    pub fn line(&self) -> String {
        let orientation = match self.orientation {
            Some(o) => format!(", the orientation by {o:.1e} rad"),
            None => String::new(),
        };
        let what = match self.measured {
            Some(m) => format!("{m} may be off by {:.1e} of their start", self.omega),
            None => format!("Omega may be off by {:.1e} of |Omega0|", self.omega),
        };
        format!(
            "{what}{orientation}, against {} ({})",
            self.against, self.how
        )
    }

    /// The larger of the two errors.
    pub fn worst(&self) -> Real {
        self.omega.max(self.orientation.unwrap_or(0.0))
    }

    /// This estimate with a model's own error (against the physical solution
    /// of (3.4)) added to it.
    pub fn with_model_error(mut self, omega: Real, orientation: Real, how: &str) -> Self {
        self.omega += omega;
        if let Some(o) = &mut self.orientation {
            *o = (*o + orientation).min(std::f64::consts::PI as Real);
        }
        self.against = "the physical solution of (3.4)".to_string();
        self.how = format!("{how}; {}", self.how);
        self
    }
}

/// What rounding alone may leave after turning `angle` radians: a few
/// units in the last place, and 4ε per radian of the phase (each step
/// rounds the phase it adds; a long run's phase is as good as its last
/// digits). Measured on the symmetric and general tops of the tests: the
/// tightest runs stayed below a quarter of it.
pub fn rounding(angle: Real) -> Real {
    1e-14 + 4.0 * Real::EPSILON * angle.abs()
}

/// What rounding alone may leave in Ω, relative to |Ω₀|: a phase error
/// δφ moves Ω by δφ times the part of Ω that turns (Ω⊥ for a symmetric top,
/// all of Ω for another), so the phase's [`rounding`] at each sample counts
/// in proportion to that part there (a decayed Ω⊥ has no phase to lose).
/// A phase lost entirely moves the turning part by at most twice its size,
/// so the phase's share is capped at 2 (past some 10¹⁶ rad the phase is
/// unknown in doubles, and the bound says so, but no more than that).
/// `points` are (t, Ω(t)).
pub fn omega_rounding(
    model: &Model,
    omega0: &Vec3,
    points: impl IntoIterator<Item = (Real, Vec3)>,
) -> Real {
    let scale = omega0.norm();
    if scale == 0.0 {
        return rounding(0.0);
    }
    let symmetric = matches!(
        model,
        Model::Truncated(_) | Model::Reduced(_) | Model::Full(_)
    );
    let worst = points
        .into_iter()
        .map(|(t, w)| {
            let turning = if symmetric { w.x.hypot(w.y) } else { w.norm() };
            let phase = rounding(turning_angle(model, omega0, t)) - rounding(0.0);
            phase.min(2.0) * (turning / scale).min(1.0)
        })
        .fold(0.0 as Real, Real::max);
    rounding(0.0) + worst
}

/// The settings of the second run, or `None` where there is none tighter
/// (a closed form, or a tolerance already at [`MIN_RTOL`]).
fn tighter(method: Method, options: &MethodOptions) -> Option<MethodOptions> {
    // NOTE: finer in every cap on a step too (half of it): where a cap holds
    // the steps, a tighter rtol alone gives the same steps, and the two runs
    // agreed to 1e-14 while both were 4e-11 rad off (the orientation of a
    // physical solution at rtol 1e-8, stepped 1 rad at a time).
    match method {
        Method::ClosedForm => None,
        Method::Rk4 => options.with_step(0.5 * options.step()).ok(),
        _ => {
            let rtol = if method == Method::Physical {
                internal_rtol(options.rtol())
            } else {
                options.rtol()
            };
            let tight = (rtol / TIGHTER).max(MIN_RTOL);
            options.with_rtol(tight).ok().map(|o| o.refined(0.5))
        }
    }
}

/// The settings of a looser second run, where a tighter one costs too much.
fn looser(method: Method, options: &MethodOptions) -> Option<MethodOptions> {
    match method {
        Method::ClosedForm => None,
        Method::Rk4 => options.with_step(2.0 * options.step()).ok(),
        _ => options.with_rtol((options.rtol() * TIGHTER).min(1e-3)).ok(),
    }
}

/// The largest angle between two orientations.
fn angle_between(a: &Mat3, b: &Mat3) -> Real {
    let r = a.transpose() * b;
    let skew = (r[(2, 1)] - r[(1, 2)])
        .hypot(r[(0, 2)] - r[(2, 0)])
        .hypot(r[(1, 0)] - r[(0, 1)]);
    (0.5 * skew).atan2(0.5 * (r.trace() - 1.0))
}

/// The error of `samples`, run by `method` on `model` from `initial` at
/// `options`, against the model's own exact solution: the distance to the
/// same run at tighter settings, doubled, plus [`rounding`] over the
/// turning `angle`. `orientation` says whether the samples' orientation is
/// reported.
pub fn numerical_error(
    model: &Model,
    method: Method,
    options: &MethodOptions,
    initial: &InitialState,
    samples: &[Sample],
    angle: Real,
    orientation: bool,
) -> Result<ErrorEstimate, SimError> {
    let floor = rounding(angle);
    let omega_floor = omega_rounding(
        model,
        &initial.omega,
        samples.iter().map(|s| (s.t, s.omega_vec())),
    );
    let scale = initial.omega.norm().max(Real::MIN_POSITIVE);
    let times: Vec<Real> = samples.iter().map(|s| s.t).collect();
    let horizon = times.last().copied();
    let (mut omega, mut turn) = (0.0 as Real, 0.0 as Real);
    let distance = |other: MethodOptions| -> Result<(Real, Real), SimError> {
        let mut again = Simulation::with_method(*model, method, other, *initial, horizon)?;
        let (mut omega, mut turn) = (0.0 as Real, 0.0 as Real);
        for (s, &t) in samples.iter().zip(&times) {
            let other = again.advance_to(t)?;
            omega = omega.max((s.omega_vec() - other.omega_vec()).norm() / scale);
            turn = turn.max(angle_between(
                &s.rotation_matrix(),
                &other.rotation_matrix(),
            ));
        }
        Ok((omega, turn))
    };
    let settings = |o: &MethodOptions| {
        if method == Method::Rk4 {
            format!("step {:e}", o.step())
        } else {
            format!("rtol {:.0e}", o.rtol())
        }
    };
    // Ω's and the orientation's floors, as the `how` quotes them.
    let floors = || {
        if orientation {
            format!("{omega_floor:.0e} in Omega and {floor:.0e} rad in the orientation")
        } else {
            format!("{omega_floor:.0e}")
        }
    };
    let mut safety = SAFETY;
    let how = match tighter(method, options) {
        Some(tight) => match distance(tight) {
            Ok(d) => {
                (omega, turn) = d;
                format!(
                    "twice the distance to the same run at {}, plus {} for rounding, the largest over the samples",
                    settings(&tight),
                    floors()
                )
            }
            // The tighter run would overrun the step budget: a looser one,
            // whose error is the larger, bounds this run's by its distance.
            Err(SimError::TooCostly(_)) => {
                let loose = looser(method, options).ok_or(SimError::OutOfRange(
                    "no second run fits the step budget to estimate the error",
                ))?;
                (omega, turn) = distance(loose)?;
                safety = 1.0;
                format!(
                    "the distance to the same run at {} (a tighter one would overrun the step budget), plus {} for rounding",
                    settings(&loose),
                    floors()
                )
            }
            Err(e) => return Err(e),
        },
        None if method == Method::ClosedForm => {
            format!(
                "closed forms: only rounding, {} over the run's {angle:.1e} rad",
                floors()
            )
        }
        None => format!(
            "the tolerance is already the tightest: rounding, {} over the run's {angle:.1e} rad",
            floors()
        ),
    };
    let against = format!("the exact solution of the {} model", model.name());
    Ok(ErrorEstimate {
        omega: (safety * omega + omega_floor).min(2.0),
        orientation: orientation.then(|| (safety * turn + floor).min(std::f64::consts::PI as Real)),
        rounding: omega_floor.min(2.0),
        orientation_rounding: orientation.then_some(floor),
        measured: None,
        against,
        how,
    })
}

/// The tightest tolerance a second secular run is taken at.
const SECULAR_TIGHTEST: Real = 1e-13;

// ANCHOR: secular_error
/// The error of a secular `run` of `law` (at `rtol`) in E and |L|, each
/// relative to its value at the start, against the exact solution of its
/// model ((3.3) or the reduced (3.4)), over the run.
///
/// Beyond the paper (first-order averaging).
///
/// ```text
/// error = 2·max |X − X′| + swing + rounding
/// ```
///
/// X′ is the same secular run at rtol/100 (at most 10⁻¹³): the distance is
/// the slow integration's own error, which grows with the drift and not
/// with the turning (at rtol 1e-2 a symmetric top's E was 6.7e-6 off, and
/// the run at 1e-4 4e-8). The swing ([`averaging_error`]) is what averaging
/// leaves out: the invariants of the model swing within each turn about the
/// drift the secular model follows. Rounding is [`rounding`] with no phase
/// (the secular model follows no phase), and, for a top so slow that E is
/// subnormal, the part of E a double drops.
pub fn secular_error(
    top: &GeneralTop,
    law: Law,
    omega0: &Vec3,
    run: &SecularRun,
    rtol: Real,
) -> Result<ErrorEstimate, IntegrateError> {
    // What a double keeps of E itself: a slow top's E (|Ω₀| ≲ 1e-154) is
    // subnormal, or 0 (then nothing of it).
    let s = omega0.norm().max(Real::MIN_POSITIVE);
    let e_unit = invariants(&top.inertia(), &(omega0 / s)).0;
    let floor = rounding(0.0) + (Real::from_bits(1) / s / s / e_unit).min(1.0);
    let swing = swing_over_run(top, law, omega0, run);
    let scale = invariants(&top.inertia(), omega0);
    let times: Vec<Real> = run.samples.iter().map(|s| s.t).collect();
    let tight = (rtol / TIGHTER).max(SECULAR_TIGHTEST);
    let distance = |r: Real| -> Result<Real, IntegrateError> {
        let again = secular(top, law, omega0, &times, r)?;
        Ok(secular_gap(&run.samples, &again.samples, scale))
    };
    let (distance, how) = match (tight < rtol).then(|| distance(tight)) {
        Some(Ok(d)) => (
            SAFETY * d,
            format!("twice the distance to the same run at rtol {tight:.0e}"),
        ),
        // The tighter run would overrun the slow steps allowed: a looser
        // one, whose error is the larger, bounds this run's by its distance.
        Some(Err(IntegrateError::TooManySteps { .. })) => {
            let loose = (rtol * TIGHTER).min(1e-1);
            (
                distance(loose)?,
                format!(
                    "the distance to the same run at rtol {loose:.0e} (a tighter one would overrun the slow steps allowed)"
                ),
            )
        }
        Some(Err(e)) => return Err(e),
        None => (0.0, "the tolerance is already the tightest".to_string()),
    };
    let model = if law == Law::Truncated {
        "general"
    } else {
        "general-reduced"
    };
    Ok(ErrorEstimate {
        omega: (distance + swing + floor).min(2.0),
        orientation: None,
        rounding: floor,
        orientation_rounding: None,
        measured: Some("E and |L|"),
        against: format!("the exact solution of the {model} model"),
        how: format!(
            "{how}, plus {swing:.1e} for the swing of E and |L| within a turn that averaging leaves out (at each sample, and as the drift carries it), plus {floor:.0e} for rounding, the largest over the samples"
        ),
    })
}
// ANCHOR_END: secular_error

/// What averaging leaves out at the samples, relative to the invariants at
/// the start. Two parts, each relative to the sample's own invariants and
/// then scaled by the larger of E/E₀ and |L|/|L₀| there: the swing within a
/// turn on the polhode the sample reached ([`averaging_error`] there), and
/// what the drift carries from earlier turns, the swing at the start scaled
/// by τ_f|Ω| (∝ √E) as it falls. At t = 0 the sample is the input itself.
///
/// NOTE: the swing at the start alone was printed for every sample, but it
/// shrinks as the top slows down: an asymmetric top (issue 46, review F2)
/// printed 8.2e-4 over [0, 2.5·10¹⁰] where its E and |L| were 9.1e-6 off.
/// Nor is the local swing enough: as that top slows, its polhode closes
/// round the third axis and the local swing falls to 1e-5 of the
/// invariants, while the error the averaged drift has gathered over the
/// decay stays at 5e-5 – 2e-4 of them, falling like τ_f|Ω|. Against the
/// top stepped directly, the claim (this with the integration's part) was
/// 2.1–3.4 times the real error at each sample from 2·10⁹ to 2.5·10¹⁰, and
/// 2.6 times over a run sampled from 10⁸ (the test of F2).
fn swing_over_run(top: &GeneralTop, law: Law, omega0: &Vec3, run: &SecularRun) -> Real {
    let i = top.inertia();
    // Scale-free (see `secular`): a slow top's E underflows.
    let (unit, s) = unit_scaled(top, omega0).unwrap_or((*top, 1.0));
    let (e0, l0) = invariants(&i, &(omega0 / s));
    let start = averaging_error(&unit, law, &(omega0 / s));
    run.samples
        .iter()
        .filter(|sample| sample.t > 0.0)
        .map(|sample| {
            let (e, l) = (sample.energy / s / s, sample.l_norm / s);
            let w = Polhode::of(&i, 2.0 * e, l * l).omega_at(0.0);
            let carried = start * (e / e0).max(0.0).sqrt();
            let at = averaging_error(&unit, law, &w).max(carried) * (e / e0).max(l / l0);
            if at.is_finite() { at.min(start) } else { start }
        })
        .fold(0.0, Real::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::symmetric_top::SymmetricTop;

    /// The phase's share of the rounding grows as 4ε per radian while Ω⊥
    /// turns, and stops at twice the turning part: a lost phase moves
    /// (Ω₁, Ω₂) by at most 2|Ω⊥| (the nanoparticle of the real-particles
    /// chapter turns 2·10¹⁹ rad and printed 2.4e2 of |Ω₀| before the cap).
    #[test]
    fn omega_rounding_grows_with_the_phase_and_stops_at_twice_the_turning_part() {
        let model = Model::Reduced(SymmetricTop::figure());
        let omega0 = Vec3::new(0.0, 0.6, 0.8);
        let at = |t: Real| omega_rounding(&model, &omega0, [(t, omega0)]);
        let angle = |t: Real| turning_angle(&model, &omega0, t);
        let share = 0.6;
        assert!(
            (at(1e3) - (rounding(0.0) + 4.0 * Real::EPSILON * angle(1e3) * share)).abs() < 1e-20
        );
        assert!(
            at(1e30) <= rounding(0.0) + 2.0 * share + 1e-15,
            "{}",
            at(1e30)
        );
        assert!(at(1e30) >= 2.0 * share);
        // A decayed Ω⊥ has no phase to lose, however long the run.
        let stood_up = Vec3::new(0.0, 0.0, 0.8);
        assert_eq!(
            omega_rounding(&model, &omega0, [(1e30, stood_up)]),
            rounding(0.0)
        );
    }
}
