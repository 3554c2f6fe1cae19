//! assignment: truncated_omega_perp
//! mistake: the factor 2 inside the root dropped, R = √(1 + τΩ⊥₀²t) instead of √(1 + 2τΩ⊥₀²t)
//! says: factor 2
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    let _ = ratio;
    omega_perp0 / (1.0 + tau * omega_perp0 * omega_perp0 * t).sqrt()
}
