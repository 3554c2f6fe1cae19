//! Choosing the lightest model that answers a scene, before anything runs.
//!
//! `auto` takes a closed form wherever one exists and integrates only what
//! has none:
//!
//! | model | Ω(t) | orientation O(t) |
//! |---|---|---|
//! | truncated | closed form (4.7) | closed form (4.9), or skipped when its phase outgrows a double |
//! | reduced | closed form (4.15)–(4.16) | Q′ = QΩ̂(t) alone on SO(3), or skipped when that would take too many steps |
//! | general | DOP853, or the Taylor method at rtol ≤ 1e-10 ([`crate::sim::auto_integrator`]) | the same method, with Ω |
//! | full | physical solution of (3.4), backward shooting | driven by it |
//!
//! A span that would need more steps than [`MAX_STEPS`] is refused for the
//! integrators before they start; with a closed form at hand it is answered
//! from the closed form instead, however long it is.

use crate::math::{Real, Vec3};
use crate::numbers::{fmt_about, fmt_time};
use crate::physics::central::Potential;
use crate::physics::rigid_body::{angular_momentum_body, energy, omega_perp, tilt};
use crate::physics::shell::ShellModel;
use crate::physics::symmetric_top::{
    SymmetricTop, reduced_closed_form, reduced_closed_form_many, truncated_clock,
    truncated_closed_form,
};
use crate::sim::accuracy::{general_errors, secular_errors, symmetric_errors};
use crate::sim::cost::{TIGHTEST_RTOL, stepping_error, steps_per_radian, tolerance_for};
use crate::sim::orbit::{Force, OrbitConfig};
use crate::sim::secular::{Law, averaging_error};
use crate::sim::{
    InitialState, Method, MethodChoice, MethodOptions, Model, Sample, auto_integrator,
};
use serde::Serialize;

/// The most steps any integration of a scene may take (the integrators' own cap).
pub use crate::sim::cost::MAX_STEPS;

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

/// Euler angles within this sin θ of a pole get a warning.
pub const POLE_SIN: Real = 1e-2;

/// The method used, as outputs label it, and why.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Chosen {
    /// The label of the method (`exact`, `exact+dop853`, `dop853`, …), the
    /// same as the output's `method` where the output has one.
    pub method: String,
    /// Why, in one sentence.
    pub reason: String,
}

impl Chosen {
    fn new(method: &str, reason: impl Into<String>) -> Self {
        Self {
            method: method.to_string(),
            reason: reason.into(),
        }
    }
}

/// Whether a top scene's orientation is computed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// O(t) is computed with Ω(t).
    Computed,
    /// Only the body-frame quantities are given; the string says why.
    Skipped(String),
}

/// Which key a refusal points at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Blame {
    /// `[solve] method`.
    Method,
    /// `[solve] times` / `t_end`.
    Times,
}

/// A top scene that asks for more work than any method may do.
pub(super) struct Refusal {
    pub at: Blame,
    pub message: String,
}

/// What `plan_top` decided.
pub(super) struct TopPlan {
    pub chosen: Chosen,
    pub orientation: Orientation,
    pub warnings: Vec<String>,
    /// The integrator's tolerance, where `auto` tightens the scene's.
    pub rtol: Option<Real>,
}

pub use crate::sim::cost::turning_angle;

/// The label the simulation will report for a method on a model (the
/// method a choice runs is [`Model::method`]'s to say; a refused choice,
/// which the scene's validation has already turned away, is labelled by its
/// name).
fn label(model: &Model, method: MethodChoice, options: &MethodOptions) -> &'static str {
    model
        .method(method, options)
        .map_or(method.name(), |m| m.label())
}

/// How a scene's reason names the integrator `auto` steps an asymmetric top
/// with.
fn integrator_words(method: Method) -> String {
    match method {
        Method::Taylor => format!(
            "the Taylor series method (orientation as a unit quaternion; at rtol <= {:.0e} it is faster than DOP853, measured)",
            crate::sim::TAYLOR_AUTO_RTOL
        ),
        _ => "DOP853 (orientation on SO(3))".to_string(),
    }
}

