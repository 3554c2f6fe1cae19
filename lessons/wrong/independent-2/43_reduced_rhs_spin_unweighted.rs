//! assignment: reduced_ale_rhs
//! mistake: the damping rate τ|Ω|² without the weight (I₃/I₁)² on Ω₃², i.e. τ(Ω₁² + Ω₂² + Ω₃²)
//! says: ratio, damping, wrong term
use spintop::assignment::Vec3;

pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let precession = (1.0 - ratio) * omega.z;
    let damping = tau * omega.norm_squared();
    Vec3::new(
        precession * omega.y - damping * omega.x,
        -precession * omega.x - damping * omega.y,
        0.0,
    )
}
