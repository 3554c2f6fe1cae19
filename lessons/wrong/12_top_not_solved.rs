//! assignment: truncated_ale_rhs
//! mistake: the term with the angular acceleration dropped instead of solved
//! says: must be solved for it
use spintop::assignment::Vec3;

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    b.component_div(&inertia)
}
