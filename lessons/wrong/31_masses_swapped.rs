//! assignment: shell_masses
//! mistake: m_em returned first
//! says: swapped
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = tau0 / delta;
    (m_em, 1.0 - m_em)
}
