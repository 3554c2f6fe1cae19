//! assignment: shell_masses
//! mistake: the field's mass written δ/τ₀ instead of τ₀/δ
//! says: inverted, m_em
pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = delta / tau0;
    (1.0 - m_em, m_em)
}
