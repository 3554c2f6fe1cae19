//! A simulation: one model of the top, one method, stepped and sampled.
//!
//! Pure like the physics: no clock, no I/O. The same inputs give the same bits,
//! so the CLI, the TUI and the tests all see identical numbers.
//!
//! The lightest adequate path is used (`MethodChoice::Auto`):
//!
//! | model | Ω(t) | orientation O(t) |
//! |---|---|---|
//! | truncated (4.2)–(4.4) | closed form (4.7) | closed form, Rot(n_L, |L₀|ϑ)·O₀·R_z(Ω̃₃₀ϑ) |
//! | reduced (4.12)–(4.14) | closed form (4.15)–(4.16) | O = Q·R_z(Ω̃₃t): the precession exact, Q by DOP853 on SO(3), driven by the closed form |
//! | general (3.3) | DOP853, or the Taylor method at rtol ≤ [`TAYLOR_AUTO_RTOL`] | the same method, in the same state (the Taylor method carries a unit quaternion) |
//!
//! Orientations are integrated on the group: the state carries a small rotation
//! vector σ with `O = O_base exp(σ̂)` and `dσ/dt = J_r⁻¹(σ) Ω`
//! (Runge–Kutta–Munthe-Kaas). σ is folded into `O_base` (a unit quaternion)
//! before it grows large, so O is only ever changed by multiplying rotations and
//! stays orthonormal to rounding.

use crate::integrate::taylor::{
    GeneralReduced, GeneralTruncated, SymmetricReduced, SymmetricTruncated, TaylorRhs,
    WithOrientation,
};
use crate::integrate::{
    AdaptiveOptions, Dop853, Dopri5, IntegrateError, Radau5, Rhs, Rk4, Stats, Stepper, Taylor,
};
use crate::math::{Mat3, Quat, Real, State, Vec3, all_finite, dexpinv_right, exp_so3, rot_z};
use crate::physics::ParamError;
use crate::physics::euler_angles::{EulerAngles, euler_rates};
use crate::physics::general_top::{self, GeneralTop};
use crate::physics::rigid_body::{BodyDynamics, Observables};
use crate::physics::symmetric_top::{
    self, SymmetricTop, reduced_closed_form, reduced_corotating_rate, truncated_closed_form,
    truncated_orientation,
};
use serde::Serialize;
use thiserror::Error;

pub mod accuracy;
pub mod cost;
pub mod orbit;
pub mod physical;
pub mod secular;
pub mod shell;
pub mod split;
pub mod times;

use physical::general;

/// Which equation of motion the top follows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Model {
    /// The symmetric top without the Schott term, (4.2)–(4.4).
    Truncated(SymmetricTop),
    /// The symmetric top with the Schott term, reduced, (4.12)–(4.14).
    Reduced(SymmetricTop),
    /// Any top under the truncated ALE (3.3), κ = 1 units.
    General(GeneralTop),
    /// Any top under the reduced ALE: (3.4) with the free motion's rates in
    /// its small terms, κ = 1 units.
    GeneralReduced(GeneralTop),
    /// The symmetric top under the full ALE (3.4), Schott term and Ω̈ kept: its
    /// physical (non-runaway) solution, or a forward run that shows the runaway.
    Full(SymmetricTop),
    /// Any top under the full ALE (3.4), κ = 1 units: its physical solution,
    /// or a forward run that shows the runaway.
    GeneralFull(GeneralTop),
}

