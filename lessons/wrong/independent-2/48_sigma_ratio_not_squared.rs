//! assignment: reduced_decay_time
//! mistake: the ratio of moments not squared: 1/(τ (I₃/I₁) Ω₃²) instead of 1/(τ (I₃/I₁)² Ω₃²)
//! says: ratio, square
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / (tau * ratio * omega3 * omega3)
}
