//! Which equation of motion a top follows: the six models of the paper and
//! beyond, each with its top, its name, its equations and its closed form.

use super::method::{Method, MethodChoice, MethodOptions, MethodRefused, auto_integrator};
use crate::math::{Real, Vec3};
use crate::physics::general_top::GeneralTop;
use crate::physics::symmetric_top::{SymmetricTop, reduced_closed_form, truncated_closed_form};

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
            (_, C::Auto) => auto_integrator(options.rtol()),
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
    pub(super) fn first_order(&self) -> Option<FirstOrder> {
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
pub(super) enum FirstOrder {
    Truncated(SymmetricTop),
    Reduced(SymmetricTop),
    General(GeneralTop),
    GeneralReduced(GeneralTop),
}
