//! Section 2: the two balance laws for a dipole trajectory. Units: κ = 2/(3c³) = 1.
//!
//! Each function but the last gets the jet `[d, d', d'', d''']` of the dipole
//! at one instant. Easy to hard: (2.1), (2.4), (2.2), (2.3), the axial
//! projection, the precessing dipole.

#[cfg(not(feature = "solutions"))]
use spintop::assignment::{Jet, Vec3};

/// dL/dt by the Larmor-like law. Paper: Eq. (2.1). Book: Section 2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn larmor_rate(jet: &Jet) -> Vec3 {
    todo!("Eq. (2.1): see the book, chapter 'Section 2', the two laws")
}

/// The Schott angular momentum L_S. Paper: Eq. (2.4). Book: Section 2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    todo!("Eq. (2.4): see the book, chapter 'Section 2', the Schott term")
}

/// dL/dt by the radiation-reaction torque. Paper: Eq. (2.2). Book: Section 2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn torque_rate(jet: &Jet) -> Vec3 {
    todo!("Eq. (2.2): see the book, chapter 'Section 2', the two laws")
}

/// dL_S/dt, by which the two laws differ. Paper: Eq. (2.3). Book: Section 2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn schott_rate(jet: &Jet) -> Vec3 {
    todo!("Eq. (2.3): see the book, chapter 'Section 2', the Schott term")
}

/// n · dL_S/dt with n = d/|d|, the part of the difference of the two laws
/// along the dipole. Paper: Eqs. (2.3)–(2.4). Book: Section 2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn axial_schott_rate(jet: &Jet) -> f64 {
    todo!("Eqs. (2.3)-(2.4): see the book, chapter 'Section 2', the axial projection")
}

/// The jet `[d, d', d'', d''']` at time `t` of a unit dipole precessing on a
/// cone of half-angle `theta` about z at the rate `omega`, starting in the
/// x–z plane. Book: Section 2, the precessing dipole.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn precessing_dipole_jet(theta: f64, omega: f64, t: f64) -> Jet {
    todo!("Section 2: see the book, the precessing dipole")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::ch2::*;
