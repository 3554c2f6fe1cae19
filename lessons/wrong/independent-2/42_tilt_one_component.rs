//! assignment: precession_tilt
//! mistake: Ω⊥₀ taken as |Ω₂₀| alone (the paper's start has Ω₁₀ = 0), Ω₁₀ forgotten
//! says: component, perpendicular
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    omega0.y.abs().atan2(ratio * omega0.z)
}
