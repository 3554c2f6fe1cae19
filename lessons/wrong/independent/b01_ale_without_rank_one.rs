//! assignment: truncated_ale_rhs
//! mistake: the d (d x Omega)^T term on the left left out: Omega' = I^-1 (right-hand side)
//! says: solved for it
use spintop::assignment::{Mat3, Vec3};

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    b.component_div(&inertia)
}
