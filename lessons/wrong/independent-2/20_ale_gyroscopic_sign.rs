//! assignment: truncated_ale_rhs
//! mistake: the gyroscopic term with the wrong sign, +Ω × IΩ on the right-hand side instead of -Ω × IΩ
//! says: sign, gyroscopic
use spintop::assignment::{Mat3, Vec3};

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let a = Mat3::from_diagonal(&inertia) + dipole * w.transpose();
    let b = omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    a.lu().solve(&b).unwrap_or_else(|| Vec3::repeat(f64::NAN))
}
