//! assignment: shell_masses
//! mistake: m0 = 1 + m_em: the field's mass added instead of subtracted
//! says: add up to m = 1

pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = tau0 / delta;
    (1.0 + m_em, m_em)
}
