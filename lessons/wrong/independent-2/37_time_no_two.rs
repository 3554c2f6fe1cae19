//! assignment: truncated_time_to_factor
//! mistake: the factor 2 of 2τΩ⊥₀² left out of the denominator, so the time is twice too long
//! says: factor 2
pub fn truncated_time_to_factor(ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    let _ = ratio;
    (1.0 / (p * p) - 1.0) / (tau * omega_perp0 * omega_perp0)
}
