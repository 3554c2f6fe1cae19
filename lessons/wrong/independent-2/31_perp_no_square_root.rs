//! assignment: truncated_omega_perp
//! mistake: the square root of R forgotten: Ω⊥₀/(1 + 2τΩ⊥₀²t), a decay like 1/t instead of 1/√t
//! says: square root
pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    let _ = ratio;
    omega_perp0 / (1.0 + 2.0 * tau * omega_perp0 * omega_perp0 * t)
}
