//! assignment: truncated_ale_rhs
//! mistake: the damping coefficient |d × Ω|² replaced by |d|²|Ω|² (the angle between d and Ω forgotten)
//! says: damping, cross product, wrong term
use spintop::assignment::{Mat3, Vec3};

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let a = Mat3::from_diagonal(&inertia) + dipole * w.transpose();
    let damping = dipole.norm_squared() * omega.norm_squared();
    let b = -omega.cross(&inertia.component_mul(&omega)) - damping * omega;
    a.lu().solve(&b).unwrap_or_else(|| Vec3::repeat(f64::NAN))
}
