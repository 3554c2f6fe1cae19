//! assignment: shell_masses
//! mistake: the pair returned in the wrong order, (m_em, m₀) instead of (m₀, m_em)
//! says: swapped, order
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = tau0 / delta;
    (m_em, 1.0 - m_em)
}
