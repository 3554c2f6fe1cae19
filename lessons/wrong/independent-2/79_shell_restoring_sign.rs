//! assignment: shell_acceleration
//! mistake: the restoring force with the wrong sign, (+Z - m_em Z''(t - δ))/m₀ (Z moved to the other side without changing its sign)
//! says: sign, restoring
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    (z - z_ddot_ret * m_em) / m0
}
