//! assignment: shell_masses
//! mistake: m_em = delta/tau0 (the ratio upside down)
//! says: upside down

pub fn shell_masses(tau0: f64, delta: f64) -> (f64, f64) {
    let m_em = delta / tau0;
    (1.0 - m_em, m_em)
}
