use spintop::assignment::{Mat3, Vec3};

/// Eq. (3.3): (I + d (d × Ω)ᵀ) Ω̇ = −Ω × IΩ − |d × Ω|² Ω, solved by LU.
pub fn truncated_ale_rhs(inertia: Vec3, dipole: Vec3, omega: Vec3) -> Vec3 {
    let w = dipole.cross(&omega);
    let a = Mat3::from_diagonal(&inertia) + dipole * w.transpose();
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    a.lu().solve(&b).unwrap_or_else(|| Vec3::repeat(f64::NAN))
}

/// dE/dt = Ω · IΩ̇ with Ω̇ from (3.3).
pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let omega_dot = truncated_ale_rhs(inertia, dipole, omega);
    omega.dot(&inertia.component_mul(&omega_dot))
}
