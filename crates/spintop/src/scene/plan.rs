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
use crate::numbers::fmt_time;
use crate::output::Entry;
use crate::physics::central::Potential;
use crate::physics::rigid_body::{angular_momentum_body, energy, omega_perp, tilt};
use crate::physics::shell::ShellModel;
use crate::physics::symmetric_top::{
    SymmetricTop, reduced_closed_form, reduced_closed_form_many, truncated_clock,
    truncated_closed_form,
};
use crate::sim::claim::ModelEstimates;
use crate::sim::cost::Cheaper;
use crate::sim::orbit::{Force, OrbitConfig};
use crate::sim::{
    InitialState, Method, MethodChoice, MethodOptions, Model, Sample, auto_integrator,
};
use serde::Serialize;

use super::choose::{
    GeneralPath, MAX_PHASE, STRONG_SPIN, general_path, radiation_share, reduced_tau_k,
    secular_error, symmetric_orientation_skip,
};

/// The most steps any integration of a scene may take (the integrators' own cap).
pub use crate::sim::cost::MAX_STEPS;

/// Euler angles within this sin θ of a pole get a warning.
pub const POLE_SIN: Real = 1e-2;

/// The method used, as outputs label it, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Chosen {
    /// The label of the method (`exact`, `exact+dop853`, `dop853`, …), the
    /// same as the output's `method` where the output has one.
    pub method: String,
    /// Why, in one sentence.
    pub reason: String,
    /// With `model = "auto"`: the estimated errors of the two lighter models
    /// against the physical solution of (3.4), by which it chose.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimates: Option<ModelEstimates>,
}

impl Chosen {
    fn new(method: &str, reason: impl Into<String>) -> Self {
        Self {
            method: method.to_string(),
            reason: reason.into(),
            estimates: None,
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

/// What a top scene asks of a plan.
struct Ask<'a> {
    model: &'a Model,
    method: MethodChoice,
    options: &'a MethodOptions,
    omega0: Vec3,
    t_last: Real,
    /// How far the body turns over the run, radians.
    angle: Real,
    skip_orientation: Option<&'a str>,
}

impl Ask<'_> {
    /// The label `auto` would run under.
    fn auto(&self) -> &'static str {
        label(self.model, MethodChoice::Auto, self.options)
    }

    /// The reason of a method the scene asked for.
    fn asked(&self, name: &str) -> String {
        format!(
            "method = \"{name}\" was asked for in [solve]; auto would use {}",
            self.auto()
        )
    }

    /// The one step-budget rule of a planned run (the simulation's own
    /// estimate, [`crate::sim::cost`], so that what it would refuse is
    /// refused here, before anything runs, with the scene's line): `steps`
    /// for `what` over [`MAX_STEPS`] (or not a number) is refused at `at`.
    fn within_budget(
        &self,
        steps: Real,
        what: &str,
        cheaper: Cheaper,
        at: Blame,
    ) -> Result<(), Refusal> {
        if !(steps.is_nan() || steps > MAX_STEPS) {
            return Ok(());
        }
        Err(Refusal {
            at,
            message: format!(
                "[solve] {}; {}",
                crate::sim::cost::over_budget(what, steps, self.t_last),
                crate::output::cheaper(cheaper, Entry::Scene)
            ),
        })
    }

