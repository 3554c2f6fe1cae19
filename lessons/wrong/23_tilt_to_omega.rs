//! assignment: precession_tilt
//! mistake: the angle to Omega, not to L
//! says: not L
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    let _ = ratio;
    omega0.x.hypot(omega0.y).atan2(omega0.z)
}
