//! How `auto` answers an asymmetric top: stepped within the step budget,
//! by the secular model, or refused with what to ask for instead.

use super::{SECULAR_MAX_SHARE, STRONG_SPIN, radiation_share};
use crate::math::{Real, Vec3};
use crate::numbers::{fmt_about, fmt_time};
use crate::sim::accuracy::secular_errors;
use crate::sim::cost::{
    MAX_STEPS, TIGHTEST_RTOL, stepping_error, steps_per_radian, tolerance_for, turning_angle,
};
use crate::sim::secular::{Law, averaging_error};
use crate::sim::{Method, MethodChoice, MethodOptions, Model, auto_integrator};

/// How a general top's run is answered when its method is `auto`.
#[derive(Clone, Debug, PartialEq)]
pub(in crate::scene) enum GeneralPath {
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
pub(in crate::scene) fn general_path(
    model: &Model,
    omega0: &Vec3,
    t_last: Real,
    rtol: Real,
) -> GeneralPath {
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
pub(in crate::scene) fn secular_error(model: &Model, omega0: &Vec3) -> Option<Real> {
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
pub(in crate::scene) fn secular_fallback(
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
pub(super) fn longest_stepped_turning(rtol: Real, angle: Real) -> Real {
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