fn reduced_tau_k(top: &SymmetricTop, omega0: &Vec3) -> Real {
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
    let (Model::General(top) | Model::GeneralReduced(top)) = model else {
        return GeneralPath::Neither(format!("{} has no secular model", model.name()));
    };
    let law = if matches!(model, Model::General(_)) {
        Law::Truncated
    } else {
        Law::Reduced
    };
    let share = radiation_share(model, omega0);
    let secular_error = (share <= SECULAR_MAX_SHARE).then(|| averaging_error(top, law, omega0));
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
        Some((r, steps)) => format!(
            "it would take {} steps at rtol {r:.0e}, more than the {MAX_STEPS:.0e} allowed",
            fmt_about(steps)
        ),
        None => format!(
            "an integrator's error of Omega and the orientation grows like the square of the turning: {} even at rtol {TIGHTEST_RTOL:.0e}",
            fmt_about(stepping_error(TIGHTEST_RTOL, angle))
        ),
    };
    let secular = match secular_error {
        Some(e) => format!(
            "the secular model, which answers E and |L| alone, is good to about {e:.1e} here"
        ),
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
    GeneralPath::Neither(format!(
        "the asymmetric top ({}) turns {} rad by t = {}: stepping it cannot hold its answer within rtol = {rtol:.0e} ({why}), and {secular}; {instead}{looser}",
        model.equations(),
        fmt_about(angle),
        fmt_time(t_last)
    ))
}
// ANCHOR_END: general_path

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
fn symmetric_orientation_skip(truncated: bool, angle: Real) -> Option<String> {
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
    let (errors, measured, how, secular) = match &tiers[1] {
        Model::Reduced(top) | Model::Truncated(top) | Model::Full(top) => (
            symmetric_errors(top, omega0, t_last),
            "Omega",
            "in closed form",
            false,
        ),
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
                    "integrated along the run",
                    secular,
                ),
            }
        }
    };
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
    if errors.exact {
        let axis = if tiers[0].has_closed_form() {
            "lies along the symmetry axis, which carries the dipole"
        } else {
            "is a steady spin about a principal axis along the dipole"
        };
        return ModelChoice {
            tier: 0,
            reason: format!(
                "model = \"auto\": Omega0 {axis}, so nothing radiates and every model keeps the same steady spin; the lightest, {}, answers exactly",
                name(0)
            ),
            without_orientation: None,
            why_physical: None,
        };
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
        "model = \"auto\": over the run the truncated ALE (3.3), which drops the Schott term, may be off by {:.1e} and the reduced ALE, right through first order, by {:.1e}{strong_note} in {measured}{turned} (their leading errors against the physical solution of (3.4), {how})",
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
    ModelChoice {
        tier,
        why_physical,
        reason: format!(
            "{estimates}; the lightest within rtol = {tol:.0e} is {}, so it answers",
            name(tier)
        ),
        without_orientation,
    }
}
// ANCHOR_END: choose_model

/// Above this share of spin lost per radian, the secular model is not
/// offered: averaging over a turn assumes the turn changes little.
pub const SECULAR_MAX_SHARE: Real = 1e-2;

