use spintop::assignment::C;

/// Eq. (A.1): m_em = τ₀/δ, m₀ = 1 − m_em.
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = tau0 / delta;
    (1.0 - m_em, m_em)
}

/// Eq. (A.1): m₀Z'' + Z = −m_em Z''(t − δ), m_em = τ₀/δ, m₀ = 1 − m_em.
pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let (m0, m_em) = shell_masses(tau0, delta);
    (-z - z_ddot_ret * m_em) / m0
}

/// Newton's method on P(s) = s²(m₀ + m_em e^{−sδ}) + 1 from s = i.
pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let (m0, m_em) = shell_masses(tau0, delta);
    let mut s = C::new(0.0, 1.0);
    for _ in 0..100 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        let step = p / dp;
        s -= step;
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    s
}
