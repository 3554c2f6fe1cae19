//! Row 3 of the stability suite: stiffness of the reduced model at τΩ² ≫ 1.

use super::{Row, RowError};
use crate::integrate::Rhs;
use crate::math::{Real, State};
use crate::physics::symmetric_top::{SymmetricTop, reduced_ale_jacobian, reduced_ale_rhs};
use nalgebra::SMatrix;

/// The reduced ALE (4.12)–(4.14) as a right-hand side `Ω̇ = F(Ω)` with its
/// analytic Jacobian, for the implicit method.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedAle(pub SymmetricTop);

impl Rhs<3> for ReducedAle {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        reduced_ale_rhs(&self.0, y)
    }

    fn jacobian(&self, _t: Real, y: &State<3>) -> SMatrix<Real, 3, 3> {
        reduced_ale_jacobian(&self.0, y)
    }
}

/// The measurement of row 3.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement;

/// Run the experiment of row 3.
pub fn measure() -> Result<Measurement, RowError> {
    Err(RowError::new(3, "not built yet"))
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        Row {
            number: 3,
            problem: String::new(),
            naive: Vec::new(),
            fix: Vec::new(),
            notes: Vec::new(),
        }
    }
}
