//! What a run will cost, estimated before it starts.
//!
//! One estimate for every caller: [`crate::sim::Simulation::new`] refuses a
//! run whose estimate is above [`MAX_STEPS`] (so `simulate`, `plot`, the live
//! view and scenes never allocate or step from an unchecked horizon), and the
//! scene planner uses the same [`turning_angle`] and [`FULL_TURN_PER_STEP`]
//! to choose its method and word its refusals.

use super::{Method, MethodOptions, Model};
use crate::math::{Real, Vec3};
use crate::physics::rigid_body::{energy, omega_perp};
use crate::physics::symmetric_top::truncated_clock;

/// The most steps (or table points) one run may take: the integrators' own cap.
pub const MAX_STEPS: Real = crate::integrate::DEFAULT_MAX_STEPS as Real;

/// The step budget as the help and the book state it, in one place: what
/// is refused before a run starts (the estimate, [`estimate`]), what the
/// steps count, and what stops a run while it runs.
pub fn budget_rule() -> String {
    format!(
        "A run estimated at more than {} steps (accepted and rejected, from the steps per radian each method was measured to take) is refused before it starts, with the estimate and a cheaper way; the steps of the run's error estimate (the same run at a tighter rtol) come on top, and any single integration that still passes {} steps stops the run with exit 3",
        crate::numbers::fmt_budget(MAX_STEPS),
        crate::numbers::fmt_budget(MAX_STEPS)
    )
}

/// The full model's physical solution is tabulated with hΩ ≤ 0.05.
pub const FULL_TURN_PER_STEP: Real = 0.05;

// ANCHOR: steps_per_radian
/// Steps (accepted and rejected) DP5, DOP853, Radau IIA 5 and the Taylor
/// method take per radian the body turns, at each tolerance: the most any of
/// six free tops took (asymmetric, elongated, near the separatrix,
/// symmetric), Ω and the orientation stepped together, with 10 % to spare
/// (30 % for Radau IIA 5, measured on fewer turns; the Taylor method's on
/// the three asymmetric tops of `crates/spintop/tests/numerics/cost.rs`, which measures
/// them all again).
const STEPS_PER_RADIAN: [(Real, [Real; 4]); 8] = [
    //  rtol    DP5   DOP853 Radau5 Taylor
    (1e-4, [3.2, 1.0, 3.5, 2.0]),
    (1e-6, [6.6, 1.1, 7.8, 2.0]),
    (1e-8, [16.0, 2.3, 18.0, 1.9]),
    (1e-10, [41.0, 4.0, 37.0, 1.9]),
    (1e-11, [64.0, 5.4, 54.0, 1.9]),
    (1e-12, [100.0, 6.9, 78.0, 1.9]),
    (1e-13, [155.0, 9.0, 113.0, 1.9]),
    (1e-14, [242.0, 12.6, 165.0, 1.9]),
];
// ANCHOR_END: steps_per_radian

/// Steps an adaptive method takes per radian of turning at `rtol`, read
/// from [`STEPS_PER_RADIAN`] (linear in ln steps against ln rtol between its
/// rows, its end rows beyond them); 1 for any other method, which the
/// orientation's 1 rad per step bounds.
pub fn steps_per_radian(method: Method, rtol: Real) -> Real {
    let column = match method {
        Method::Dopri5 => 0,
        Method::Dop853 => 1,
        Method::Radau5 => 2,
        Method::Taylor => 3,
        _ => return 1.0,
    };
    let x = rtol.clamp(1e-14, 1e-4).log10();
    let rows = &STEPS_PER_RADIAN;
    let i = rows
        .windows(2)
        .position(|w| x >= w[1].0.log10())
        .unwrap_or(rows.len() - 2);
    let (x0, y0) = (rows[i].0.log10(), rows[i].1[column].ln());
    let (x1, y1) = (rows[i + 1].0.log10(), rows[i + 1].1[column].ln());
    (y0 + (y1 - y0) * (x - x0) / (x1 - x0)).exp()
}