/// Choose how to answer a top scene, refuse what no method can do, and warn
/// where the model is asked for more than it gives.
pub(super) fn plan_top(
    model: &Model,
    method: MethodChoice,
    options: &MethodOptions,
    initial: &InitialState,
    t_last: Real,
    skip_orientation: Option<&str>,
) -> Result<TopPlan, Refusal> {
    let omega0 = initial.omega;
    let angle = turning_angle(model, &omega0, t_last);
    let mut warnings = Vec::new();
    if let Model::Reduced(top) = model {
        let tk = reduced_tau_k(top, &omega0);
        if tk >= STRONG_SPIN {
            warnings.push(format!(
                "tau k = {} >= {STRONG_SPIN}: the reduced model (4.12)-(4.14) is right only through first order in tau k, and its decay rate is off at third order; compare model = \"full\", the physical solution of (3.4)",
                crate::numbers::fixed_or_exp(tk, 3, 3, 1e5)
            ));
        }
    }
    let auto = label(model, MethodChoice::Auto, options);
    let closed = model.has_closed_form();
    let too_many = |steps: Real, what: &str| -> String {
        let hint = if closed {
            "; method = \"auto\" answers from the closed forms instead"
        } else {
            "; ask for shorter times"
        };
        format!(
            "{what} would take {} steps to reach t = {} tau, more than the {MAX_STEPS:.0e} allowed{hint}",
            fmt_about(steps),
            fmt_time(t_last)
        )
    };
    let asked =
        |name: &str| format!("method = \"{name}\" was asked for in [solve]; auto would use {auto}");
    // The symmetric models' path: `top` comes from the match arm below.
    let mut symmetric_path = |top: &SymmetricTop, exact: bool| -> TopPlan {
        let truncated = matches!(model, Model::Truncated(_));
        let skip = skip_orientation
            .map(str::to_string)
            .or_else(|| symmetric_orientation_skip(truncated, angle));
        let orientation = match skip {
            Some(why) => {
                let phase = top.omega3_tilde(omega0.z).abs()
                    * if truncated {
                        truncated_clock(top, omega_perp(&omega0), t_last).vartheta
                    } else {
                        t_last
                    };
                if phase > MAX_PHASE {
                    warnings.push(format!(
                        "the body-frame precession phase of (omega1, omega2) reaches {phase:.1e} rad: their phase is not resolved by a double, while omega_perp, omega3, the tilt and the energy are exact"
                    ));
                }
                Orientation::Skipped(why)
            }
            None => Orientation::Computed,
        };
        let (method_label, how) = match (&orientation, truncated) {
            (Orientation::Skipped(why), true) => (
                "exact",
                format!("omega(t) from the closed form (4.7), the times from (4.6) and (4.16); {why}, so it is skipped"),
            ),
            (Orientation::Skipped(why), false) => (
                "exact",
                format!("omega(t) from the closed form (4.15)-(4.16), the times from (4.6) and (4.16); {why}, so it is skipped"),
            ),
            (Orientation::Computed, true) => (
                "exact",
                "omega(t) from the closed form (4.7) and O(t) from the closed form (4.9), Rot(n_L, |L0| vartheta) O(0) Rz(Omega3~ vartheta): nothing is stepped".to_string(),
            ),
            (Orientation::Computed, false) => (
                "exact+dop853",
                "omega(t) from the closed form (4.15)-(4.16); the orientation has no closed form, so only Q' = Q Omega^(t) is integrated (DOP853 on SO(3)), driven by the closed-form omega(t)".to_string(),
            ),
        };
        let reason = if exact {
            format!("method = \"exact\" was asked for in [solve]: {how}")
        } else {
            how
        };
        TopPlan {
            chosen: Chosen::new(method_label, reason),
            orientation,
            warnings: std::mem::take(&mut warnings),
            rtol: None,
        }
    };
    let plan = match (model, method) {
        (Model::Truncated(top) | Model::Reduced(top), MethodChoice::Auto | MethodChoice::Exact) => {
            symmetric_path(top, method == MethodChoice::Exact)
        }
        (_, MethodChoice::Rk4) => {
            let steps = t_last / options.step();
            if steps > MAX_STEPS {
                return Err(Refusal {
                    at: Blame::Method,
                    message: format!(
                        "[solve] {}",
                        too_many(steps, "method = \"rk4\" with this step")
                    ),
                });
            }
            TopPlan {
                chosen: Chosen::new("rk4", asked("rk4")),
                orientation: Orientation::Computed,
                warnings,
                rtol: None,
            }
        }
        (Model::Full(_) | Model::GeneralFull(_), _) => {
            // The simulation's own estimate (one rule: `sim::cost`), so that
            // a run the simulation would refuse is refused here, with the
            // scene's line, before anything runs.
            let estimate = model
                .method(method, options)
                .ok()
                .and_then(|m| crate::sim::cost::estimate(model, m, options, &omega0, t_last));
            if let Some(e) = &estimate
                && (e.steps.is_nan() || e.steps > MAX_STEPS)
            {
                let at = if method == MethodChoice::Auto {
                    Blame::Times
                } else {
                    Blame::Method
                };
                return Err(Refusal {
                    at,
                    message: format!("[solve] {}", too_many(e.steps, &e.what)),
                });
            }
            let (label, reason) = match method {
                MethodChoice::Forward => ("forward", asked("forward")),
                MethodChoice::Auto => (
                    "physical",
                    "(3.4) has no closed form and runs away forward at a rate of about 1/tau: its physical solution by backward shooting (DOP853), the orientation driven by it".to_string(),
                ),
                other => ("physical", asked(other.name())),
            };
            TopPlan {
                chosen: Chosen::new(label, reason),
                orientation: Orientation::Computed,
                warnings,
                rtol: None,
            }
        }
        (Model::General(_) | Model::GeneralReduced(_), MethodChoice::Auto) => {
            let equations = model.equations();
            match general_path(model, &omega0, t_last, options.rtol()) {
                GeneralPath::Stepped { rtol, steps } => {
                    let tighter = if rtol < options.rtol() {
                        format!(
                            ", at rtol {rtol:.1e}, tighter than the scene's {:.0e} so that its error over {angle:.1e} rad stays within it (an integrator's error of the phase grows like the square of the turning)",
                            options.rtol()
                        )
                    } else {
                        String::new()
                    };
                    let integrator = auto_integrator(rtol);
                    TopPlan {
                        chosen: Chosen::new(
                            integrator.label(),
                            format!(
                                "the asymmetric top ({equations}) has no closed form: omega and the orientation are integrated together by {}{tighter}, about {steps:.1e} steps",
                                integrator_words(integrator)
                            ),
                        ),
                        orientation: Orientation::Computed,
                        warnings,
                        rtol: (rtol < options.rtol()).then_some(rtol),
                    }
                }
                GeneralPath::Secular { error } => {
                    let eps = radiation_share(model, &omega0);
                    let why = format!(
                        "the secular model follows E and |L| only: the phase round the polhode and the orientation after {angle:.1e} rad are beyond what stepping holds within rtol"
                    );
                    TopPlan {
                        chosen: Chosen::new(
                            "secular",
                            format!(
                                "{angle:.1e} rad are too many turns to step within rtol = {:.0e} and the asymmetric top has no closed form, but its radiation changes Omega by only {eps:.1e} per radian: the free motion is taken in closed form (Jacobi's elliptic functions) and only the period-averaged drift of E and |L| under {} is integrated (DOP853), good to about {error:.1e} (the swing of E and |L| within a turn, which averaging leaves out)",
                                options.rtol(),
                                if matches!(model, Model::General(_)) {
                                    "(3.3)"
                                } else {
                                    "the reduced (3.4)"
                                }
                            ),
                        ),
                        orientation: Orientation::Skipped(why),
                        warnings,
                        rtol: None,
                    }
                }
                GeneralPath::Neither(message) => {
                    return Err(Refusal {
                        at: Blame::Times,
                        message: format!("[solve] {message}"),
                    });
                }
            }
        }
        (
            _,
            MethodChoice::Dopri5
            | MethodChoice::Dop853
            | MethodChoice::Radau5
            | MethodChoice::Taylor,
        ) => {
            let name = label(model, method, options);
            let resolved = model.method(method, options).ok();
            let estimate = resolved
                .and_then(|m| crate::sim::cost::estimate(model, m, options, &omega0, t_last));
            if let Some(e) = &estimate
                && (e.steps.is_nan() || e.steps > MAX_STEPS)
            {
                return Err(Refusal {
                    at: Blame::Method,
                    message: format!(
                        "[solve] method = \"{name}\": {}",
                        too_many(e.steps, &e.what)
                    ),
                });
            }
            let drift = stepping_error(options.rtol(), angle);
            if !closed && drift > options.rtol() {
                warnings.push(format!(
                    "over {angle:.1e} rad an integrator's error of the phase grows like the square of the turning: {name} at rtol {:.0e} may be off by about {drift:.1e}; method = \"auto\" tightens the tolerance or answers with the secular model",
                    options.rtol()
                ));
            }
            TopPlan {
                chosen: Chosen::new(name, asked(name)),
                orientation: Orientation::Computed,
                warnings,
                rtol: None,
            }
        }
        (_, MethodChoice::Exact | MethodChoice::Forward) => {
            // Refused while validating [solve] method; said again here
            // rather than assumed.
            return Err(Refusal {
                at: Blame::Method,
                message: match model.check_method(method) {
                    Err(e) => format!("[solve] method = \"{}\": {e}", method.name()),
                    Ok(()) => format!(
                        "[solve] method = \"{}\" cannot be planned here",
                        method.name()
                    ),
                },
            });
        }
    };
    Ok(plan)
}

