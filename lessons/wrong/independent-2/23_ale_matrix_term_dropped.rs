//! assignment: truncated_ale_rhs
//! mistake: the term d (d × Ω)ᵀ Ω̇ of the left-hand side dropped, so only I Ω̇ = -Ω × IΩ - |d × Ω|² Ω is solved
//! says: matrix, left-hand side, missing term
use spintop::assignment::Vec3;

pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    b.component_div(&inertia)
}
