//! Section 4: the symmetric top. Units: τ as given, I₁ = 1, `ratio` = I₃/I₁.
//!
//! Section 4.1 (the truncated top) first, then Section 4.2 (the reduced top).

#[cfg(not(feature = "solutions"))]
use spintop::assignment::Vec3;

/// Ω⊥(t) of the truncated model from Ω⊥(0) = `omega_perp0`.
/// Paper: Eqs. (4.5)–(4.6). Book: Section 4.1, the truncated top.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    todo!("Eqs. (4.5)-(4.6): see the book, chapter 'Section 4.1: the truncated top'")
}

/// Ω(t) of the truncated model for any start Ω₀ (Ω₁₀ need not be 0).
/// Paper: Eq. (4.7). Book: Section 4.1.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    todo!("Eq. (4.7): see the book, chapter 'Section 4.1: the truncated top'")
}

/// How long the truncated model takes to slow every rate by the factor `p`
/// (0 < p < 1). Paper: Eq. (4.6), inverted. Book: Section 4.1.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn truncated_time_to_factor(ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    todo!("Eq. (4.6): see the book, chapter 'Section 4.1: the truncated top'")
}

/// The constant angle θ between the symmetry axis and L in the truncated
/// model. Paper: Eq. (4.11), as corrected on the Errata page. Book: Section 4.1.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    todo!("Eq. (4.11): see the book, chapter 'Section 4.1: the truncated top' and the Errata page")
}

/// Ω̇ of the reduced model. Paper: Eqs. (4.12)–(4.14). Book: Section 4.2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    todo!("Eqs. (4.12)-(4.14): see the book, chapter 'Section 4.2: the reduced top'")
}

/// σ, the late-time decay time of Ω⊥ in the reduced model, for the spin
/// `omega3`. Paper: Eq. (4.16). Book: Section 4.2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    todo!("Eq. (4.16): see the book, chapter 'Section 4.2: the reduced top'")
}

/// Ω(t) of the reduced model for any start Ω₀ (Ω₁₀ need not be 0).
/// Paper: Eqs. (4.15)–(4.16). Book: Section 4.2, the reduced top.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    todo!("Eqs. (4.15)-(4.16): see the book, chapter 'Section 4.2: the reduced top'")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::ch4::*;
