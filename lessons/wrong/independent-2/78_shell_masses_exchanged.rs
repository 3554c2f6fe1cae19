//! assignment: shell_acceleration
//! mistake: the two masses exchanged in the update: (-Z - m₀ Z''(t - δ))/m_em
//! says: swapped, masses
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    (-z - z_ddot_ret * m0) / m_em
}
