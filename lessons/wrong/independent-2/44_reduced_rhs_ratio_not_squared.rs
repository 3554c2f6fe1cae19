//! assignment: reduced_ale_rhs
//! mistake: the weight of Ω₃² in the damping rate is I₃/I₁ instead of (I₃/I₁)²
//! says: ratio, square, damping
use spintop::assignment::Vec3;

pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let precession = (1.0 - ratio) * omega.z;
    let damping = tau * (omega.x * omega.x + omega.y * omega.y + ratio * omega.z * omega.z);
    Vec3::new(
        precession * omega.y - damping * omega.x,
        -precession * omega.x - damping * omega.y,
        0.0,
    )
}
