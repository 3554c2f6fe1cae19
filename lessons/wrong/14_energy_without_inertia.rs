//! assignment: energy_rate
//! mistake: Omega . dOmega/dt, the moments left out
//! says: moments of inertia are missing
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    omega.dot(&crate::ch3::truncated_ale_rhs(inertia, dipole, omega))
}
