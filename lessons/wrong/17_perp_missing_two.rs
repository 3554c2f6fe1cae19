//! assignment: truncated_omega_perp
//! mistake: 1 + tau Omega^2 t under the root
//! says: factor 2 inside the square root
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    let _ = ratio;
    omega_perp0 / (1.0 + tau * omega_perp0 * omega_perp0 * t).sqrt()
}
