//! assignment: precession_tilt
//! mistake: atan(Omega_perp / (ratio Omega_3)): wrong for Omega_3 < 0
//! says: Omega_3 < 0
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    (omega0.x.hypot(omega0.y) / (ratio * omega0.z)).atan()
}