/// The body-frame observables at one time, where the orientation is skipped.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OmegaSample {
    /// Time, in units of τ.
    pub t: Real,
    /// Time in the scene's output unit (`[units] time_unit`), when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_unit: Option<Real>,
    /// Body-frame Ω, in 1/τ.
    pub omega: [Real; 3],
    /// Ω⊥.
    pub omega_perp: Real,
    /// E = ½ Ω·IΩ.
    pub energy: Real,
    /// L in the body frame.
    pub l_body: [Real; 3],
    /// Angle between the symmetry axis and L.
    pub tilt: Real,
}

/// Ω(t) and the body-frame observables from the closed forms, for the two
/// symmetric models (`None` for the others, which have no closed form).
///
/// Paper: Eq. (4.7), Eq. (4.15), Eq. (4.16).
pub fn omega_samples(
    model: &Model,
    omega0: &Vec3,
    times: &[Real],
    tau_per_unit: Option<Real>,
) -> Option<Vec<OmegaSample>> {
    type ClosedForm = fn(&SymmetricTop, &Vec3, Real) -> Vec3;
    let (top, closed): (SymmetricTop, ClosedForm) = match model {
        Model::Truncated(top) => (*top, truncated_closed_form),
        Model::Reduced(top) => (*top, reduced_closed_form),
        _ => return None,
    };
    let inertia = top.inertia();
    let omegas: Vec<Vec3> = match model {
        Model::Reduced(_) => reduced_closed_form_many(&top, omega0, times),
        _ => times.iter().map(|&t| closed(&top, omega0, t)).collect(),
    };
    Some(
        times
            .iter()
            .zip(omegas)
            .map(|(&t, omega)| OmegaSample {
                t,
                t_unit: tau_per_unit.map(|k| t / k),
                omega: omega.into(),
                omega_perp: omega_perp(&omega),
                energy: energy(&inertia, &omega),
                l_body: angular_momentum_body(&inertia, &omega).into(),
                tilt: tilt(&inertia, &omega),
            })
            .collect(),
    )
}

