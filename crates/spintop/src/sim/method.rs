//! How a model is stepped: the user's choice ([`MethodChoice`]), the method
//! it runs ([`Method`]), and the tolerance and step ([`MethodOptions`]).

use crate::math::Real;
use thiserror::Error;

/// What the user chose: a method by name, or `auto` for the lightest one that
/// is right for the model. Every entry point (the command line's `--method`,
/// a scene's `[solve] method`, the live view's `--method` and `m` key) takes
/// this type, checks it against the model with [`Model::check_method`], and
/// the simulation turns it into the [`Method`] it runs with [`Model::method`]
/// (the one step from a choice to a method).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodChoice {
    /// Closed forms where they exist, DOP853 for the rest (the Taylor
    /// method at rtol ≤ [`TAYLOR_AUTO_RTOL`]).
    Auto,
    /// Closed forms only (refused for a model without one); the reduced
    /// model's orientation, which has none, is still integrated with DOP853.
    Exact,
    /// Fixed-step classical RK4 on Ω and the orientation together.
    Rk4,
    /// Dormand–Prince 5(4) on Ω and the orientation together.
    Dopri5,
    /// DOP853 on Ω and the orientation together.
    Dop853,
    /// Radau IIA of order 5 (implicit, L-stable) on Ω and the orientation
    /// together: for a stiff top (τΩ not small).
    Radau5,
    /// The Taylor series method of variable order on Ω and the orientation
    /// (a unit quaternion) together: the fastest at tight tolerances.
    Taylor,
    /// Full ALE only: integrate (3.4) forward, which runs away.
    Forward,
}

impl MethodChoice {
    /// Every choice, in the order of [`MethodChoice::NAMES`].
    pub const ALL: [MethodChoice; 8] = [
        MethodChoice::Auto,
        MethodChoice::Exact,
        MethodChoice::Rk4,
        MethodChoice::Dopri5,
        MethodChoice::Dop853,
        MethodChoice::Radau5,
        MethodChoice::Taylor,
        MethodChoice::Forward,
    ];

    /// The names the user types (`--method NAME`, `method = "NAME"`), in the
    /// order of [`MethodChoice::ALL`].
    pub const NAMES: [&'static str; 8] = [
        "auto", "exact", "rk4", "dopri5", "dop853", "radau5", "taylor", "forward",
    ];

    /// The name the user types: `auto`, `exact`, `rk4`, …
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The choice of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
    }

    /// One line on the choice, as `--help` lists it; the setting it takes
    /// ([`MethodChoice::setting`]) is the entry point's to name.
    pub fn help(self) -> &'static str {
        match self {
            MethodChoice::Auto => {
                "Closed forms where they exist, DOP853 for the rest (Taylor at rtol <= 1e-10)"
            }
            MethodChoice::Exact => "Closed forms only",
            MethodChoice::Rk4 => "Fixed-step classical RK4",
            MethodChoice::Dopri5 => "Dormand-Prince 5(4), adaptive",
            MethodChoice::Dop853 => "DOP853, adaptive",
            MethodChoice::Radau5 => "Radau IIA 5, implicit and L-stable, adaptive, for stiff tops",
            MethodChoice::Taylor => {
                "Taylor series of variable order, adaptive, the fastest at tight tolerances"
            }
            MethodChoice::Forward => {
                "Full model only: integrate (3.4) forward and watch it run away"
            }
        }
    }

    /// The key of `[solve]` that sets how it steps: `step` for RK4, `rtol`
    /// for the adaptive methods, none for the rest.
    pub fn setting(self) -> Option<&'static str> {
        match self {
            MethodChoice::Rk4 => Some("step"),
            MethodChoice::Dopri5
            | MethodChoice::Dop853
            | MethodChoice::Radau5
            | MethodChoice::Taylor => Some("rtol"),
            MethodChoice::Auto | MethodChoice::Exact | MethodChoice::Forward => None,
        }
    }

    /// The short title a screen shows: `closed form`, `RK4`, `DP5`, `DOP853`,
    /// `Radau5`, `Taylor`.
    pub fn title(self) -> &'static str {
        match self {
            MethodChoice::Auto => "auto",
            MethodChoice::Exact => "closed form",
            MethodChoice::Rk4 => "RK4",
            MethodChoice::Dopri5 => "DP5",
            MethodChoice::Dop853 => "DOP853",
            MethodChoice::Radau5 => "Radau5",
            MethodChoice::Taylor => "Taylor",
            MethodChoice::Forward => "forward",
        }
    }
}

