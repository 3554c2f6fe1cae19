//! `model = "auto"`: which of the truncated ALE, the reduced ALE and the
//! physical solution of (3.4) answers a top scene, judged by their error
//! estimates ([`crate::sim::accuracy`]) in Ω and, where the run reports it,
//! in the orientation; and how an asymmetric top's run is answered
//! (stepped, secular, or refused). [`super::plan`] turns the choice into a
//! plan.

use crate::math::{Real, Vec3};
use crate::numbers::{fmt_about, fmt_time};
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::accuracy::{
    ModelErrors, changes_nothing, general_errors, secular_errors, symmetric_errors,
};
use crate::sim::claim::{ModelEstimates, TierEstimate};
use crate::sim::cost::{
    MAX_STEPS, TIGHTEST_RTOL, stepping_error, steps_per_radian, tolerance_for, turning_angle,
};
use crate::sim::measured::symmetric_measured;
use crate::sim::secular::{Law, averaging_error};
use crate::sim::{Method, MethodChoice, MethodOptions, Model, auto_integrator};

/// Above this many steps, `auto` skips the reduced model's orientation
/// rather than integrate it.
///
/// NOTE: the orientation integrator turns the body by at most 1 rad per step;
/// 10⁶ steps (about 1.2 × 10⁷ evaluations of a 3-vector right-hand side) is a
/// fraction of a second. Beyond that, and long before the 10²⁶ steps of a
/// nanoparticle, the question is about Ω, the tilt and the times, which the
/// closed forms answer exactly.
pub const ORIENTATION_STEP_LIMIT: Real = 1e6;

/// Above this phase, in radians, an angle is not resolved by a double
/// (its last digit is worth 10⁻⁷ rad), so orientations are not reported.
pub const MAX_PHASE: Real = 1e9;

/// τk at and above which the reduced model is doubtful (physics notes: its
/// errors are O(τ²) in the precession and O(τ³) in the decay rate, and at
/// τk ~ 1 it is qualitatively wrong).
pub const STRONG_SPIN: Real = 0.3;

/// Above this share of spin lost per radian, the secular model is not
/// offered: averaging over a turn assumes the turn changes little.
pub const SECULAR_MAX_SHARE: Real = 1e-2;

pub(super) fn reduced_tau_k(top: &SymmetricTop, omega0: &Vec3) -> Real {
    top.tau() * (top.ratio() * omega0.z).abs()
}

/// The radiation's share per radian of turning: τ|Ω₀| for the symmetric
/// top (τ = 1 in its units), τ_f|Ω₀| with τ_f = |d|²/min I for any other.
pub fn radiation_share(model: &Model, omega0: &Vec3) -> Real {
    let time = match model {
        Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => top.tau(),
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            crate::sim::physical::general::fast_time(top)
        }
    };
    time * omega0.norm()
}

/// How a general top's run is answered when its method is `auto`.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum GeneralPath {
    /// `auto`'s integrator on Ω and the orientation (DOP853, or the Taylor
    /// method: [`crate::sim::auto_integrator`]), at this integrator
    /// tolerance (at most the scene's, tightened so that the error over the
    /// run stays within it), taking about this many steps.
    Stepped {
        /// The integrator's tolerance.
        rtol: Real,
        /// The steps it will take.
        steps: Real,
    },
    /// The secular model (E and |L| alone), good to about `error`.
    Secular {
        /// Its estimated error, relative.
        error: Real,
    },
    /// Neither holds the answer within `rtol`: the refusal, with the cheaper ways.
    Neither(String),
}

