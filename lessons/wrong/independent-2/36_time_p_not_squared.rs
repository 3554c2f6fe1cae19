//! assignment: truncated_time_to_factor
//! mistake: R = 1/p inverted without squaring: t = (1/p - 1)/(2τΩ⊥₀²) instead of (1/p² - 1)/(2τΩ⊥₀²)
//! says: square, p
pub fn truncated_time_to_factor(ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    let _ = ratio;
    (1.0 / p - 1.0) / (2.0 * tau * omega_perp0 * omega_perp0)
}
