//! assignment: energy_rate
//! mistake: I Omega . I Omega' : the inertia on both factors
//! says: inertia
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let od = crate::ch3::truncated_ale_rhs(inertia, dipole, omega);
    inertia.component_mul(&omega).dot(&inertia.component_mul(&od))
}