// ANCHOR: general_path
/// How to answer a general top over `t_last` within `rtol`: stepped, with
/// the tolerance that keeps the integrator's error within `rtol` if that
/// fits the step budget; else the secular model, if its own error
/// ([`averaging_error`]) is within `rtol`; else neither, with what to ask
/// for instead.
pub(super) fn general_path(model: &Model, omega0: &Vec3, t_last: Real, rtol: Real) -> GeneralPath {
    let angle = turning_angle(model, omega0, t_last);
    let per_radian = |r: Real| steps_per_radian(auto_integrator(r), r);
    let stepped = tolerance_for(rtol, angle).map(|r| (r, angle * per_radian(r)));
    if let Some((r, steps)) = stepped
        && steps <= MAX_STEPS
    {
        return GeneralPath::Stepped { rtol: r, steps };
    }
    if !matches!(model, Model::General(_) | Model::GeneralReduced(_)) {
        return GeneralPath::Neither(format!("{} has no secular model", model.name()));
    }
    let share = radiation_share(model, omega0);
    let secular_error = secular_error(model, omega0);
    if let Some(error) = secular_error
        && error <= rtol
    {
        return GeneralPath::Secular { error };
    }
    // A general top turns in proportion to the time (also when the whole
    // turning overflows a double).
    let rate = turning_angle(model, omega0, 1.0);
    let t_max = longest_stepped_turning(rtol, angle) / rate;
    let why = match stepped {
        Some((r, steps)) => crate::sim::cost::over_budget(
            &format!("stepping at rtol {}", crate::numbers::exponent(r, 0)),
            steps,
            t_last,
        ),
        None => format!(
            "an integrator's error of Omega and the orientation grows like the square of the turning: {} even at rtol {TIGHTEST_RTOL:.0e}",
            fmt_about(stepping_error(TIGHTEST_RTOL, angle))
        ),
    };
    let secular = match secular_error {
        Some(e) => match secular_achievable(model, omega0, t_last, e * 1.5) {
            Some(met) => format!(
                "the secular model, which answers E and |L| alone, is offered only at rtol >= {:.0e} (the swing of E and |L| within a turn at the start, {e:.1e}, is above rtol), and there would print an error of {met:.1e} over five samples to t = {} (up to about {e:.1e} with samples early in the run)",
                e * 1.5,
                fmt_time(t_last)
            ),
            None => format!(
                "the secular model, which answers E and |L| alone, is offered only at rtol >= {:.0e} (the swing of E and |L| within a turn at the start, {e:.1e}, is above rtol)",
                e * 1.5
            ),
        },
        None => format!(
            "the secular model is not offered at this radiation share, {} per radian (above {SECULAR_MAX_SHARE:.0e}, where averaging over a turn fails)",
            fmt_about(share)
        ),
    };
    let looser = match secular_error {
        Some(e) => format!("; or rtol >= {:.0e} for the secular model", e * 1.5),
        None => String::new(),
    };
    // Below TIGHTEST_RTOL no run is held within rtol, however short.
    let instead = if t_max > 0.0 {
        format!("ask for times up to {} at this rtol", fmt_time(t_max))
    } else {
        format!("ask for rtol >= {TIGHTEST_RTOL:.0e}")
    };
    // Where the run the command line would make at this rtol is over the
    // step budget, its refusal first, in the same words (`simulate --model
    // general` and a scene then say the same about the steps).
    let budget = MethodOptions::default()
        .with_rtol(rtol)
        .ok()
        .and_then(|o| {
            let method = model.method(MethodChoice::Auto, &o).ok()?;
            crate::sim::cost::check(model, method, &o, omega0, t_last).err()
        })
        .map_or(String::new(), |e| format!("{e}; "));
    GeneralPath::Neither(format!(
        "{budget}the asymmetric top ({}) turns {} rad by t = {}: stepping it cannot hold its answer within rtol = {rtol:.0e} ({why}), and {secular}; {instead}{looser}",
        model.equations(),
        fmt_about(angle),
        fmt_time(t_last)
    ))
}
// ANCHOR_END: general_path

/// The error a secular run of `model` over [0, `t_last`] at `rtol` would
/// print, against its own model ([`crate::sim::claim::secular_error`], the
/// one rule for it), sampled at five evenly spaced times; `None` where the
/// model has no secular form or the run stops.
///
/// NOTE: a refusal quoted the swing at the start ("good to about …") as
/// what the secular model would meet; the run's printed error is what it
/// meets (issue 46, review).
fn secular_achievable(model: &Model, omega0: &Vec3, t_last: Real, rtol: Real) -> Option<Real> {
    let (law, top) = match model {
        Model::General(top) => (Law::Truncated, top),
        Model::GeneralReduced(top) => (Law::Reduced, top),
        _ => return None,
    };
    let rtol = rtol.clamp(crate::sim::MIN_RTOL, 0.5);
    let times: Vec<Real> = (0..5).map(|k| t_last * k as Real / 4.0).collect();
    let run = crate::sim::secular::secular(top, law, omega0, &times, rtol).ok()?;
    crate::sim::claim::secular_error(top, law, omega0, &run, rtol)
        .ok()
        .map(|e| e.omega)
}

