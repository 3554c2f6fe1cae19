//! assignment: energy_rate
//! mistake: a minus sign added because the top loses energy, -Ω·IΩ̇ although Ω·IΩ̇ is already negative
//! says: sign
use spintop::assignment::{Mat3, Vec3};

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let w = dipole.cross(&omega);
    let a = Mat3::from_diagonal(&inertia) + dipole * w.transpose();
    let b = -omega.cross(&inertia.component_mul(&omega)) - w.norm_squared() * omega;
    let omega_dot = a.lu().solve(&b).unwrap_or_else(|| Vec3::repeat(f64::NAN));
    -omega.dot(&inertia.component_mul(&omega_dot))
}
