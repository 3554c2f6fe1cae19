//! assignment: precession_tilt
//! mistake: Omega_perp taken as |Omega1| alone, Omega2 forgotten
//! says: Omega_2 is left out
use spintop::assignment::Vec3;

pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    omega0.x.abs().atan2(ratio * omega0.z)
}
