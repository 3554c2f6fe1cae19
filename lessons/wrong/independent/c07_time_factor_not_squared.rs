//! assignment: truncated_time_to_factor
//! mistake: 1/p - 1 where 1/p^2 - 1 belongs
//! says: not squared

pub fn truncated_time_to_factor(_ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    (1.0 / p - 1.0) / (2.0 * tau * omega_perp0 * omega_perp0)
}
