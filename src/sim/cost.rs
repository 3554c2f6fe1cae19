//! What a run will cost, estimated before it starts.
//!
//! One estimate for every caller: [`crate::sim::Simulation::new`] refuses a
//! run whose estimate is above [`MAX_STEPS`] (so `simulate`, `plot`, the live
//! view and scenes never allocate or step from an unchecked horizon), and the
//! scene planner uses the same [`turning_angle`] and [`FULL_TURN_PER_STEP`]
//! to choose its method and word its refusals.

use super::{MethodChoice, MethodOptions, Model};
use crate::math::{Real, Vec3};
use crate::physics::rigid_body::{energy, omega_perp};
use crate::physics::symmetric_top::truncated_clock;

/// The most steps (or table points) one run may take: the integrators' own cap.
pub const MAX_STEPS: Real = crate::integrate::DEFAULT_MAX_STEPS as Real;

/// The full model's physical solution is tabulated with hΩ ≤ 0.05.
pub const FULL_TURN_PER_STEP: Real = 0.05;

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
    /// The cheaper way to the same answer, for the message.
    pub cheaper: &'static str,
}

/// The work of a run of `model` by `choice` from `omega0` to `t_last`;
/// `None` when nothing is stepped (a closed form).
pub fn estimate(
    model: &Model,
    choice: MethodChoice,
    options: &MethodOptions,
    omega0: &Vec3,
    t_last: Real,
) -> Option<Estimate> {
    let angle = turning_angle(model, omega0, t_last);
    let closed = model.has_closed_form();
    let cheaper = if closed {
        "the closed forms (method auto or exact) answer any time at once"
    } else {
        "ask for an earlier last time"
    };
    let e = |steps: Real, what: String| {
        Some(Estimate {
            steps,
            what,
            cheaper,
        })
    };
    match (model, choice) {
        (Model::Truncated(_), MethodChoice::Auto | MethodChoice::Exact) => None,
        (Model::Reduced(_), MethodChoice::Auto | MethodChoice::Exact) => Some(Estimate {
            steps: angle,
            what: "the reduced model's orientation (no closed form; at most 1 rad per step)".into(),
            cheaper: "ask for an earlier last time; a scene file (`spintop run`) answers Omega alone from the closed form at any time",
        }),
        (_, MethodChoice::Rk4) => e(
            t_last / options.step,
            format!("RK4 with step {}", crate::math::fmt_value(options.step)),
        ),
        (Model::Full(top), MethodChoice::Forward) => {
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
        (Model::GeneralFull(top), choice) => {
            // Each 40 tau_f segment costs about ten backward shots over twice
            // its length, each step at most tau_f/4 (the fast modes' scale).
            let tau_f = crate::sim::physical::general::fast_time(top);
            let table = (angle / FULL_TURN_PER_STEP).max(t_last / (0.25 * tau_f));
            let (steps, what) = if choice == MethodChoice::Forward {
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
            (angle / FULL_TURN_PER_STEP).max(t_last / (0.25 * top.tau())),
            "the full ALE (3.4)'s physical solution (a table with hOmega <= 0.05 and h <= tau/4)"
                .into(),
        ),
        (
            Model::Reduced(top),
            MethodChoice::Dopri5 | MethodChoice::Dop853 | MethodChoice::Taylor,
        ) => {
            // The reduced model's damping rate never falls below tau k^2
            // (k = (I3/I1) Omega3 is constant), and an explicit method's step
            // cannot exceed its stability limit over that rate: about 3.3/λ
            // for DP5 and 6/λ for DOP853 (the where-methods-fail chapter
            // measures 19378 DP5 steps at S = 1000, t = 10; this gives 19393).
            let k = top.ratio() * omega0.z;
            let rate = top.tau() * k * k;
            // NOTE: the Taylor method's step on y' = −λy is ρ/e² with
            // ρ ≈ (p!)^(1/p)/λ, about 0.6/λ at order 11 (rtol 1e-8) and
            // 0.95/λ at order 18.
            let limit = match choice {
                MethodChoice::Dopri5 => 3.3,
                MethodChoice::Taylor => 0.6,
                _ => 6.0,
            };
            let stiff = t_last * rate / limit;
            if stiff > angle {
                Some(Estimate {
                    steps: stiff,
                    what: format!(
                        "{} on a stiff problem (the damping rate tau k^2 = {rate:.2e}/tau holds an explicit step below {:.1e} tau)",
                        choice_name(choice, model),
                        limit / rate
                    ),
                    cheaper: "the closed forms (--method exact) take no steps at all",
                })
            } else {
                e(
                    angle,
                    format!(
                        "{} (at most 1 rad of turning per step)",
                        choice_name(choice, model)
                    ),
                )
            }
        }
        (
            _,
            MethodChoice::Dopri5
            | MethodChoice::Dop853
            | MethodChoice::Radau5
            | MethodChoice::Taylor
            | MethodChoice::Auto
            | MethodChoice::Exact
            | MethodChoice::Forward,
        ) => e(
            angle,
            format!(
                "{} (at most 1 rad of turning per step)",
                choice_name(choice, model)
            ),
        ),
    }
}

fn choice_name(choice: MethodChoice, model: &Model) -> &'static str {
    match choice {
        MethodChoice::Dopri5 => "DP5",
        MethodChoice::Dop853 => "DOP853",
        MethodChoice::Radau5 => "Radau IIA 5",
        MethodChoice::Taylor => "the Taylor method",
        _ if matches!(model, Model::General(_)) => "DOP853 on the general top (3.3)",
        _ => "the integration",
    }
}

/// Refuses a run whose estimate exceeds [`MAX_STEPS`] (or is not finite).
pub fn check(
    model: &Model,
    choice: MethodChoice,
    options: &MethodOptions,
    omega0: &Vec3,
    t_last: Real,
) -> Result<(), TooCostly> {
    match estimate(model, choice, options, omega0, t_last) {
        Some(e) if e.steps.is_nan() || e.steps > MAX_STEPS => Err(TooCostly {
            estimate: e,
            t_last,
        }),
        _ => Ok(()),
    }
}

/// A run refused before it started.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "{} would take about {:.1e} steps to reach t = {:.3e}, more than the {MAX_STEPS:.0e} allowed; {}",
    estimate.what, estimate.steps, t_last, estimate.cheaper
)]
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
        let o = MethodOptions {
            rtol: 1e-10,
            step: 0.01,
        };
        let w = Vec3::new(0.0, 0.1, 0.2);
        let e = estimate(&Model::Reduced(top), MethodChoice::Rk4, &o, &w, 100.0).unwrap();
        assert_eq!(e.steps, 1e4);
        assert!(estimate(&Model::Truncated(top), MethodChoice::Auto, &o, &w, 1e300).is_none());
        assert!(check(&Model::Reduced(top), MethodChoice::Rk4, &o, &w, 1e6).is_err());
        assert!(check(&Model::Reduced(top), MethodChoice::Rk4, &o, &w, 1e4).is_ok());
    }

    #[test]
    fn stiffness_of_the_reduced_model_bounds_an_explicit_methods_steps() {
        // Where methods fail, row 3: S = 1000, t = 10, DP5 took 19378 steps.
        let top = SymmetricTop::figure();
        let o = MethodOptions {
            rtol: 1e-10,
            step: 0.01,
        };
        let w = Vec3::new(0.0, 100.0, 200.0);
        let e = estimate(&Model::Reduced(top), MethodChoice::Dopri5, &o, &w, 10.0).unwrap();
        assert!((e.steps / 19378.0 - 1.0).abs() < 0.01, "{e:?}");
        assert!(e.what.contains("stiff"), "{e:?}");
        // A thousand times longer is refused up front, naming the stiffness.
        let err = check(&Model::Reduced(top), MethodChoice::Dop853, &o, &w, 1e4).unwrap_err();
        assert!(
            err.to_string().contains("stiff") && err.to_string().contains("--method exact"),
            "{err}"
        );
    }

    #[test]
    fn the_full_models_table_is_sized_before_it_is_allocated() {
        let top = SymmetricTop::figure();
        let o = MethodOptions {
            rtol: 1e-10,
            step: 0.01,
        };
        let w = Vec3::new(0.0, 0.1, 0.2);
        // t = 1e8 tau: 4e8 points at h = tau/4, and |Omega0| t / 0.05 = 4.47e8
        // at h|Omega| = 0.05; the table takes the finer of the two.
        let err = check(&Model::Full(top), MethodChoice::Auto, &o, &w, 1e8).unwrap_err();
        let expected = (w.norm() * 1e8 / 0.05).max(4e8);
        assert!((err.estimate.steps - expected).abs() < 1.0, "{err}");
        assert!(
            check(
                &Model::Full(top),
                MethodChoice::Auto,
                &o,
                &Vec3::new(0.0, 1e50, 1e50),
                10.0
            )
            .is_err()
        );
        assert!(check(&Model::Full(top), MethodChoice::Auto, &o, &w, 1e300).is_err());
        assert!(check(&Model::Full(top), MethodChoice::Auto, &o, &w, 1000.0).is_ok());
        assert!(check(&Model::Full(top), MethodChoice::Auto, &o, &w, Real::NAN).is_err());
    }
}