    /// The simulation's estimate of the run by the chosen method, held to
    /// the budget ([`Ask::within_budget`]); `prefix` names the method.
    fn estimate_within_budget(&self, prefix: &str, at: Blame) -> Result<(), Refusal> {
        let estimate = self
            .model
            .method(self.method, self.options)
            .ok()
            .and_then(|m| {
                crate::sim::cost::estimate(self.model, m, self.options, &self.omega0, self.t_last)
            });
        match estimate {
            Some(e) => self.within_budget(e.steps, &format!("{prefix}{}", e.what), e.cheaper, at),
            None => Ok(()),
        }
    }
}

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
    let ask = Ask {
        model,
        method,
        options,
        omega0,
        t_last,
        angle: turning_angle(model, &omega0, t_last),
        skip_orientation,
    };
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
    warnings.extend(crate::sim::regime::fast_spin_note(model, &omega0));
    let computed = |chosen: Chosen, warnings: Vec<String>| TopPlan {
        chosen,
        orientation: Orientation::Computed,
        warnings,
        rtol: None,
    };
    match (model, method) {
        (Model::Truncated(top) | Model::Reduced(top), MethodChoice::Auto | MethodChoice::Exact) => {
            Ok(symmetric_plan(&ask, top, warnings))
        }
        (_, MethodChoice::Rk4) => {
            // The simulation's own estimate (`RK4 with step h`), as on the
            // command line.
            ask.estimate_within_budget("method = \"rk4\": ", Blame::Method)?;
            Ok(computed(Chosen::new("rk4", ask.asked("rk4")), warnings))
        }
        (Model::Full(_) | Model::GeneralFull(_), _) => {
            let at = if method == MethodChoice::Auto {
                Blame::Times
            } else {
                Blame::Method
            };
            ask.estimate_within_budget("", at)?;
            let (label, reason) = match method {
                MethodChoice::Forward => ("forward", ask.asked("forward")),
                MethodChoice::Auto => (
                    "physical",
                    "(3.4) has no closed form and runs away forward at a rate of about 1/tau: its physical solution by backward shooting (DOP853), the orientation driven by it".to_string(),
                ),
                other => ("physical", ask.asked(other.name())),
            };
            Ok(computed(Chosen::new(label, reason), warnings))
        }
        (Model::General(_) | Model::GeneralReduced(_), MethodChoice::Auto) => {
            general_auto_plan(&ask, warnings)
        }
        (
            _,
            MethodChoice::Dopri5
            | MethodChoice::Dop853
            | MethodChoice::Radau5
            | MethodChoice::Taylor,
        ) => {
            let name = label(model, method, options);
            ask.estimate_within_budget(&format!("method = \"{name}\": "), Blame::Method)?;
            // NOTE: no prediction of the error over the run here: the run
            // measures it (`sim::claim`) and the answer warns when it is
            // above rtol (a predicted 2.9e-4 stood beside a real 2.7e-7).
            Ok(computed(Chosen::new(name, ask.asked(name)), warnings))
        }
        (_, MethodChoice::Exact | MethodChoice::Forward) => {
            // Refused while validating [solve] method; said again here
            // rather than assumed.
            Err(Refusal {
                at: Blame::Method,
                message: match model.check_method(method) {
                    Err(e) => format!("[solve] method = \"{}\": {e}", method.name()),
                    Ok(()) => format!(
                        "[solve] method = \"{}\" cannot be planned here",
                        method.name()
                    ),
                },
            })
        }
    }
}

/// The symmetric models' closed forms: Ω exact, the orientation computed
/// or skipped.
fn symmetric_plan(ask: &Ask, top: &SymmetricTop, mut warnings: Vec<String>) -> TopPlan {
    let (model, omega0, t_last) = (ask.model, ask.omega0, ask.t_last);
    let truncated = matches!(model, Model::Truncated(_));
    let skip = ask
        .skip_orientation
        .map(str::to_string)
        .or_else(|| symmetric_orientation_skip(truncated, ask.angle));
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
    let reason = if ask.method == MethodChoice::Exact {
        format!("method = \"exact\" was asked for in [solve]: {how}")
    } else {
        how
    };
    TopPlan {
        chosen: Chosen::new(method_label, reason),
        orientation,
        warnings,
        rtol: None,
    }
}

/// An asymmetric top with `method = "auto"`: stepped (at a tighter rtol
/// where the turning asks for it), or the secular model, or refused.
fn general_auto_plan(ask: &Ask, warnings: Vec<String>) -> Result<TopPlan, Refusal> {
    let (model, options, angle) = (ask.model, ask.options, ask.angle);
    let equations = model.equations();
    // Asked without the orientation (`auto`'s fallback when the physical
    // solution does not fit the budget): the secular model, where it holds.
    let path = match (ask.skip_orientation, secular_error(model, &ask.omega0)) {
        (Some(_), Some(error)) if error <= options.rtol() => GeneralPath::Secular { error },
        _ => general_path(model, &ask.omega0, ask.t_last, options.rtol()),
    };
    match path {
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
            Ok(TopPlan {
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
            })
        }
        GeneralPath::Secular { error } => {
            let eps = radiation_share(model, &ask.omega0);
            let why = ask.skip_orientation.map_or_else(
                || format!(
                    "the secular model follows E and |L| only: the phase round the polhode and the orientation after {angle:.1e} rad are beyond what stepping holds within rtol"
                ),
                |why| format!("the secular model follows E and |L| only: {why}"),
            );
            Ok(TopPlan {
                chosen: Chosen::new(
                    "secular",
                    format!(
                        "{} and the asymmetric top has no closed form, but its radiation changes Omega by only {eps:.1e} per radian: the free motion is taken in closed form (Jacobi's elliptic functions) and only the period-averaged drift of E and |L| under {} is integrated (DOP853); averaging leaves out only the swing of E and |L| within a turn, {error:.1e} here (the error over the run, the integration's and the model's with it, is printed with the samples)",
                        if ask.skip_orientation.is_some() {
                            "the orientation is not held within rtol on the step budget".to_string()
                        } else {
                            format!(
                                "{angle:.1e} rad are too many turns to step within rtol = {:.0e}",
                                options.rtol()
                            )
                        },
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
            })
        }
        GeneralPath::Neither(message) => Err(Refusal {
            at: Blame::Times,
            message: format!("[solve] {message}"),
        }),
    }
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