/// How fast an integrator's error of Ω and the orientation grows with the
/// turning: after φ radians at tolerance r it is about r·(1 + C·φ²). Over
/// many turns every step's error in the invariants shifts the frequency of
/// the motion, and the phase error is the integral of that shift; C is the
/// largest r·φ² ratio DOP853 showed on the six tops of [`STEPS_PER_RADIAN`]
/// (4.7e-3, for the orientation of an asymmetric top), rounded up.
pub const PHASE_GROWTH: Real = 5e-3;

/// The estimated error of Ω and the orientation, relative, after stepping
/// `angle` radians at integrator tolerance `rtol`.
pub fn stepping_error(rtol: Real, angle: Real) -> Real {
    rtol * (1.0 + PHASE_GROWTH * angle * angle)
}

/// The tightest tolerance the planner asks of an integrator: below it,
/// rounding in a double takes over from the method's own error.
pub const TIGHTEST_RTOL: Real = 1e-13;

/// How a run that steps Ω will be stepped to stay within `rtol` over `angle`
/// radians: the integrator's tolerance (at most `rtol`, tightened so that
/// [`stepping_error`] stays within `rtol`), its steps, and its error; `None`
/// when even [`TIGHTEST_RTOL`] would not hold the error within `rtol`.
pub fn tolerance_for(rtol: Real, angle: Real) -> Option<Real> {
    let needed = rtol / (1.0 + PHASE_GROWTH * angle * angle);
    (needed >= TIGHTEST_RTOL).then_some(needed.min(rtol))
}

/// How far the body turns by `t`, in radians: exactly |Ω₀|ϑ(t) for the
/// truncated model (every rate falls as 1/R), at most |Ω₀|t for the reduced
/// and full ones (neither speeds up), and about √(2E₀/I_min) t for the general
/// top (a bound on |Ω| while the energy does not grow).
pub fn turning_angle(model: &Model, omega0: &Vec3, t: Real) -> Real {
    match model {
        Model::Truncated(top) => {
            omega0.norm() * truncated_clock(top, omega_perp(omega0), t).vartheta
        }
        Model::Reduced(_) | Model::Full(_) => omega0.norm() * t,
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            let inertia = top.inertia();
            (2.0 * energy(&inertia, omega0) / inertia.min()).sqrt() * t
        }
    }
}

/// An estimate of a run's work.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Steps (or table points) the run would take.
    pub steps: Real,
    /// What takes them, for the message ("RK4 with --step 0.01", …).
    pub what: String,
    /// The cheaper way to the same answer, for the message (each entry
    /// point names its settings: `crate::output::too_costly`).
    pub cheaper: Cheaper,
}

/// The cheaper way a refusal over the step budget points to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cheaper {
    /// The closed forms (method `auto` or `exact`) answer any time at once.
    ClosedForms,
    /// The closed forms (method `exact`) take no steps at all.
    Exact,
    /// An earlier last time.
    EarlierTime,
    /// An earlier last time; a scene answers Ω alone from its closed form.
    EarlierOrOmegaAlone,
}

