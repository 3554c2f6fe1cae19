//! assignment: truncated_omega_perp
//! mistake: an exponential decay
//! says: exponential
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    let _ = ratio;
    omega_perp0 * (-2.0 * tau * omega_perp0 * omega_perp0 * t).exp()
}
