//! assignment: shell_acceleration
//! mistake: the retarded acceleration without its mass m_em: (-Z - Z''(t - δ))/m₀
//! says: m_em, factor, retarded
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let m0 = 1.0 - tau0 / delta;
    (-z - z_ddot_ret) / m0
}
