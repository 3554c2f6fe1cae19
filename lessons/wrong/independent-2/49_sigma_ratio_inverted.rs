//! assignment: reduced_decay_time
//! mistake: the ratio of moments inverted: I₃²/(I₁²Ω₃²τ) instead of I₁²/(I₃²Ω₃²τ)
//! says: ratio, inverted
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    ratio * ratio / (omega3 * omega3 * tau)
}