/// The secular model's own error ([`averaging_error`]) for a general tier
/// (under (3.3) for `general`, the reduced (3.4) for `general-reduced`),
/// where it is offered: the radiation's share per radian at most
/// [`SECULAR_MAX_SHARE`]. `None` for any other model.
pub(super) fn secular_error(model: &Model, omega0: &Vec3) -> Option<Real> {
    let (law, top) = match model {
        Model::General(top) => (Law::Truncated, top),
        Model::GeneralReduced(top) => (Law::Reduced, top),
        _ => return None,
    };
    (radiation_share(model, omega0) <= SECULAR_MAX_SHARE).then(|| averaging_error(top, law, omega0))
}

/// When `auto` chose the physical solution of a general top for Ω or the
/// orientation and the physical solution does not fit the step budget: the
/// lightest general tier whose secular model holds E and |L| within `tol`
/// over `times` (its drift against the physical solution's,
/// [`secular_errors`], and its own averaging error, [`secular_error`]),
/// with the reason it answers them without the orientation, and its drift
/// (the model's own error in E and |L|, relative). This is what
/// `auto` answers at a longer horizon or a tighter rtol, where stepping no
/// longer fits and the secular model is chosen outright: so a refusal is
/// monotonic in the horizon and in rtol. `None` for a symmetric top, or
/// where no secular model holds.
pub(super) fn secular_fallback(
    tiers: &[Model; 3],
    omega0: &Vec3,
    times: &[Real],
    tol: Real,
) -> Option<(usize, String, Real)> {
    let Model::GeneralReduced(top) = &tiers[1] else {
        return None;
    };
    // Neither secular model is offered at this share: nothing to compute.
    secular_error(&tiers[0], omega0)?;
    let errors = secular_errors(top, omega0, times, tol).ok()?;
    let strong = radiation_share(&tiers[0], omega0) >= STRONG_SPIN;
    let drift = [errors.truncated, errors.reduced];
    let tier = (0..2).find(|&t| {
        (t == 0 || !strong)
            && drift[t] <= tol
            && secular_error(&tiers[t], omega0).is_some_and(|e| e <= tol)
    })?;
    let name = ["the truncated ALE (3.3)", "the reduced ALE"][tier];
    Some((
        tier,
        format!(
            "model = \"auto\": the physical solution of (3.4) would take more steps than allowed, and no lighter model holds Omega and the orientation within rtol = {tol:.0e}; the secular model of {name} holds E and |L| within it (its drift off the physical solution's {:.1e}, its averaging {:.1e}), so it answers them, and the orientation is not computed",
            drift[tier],
            secular_error(&tiers[tier], omega0).unwrap_or(0.0)
        ),
        drift[tier],
    ))
}

