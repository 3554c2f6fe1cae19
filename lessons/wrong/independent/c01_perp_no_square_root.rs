//! assignment: truncated_omega_perp
//! mistake: Omega_perp0 / R^2: the square root forgotten
//! says: square root

pub fn truncated_omega_perp(_ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    omega_perp0 / (1.0 + 2.0 * tau * omega_perp0 * omega_perp0 * t)
}
