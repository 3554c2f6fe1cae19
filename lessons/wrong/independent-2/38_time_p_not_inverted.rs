//! assignment: truncated_time_to_factor
//! mistake: R = p used instead of R = 1/p, and the sign fixed by hand: t = (1 - p²)/(2τΩ⊥₀²)
//! says: inverted, 1/p
pub fn truncated_time_to_factor(ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    let _ = ratio;
    (1.0 - p * p) / (2.0 * tau * omega_perp0 * omega_perp0)
}
