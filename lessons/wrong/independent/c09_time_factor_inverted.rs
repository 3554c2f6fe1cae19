//! assignment: truncated_time_to_factor
//! mistake: R = p instead of R = 1/p: 1 - p^2 in the numerator
//! says: upside down

pub fn truncated_time_to_factor(_ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    (1.0 - p * p) / (2.0 * tau * omega_perp0 * omega_perp0)
}