/// The work of a run of `model` by `method` from `omega0` to `t_last`;
/// `None` when nothing is stepped (a closed form).
pub fn estimate(
    model: &Model,
    method: Method,
    options: &MethodOptions,
    omega0: &Vec3,
    t_last: Real,
) -> Option<Estimate> {
    let angle = turning_angle(model, omega0, t_last);
    let closed = model.has_closed_form();
    let cheaper = if closed {
        Cheaper::ClosedForms
    } else {
        Cheaper::EarlierTime
    };
    let e = |steps: Real, what: String| {
        Some(Estimate {
            steps,
            what,
            cheaper,
        })
    };
    match (model, method) {
        (_, Method::ClosedForm) => None,
        (_, Method::ClosedFormDop853) => Some(Estimate {
            steps: angle,
            what: "the reduced model's orientation (no closed form; at most 1 rad per step)".into(),
            cheaper: Cheaper::EarlierOrOmegaAlone,
        }),
        (_, Method::Rk4) => e(
            t_last / options.step(),
            format!(
                "RK4 with step {}",
                crate::numbers::fmt_value(options.step())
            ),
        ),
        (Model::Full(top), Method::Forward) => {
            // A forward run stops at its runaway, a few tau in; its table is
            // still sized by the horizon.
            e(
                angle / FULL_TURN_PER_STEP,
                "the full ALE (3.4) forward".into(),
            )
            .map(|mut x| {
                x.steps = x.steps.max(t_last / (0.25 * top.tau()));
                x
            })
        }
        (Model::GeneralFull(top), method) => {
            // Each 40 tau_f segment costs about ten backward shots over twice
            // its length, each step at most tau_f/4 (the fast modes' scale).
            let tau_f = crate::sim::physical::general::fast_time(top);
            let table = (angle / FULL_TURN_PER_STEP).max(t_last / (0.25 * tau_f));
            let (steps, what) = if method == Method::Forward {
                (table, "the full ALE (3.4) of a general top forward")
            } else {
                (
                    20.0 * table,
                    "the full ALE (3.4)'s physical solution for a general top (about twenty backward passes, steps <= tau_f/4)",
                )
            };
            e(steps, what.into())
        }
        (Model::Full(top), _) => e(
            symmetric_physical_steps(top, omega0, options, t_last),
            "the full ALE (3.4)'s physical solution (its table until Omega_perp takes its closed form, the orientation stepped until Omega_perp no longer turns it)"
                .into(),
        ),
        (Model::Reduced(top), Method::Dopri5 | Method::Dop853 | Method::Taylor) => {
            let turning = angle * steps_per_radian(method, options.rtol());
            // The reduced model's damping rate never falls below tau k^2
            // (k = (I3/I1) Omega3 is constant), and an explicit method's step
            // cannot exceed its stability limit over that rate: about 3.3/λ
            // for DP5 and 6/λ for DOP853 (the where-methods-fail chapter
            // measures 19378 DP5 steps at S = 1000, t = 10; this gives 19393).
            // The Taylor method's is its series' stability interval, 5.45/λ
            // at rtol 1e-8 to 8.1/λ at 1e-14.
            let k = top.ratio() * omega0.z;
            let rate = top.tau() * k * k;
            let limit = match method {
                Method::Dopri5 => 3.3,
                Method::Taylor => crate::integrate::taylor::stability_interval(options.rtol()),
                _ => 6.0,
            };
            let stiff = t_last * rate / limit;
            if stiff > turning {
                Some(Estimate {
                    steps: stiff,
                    what: format!(
                        "{} on a stiff problem (the damping rate τk² = {rate:.2e}/τ holds an explicit step below {:.1e}τ)",
                        method_name(method, model),
                        limit / rate
                    ),
                    cheaper: Cheaper::Exact,
                })
            } else {
                e(turning, per_radian(method, model, options))
            }
        }
        (_, _) => e(
            angle * steps_per_radian(method, options.rtol()),
            per_radian(method, model, options),
        ),
    }
}

/// Backward passes of a shot piece, at most (the shoot's bracket and
/// regula falsi, and the pass that records the nodes).
const SHOT_PASSES: Real = 20.0;

/// The margin on the settling times guessed before the run.
const SETTLING_MARGIN: Real = 1.25;

