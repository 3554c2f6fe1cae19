use spintop::physics::shell::C;

/// Eq. (A.1): m₀Z'' + Z = −m_em Z''(t − δ), m_em = τ₀/δ, m₀ = 1 − m_em.
pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    (-z - z_ddot_ret * m_em) / m0
}
