//! assignment: energy_rate
//! mistake: the rate of L²/2 = |IΩ|²/2 handed in for the energy's, IΩ·IΩ̇ instead of Ω·IΩ̇ (the inertia applied twice)
//! says: inertia, twice, angular momentum
use spintop::assignment::{Mat3, Vec3};

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let w = dipole.cross(&omega);
    let a = Mat3::from_diagonal(&inertia) + dipole * w.transpose();
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    let omega_dot = a.lu().solve(&b).unwrap_or_else(|| Vec3::repeat(f64::NAN));
    inertia
        .component_mul(&omega)
        .dot(&inertia.component_mul(&omega_dot))
}