impl Model {
    /// Short name used in outputs: `truncated`, `reduced` or `general`.
    pub fn name(&self) -> &'static str {
        match self {
            Model::Truncated(_) => "truncated",
            Model::Reduced(_) => "reduced",
            Model::General(_) => "general",
            Model::GeneralReduced(_) => "general-reduced",
            Model::Full(_) => "full",
            Model::GeneralFull(_) => "general-full",
        }
    }

    /// The paper's equations for this model.
    pub fn equations(&self) -> &'static str {
        match self {
            Model::Truncated(_) => "Eqs. (4.2)-(4.4)",
            Model::Reduced(_) => "Eqs. (4.12)-(4.14)",
            Model::General(_) => "Eq. (3.3)",
            Model::GeneralReduced(_) => "Eq. (3.4), reduced",
            Model::Full(_) | Model::GeneralFull(_) => "Eq. (3.4)",
        }
    }

    /// The three models of this model's top, lightest first: the truncated
    /// ALE (3.3), the reduced ALE, the physical solution of (3.4), for the
    /// symmetric top or for any other.
    pub fn tiers(&self) -> [Model; 3] {
        match *self {
            Model::Truncated(t) | Model::Reduced(t) | Model::Full(t) => {
                [Model::Truncated(t), Model::Reduced(t), Model::Full(t)]
            }
            Model::General(g) | Model::GeneralReduced(g) | Model::GeneralFull(g) => [
                Model::General(g),
                Model::GeneralReduced(g),
                Model::GeneralFull(g),
            ],
        }
    }

    /// True when Ω(t) has a closed form.
    pub fn has_closed_form(&self) -> bool {
        matches!(self, Model::Truncated(_) | Model::Reduced(_))
    }

    /// Ω(t) from Ω₀ by the closed form, for the two models that have one:
    /// (4.7) for the truncated model, (4.15)–(4.16) for the reduced one;
    /// `None` for the others.
    pub fn closed_form(&self, omega0: &Vec3, t: Real) -> Option<Vec3> {
        match self {
            Model::Truncated(top) => Some(truncated_closed_form(top, omega0, t)),
            Model::Reduced(top) => Some(reduced_closed_form(top, omega0, t)),
            Model::General(_)
            | Model::GeneralReduced(_)
            | Model::Full(_)
            | Model::GeneralFull(_) => None,
        }
    }

    // ANCHOR: auto_choice
    /// The method a choice runs on this model at these options: `auto` takes
    /// the closed forms where they exist, the physical solution for the full
    /// ALE, and for the rest DOP853, or the Taylor method where the measured
    /// crossover says it is faster ([`auto_integrator`]). A choice the model
    /// does not take is refused, with what it takes. This is the one step
    /// from a user's choice to a method.
    pub fn method(
        &self,
        choice: MethodChoice,
        options: &MethodOptions,
    ) -> Result<Method, MethodRefused> {
        use MethodChoice as C;
        let refused = MethodRefused {
            model: self.name(),
            method: choice,
        };
        Ok(match (self, choice) {
            (Model::Full(_) | Model::GeneralFull(_), C::Auto) => Method::Physical,
            (Model::Full(_) | Model::GeneralFull(_), C::Forward) => Method::Forward,
            (Model::Full(_) | Model::GeneralFull(_), _) | (_, C::Forward) => return Err(refused),
            (Model::Truncated(_), C::Auto | C::Exact) => Method::ClosedForm,
            (Model::Reduced(_), C::Auto | C::Exact) => Method::ClosedFormDop853,
            (_, C::Exact) => return Err(refused),
            (_, C::Auto) => auto_integrator(options.rtol),
            (_, C::Dop853) => Method::Dop853,
            (_, C::Rk4) => Method::Rk4,
            (_, C::Dopri5) => Method::Dopri5,
            (_, C::Radau5) => Method::Radau5,
            (_, C::Taylor) => Method::Taylor,
        })
    }
    // ANCHOR_END: auto_choice

    /// Refuse a choice this model does not take (see [`Model::method`]):
    /// every entry point (the command line, scenes, the live view) asks here.
    /// Whether a model takes a choice does not depend on the tolerance.
    pub fn check_method(&self, choice: MethodChoice) -> Result<(), MethodRefused> {
        self.method(choice, &MethodOptions::default()).map(|_| ())
    }

    /// The principal moments.
    pub fn inertia(&self) -> Vec3 {
        match self {
            Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => top.inertia(),
            Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
                top.inertia()
            }
        }
    }

    /// The unit of time of the model's numbers: τ for the symmetric top
    /// (Section 4's unit, I₁ = 1), "u" for a general top, whose numbers are in
    /// units where κ = 2/(3c³) = 1.
    pub fn time_unit(&self) -> &'static str {
        match self {
            Model::Truncated(_) | Model::Reduced(_) | Model::Full(_) => "τ",
            Model::General(_) | Model::GeneralReduced(_) | Model::GeneralFull(_) => "u",
        }
    }

    /// True for the full ALE (3.4), of either top.
    pub fn is_full(&self) -> bool {
        matches!(self, Model::Full(_) | Model::GeneralFull(_))
    }

    /// The model as Ω̇ = F(Ω), for the models that have that form (not the full
    /// ALE, whose state also holds Ω̇).
    fn first_order(&self) -> Option<FirstOrder> {
        match *self {
            Model::Truncated(top) => Some(FirstOrder::Truncated(top)),
            Model::Reduced(top) => Some(FirstOrder::Reduced(top)),
            Model::General(top) => Some(FirstOrder::General(top)),
            Model::GeneralReduced(top) => Some(FirstOrder::GeneralReduced(top)),
            Model::Full(_) | Model::GeneralFull(_) => None,
        }
    }
}

/// The models of the form Ω̇ = F(Ω).
#[derive(Clone, Copy, Debug, PartialEq)]
enum FirstOrder {
    Truncated(SymmetricTop),
    Reduced(SymmetricTop),
    General(GeneralTop),
    GeneralReduced(GeneralTop),
}

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

    /// One line on the choice, as `--help` lists it.
    pub fn help(self) -> &'static str {
        match self {
            MethodChoice::Auto => {
                "Closed forms where they exist, DOP853 for the rest (Taylor at rtol <= 1e-10)"
            }
            MethodChoice::Exact => "Closed forms only",
            MethodChoice::Rk4 => "Fixed-step classical RK4 (--step)",
            MethodChoice::Dopri5 => "Dormand-Prince 5(4), adaptive (--rtol)",
            MethodChoice::Dop853 => "DOP853, adaptive (--rtol)",
            MethodChoice::Radau5 => {
                "Radau IIA 5, implicit and L-stable, adaptive (--rtol): for stiff tops"
            }
            MethodChoice::Taylor => {
                "Taylor series of variable order, adaptive (--rtol): the fastest at tight tolerances"
            }
            MethodChoice::Forward => {
                "Full model only: integrate (3.4) forward and watch it run away"
            }
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
    #[error("rtol must lie in (0, 1), got {}", crate::numbers::fmt_value(*.0))]
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
        }
    }
}

/// Initial body rate Ω₀ and orientation O(0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialState {
    /// Ω₀ in the body frame.
    pub omega: Vec3,
    /// O(0), body → lab.
    pub rotation: Mat3,
}

impl InitialState {
    /// Ω₀ and the z-x-z Euler angles of O(0); refuses non-finite numbers.
    pub fn new(omega: Vec3, euler: EulerAngles) -> Result<Self, SimError> {
        check_rate(&omega)?;
        if !(euler.phi.is_finite() && euler.theta.is_finite() && euler.psi.is_finite()) {
            return Err(SimError::NotFinite("the initial Euler angles"));
        }
        Ok(Self {
            omega,
            rotation: euler.to_rotation(),
        })
    }
}

/// The one check of an initial body rate Ω₀ (every entry point's, through
/// [`InitialState::new`] or, where a scene points at its key, directly):
/// finite, and each component at most [`MAX_RATE`] in units of 1/τ.
pub fn check_rate(omega: &Vec3) -> Result<(), SimError> {
    if !all_finite(omega) {
        return Err(SimError::NotFinite("the initial angular velocity"));
    }
    // NOTE: in units of 1/τ a real top has |Ω| far below 1 (τΩ ~ 1e-20 for a
    // nanoparticle); above 1e100 the products τΩ²t overflow a double.
    if omega.amax() > MAX_RATE {
        return Err(SimError::OutOfRange(
            "each component of the initial angular velocity must be at most 1e100 in units of 1/tau",
        ));
    }
    Ok(())
}

