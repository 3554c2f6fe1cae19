//! assignment: truncated_time_to_factor
//! mistake: the 2 of 2 tau Omega^2 t lost when solving for t
//! says: factor 2

pub fn truncated_time_to_factor(_ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    (1.0 / (p * p) - 1.0) / (tau * omega_perp0 * omega_perp0)
}
