//! assignment: reduced_decay_time
//! mistake: the decay time of Ω⊥² given for that of Ω⊥: σ/2 = 1/(2τ(I₃Ω₃/I₁)²)
//! says: factor 2, half
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / (2.0 * tau * (ratio * omega3).powi(2))
}
