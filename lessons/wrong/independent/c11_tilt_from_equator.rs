//! assignment: precession_tilt
//! mistake: the complement: the angle from the equatorial plane, atan2(I3 Omega3, I1 Omega_perp)
//! says: angle from the equator
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    (ratio * omega0.z).atan2(omega0.x.hypot(omega0.y))
}
