//! Appendix: the charge as a small shell. Units: m = m₀ + m_em = 1, k = 1.

#[cfg(not(feature = "solutions"))]
use spintop::assignment::C;

/// The bare mass m₀ and the field's mass m_em, as `(m0, m_em)`, for the
/// radiation time `tau0` and the delay `delta`. Paper: Eq. (A.1). Book: Appendix.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    todo!("Eq. (A.1): see the book, chapter 'Appendix', the two masses")
}

/// The method-of-steps update of (A.1): Z''(t) from Z(t) and the retarded
/// Z''(t − δ), for radiation time `tau0` and delay `delta`.
/// Paper: Eq. (A.1). Book: Appendix.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    todo!("Eq. (A.1): see the book, chapter 'Appendix', the delay equation")
}

/// The root s of the characteristic function of (A.1) (Z ∝ e^{st}) that
/// continues the undamped oscillation s = i. Paper: Eq. (A.1). Book: Appendix.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    todo!("Eq. (A.1): see the book, chapter 'Appendix', its characteristic roots")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::appendix::*;
