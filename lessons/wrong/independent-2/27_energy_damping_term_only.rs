//! assignment: energy_rate
//! mistake: only the damping term kept, -|d × Ω|² |Ω|²; the term -(Ω·d)((d × Ω)·Ω̇) from the matrix on the left-hand side is missing
//! says: missing term, matrix
use spintop::assignment::Vec3;

pub fn energy_rate(inertia: Vec3, dipole: Vec3, omega: Vec3) -> f64 {
    let _ = inertia;
    -dipole.cross(&omega).norm_squared() * omega.norm_squared()
}