/// Why a simulation could not be built or advanced.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SimError {
    /// A physical parameter was refused.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// An input was NaN or infinite.
    #[error("{0} must be finite numbers")]
    NotFinite(&'static str),
    /// The model does not take the method chosen.
    #[error(transparent)]
    Refused(#[from] MethodRefused),
    /// An input lies beyond what the model can represent.
    #[error("{0}")]
    OutOfRange(&'static str),
    /// A sample came out non-finite although the method reported no failure
    /// (a last guard: spintop never prints a NaN table).
    #[error("the state became non-finite at t = {}", crate::numbers::fmt_time(*.0))]
    NonFiniteSample(Real),
    /// A requested time was negative, non-finite or earlier than the last one.
    #[error(
        "output times must be finite, >= 0 and non-decreasing (got {} after {})",
        crate::numbers::fmt_value(*.0),
        crate::numbers::fmt_value(*.1)
    )]
    BadTime(Real, Real),
    /// The integrator failed; the error carries the time.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// A method named directly ([`Simulation::with_method`]) cannot run the
    /// model.
    #[error("the method {method} does not run the {model} model")]
    MethodNotForModel {
        /// The method's label.
        method: &'static str,
        /// The model's name.
        model: &'static str,
    },
    /// The model needs to know its last time in advance.
    #[error("the {0} model needs the last output time in advance")]
    NeedsHorizon(&'static str),
    /// The physical solution of the full ALE could not be found.
    #[error(transparent)]
    Physical(#[from] physical::PhysicalError),
    /// A forward run of the full ALE ran away before the requested time.
    #[error("{0}")]
    Runaway(physical::Runaway),
    /// The run would take more work than allowed (estimated before it starts).
    #[error(transparent)]
    TooCostly(#[from] cost::TooCostly),
}

/// Everything observed at one time. Serialises to the `simulate` JSON contract.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time, in units of τ.
    pub t: Real,
    /// Body-frame Ω.
    pub omega: [Real; 3],
    /// O(t), body → lab, as rows.
    pub rotation: [[Real; 3]; 3],
    /// z-x-z Euler angles [φ, θ, ψ] of O(t).
    pub euler: [Real; 3],
    /// E = ½ Ω·IΩ.
    pub energy: Real,
    /// L in the lab frame.
    pub l_lab: [Real; 3],
    /// Ω⊥.
    pub omega_perp: Real,
    /// L in the body frame.
    pub l_body: [Real; 3],
    /// Angle between the symmetry axis (body axis 3) and L.
    pub tilt: Real,
    /// [φ̇, θ̇, ψ̇] from (4.8); `None` on a pole, where they are undefined.
    pub euler_rates: Option<[Real; 3]>,
}

impl Sample {
    /// Observe a state.
    pub fn new(t: Real, inertia: &Vec3, rotation: &Mat3, omega: &Vec3) -> Self {
        let obs = Observables::new(inertia, rotation, omega);
        let euler = EulerAngles::from_rotation(rotation);
        let rows = |i: usize| [rotation[(i, 0)], rotation[(i, 1)], rotation[(i, 2)]];
        Self {
            t,
            omega: (*omega).into(),
            rotation: [rows(0), rows(1), rows(2)],
            euler: [euler.phi, euler.theta, euler.psi],
            energy: obs.energy,
            l_lab: obs.l_lab.into(),
            omega_perp: obs.omega_perp,
            l_body: obs.l_body.into(),
            tilt: obs.tilt,
            euler_rates: euler_rates(&euler, omega).map(|r| [r.phi_dot, r.theta_dot, r.psi_dot]),
        }
    }

    /// True when every number of the sample is finite.
    pub fn is_finite(&self) -> bool {
        let finite = |xs: &[Real]| xs.iter().all(|x| x.is_finite());
        finite(&[self.t, self.energy, self.omega_perp, self.tilt])
            && finite(&self.omega)
            && finite(&self.l_lab)
            && finite(&self.l_body)
            && finite(&self.euler)
            && self.rotation.iter().all(|r| finite(r))
            && self.euler_rates.is_none_or(|r| finite(&r))
    }

    /// Ω as a vector.
    pub fn omega_vec(&self) -> Vec3 {
        Vec3::from(self.omega)
    }

    /// O(t) as a matrix.
    pub fn rotation_matrix(&self) -> Mat3 {
        let r = &self.rotation;
        Mat3::new(
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
        )
    }
}

/// The largest |Ω| component accepted, in units of 1/τ.
pub const MAX_RATE: Real = 1e100;

/// Fold σ into the base orientation once |σ| exceeds this.
///
/// NOTE: J_r⁻¹(σ) is smooth for |σ| < 2π, but its derivatives grow with |σ|;
/// folding at 0.5 rad keeps the σ equation nearly linear, and costs one extra
/// right-hand-side evaluation (the FSAL stage is lost) every 0.5/|Ω| time units.
const FOLD_ANGLE: Real = 0.5;

/// Cap each step so that the body turns by at most this angle in it.
///
/// NOTE: J_r⁻¹(σ) is singular at |σ| = 2π. Once Ω settles (the reduced top
/// ends spinning steadily) σ grows linearly, the error estimate sees nothing,
/// and unchecked steps would carry σ through the singularity. With the fold at
/// 0.5 rad and at most 1 rad per step, |σ| stays below 1.5 rad.
const MAX_TURN_PER_STEP: Real = 1.0;

/// One of the integrators, chosen at run time.
#[derive(Clone, Debug)]
enum AnyStepper<const N: usize> {
    Rk4(Rk4<N>),
    Dopri5(Dopri5<N>),
    Dop853(Dop853<N>),
    Radau5(Radau5<N>),
}

impl<const N: usize> AnyStepper<N> {
    /// The stepper of `which`, or `None` when `which` is not one of the four
    /// steppers.
    fn new(
        which: Method,
        y0: State<N>,
        options: &MethodOptions,
        scale: Real,
    ) -> Result<Option<Self>, IntegrateError> {
        // NOTE: the absolute tolerance only matters where a component passes
        // through zero; tying it to the size of Ω₀ keeps the control relative
        // for tops of any speed (and positive for a top at rest).
        Self::with_atol(
            which,
            y0,
            options,
            (1e-6 * options.rtol * scale).max(1e-300),
        )
    }

    fn with_atol(
        which: Method,
        y0: State<N>,
        options: &MethodOptions,
        atol: Real,
    ) -> Result<Option<Self>, IntegrateError> {
        let adaptive = || AdaptiveOptions::new(options.rtol, atol);
        Ok(Some(match which {
            Method::Rk4 => AnyStepper::Rk4(Rk4::new(0.0, y0, options.step)?),
            Method::Dopri5 => AnyStepper::Dopri5(Dopri5::new(0.0, y0, adaptive()?)?),
            Method::Dop853 => AnyStepper::Dop853(Dop853::new(0.0, y0, adaptive()?)?),
            Method::Radau5 => AnyStepper::Radau5(Radau5::new(0.0, y0, adaptive()?)?),
            _ => return Ok(None),
        }))
    }
}

impl<const N: usize> AnyStepper<N> {
    /// Cap the adaptive step (a fixed RK4 step is the user's choice and is kept).
    fn set_h_max(&mut self, h_max: Real) {
        match self {
            AnyStepper::Rk4(_) => {}
            AnyStepper::Dopri5(s) => s.set_h_max(h_max),
            AnyStepper::Dop853(s) => s.set_h_max(h_max),
            AnyStepper::Radau5(s) => s.set_h_max(h_max),
        }
    }
}

macro_rules! dispatch {
    ($self:expr, $s:ident => $body:expr) => {
        match $self {
            AnyStepper::Rk4($s) => $body,
            AnyStepper::Dopri5($s) => $body,
            AnyStepper::Dop853($s) => $body,
            AnyStepper::Radau5($s) => $body,
        }
    };
}

impl<const N: usize> Stepper<N> for AnyStepper<N> {
    fn t(&self) -> Real {
        dispatch!(self, s => s.t())
    }
    fn y(&self) -> &State<N> {
        dispatch!(self, s => s.y())
    }
    fn t_prev(&self) -> Real {
        dispatch!(self, s => s.t_prev())
    }
    fn last_step(&self) -> Real {
        dispatch!(self, s => s.last_step())
    }
    fn stats(&self) -> Stats {
        dispatch!(self, s => s.stats())
    }
    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        dispatch!(self, s => s.step(rhs, t_stop))
    }
    fn dense<R: Rhs<N>>(&mut self, rhs: &R, t: Real) -> State<N> {
        dispatch!(self, s => s.dense(rhs, t))
    }
    fn reset(&mut self, y: State<N>) {
        dispatch!(self, s => s.reset(y))
    }
}

/// Ω and σ together: `d(Ω, σ)/dt = (F(Ω), J_r⁻¹(σ) Ω)`, generic in the
/// dynamics so that the step loop is monomorphic in the model (chosen once
/// per advance, see [`Simulation::advance_to`]).
struct CoupledRhs<D: BodyDynamics>(D);

impl<D: BodyDynamics> Rhs<6> for CoupledRhs<D> {
    fn eval(&self, _t: Real, y: &State<6>) -> State<6> {
        let omega = y.fixed_rows::<3>(0).into_owned();
        let sigma = y.fixed_rows::<3>(3).into_owned();
        let mut out = State::<6>::zeros();
        out.fixed_rows_mut::<3>(0)
            .copy_from(&self.0.omega_dot(&omega));
        out.fixed_rows_mut::<3>(3)
            .copy_from(&dexpinv_right(&sigma, &omega));
        out
    }
}

/// σ alone, driven by a known Ω(t): `dσ/dt = J_r⁻¹(σ) Ω(t)`.
struct OrientationRhs<F: Fn(Real) -> Vec3>(F);

impl<F: Fn(Real) -> Vec3> Rhs<3> for OrientationRhs<F> {
    fn eval(&self, t: Real, sigma: &State<3>) -> State<3> {
        dexpinv_right(sigma, &(self.0)(t))
    }
}

/// A stepper whose state ends with σ, plus the base orientation σ is relative to.
#[derive(Clone, Debug)]
struct OnGroup<const N: usize> {
    stepper: AnyStepper<N>,
    base: Quat,
}

impl<const N: usize> OnGroup<N> {
    fn sigma(y: &State<N>) -> Vec3 {
        y.fixed_rows::<3>(N - 3).into_owned()
    }

    // ANCHOR: fold
    /// Step once; σ is folded into the base first if it has grown, so that the
    /// base is always the one the last step's continuous output refers to.
    /// `omega` gives the body rate at a time and state, to cap the step.
    fn step<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        omega: &impl Fn(Real, &State<N>) -> Vec3,
        t_stop: Real,
    ) -> Result<(), IntegrateError> {
        let y = *self.stepper.y();
        let rate = omega(self.stepper.t(), &y).norm();
        if rate > 0.0 {
            self.stepper.set_h_max(MAX_TURN_PER_STEP / rate);
        }
        let sigma = Self::sigma(&y);
        if sigma.norm() > FOLD_ANGLE {
            self.base = Quat::new_normalize((self.base * exp_so3(&sigma)).into_inner());
            let mut folded = y;
            folded.fixed_rows_mut::<3>(N - 3).fill(0.0);
            self.stepper.reset(folded);
        }
        self.stepper.step(rhs, t_stop)
    }
    // ANCHOR_END: fold

    /// Step until `t` lies in the last step, then read the state and O there.
    fn advance<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        omega: &impl Fn(Real, &State<N>) -> Vec3,
        t: Real,
        horizon: Real,
    ) -> Result<(State<N>, Mat3), IntegrateError> {
        // NOTE: Radau5's continuous extension is only of order 3 and not
        // error-controlled, so it steps exactly onto every output time.
        let stop = if matches!(self.stepper, AnyStepper::Radau5(_)) {
            t
        } else {
            horizon
        };
        while self.stepper.t() < t {
            self.step(rhs, omega, stop)?;
        }
        let y = if t == self.stepper.t() {
            *self.stepper.y()
        } else {
            self.stepper.dense(rhs, t)
        };
        let q = self.base * exp_so3(&Self::sigma(&y));
        Ok((y, q.to_rotation_matrix().into_inner()))
    }
}

