//! Section 4: the symmetric top. Units: τ as given, I₁ = 1, `ratio` = I₃/I₁.

#[cfg(not(feature = "solutions"))]
use spintop::math::Vec3;

/// Ω(t) of the reduced model for any start Ω₀ (Ω₁₀ need not be 0).
/// Paper: Eqs. (4.15)–(4.16). Book: Section 4.2, the reduced top.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    todo!("Eqs. (4.15)-(4.16): see the book, chapter 'Section 4.2: the reduced top'")
}

/// The constant angle θ between the symmetry axis and L in the truncated
/// model. Paper: Eq. (4.11), as corrected on the Errata page. Book: Section 4.1.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    todo!("Eq. (4.11): see the book, chapter 'Section 4.1: the truncated top' and the Errata page")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::ch4::*;