/// The steps of the symmetric top's physical solution of (3.4) to `t_last`
/// ([`crate::sim::physical::slow`]): only until it settles
/// ([`settling`](crate::sim::physical::slow::settling)), for past that Ω
/// and the orientation are closed forms, so a long horizon or a fast spin
/// whose Ω⊥ has decayed costs no more than the decay itself.
///
/// - the table: up to [`SHOT_PASSES`] passes over nodes [`NODE_TURN`] apart
///   in ln w, until its closed-form tail; w′/w ≈ c₀ + c₁u, and u falls at
///   least as fast as u₀/(1 + 2τu₀t) (the reduced amplitude (4.16) without
///   its exponential), so ∫|w′/w| dt ≤ |c₀|t + |c₁| ln(1 + 2τu₀t)/(2τ);
/// - the orientation Q (O = Q·R_z(Ω̃₃t)), turning at |(w, k)| ≤ |w| + |k|
///   (∫|w| dt ≤ (√(1 + 2τu₀t) − 1)/(τ√u₀) on the same bound of u) and
///   driven by w, which changes at |w′/w|: DOP853's measured steps per
///   radian ([`steps_per_radian`]) at the orientation's tolerance, rtol/10,
///   until Ω⊥ no longer turns it.
fn symmetric_physical_steps(
    top: &crate::physics::symmetric_top::SymmetricTop,
    omega0: &Vec3,
    options: &MethodOptions,
    t_last: Real,
) -> Real {
    use crate::sim::physical::slow::{NODE_TURN, settling};
    if t_last.is_nan() {
        return Real::NAN;
    }
    let settle = settling(top, omega0);
    let [c0, c1] = settle.c;
    let (tau, u0) = (top.tau(), omega_perp(omega0).powi(2));
    // ∫₀ᵗ u dt ≤ ln(1 + 2τu₀t)/(2τ) (u₀t where τ = 0).
    let u_integral = |t: Real| {
        if tau > 0.0 {
            (2.0 * tau * u0 * t).ln_1p() / (2.0 * tau)
        } else {
            u0 * t
        }
    };
    let table_time = t_last.min(SETTLING_MARGIN * settle.tail);
    let still_time = t_last.min(SETTLING_MARGIN * settle.still);
    let w_turn = |t: Real| c0 * t + c1 * u_integral(t);
    // Nodes are spaced at |w′/w| + 4|w′/w − c₀| ≤ |c₀| + 5|c₁|u.
    let table = SHOT_PASSES * (c0 * table_time + 5.0 * c1 * u_integral(table_time)) / NODE_TURN;
    // Q turns at |(w, k)| ≤ |w| + |k|, and ∫|w| dt ≤ ∫ a₀/√(1 + 2τu₀t) dt
    // = a₀(√(1 + 2τu₀t) − 1)/(τu₀), written without the cancellation.
    let a0 = omega_perp(omega0);
    let perp_turn = |t: Real| 2.0 * a0 * t / (1.0 + (1.0 + 2.0 * tau * u0 * t).sqrt());
    let turning = (top.ratio() * omega0.z).abs() * still_time + perp_turn(still_time);
    let per_radian = steps_per_radian(Method::Dop853, 0.1 * options.rtol());
    table + (turning + w_turn(still_time)) * per_radian
}

/// "DOP853 at rtol 1e-10 (about 4.0 steps per radian of turning, measured)".
fn per_radian(method: Method, model: &Model, options: &MethodOptions) -> String {
    let name = method_name(method, model);
    match method {
        Method::Dopri5 | Method::Dop853 | Method::Radau5 | Method::Taylor => format!(
            "{name} at rtol {:.0e} (about {:.1} steps per radian of turning, measured)",
            options.rtol(),
            steps_per_radian(method, options.rtol())
        ),
        _ => format!("{name} (at most 1 rad of turning per step)"),
    }
}

fn method_name(method: Method, model: &Model) -> &'static str {
    match method {
        Method::Dopri5 => "DP5",
        Method::Dop853 if matches!(model, Model::General(_)) => "DOP853 on the general top (3.3)",
        Method::Dop853 => "DOP853",
        Method::Radau5 => "Radau IIA 5",
        Method::Taylor => "the Taylor method",
        _ => "the integration",
    }
}

/// Refuses a run whose estimate exceeds [`MAX_STEPS`] (or is not finite).
pub fn check(
    model: &Model,
    method: Method,
    options: &MethodOptions,
    omega0: &Vec3,
    t_last: Real,
) -> Result<(), TooCostly> {
    match estimate(model, method, options, omega0, t_last) {
        Some(e) if e.steps.is_nan() || e.steps > MAX_STEPS => Err(TooCostly {
            estimate: e,
            t_last,
        }),
        _ => Ok(()),
    }
}

/// The one wording of a run over the step budget, on the command line and
/// in a scene: `{what} would take about N steps to reach t = T, more than the
/// 1e7 allowed` (the cheaper way follows, in the entry point's words).
pub fn over_budget(what: &str, steps: Real, t_last: Real) -> String {
    format!(
        "{what} would take {} steps to reach t = {}, more than the {} allowed",
        crate::numbers::fmt_about(steps),
        crate::numbers::fmt_time(t_last),
        crate::numbers::fmt_budget(MAX_STEPS)
    )
}

/// A run refused before it started. Its `Display` names no setting; an
/// entry point renders it with its own (`crate::output::too_costly`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", over_budget(&estimate.what, estimate.steps, *t_last))]
pub struct TooCostly {
    /// The estimate.
    pub estimate: Estimate,
    /// The last time asked for.
    pub t_last: Real,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::symmetric_top::SymmetricTop;

