//! assignment: truncated_omega_perp
//! mistake: Ω⊥₀ not squared inside R: √(1 + 2τΩ⊥₀t) instead of √(1 + 2τΩ⊥₀²t)
//! says: square
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    let _ = ratio;
    omega_perp0 / (1.0 + 2.0 * tau * omega_perp0 * t).sqrt()
}
