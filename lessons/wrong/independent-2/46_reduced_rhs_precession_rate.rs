//! assignment: reduced_ale_rhs
//! mistake: the precession rate written (I₃/I₁)Ω₃ instead of (1 - I₃/I₁)Ω₃
//! says: precession, rate, wrong term
use spintop::assignment::Vec3;

pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let precession = ratio * omega.z;
    let damping = tau * (omega.x * omega.x + omega.y * omega.y + (ratio * omega.z).powi(2));
    Vec3::new(
        precession * omega.y - damping * omega.x,
        -precession * omega.x - damping * omega.y,
        0.0,
    )
}
