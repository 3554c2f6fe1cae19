//! Section 3: the equations of motion of a polarized top. Units: κ = 1.

#[cfg(not(feature = "solutions"))]
use spintop::math::Vec3;

/// Ω̇ of the truncated ALE for a top with principal moments `inertia` and a
/// body-frame dipole `dipole`, at body angular velocity `omega`.
/// Paper: Eq. (3.3). Book: Section 3.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    todo!("Eq. (3.3): see the book, chapter 'Section 3', the truncated ALE")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::ch3::*;
