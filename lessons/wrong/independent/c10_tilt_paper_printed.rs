//! assignment: precession_tilt
//! mistake: the ratio on the wrong side, as (4.11) was printed before the errata: tan theta = ratio Omega_perp / Omega3
//! says: moments of inertia are swapped
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    (ratio * omega0.x.hypot(omega0.y)).atan2(omega0.z)
}
