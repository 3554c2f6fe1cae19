//! assignment: shell_masses
//! mistake: the bare mass written m₀ = 1 + m_em (the field's mass added to the total instead of taken from it)
//! says: sign, bare mass
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = tau0 / delta;
    (1.0 + m_em, m_em)
}
