//! assignment: shell_acceleration
//! mistake: +m_em Z''(t - delta): the retarded term's sign
//! says: retarded term has the wrong sign
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let (m0, m_em) = crate::appendix::shell_masses(tau0, delta);
    (-z + z_ddot_ret * m_em) / m0
}
