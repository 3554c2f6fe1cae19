//! Section 3: the truncated ALE of a general top. Units: κ = 1, body frame.

#[cfg(not(feature = "solutions"))]
use spintop::assignment::Vec3;

/// Ω̇ of the truncated ALE for a top with principal moments `inertia`, a
/// body-fixed dipole `dipole`, rotating at `omega`.
/// Paper: Eq. (3.3). Book: Section 3.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    todo!("Eq. (3.3): see the book, chapter 'Section 3', the truncated ALE")
}

/// dE/dt, the rate of change of the kinetic energy E = ½ Ω·IΩ under (3.3).
/// You may call your own `truncated_ale_rhs`. Paper: Eq. (3.3). Book: Section 3.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    todo!("Eq. (3.3): see the book, chapter 'Section 3', the energy it loses")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::ch3::*;