#[derive(Clone, Debug)]
enum Engine {
    /// Truncated model: everything in closed form.
    ClosedForm(SymmetricTop),
    /// Reduced model: Ω closed form, σ integrated.
    ReducedOrientation(SymmetricTop, Box<OnGroup<3>>),
    /// Ω and σ integrated together by one of the steppers.
    Coupled(Method, FirstOrder, Box<OnGroup<6>>),
    /// Full ALE: Ω from a table (the physical solution, or a forward run up to
    /// its runaway), σ integrated along it.
    Table(Box<physical::OmegaTable>, TableKind, Stats, Box<OnGroup<3>>),
    /// Ω and the orientation quaternion by the Taylor method.
    Taylor(Box<TaylorRun>),
}

/// The Taylor method on (Ω, q), with one model's recurrences.
///
/// NOTE: a unit quaternion, not σ on the group as the Runge–Kutta methods
/// carry: q̇ = ½ q ⊗ (0, Ω) is a polynomial in (q, Ω), so the series takes it
/// as it takes Ω, and its linearity means rounding only scales q, which is
/// normalised as it is read.
// NOTE: the variants differ by their auxiliary series (a few kB); the whole
// enum is boxed once in `Engine`, so boxing each variant would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum TaylorRun {
    Truncated(Taylor<7, WithOrientation<SymmetricTruncated>>),
    Reduced(Taylor<7, WithOrientation<SymmetricReduced>>),
    General(Taylor<7, WithOrientation<GeneralTruncated>>),
    GeneralReduced(Taylor<7, WithOrientation<GeneralReduced>>),
}

