//! assignment: energy_rate
//! mistake: only the |d x Omega|^2 Omega^2 term
//! says: only the first damping term
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let _ = inertia;
    -dipole.cross(&omega).norm_squared() * omega.norm_squared()
}
