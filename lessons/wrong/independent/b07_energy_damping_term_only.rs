//! assignment: energy_rate
//! mistake: -|d x Omega|^2 |Omega|^2 : only the damping term dotted with Omega, the d (d x Omega)^T Omega' part dropped
//! says: only the first damping term
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    -dipole.cross(&omega).norm_squared() * omega.norm_squared()
}
