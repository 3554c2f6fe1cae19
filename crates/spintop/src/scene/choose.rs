//! `model = "auto"`: which of the truncated ALE, the reduced ALE and the
//! physical solution of (3.4) answers a top scene, judged by their error
//! estimates ([`crate::sim::accuracy`]) in Ω and, where the run reports it,
//! in the orientation; and how an asymmetric top's run is answered
//! (stepped, secular, or refused). [`super::plan`] turns the choice into a
//! plan.

use crate::math::{Real, Vec3};
use crate::numbers::fmt_about;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::accuracy::{
    ModelErrors, changes_nothing, general_errors, secular_errors, symmetric_errors,
};
use crate::sim::claim::{ModelEstimates, TierEstimate};
use crate::sim::cost::turning_angle;
use crate::sim::measured::symmetric_measured;
use crate::sim::{MethodChoice, Model};

/// Above this many steps, `auto` skips the reduced model's orientation
/// rather than integrate it.
///
/// NOTE: the orientation integrator turns the body by at most 1 rad per step;
/// 10⁶ steps (about 1.2 × 10⁷ evaluations of a 3-vector right-hand side) is a
/// fraction of a second. Beyond that, and long before the 10²⁶ steps of a
/// nanoparticle, the question is about Ω, the tilt and the times, which the
/// closed forms answer exactly.
pub const ORIENTATION_STEP_LIMIT: Real = 1e6;

pub use crate::sim::cost::MAX_PHASE;

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

mod general;
#[cfg(test)]
use general::longest_stepped_turning;
pub(super) use general::{GeneralPath, general_path, secular_error, secular_fallback};

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
    use crate::sim::cost::TIGHTEST_RTOL;

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
