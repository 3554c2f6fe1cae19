//! assignment: precession_tilt
//! mistake: the ratio of moments inverted: tan θ = I₃Ω⊥₀/(I₁Ω₃₀) instead of I₁Ω⊥₀/(I₃Ω₃₀)
//! says: ratio, inverted
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    omega0.x.hypot(omega0.y).atan2(omega0.z / ratio)
}