/// A warning when Euler angles are printed near their pole, where they are
/// degenerate; `None` when every sample is clear of it.
pub fn pole_warning(samples: &[Sample]) -> Option<String> {
    let near: Vec<&Sample> = samples
        .iter()
        .filter(|s| s.euler[1].sin().abs() < POLE_SIN)
        .collect();
    let first = near.first()?;
    Some(format!(
        "{} of {} samples have the Euler angles near their pole (first: theta = {:.3e} rad at t = {}): there z-x-z angles are degenerate, only phi + psi (theta near 0) or phi - psi (theta near pi) is defined, and the rates (4.8) grow like 1/sin(theta); the rotation matrix (JSON, CSV) and the tilt are exact",
        near.len(),
        samples.len(),
        first.euler[1],
        fmt_time(first.t)
    ))
}

/// The choice for a `balance` scene: nothing is integrated.
pub(super) fn balance_choice() -> Chosen {
    Chosen::new(
        "exact",
        "the dipole trajectory is a closed-form function of time: (2.1), (2.2) and (2.4) are evaluated from its exact derivatives, the period averages by the trapezoid rule, exact for trigonometric polynomials",
    )
}

/// The choice for an `orbit` scene, the same mapping as `run_orbit`.
pub(super) fn orbit_choice(config: &OrbitConfig) -> Chosen {
    match (config.force, config.charge.potential()) {
        (Force::LandauLifshitz, Potential::Harmonic) => Chosen::new(
            "exact",
            "the Landau-Lifshitz oscillator is linear: its solution is the closed-form mode of the root of s^2 + tau0 s + 1 = 0",
        ),
        (Force::AbrahamLorentz, Potential::Harmonic) => Chosen::new(
            "exact",
            "the physical solution of (2.5) for the oscillator is the closed-form mode of the physical root of tau0 s^3 - s^2 - 1 = 0",
        ),
        (Force::LandauLifshitz, Potential::Coulomb) => Chosen::new(
            "dop853",
            "the decaying Kepler orbit has no closed form (only its orbit average has): DOP853 on the Landau-Lifshitz equation",
        ),
        (Force::AbrahamLorentz, Potential::Coulomb) => Chosen::new(
            "dop853-backward",
            "(2.5) runs away forward: its physical solution by backward integration (DOP853), shooting on the data at t = 0",
        ),
        (Force::AbrahamLorentzForward, _) => Chosen::new(
            "dop853",
            "force = \"al-forward\" asks for (2.5) integrated forward from the Newtonian acceleration, to show its runaway",
        ),
    }
}

/// The choice for a `shell` scene.
pub(super) fn shell_choice(model: &ShellModel) -> Chosen {
    Chosen::new(
        "rk4-steps",
        format!(
            "(A.1) is a neutral delay equation with no closed form: the method of steps, RK4 with {} steps per delay, from the Abraham-Lorentz mode as history",
            crate::sim::shell::default_steps_per_delay(model.delta())
        ),
    )
}

/// The choice for a `stability` scene.
pub(super) fn stability_choice(row: u8) -> Chosen {
    Chosen::new(
        &format!("stability-row-{row}"),
        format!(
            "row {row} runs a natural method beside spintop's own, each with the methods and times the row fixes (spintop stability --row {row})"
        ),
    )
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
