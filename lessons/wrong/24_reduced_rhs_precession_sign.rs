//! assignment: reduced_ale_rhs
//! mistake: both precession terms with the wrong sign
//! says: turns the wrong way
use spintop::assignment::Vec3;

pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let wt3 = (1.0 - ratio) * omega.z;
    let damp = tau * (omega.x * omega.x + omega.y * omega.y + (ratio * omega.z).powi(2));
    Vec3::new(-wt3 * omega.y - damp * omega.x, wt3 * omega.x - damp * omega.y, 0.0)
}