/// A numerical method of the core: what a simulation reports it ran, what the
/// work-precision sweep and the stability rows compare. A [`Simulation`]
/// runs the first nine; the splittings are run by
/// [`crate::integrate::splitting`] directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Ω and O both from the closed forms (4.7), (4.9)–(4.11): no integration.
    ClosedForm,
    /// Ω from its closed form (4.15)–(4.16), O integrated by DOP853 on SO(3).
    ClosedFormDop853,
    /// Classical RK4 at a fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive.
    Dopri5,
    /// DOP853, adaptive.
    Dop853,
    /// Radau IIA 5, implicit and L-stable, adaptive.
    Radau5,
    /// The full ALE's physical solution: DOP853 backward from the slow
    /// manifold, shooting on the final state; O driven by it.
    Physical,
    /// The full ALE integrated forward (it runs away), O driven by it.
    Forward,
    /// The Taylor series method of variable order (Jorba & Zou's order and
    /// step, coefficients by recurrence), on Ω and the orientation
    /// quaternion together.
    Taylor,
    /// The reduced model split into its rotation and its damping, each solved
    /// exactly (they commute, so the split is exact for any step).
    RotationDamping,
    /// The Strang splitting of the free rigid body into axis rotations.
    Strang,
    /// Yoshida's fourth-order composition of the same splitting.
    Yoshida4,
}

impl Method {
    /// Short label, as outputs report it: `exact`, `exact+dop853`, `rk4`,
    /// `dopri5`, `dop853`, `radau5`, `physical`, `forward`, …
    pub fn label(&self) -> &'static str {
        match self {
            Method::ClosedForm => "exact",
            Method::ClosedFormDop853 => "exact+dop853",
            Method::Rk4 => "rk4",
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Radau5 => "radau5",
            Method::Physical => "physical",
            Method::Forward => "forward",
            Method::Taylor => "taylor",
            Method::RotationDamping => "rotation-damping",
            Method::Strang => "strang",
            Method::Yoshida4 => "yoshida4",
        }
    }

    /// The user's choice that bears this method's name, if one does: a
    /// choice and the integrator it runs share their name (`rk4`, `dop853`,
    /// `taylor`, …, and `exact` for the closed form), so this reads the one
    /// name table both use rather than mapping one enum onto the other by
    /// hand. The closed form with DOP853, the physical solution and the
    /// splittings are no choice's name.
    pub fn choice(&self) -> Option<MethodChoice> {
        MethodChoice::from_name(self.label())
    }

    /// One sentence saying what was computed how.
    pub fn detail(&self) -> &'static str {
        match self {
            Method::ClosedForm => "omega and orientation from closed forms (4.7), (4.9)",
            Method::ClosedFormDop853 => {
                "omega from the closed form (4.15)-(4.16); orientation O = Q Rz(Omega3~ t), the precession exact and Q integrated by DOP853 on SO(3)"
            }
            Method::Rk4 => {
                "omega and orientation integrated together by fixed-step RK4 (orientation on SO(3))"
            }
            Method::Dopri5 => {
                "omega and orientation integrated together by Dormand-Prince 5(4) (orientation on SO(3))"
            }
            Method::Dop853 => {
                "omega and orientation integrated together by DOP853 (orientation on SO(3))"
            }
            Method::Radau5 => {
                "omega and orientation integrated together by Radau IIA 5, implicit (orientation on SO(3))"
            }
            Method::Physical => {
                "the physical solution of (3.4): DOP853 backward from final data near the slow manifold, shooting on the final rate; orientation by DOP853 on SO(3)"
            }
            Method::Forward => {
                "(3.4) integrated forward by DOP853 from the reduced model's slope, with a runaway monitor; orientation by DOP853 on SO(3)"
            }
            Method::Taylor => {
                "omega and the orientation quaternion integrated together by the Taylor series method (order and step of Jorba and Zou)"
            }
            Method::RotationDamping => {
                "omega by the reduced model split into its rotation and its damping, each exact"
            }
            Method::Strang => "the free rigid body split into exact axis rotations (Strang)",
            Method::Yoshida4 => {
                "the free rigid body split into exact axis rotations (Yoshida's fourth order)"
            }
        }
    }

    /// True for the methods that step (all but the closed forms of Ω and O).
    pub fn is_integrated(&self) -> bool {
        !matches!(self, Method::ClosedForm)
    }
}

