//! assignment: truncated_ale_rhs
//! mistake: Euler's equations only, the radiation forgotten
//! says: radiation damping is missing
use spintop::assignment::Vec3;

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let _ = dipole;
    (-omega.cross(&inertia.component_mul(&omega))).component_div(&inertia)
}
