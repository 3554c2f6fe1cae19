//! assignment: reduced_ale_rhs
//! mistake: the Ω⊥² part of the damping rate left out: only τ(I₃Ω₃/I₁)²
//! says: perpendicular, damping, missing term
use spintop::assignment::Vec3;

pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let precession = (1.0 - ratio) * omega.z;
    let damping = tau * (ratio * omega.z).powi(2);
    Vec3::new(
        precession * omega.y - damping * omega.x,
        -precession * omega.x - damping * omega.y,
        0.0,
    )
}
