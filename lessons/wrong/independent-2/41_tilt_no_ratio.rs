//! assignment: precession_tilt
//! mistake: the moments of inertia left out: the angle between the axis and Ω, atan2(Ω⊥₀, Ω₃₀), instead of the angle to L = IΩ
//! says: ratio, inertia, missing
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    let _ = ratio;
    omega0.x.hypot(omega0.y).atan2(omega0.z)
}