/// The longest turning, up to `angle`, that stepping holds within `rtol`
/// on the step budget: where either the error ([`tolerance_for`]) or the
/// budget runs out, both growing with the turning; 0 when no turning is
/// held (rtol below [`TIGHTEST_RTOL`]).
fn longest_stepped_turning(rtol: Real, angle: Real) -> Real {
    let fits = |phi: Real| {
        tolerance_for(rtol, phi)
            .is_some_and(|r| phi * steps_per_radian(Method::Dop853, r) <= MAX_STEPS)
    };
    if fits(angle) {
        return angle;
    }
    // NOTE: halved first, down to where it fits, then bisected: a bisection
    // from 0 alone resolves only angle/2^60, and an angle of 1e299 rad left
    // a bound of 0 (the advice read `times up to 0`).
    let mut hi = angle.min(Real::MAX);
    while hi > 0.0 && !fits(hi) {
        hi *= 0.5;
    }
    if hi == 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (hi, (2.0 * hi).min(angle));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Why the symmetric models' closed-form path (`auto` or `exact`) skips the
/// orientation of a run that turns `angle` radians, if it does: the
/// truncated model's closed form (4.9) past [`MAX_PHASE`], the reduced
/// model's Q′ = QΩ̂ past [`ORIENTATION_STEP_LIMIT`] steps.
pub(super) fn symmetric_orientation_skip(truncated: bool, angle: Real) -> Option<String> {
    let steps = angle; // at most 1 rad per orientation step
    if truncated {
        (angle > MAX_PHASE).then(|| {
            format!(
                "the orientation's phase reaches about {angle:.1e} rad, which a double cannot resolve (its closed form (4.9) would return noise)"
            )
        })
    } else {
        (steps > ORIENTATION_STEP_LIMIT).then(|| {
            format!(
                "the orientation has no closed form, and Q' = Q Omega^(t) would take {} steps (the body turns {} rad, at most 1 rad per step)",
                fmt_about(steps),
                fmt_about(angle)
            )
        })
    }
}

/// Whether a run of `model` by `method` reports the orientation (the
/// general models' secular path, which reports none, aside).
fn reports_orientation(model: &Model, method: MethodChoice, omega0: &Vec3, t_last: Real) -> bool {
    match (model, method) {
        (Model::Truncated(_) | Model::Reduced(_), MethodChoice::Auto | MethodChoice::Exact) => {
            let truncated = matches!(model, Model::Truncated(_));
            symmetric_orientation_skip(truncated, turning_angle(model, omega0, t_last)).is_none()
        }
        _ => true,
    }
}

/// The symmetric top's two lighter models against the physical solution of
/// (3.4): measured ([`symmetric_measured`]) where the physical solution fits
/// the step budget, the orientations where the body turns at most
/// [`crate::sim::measured::DIRECT_TURN`] radians; the leading-order
/// estimates in closed form ([`symmetric_errors`]) for the rest. With how
/// they were found, for the reason.
fn symmetric_model_errors(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
) -> (ModelErrors, &'static str) {
    let t_last = times.last().copied().unwrap_or(0.0);
    let analytic = symmetric_errors(top, omega0, t_last);
    if analytic.exact {
        return (analytic, "their leading terms in closed form");
    }
    match symmetric_measured(top, omega0, times) {
        Some((m, true)) => (m, "measured against it over the run"),
        Some((m, false)) => (
            ModelErrors {
                truncated_orientation: analytic.truncated_orientation,
                reduced_orientation: analytic.reduced_orientation,
                ..m
            },
            "measured against it over the run in Omega, their leading terms in closed form in the orientation",
        ),
        None => (analytic, "their leading terms in closed form"),
    }
}

/// What `model = "auto"` chose: 0 truncated, 1 reduced, 2 physical.
pub(super) struct ModelChoice {
    pub tier: usize,
    pub reason: String,
    /// When the physical solution was chosen only for the orientation: the
    /// lighter closed-form tier that holds Ω within rtol, and why its
    /// orientation is left out, for a run the physical solution cannot
    /// take on the step budget.
    pub without_orientation: Option<(usize, String)>,
    /// When the physical solution was chosen: why, for the refusal of a run
    /// it cannot take (the lighter model that holds Ω, if any).
    pub why_physical: Option<String>,
    /// The estimates of the two lighter models, as printed.
    pub estimates: ModelEstimates,
}

impl ModelChoice {
    /// The estimated error of `tier` against the physical solution (`None`
    /// for the physical solution itself), with its orientation where the
    /// run reports it.
    pub fn model_error(&self, tier: usize) -> Option<TierEstimate> {
        match tier {
            0 => Some(self.estimates.truncated),
            1 => Some(self.estimates.reduced),
            _ => None,
        }
    }
}

// ANCHOR: choose_model
/// `model = "auto"`: the lightest of the truncated ALE, the reduced ALE and
/// the physical solution of (3.4) whose estimated error over the scene's
/// `times` stays within the scene's tolerance `tol` ([`crate::sim::accuracy`]:
/// closed forms for the symmetric top, the leading errors integrated along
/// the run for any other, in E and |L| when the secular model will answer).
/// The reduced model is never chosen at τk ≥ [`STRONG_SPIN`], where it is
/// qualitatively off.
pub(super) fn choose_model(
    tiers: &[Model; 3],
    method: MethodChoice,
    omega0: &Vec3,
    times: &[Real],
    tol: Real,
) -> ModelChoice {
    let t_last = times.last().copied().unwrap_or(0.0);
    // `secular`: the run will be answered by the secular model, which
    // reports E and |L| and no orientation.
    let (errors, measured, how, secular) = model_errors(tiers, omega0, times, tol);
    let strong = match &tiers[1] {
        Model::Reduced(top) => reduced_tau_k(top, omega0) >= STRONG_SPIN,
        _ => radiation_share(&tiers[0], omega0) >= STRONG_SPIN,
    };
    let name = |tier: usize| {
        [
            "the truncated ALE (3.3)",
            "the reduced ALE",
            "the physical solution of (3.4)",
        ][tier]
    };
    let oriented_exact = |tier: usize| {
        (!secular && reports_orientation(&tiers[tier], method, omega0, t_last)).then_some(0.0)
    };
    if errors.exact {
        return exact_choice(tiers, omega0, t_last, measured, oriented_exact);
    }
    // The orientation counts where the tier's run reports it (an angle in
    // radians against a relative rtol: the rotation matrix's entries move by
    // about that much); the secular model reports none.
    let turns = [errors.truncated_orientation, errors.reduced_orientation];
    let oriented: [Option<Real>; 2] = std::array::from_fn(|tier| {
        (!secular && reports_orientation(&tiers[tier], method, omega0, t_last))
            .then_some(turns[tier])
    });
    let omegas = [errors.truncated, errors.reduced];
    // The lightest tier that `holds` (the reduced model never at strong spin).
    let lightest = |holds: &dyn Fn(usize) -> bool| {
        (0..2)
            .find(|&tier| holds(tier) && (tier == 0 || !strong))
            .unwrap_or(2)
    };
    let tier = lightest(&|t| omegas[t] <= tol && oriented[t].is_none_or(|o| o <= tol));
    let omega_tier = lightest(&|t| omegas[t] <= tol);
    let strong_note = if strong {
        " (qualitatively off at this spin)"
    } else {
        ""
    };
    let turned = match oriented {
        [Some(t), Some(r)] => format!(", and by {t:.1e} and {r:.1e} rad in the orientation"),
        [None, Some(r)] => format!(
            ", and the reduced ALE by {r:.1e} rad in the orientation, which a truncated run would skip"
        ),
        [Some(t), None] => format!(
            ", and the truncated ALE by {t:.1e} rad in the orientation, which a reduced run would skip"
        ),
        [None, None] => String::new(),
    };
    let estimates = format!(
        "model = \"auto\": over the run the truncated ALE (3.3), which drops the Schott term, may be off by {:.1e} and the reduced ALE, right through first order, by {:.1e}{strong_note} in {measured}{turned} (their errors against the physical solution of (3.4), {how})",
        errors.truncated, errors.reduced,
    );
    let without_orientation = (tier == 2 && omega_tier < 2 && tiers[omega_tier].has_closed_form())
        .then(|| {
            let off = turns[omega_tier];
            (
                omega_tier,
                format!(
                    "{estimates}; the physical solution of (3.4) would take more steps than allowed, and the orientation of {} may be off by {off:.1e} rad, more than rtol = {tol:.0e}: {} answers Omega, and the orientation is not computed",
                    name(omega_tier),
                    name(omega_tier)
                ),
            )
        });
    let why_physical = (tier == 2).then(|| {
        if omega_tier < 2 {
            let off = turns[omega_tier];
            format!(
                "model = \"auto\" chose it for the orientation alone: {} holds Omega within rtol = {tol:.0e} (model = \"{}\"), its orientation may be off by {off:.1e} rad",
                name(omega_tier),
                ["truncated", "reduced"][omega_tier]
            )
        } else {
            format!(
                "model = \"auto\" chose it: the truncated and the reduced ALE may be off by {:.1e} and {:.1e}{strong_note} in {measured}, more than rtol = {tol:.0e}",
                errors.truncated, errors.reduced
            )
        }
    });
    let model_estimates = ModelEstimates {
        truncated: TierEstimate {
            omega: errors.truncated,
            orientation: oriented[0],
        },
        reduced: TierEstimate {
            omega: errors.reduced,
            orientation: oriented[1],
        },
        measured,
    };
    ModelChoice {
        tier,
        estimates: model_estimates,
        why_physical,
        reason: format!(
            "{estimates}; the lightest within rtol = {tol:.0e} is {}, so it answers",
            name(tier)
        ),
        without_orientation,
    }
}
// ANCHOR_END: choose_model

/// The two lighter models' errors against the physical solution of (3.4)
/// over the run, what they measure ("Omega" or "E and |L|"), how they were
/// found, and whether the secular model will answer (it reports E and |L|
/// and no orientation).
fn model_errors(
    tiers: &[Model; 3],
    omega0: &Vec3,
    times: &[Real],
    tol: Real,
) -> (ModelErrors, &'static str, &'static str, bool) {
    let t_last = times.last().copied().unwrap_or(0.0);
    // `secular`: the run will be answered by the secular model, which
    // reports E and |L| and no orientation.
    match &tiers[1] {
        Model::Reduced(top) | Model::Truncated(top) | Model::Full(top) => {
            let (errors, how) = symmetric_model_errors(top, omega0, times);
            (errors, "Omega", how, false)
        }
        Model::GeneralReduced(top) | Model::General(top) | Model::GeneralFull(top) => {
            let secular = matches!(
                general_path(&tiers[1], omega0, t_last, tol),
                GeneralPath::Secular { .. }
            );
            match secular.then(|| secular_errors(top, omega0, times, tol)) {
                Some(Ok(e)) => (e, "E and |L|", "along the secular drift of each law", true),
                _ => (
                    general_errors(top, omega0, t_last),
                    "Omega",
                    "their leading terms integrated along the run",
                    secular,
                ),
            }
        }
    }
}

/// Every model is exact: Ω₀ radiates nothing, or too little to change any
/// model by a rounding over the run. The lightest answers.
fn exact_choice(
    tiers: &[Model; 3],
    omega0: &Vec3,
    t_last: Real,
    measured: &'static str,
    oriented_exact: impl Fn(usize) -> Option<Real>,
) -> ModelChoice {
    let still = match &tiers[0] {
        Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => {
            changes_nothing(top.tau(), omega0, t_last)
        }
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            changes_nothing(
                crate::sim::physical::general::fast_time(top),
                omega0,
                t_last,
            )
        }
    };
    let axis = if still {
        "is so slow that radiation changes no model by a rounding over the run"
    } else if tiers[0].has_closed_form() {
        "lies along the symmetry axis, which carries the dipole"
    } else {
        "is a steady spin about a principal axis along the dipole"
    };
    ModelChoice {
        tier: 0,
        reason: format!(
            "model = \"auto\": Omega0 {axis}, so nothing radiates and every model keeps the same steady spin; the lightest, {}, answers exactly",
            "the truncated ALE (3.3)"
        ),
        without_orientation: None,
        why_physical: None,
        estimates: ModelEstimates {
            truncated: TierEstimate {
                omega: 0.0,
                orientation: oriented_exact(0),
            },
            reduced: TierEstimate {
                omega: 0.0,
                orientation: oriented_exact(1),
            },
            measured,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::cost::PHASE_GROWTH;

    /// The error bound rtol·(1 + Cφ²) reaches the tightest tolerance at
    /// φ = √((rtol/TIGHTEST_RTOL − 1)/C): at rtol 1e-10, 447 rad, found
    /// from a requested turning of 1e299 rad as from one of 1e3.
    #[test]
    fn the_longest_stepped_turning_solves_the_phase_error_law() {
        let rtol = 1e-10;
        let closed = ((rtol / TIGHTEST_RTOL - 1.0) / PHASE_GROWTH).sqrt();
        for angle in [1e3, 1e12, 3.7e299, Real::MAX, Real::INFINITY] {
            let phi = longest_stepped_turning(rtol, angle);
            assert!(
                (phi / closed - 1.0).abs() < 1e-9,
                "{angle}: {phi} vs {closed}"
            );
        }
        assert_eq!(longest_stepped_turning(rtol, 100.0), 100.0);
        assert_eq!(longest_stepped_turning(1e-14, 1e3), 0.0);
    }
}
