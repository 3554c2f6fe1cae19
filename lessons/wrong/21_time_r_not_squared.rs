//! assignment: truncated_time_to_factor
//! mistake: R = 1/p solved without squaring
//! says: not squared
pub fn truncated_time_to_factor(ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    let _ = ratio;
    (1.0 / p - 1.0) / (2.0 * tau * omega_perp0 * omega_perp0)
}