// ANCHOR: taylor_auto_rule
/// `auto` integrates a top without a closed form with the Taylor method at
/// this rtol and below, with DOP853 above.
///
/// NOTE: measured, not guessed (`cargo bench -p spintop-benches --bench
/// crossover`, `benches/results/crossover-2026-11-26.csv`, and
/// benches/README.md): Ω and the orientation together, as a simulation
/// computes them, on three asymmetric tops under both general models, with
/// 5 and with 1000 outputs. At rtol 1e-10 and below the Taylor method was
/// the faster in all twelve cases (1.2–1.7× at 1e-10, 1.6–2.4× at 1e-12); at
/// 1e-9 and looser DOP853 was the faster in some (by up to 1.3× at 1e-6, on
/// a top with few outputs), so there `auto` keeps DOP853, whose embedded
/// error estimate checks every step. `crates/spintop/tests/numerics/taylor.rs` holds this
/// constant to that file.
pub const TAYLOR_AUTO_RTOL: Real = 1e-10;

/// The integrator `auto` steps a model without a closed form with at `rtol`:
/// the Taylor method at and below [`TAYLOR_AUTO_RTOL`], DOP853 above (the
/// rule [`Model::method`] follows, and the scene planner counts steps by).
pub fn auto_integrator(rtol: Real) -> Method {
    if rtol <= TAYLOR_AUTO_RTOL {
        Method::Taylor
    } else {
        Method::Dop853
    }
}
// ANCHOR_END: taylor_auto_rule

/// A method the model does not take, and what it takes instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MethodRefused {
    /// The model's name.
    pub model: &'static str,
    /// What was chosen.
    pub method: MethodChoice,
}

impl std::fmt::Display for MethodRefused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (model, method) = (self.model, self.method.name());
        match (model, self.method) {
            ("full" | "general-full", _) => write!(
                f,
                "the {model} model (3.4) takes method auto (its physical solution, by DOP853 shooting backward in time) or forward (the runaway), not {method}"
            ),
            (_, MethodChoice::Forward) => {
                let takes = if model.starts_with("general") {
                    "auto, rk4, dopri5, dop853, radau5 or taylor"
                } else {
                    "auto, exact, rk4, dopri5, dop853, radau5 or taylor"
                };
                write!(
                    f,
                    "method forward is for the full model (3.4) only (it shows its runaway); the {model} model takes {takes}"
                )
            }
            _ => write!(
                f,
                "the {model} model has no closed form; it takes method auto (DOP853, or Taylor at rtol <= {TAYLOR_AUTO_RTOL:.0e}), taylor, dop853, dopri5, radau5 or rk4, not {method}"
            ),
        }
    }
}

impl std::error::Error for MethodRefused {}

/// Tolerance and step of the numerical methods, checked when built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodOptions {
    rtol: Real,
    step: Real,
    /// The share of their usual size the steps' caps take (1, or ½ for the
    /// second run that estimates a run's error: see [`crate::sim::claim`]).
    refine: Real,
}

/// The smallest relative tolerance accepted: below ~1e-14 a tolerance asks
/// for digits a double does not have.
pub const MIN_RTOL: Real = 1e-14;

