//! assignment: energy_rate
//! mistake: 1/2 Omega . I Omega' : the 1/2 of E kept in its derivative
//! says: 1/2
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let od = crate::ch3::truncated_ale_rhs(inertia, dipole, omega);
    0.5 * omega.dot(&inertia.component_mul(&od))
}
