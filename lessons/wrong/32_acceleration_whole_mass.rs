//! assignment: shell_acceleration
//! mistake: divided by m = 1 instead of m0
//! says: whole mass
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    -z - z_ddot_ret * (tau0 / delta)
}
