//! assignment: reduced_ale_rhs
//! mistake: the damping rate tau |Omega|^2 (the ratio^2 on Omega3^2 forgotten)
//! says: moment ratio
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
