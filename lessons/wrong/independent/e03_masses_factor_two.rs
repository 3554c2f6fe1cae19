//! assignment: shell_masses
//! mistake: m_em = 2 tau0/delta (the delay taken as the radius over c)
//! says: m_em is 2 times

pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = 2.0 * tau0 / delta;
    (1.0 - m_em, m_em)
}