    #[test]
    fn rk4_costs_t_over_h_and_the_closed_form_nothing() {
        let top = SymmetricTop::figure();
        let o = MethodOptions::default();
        let w = Vec3::new(0.0, 0.1, 0.2);
        let e = estimate(&Model::Reduced(top), Method::Rk4, &o, &w, 100.0).unwrap();
        assert_eq!(e.steps, 1e4);
        assert!(estimate(&Model::Truncated(top), Method::ClosedForm, &o, &w, 1e300).is_none());
        assert!(check(&Model::Reduced(top), Method::Rk4, &o, &w, 1e6).is_err());
        assert!(check(&Model::Reduced(top), Method::Rk4, &o, &w, 1e4).is_ok());
    }

    #[test]
    fn stiffness_of_the_reduced_model_bounds_an_explicit_methods_steps() {
        // Where methods fail, row 3: S = 1000, t = 10, DP5 took 19378 steps,
        // held by its stability limit whatever the tolerance; at rtol 1e-6
        // the turning (2236 rad at 6.6 steps per radian) asks for fewer.
        let top = SymmetricTop::figure();
        let o = MethodOptions::default().with_rtol(1e-6).unwrap();
        let w = Vec3::new(0.0, 100.0, 200.0);
        let e = estimate(&Model::Reduced(top), Method::Dopri5, &o, &w, 10.0).unwrap();
        assert!((e.steps / 19378.0 - 1.0).abs() < 0.01, "{e:?}");
        assert!(e.what.contains("stiff"), "{e:?}");
        // In the symbols of the rest of the screen, not spelled out.
        assert!(e.what.contains("τk²") && !e.what.contains("tau"), "{e:?}");
        // At the default rtol the turning's measured steps per radian (on
        // tumbling tops) dominate: an upper bound, above the 19378 steps.
        let o = MethodOptions::default();
        let e = estimate(&Model::Reduced(top), Method::Dopri5, &o, &w, 10.0).unwrap();
        assert!(e.steps > 19378.0 && e.what.contains("per radian"), "{e:?}");
        // A thousand times longer is refused up front, naming the stiffness.
        let err = check(&Model::Reduced(top), Method::Dop853, &o, &w, 1e4).unwrap_err();
        assert!(
            err.to_string().contains("stiff") && err.estimate.cheaper == Cheaper::Exact,
            "{err}"
        );
    }

    #[test]
    fn the_physical_solutions_cost_stops_where_it_settles() {
        let top = SymmetricTop::figure();
        let o = MethodOptions::default();
        let w = Vec3::new(0.0, 0.1, 0.2);
        let steps = |t: Real| {
            estimate(&Model::Full(top), Method::Physical, &o, &w, t)
                .unwrap()
                .steps
        };
        // Nondecreasing in the horizon, and no dearer past the settling
        // time than at it: 1e8 and 1e300 cost the same, within the budget.
        let horizons = [10.0, 100.0, 1e3, 1e4, 1e5, 1e8, 1e300];
        for pair in horizons.windows(2) {
            assert!(steps(pair[0]) <= steps(pair[1]), "{pair:?}");
        }
        assert_eq!(steps(1e8), steps(1e300));
        assert!(steps(1e300) < MAX_STEPS);
        // A rate beyond any budget, and a NaN horizon, are refused.
        let wild = Vec3::new(0.0, 1e50, 1e50);
        assert!(check(&Model::Full(top), Method::Physical, &o, &wild, 10.0).is_err());
        assert!(check(&Model::Full(top), Method::Physical, &o, &w, Real::NAN).is_err());
        // Without radiation's decay (k = 0 and tau k^2 = 0, Omega_perp falls
        // only algebraically) the cost still grows with the horizon.
        let tumbling = Vec3::new(0.0, 0.5, 0.0);
        let cost = |t: Real| {
            estimate(&Model::Full(top), Method::Physical, &o, &tumbling, t)
                .unwrap()
                .steps
        };
        assert!(cost(1e4) < cost(1e6) && cost(1e6) < MAX_STEPS);
        assert!(check(&Model::Full(top), Method::Physical, &o, &tumbling, 1e300).is_err());
    }
}
