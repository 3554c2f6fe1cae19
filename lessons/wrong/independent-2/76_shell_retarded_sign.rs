//! assignment: shell_acceleration
//! mistake: the retarded term with the wrong sign, (-Z + m_em Z''(t - δ))/m₀
//! says: sign, retarded
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    (-z + z_ddot_ret * m_em) / m0
}
