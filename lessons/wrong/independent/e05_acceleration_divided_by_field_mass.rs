//! assignment: shell_acceleration
//! mistake: divided by m_em instead of m0
//! says: field's mass
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let (_m0, m_em) = crate::appendix::shell_masses(tau0, delta);
    (-z - z_ddot_ret * m_em) / m_em
}