macro_rules! taylor_dispatch {
    ($self:expr, $s:ident => $body:expr) => {
        match $self {
            TaylorRun::Truncated($s) => $body,
            TaylorRun::Reduced($s) => $body,
            TaylorRun::General($s) => $body,
            TaylorRun::GeneralReduced($s) => $body,
        }
    };
}

impl TaylorRun {
    /// At Ω₀ and O(0) = `base`, with the tolerances of the other integrators.
    fn new(
        dynamics: FirstOrder,
        initial: &InitialState,
        base: &Quat,
        options: &MethodOptions,
    ) -> Result<Self, IntegrateError> {
        let mut y0 = State::<7>::zeros();
        y0.fixed_rows_mut::<3>(0).copy_from(&initial.omega);
        let q = base.quaternion();
        y0.fixed_rows_mut::<4>(3)
            .copy_from(&nalgebra::Vector4::new(q.w, q.i, q.j, q.k));
        // NOTE: relative control all the way down (the step rule floors the
        // state's size at atol/rtol). An atol tied to |Ω₀|, as the Runge–Kutta
        // pairs take, lets a top that collapses far below |Ω₀| (the truncated
        // top from |Ω⊥| = 10²⁰) be stepped past the series' radius of
        // convergence: its Ω flipped sign every step, within that atol, and
        // the run crawled at the stability limit instead of finishing.
        let atol = 1e-300;
        let opts = AdaptiveOptions::new(options.rtol, atol)?;
        fn build<M: TaylorRhs<3>>(
            m: M,
            y0: State<7>,
            opts: AdaptiveOptions,
        ) -> Result<Taylor<7, WithOrientation<M>>, IntegrateError> {
            Taylor::new(WithOrientation(m), 0.0, y0, opts)
        }
        Ok(match dynamics {
            FirstOrder::Truncated(top) => {
                TaylorRun::Truncated(build(SymmetricTruncated(top), y0, opts)?)
            }
            FirstOrder::Reduced(top) => TaylorRun::Reduced(build(SymmetricReduced(top), y0, opts)?),
            FirstOrder::General(top) => TaylorRun::General(build(GeneralTruncated(top), y0, opts)?),
            FirstOrder::GeneralReduced(top) => {
                TaylorRun::GeneralReduced(build(GeneralReduced(top), y0, opts)?)
            }
        })
    }

    fn stats(&self) -> Stats {
        taylor_dispatch!(self, s => s.stats())
    }

    fn last_step(&self) -> Real {
        taylor_dispatch!(self, s => s.last_step())
    }

    /// Step until `t` lies in the last step (toward `horizon`), then read Ω
    /// and O there from the step's polynomial.
    fn advance(&mut self, t: Real, horizon: Real) -> Result<(Vec3, Mat3), IntegrateError> {
        let y = taylor_dispatch!(self, s => {
            while s.t() < t {
                s.advance(horizon)?;
            }
            s.value_at(t)
        });
        let q = Quat::from_quaternion(nalgebra::Quaternion::new(y[3], y[4], y[5], y[6]));
        Ok((
            Vec3::new(y[0], y[1], y[2]),
            q.to_rotation_matrix().into_inner(),
        ))
    }
}

/// Where a full-ALE table came from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum TableKind {
    /// The physical solution (backward shooting).
    Physical,
    /// A forward run, with the runaway that stopped it, if any.
    Forward(Option<physical::Runaway>),
}

/// The physical solution of a full model's (3.4) through Ω₀ on [0, span] as a
/// table, and the work it took.
fn physical_table(
    model: &Model,
    omega0: &Vec3,
    span: Real,
    rtol: Real,
) -> Result<(physical::OmegaTable, Stats), SimError> {
    Ok(match model {
        Model::GeneralFull(top) => {
            let (table, sol) = general::general_physical_table(top, omega0, span, rtol)?;
            (table, sol.stats)
        }
        Model::Full(top) => {
            let (table, sol) = physical::physical_table(top, omega0, span, rtol)?;
            (table, sol.stats)
        }
        _ => {
            return Err(SimError::MethodNotForModel {
                method: Method::Physical.label(),
                model: model.name(),
            });
        }
    })
}