/// A tolerance or a step refused, or given for a method that ignores it.
/// Each message starts with the key's name (`rtol`, `step`), so an entry
/// point can put its own prefix before it (`--`, `[solve] `).
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum OptionsError {
    /// rtol outside (0, 1).
    #[error("rtol must lie in [{}, 1), got {}", crate::numbers::fmt_value(MIN_RTOL), crate::numbers::fmt_value(*.0))]
    RtolOutOfRange(Real),
    /// rtol below [`MIN_RTOL`].
    #[error("rtol {0:e} is below what double precision can deliver; use 1e-14 or more")]
    RtolBelowDouble(Real),
    /// A step that is not a positive finite number.
    #[error("step must be positive, got {}", crate::numbers::fmt_value(*.0))]
    StepNotPositive(Real),
    /// rtol given for the fixed-step RK4.
    #[error("rtol applies to the adaptive methods; rk4 takes step")]
    RtolForRk4,
    /// step given for a method other than RK4.
    #[error("step sets the fixed step of method rk4 only; the adaptive methods take rtol")]
    StepNotRk4,
}

impl OptionsError {
    /// The key at fault: `rtol` or `step`.
    pub fn key(&self) -> &'static str {
        match self {
            OptionsError::RtolOutOfRange(_)
            | OptionsError::RtolBelowDouble(_)
            | OptionsError::RtolForRk4 => "rtol",
            OptionsError::StepNotPositive(_) | OptionsError::StepNotRk4 => "step",
        }
    }
}

impl MethodOptions {
    /// Tolerance `rtol` in [1e-14, 1) and RK4 step `step` > 0, in units of τ.
    pub fn new(rtol: Real, step: Real) -> Result<Self, OptionsError> {
        Self::default().with_rtol(rtol)?.with_step(step)
    }

    /// These options with another tolerance, in [1e-14, 1).
    pub fn with_rtol(self, rtol: Real) -> Result<Self, OptionsError> {
        if !(rtol > 0.0 && rtol < 1.0) {
            return Err(OptionsError::RtolOutOfRange(rtol));
        }
        if rtol < MIN_RTOL {
            return Err(OptionsError::RtolBelowDouble(rtol));
        }
        Ok(Self { rtol, ..self })
    }

    /// These options with another RK4 step, positive and finite.
    pub fn with_step(self, step: Real) -> Result<Self, OptionsError> {
        if !(step > 0.0 && step.is_finite()) {
            return Err(OptionsError::StepNotPositive(step));
        }
        Ok(Self { step, ..self })
    }

    /// The options a user gave with a choice of method: a tolerance only for
    /// the adaptive methods, a step only for RK4, each checked; the default
    /// for what was not given.
    pub fn for_choice(
        choice: MethodChoice,
        rtol: Option<Real>,
        step: Option<Real>,
    ) -> Result<Self, OptionsError> {
        let rk4 = choice == MethodChoice::Rk4;
        let mut options = Self::default();
        if let Some(rtol) = rtol {
            if rk4 {
                return Err(OptionsError::RtolForRk4);
            }
            options = options.with_rtol(rtol)?;
        }
        if let Some(step) = step {
            if !rk4 {
                return Err(OptionsError::StepNotRk4);
            }
            options = options.with_step(step)?;
        }
        Ok(options)
    }

    /// These options with every cap on a step (at most 1 rad of turning, the
    /// physical solution's node spacing) scaled by `factor` in (0, 1]: the
    /// second run of an error estimate must be finer in everything that
    /// limits a step, or a cap that holds both runs alike hides its error.
    pub(crate) fn refined(self, factor: Real) -> Self {
        Self {
            refine: self.refine * factor.clamp(1e-3, 1.0),
            ..self
        }
    }

    /// The share of their usual size the steps' caps take (1 unless refined).
    pub fn refine(&self) -> Real {
        self.refine
    }

    /// Relative tolerance of the adaptive methods.
    pub fn rtol(&self) -> Real {
        self.rtol
    }

    /// Step of the fixed-step RK4, in units of τ.
    pub fn step(&self) -> Real {
        self.step
    }
}

impl Default for MethodOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            step: 0.01,
            refine: 1.0,
        }
    }
}
