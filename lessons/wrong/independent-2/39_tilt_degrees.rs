//! assignment: precession_tilt
//! mistake: the angle returned in degrees (to_degrees) instead of radians
//! says: degrees, radians
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    omega0
        .x
        .hypot(omega0.y)
        .atan2(ratio * omega0.z)
        .to_degrees()
}