/// How far ahead an open-ended full model tabulates its physical solution at a
/// time: 50 fast times (τ, or τ_f = |d|²/min Iᵢ for a general top).
fn physical_chunk_length(model: &Model) -> Real {
    match model {
        Model::GeneralFull(top) => 50.0 * general::fast_time(top),
        Model::Full(top) => 50.0 * top.tau(),
        _ => Real::MAX,
    }
}

/// A top, a method and the current time.
#[derive(Clone, Debug)]
pub struct Simulation {
    options: MethodOptions,
    model: Model,
    initial: InitialState,
    engine: Engine,
    horizon: Real,
    current: Sample,
}

impl Simulation {
    /// Build a simulation at t = 0 with the method `choice` resolves to for
    /// `model` ([`Model::method`]; a choice the model does not take is
    /// refused with what it takes).
    ///
    /// `horizon` is the last time that will be asked for (the adaptive methods
    /// step toward it and never past it); `None` means open-ended, as in the TUI.
    pub fn new(
        model: Model,
        choice: MethodChoice,
        options: MethodOptions,
        initial: InitialState,
        horizon: Option<Real>,
    ) -> Result<Self, SimError> {
        let method = model.method(choice, &options)?;
        Self::with_method(model, method, options, initial, horizon)
    }

    /// Build a simulation at t = 0 that runs `method` itself (the sweeps of
    /// [`crate::workprecision`] name the method, not a choice). A method that
    /// cannot run `model` is refused.
    pub fn with_method(
        model: Model,
        method: Method,
        options: MethodOptions,
        initial: InitialState,
        horizon: Option<Real>,
    ) -> Result<Self, SimError> {
        // NOTE: the steppers take a finite t_stop; the largest double stands for
        // "open-ended" (the TUI), and no run gets anywhere near it.
        let horizon = horizon.unwrap_or(Real::MAX);
        if horizon.is_nan() || horizon < 0.0 {
            return Err(SimError::BadTime(horizon, 0.0));
        }
        let not_for_model = || SimError::MethodNotForModel {
            method: method.label(),
            model: model.name(),
        };
        if horizon < Real::MAX {
            cost::check(&model, method, &options, &initial.omega, horizon)?;
        }
        let base = Quat::from_matrix(&initial.rotation);
        let scale = initial.omega.norm();
        let on_group = |dynamics: FirstOrder| -> Result<Engine, SimError> {
            let mut y0 = State::<6>::zeros();
            y0.fixed_rows_mut::<3>(0).copy_from(&initial.omega);
            let stepper =
                AnyStepper::new(method, y0, &options, scale)?.ok_or_else(not_for_model)?;
            Ok(Engine::Coupled(
                method,
                dynamics,
                Box::new(OnGroup { stepper, base }),
            ))
        };
        let orientation_only = || -> Result<Box<OnGroup<3>>, SimError> {
            let zero = State::<3>::zeros();
            // NOTE: σ alone is a rotation vector of at most 1.5 rad that restarts
            // from 0 at every fold; a tolerance relative to its size would ask
            // for ever more digits right after each fold. Its error is an angle:
            // rtol radians, absolute.
            let stepper = AnyStepper::with_atol(Method::Dop853, zero, &options, options.rtol)?
                .ok_or_else(not_for_model)?;
            Ok(Box::new(OnGroup { stepper, base }))
        };
        let (omega0, rtol) = (&initial.omega, options.rtol);
        let engine = match (method, model.first_order()) {
            (Method::Physical, None) => {
                // Open-ended (the live view): one chunk now, the next
                // when the view gets there (see `advance_to`).
                let span = if horizon == Real::MAX {
                    physical_chunk_length(&model)
                } else {
                    horizon
                };
                let (table, stats) = physical_table(&model, omega0, span, rtol)?;
                Engine::Table(
                    Box::new(table),
                    TableKind::Physical,
                    stats,
                    orientation_only()?,
                )
            }
            (Method::Forward, None) if horizon == Real::MAX => {
                return Err(SimError::NeedsHorizon(model.name()));
            }
            (Method::Forward, None) => {
                let (table, runaway, stats) = match model {
                    Model::GeneralFull(top) => {
                        let (table, run) =
                            general::general_forward_table(&top, omega0, horizon, rtol)?;
                        (table, run.runaway, run.stats)
                    }
                    Model::Full(top) => {
                        let (table, run) = physical::forward_table(&top, omega0, horizon, rtol)?;
                        (table, run.runaway, run.stats)
                    }
                    _ => return Err(not_for_model()),
                };
                Engine::Table(
                    Box::new(table),
                    TableKind::Forward(runaway),
                    stats,
                    orientation_only()?,
                )
            }
            (Method::ClosedForm, Some(FirstOrder::Truncated(top))) => Engine::ClosedForm(top),
            (Method::ClosedFormDop853, Some(FirstOrder::Reduced(top))) => {
                Engine::ReducedOrientation(top, orientation_only()?)
            }
            (Method::Rk4 | Method::Dopri5 | Method::Dop853 | Method::Radau5, Some(d)) => {
                on_group(d)?
            }
            (Method::Taylor, Some(d)) => {
                Engine::Taylor(Box::new(TaylorRun::new(d, &initial, &base, &options)?))
            }
            _ => return Err(not_for_model()),
        };
        let current = Sample::new(0.0, &model.inertia(), &initial.rotation, &initial.omega);
        Ok(Self {
            options,
            model,
            initial,
            engine,
            horizon,
            current,
        })
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The initial state.
    pub fn initial(&self) -> &InitialState {
        &self.initial
    }

    /// The method in use.
    pub fn method(&self) -> Method {
        match &self.engine {
            Engine::ClosedForm(_) => Method::ClosedForm,
            Engine::ReducedOrientation(..) => Method::ClosedFormDop853,
            Engine::Coupled(which, ..) => *which,
            Engine::Table(_, TableKind::Physical, ..) => Method::Physical,
            Engine::Table(_, TableKind::Forward(_), ..) => Method::Forward,
            Engine::Taylor(_) => Method::Taylor,
        }
    }

    /// The latest sample.
    pub fn current(&self) -> &Sample {
        &self.current
    }

    /// The work done so far (all zeros for the closed forms).
    pub fn stats(&self) -> Stats {
        match &self.engine {
            Engine::ClosedForm(_) => Stats::default(),
            Engine::ReducedOrientation(_, g) => g.stepper.stats(),
            Engine::Table(_, _, built, g) => {
                let mut total = *built;
                total += g.stepper.stats();
                total
            }
            Engine::Coupled(_, _, g) => g.stepper.stats(),
            Engine::Taylor(run) => run.stats(),
        }
    }

    /// The size of the integrator's last accepted step (0 for closed forms).
    pub fn last_step(&self) -> Real {
        match &self.engine {
            Engine::ClosedForm(_) => 0.0,
            Engine::ReducedOrientation(_, g) | Engine::Table(_, _, _, g) => g.stepper.last_step(),
            Engine::Coupled(_, _, g) => g.stepper.last_step(),
            Engine::Taylor(run) => run.last_step(),
        }
    }

    /// Advance to time `t` (not earlier than the current sample) and return the sample there.
    pub fn advance_to(&mut self, t: Real) -> Result<&Sample, SimError> {
        let now = self.current.t;
        if !t.is_finite() || t < now || t > self.horizon {
            return Err(SimError::BadTime(t, now));
        }
        let inertia = self.model.inertia();
        let (omega, rotation) = match &mut self.engine {
            Engine::ClosedForm(top) => (
                truncated_closed_form(top, &self.initial.omega, t),
                truncated_orientation(top, &self.initial.omega, &self.initial.rotation, t),
            ),
            Engine::ReducedOrientation(top, g) => {
                // NOTE: in axes that turn with Ω⊥ in the body the rate w(t) has
                // no fast part (see `reduced_corotating_rate`): the integrator
                // follows only the slow decay, and the precession R_z(Ω̃₃t) is
                // multiplied back exactly.
                let omega0 = self.initial.omega;
                let rhs = OrientationRhs(|t| reduced_corotating_rate(top, &omega0, t));
                let rate = |t: Real, _: &State<3>| reduced_corotating_rate(top, &omega0, t);
                let (_, q) = g.advance(&rhs, &rate, t, self.horizon)?;
                let precession = rot_z(top.omega3_tilde(omega0.z) * t);
                (reduced_closed_form(top, &omega0, t), q * precession)
            }
            Engine::Coupled(_, dynamics, g) => {
                let omega = |_: Real, y: &State<6>| y.fixed_rows::<3>(0).into_owned();
                let h = self.horizon;
                // The model is matched here, once per advance, never per evaluation.
                let (y, rotation) = match *dynamics {
                    FirstOrder::Truncated(top) => {
                        g.advance(&CoupledRhs(symmetric_top::Truncated(top)), &omega, t, h)?
                    }
                    FirstOrder::Reduced(top) => {
                        g.advance(&CoupledRhs(symmetric_top::Reduced(top)), &omega, t, h)?
                    }
                    FirstOrder::General(top) => g.advance(&CoupledRhs(top), &omega, t, h)?,
                    FirstOrder::GeneralReduced(top) => {
                        g.advance(&CoupledRhs(general_top::Reduced(top)), &omega, t, h)?
                    }
                };
                (y.fixed_rows::<3>(0).into_owned(), rotation)
            }
            Engine::Taylor(run) => run.advance(t, self.horizon)?,
            Engine::Table(table, kind, built, g) => {
                if let TableKind::Forward(Some(runaway)) = kind
                    && t > runaway.t
                {
                    return Err(SimError::Runaway(*runaway));
                }
                let open = self.horizon == Real::MAX;
                // Open-ended: carry the orientation to the end of the chunk,
                // then tabulate the next one from the state there.
                while open && t > table.t_end() {
                    let end = table.t_end();
                    let rhs = OrientationRhs(|t| table.omega_at(t));
                    let omega = |t: Real, _: &State<3>| table.omega_at(t);
                    g.advance(&rhs, &omega, end, end)?;
                    let span = physical_chunk_length(&self.model);
                    let (next, stats) =
                        physical_table(&self.model, &table.omega_at(end), span, self.options.rtol)?;
                    **table = next.starting_at(end);
                    *built += stats;
                }
                let stop = if open { table.t_end() } else { self.horizon };
                let rhs = OrientationRhs(|t| table.omega_at(t));
                let omega = |t: Real, _: &State<3>| table.omega_at(t);
                let (_, rotation) = g.advance(&rhs, &omega, t, stop)?;
                (table.omega_at(t), rotation)
            }
        };
        if !(all_finite(&omega) && all_finite(&rotation)) {
            return Err(SimError::NonFiniteSample(t));
        }
        let sample = Sample::new(t, &inertia, &rotation, &omega);
        // The observables can overflow where Ω does not (E = ΩᵀIΩ/2 with a
        // huge I or Ω): a sample is reported only when every number in it is.
        if !sample.is_finite() {
            return Err(SimError::NonFiniteSample(t));
        }
        self.current = sample;
        Ok(&self.current)
    }

    /// Sample at each of `times` (finite, ≥ 0, non-decreasing).
    pub fn run(&mut self, times: &[Real]) -> Result<Vec<Sample>, SimError> {
        let mut last = self.current.t;
        let mut out = Vec::with_capacity(times.len());
        for &t in times {
            if !t.is_finite() || t < last {
                return Err(SimError::BadTime(t, last));
            }
            last = t;
            out.push(*self.advance_to(t)?);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod method_rule_tests {
    use super::*;

    fn models() -> Vec<Model> {
        let sym = SymmetricTop::figure();
        let general = GeneralTop::new(Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.3, 0.2, 1.0)).unwrap();
        vec![
            Model::Truncated(sym),
            Model::Reduced(sym),
            Model::Full(sym),
            Model::General(general),
            Model::GeneralReduced(general),
            Model::GeneralFull(general),
        ]
    }

    /// A method's choice is the choice that runs it: for every model and
    /// every choice other than `auto`, the method the rule takes bears the
    /// choice's name or none (`exact+dop853`, `physical`); and `auto`'s
    /// integrator for a general top is named by a choice that runs it.
    #[test]
    fn a_methods_choice_runs_that_method() {
        let options = MethodOptions::default();
        for model in models() {
            for choice in MethodChoice::ALL {
                let Ok(method) = model.method(choice, &options) else {
                    continue;
                };
                match (choice, method.choice()) {
                    (MethodChoice::Auto, Some(named)) => {
                        assert_eq!(model.method(named, &options), Ok(method));
                    }
                    (_, Some(named)) => assert_eq!(named, choice, "{}", model.name()),
                    (_, None) => assert!(matches!(
                        method,
                        Method::ClosedFormDop853 | Method::Physical
                    )),
                }
            }
        }
        let general = models()[3];
        for rtol in [1e-6, 1e-12] {
            let options = MethodOptions::default().with_rtol(rtol).unwrap();
            let auto = general.method(MethodChoice::Auto, &options).unwrap();
            assert_eq!(auto, auto_integrator(rtol));
            assert!(auto.choice().is_some(), "{rtol}: {auto:?}");
        }
    }

    /// The rule every entry point asks (`Model::check_method`) and what a
    /// simulation actually builds agree for every model and every choice: a
    /// choice the rule takes builds and runs, one it refuses is refused by
    /// the simulation with the same reason.
    #[test]
    fn the_method_rule_is_what_the_simulation_runs() {
        let initial =
            InitialState::new(Vec3::new(0.0, 0.1, 0.2), EulerAngles::new(0.0, 0.0, 0.0)).unwrap();
        for model in models() {
            for choice in MethodChoice::ALL {
                let built =
                    Simulation::new(model, choice, MethodOptions::default(), initial, Some(1.0));
                match model.method(choice, &MethodOptions::default()) {
                    Ok(method) => {
                        let mut sim = built.unwrap_or_else(|e| {
                            panic!("{} by {}: {e}", model.name(), choice.name())
                        });
                        assert_eq!(sim.method(), method);
                        assert!(sim.advance_to(1.0).is_ok());
                    }
                    Err(refused) => {
                        assert_eq!(built.unwrap_err(), SimError::Refused(refused));
                        let text = refused.to_string();
                        assert!(text.contains(model.name()), "{text}");
                    }
                }
            }
        }
    }

    /// `auto` takes the closed forms where they exist and the physical
    /// solution for the full ALE at any tolerance; for the asymmetric tops
    /// DOP853 above [`TAYLOR_AUTO_RTOL`] and the Taylor method at and below
    /// it.
    #[test]
    fn auto_takes_the_closed_forms_where_they_exist() {
        let rtols = [1e-3, 1e-8, 2.0 * TAYLOR_AUTO_RTOL, TAYLOR_AUTO_RTOL, 1e-14];
        for (model, rtol) in models().into_iter().flat_map(|m| rtols.map(|r| (m, r))) {
            let options = MethodOptions::default().with_rtol(rtol).unwrap();
            let method = model.method(MethodChoice::Auto, &options).unwrap();
            let integrated = if rtol <= TAYLOR_AUTO_RTOL {
                Method::Taylor
            } else {
                Method::Dop853
            };
            let expected = match model {
                Model::Truncated(_) => Method::ClosedForm,
                Model::Reduced(_) => Method::ClosedFormDop853,
                Model::Full(_) | Model::GeneralFull(_) => Method::Physical,
                Model::General(_) | Model::GeneralReduced(_) => integrated,
            };
            assert_eq!(method, expected, "{} at {rtol:e}", model.name());
            assert_eq!(
                model.closed_form(&Vec3::new(0.0, 0.1, 0.2), 1.0).is_some(),
                model.has_closed_form()
            );
        }
    }

    #[test]
    fn options_are_checked_once_when_built() {
        assert!(MethodOptions::new(1e-10, 0.01).is_ok());
        assert_eq!(
            MethodOptions::new(0.0, 0.01),
            Err(OptionsError::RtolOutOfRange(0.0))
        );
        assert!(MethodOptions::new(Real::NAN, 0.01).is_err());
        assert_eq!(
            MethodOptions::new(1e-15, 0.01),
            Err(OptionsError::RtolBelowDouble(1e-15))
        );
        assert!(MethodOptions::new(MIN_RTOL, 0.01).is_ok());
        assert!(MethodOptions::new(1e-10, 0.0).is_err());
        assert!(MethodOptions::new(1e-10, Real::INFINITY).is_err());
        let rk4 = MethodChoice::Rk4;
        assert_eq!(
            MethodOptions::for_choice(rk4, Some(1e-8), None),
            Err(OptionsError::RtolForRk4)
        );
        assert_eq!(
            MethodOptions::for_choice(MethodChoice::Dop853, None, Some(0.1)),
            Err(OptionsError::StepNotRk4)
        );
        let o = MethodOptions::for_choice(rk4, None, Some(0.1)).unwrap();
        assert_eq!((o.rtol(), o.step()), (1e-10, 0.1));
        for e in [
            OptionsError::RtolForRk4,
            OptionsError::StepNotPositive(-1.0),
        ] {
            assert!(e.to_string().starts_with(e.key()), "{e}");
        }
    }

    #[test]
    fn every_choice_has_its_name() {
        for (choice, name) in MethodChoice::ALL.iter().zip(MethodChoice::NAMES) {
            assert_eq!(choice.name(), name);
            assert_eq!(MethodChoice::from_name(name), Some(*choice));
        }
        assert_eq!(MethodChoice::from_name("euler"), None);
    }
}
