//! assignment: shell_acceleration
//! mistake: only -Z divided by m0; the retarded term left outside the division
//! says: not divided by the bare mass
use spintop::assignment::C;

pub fn shell_acceleration(tau0: f64, delta: f64, z: C, z_ddot_ret: C) -> C {
    let (m0, m_em) = crate::appendix::shell_masses(tau0, delta);
    -z / m0 - z_ddot_ret * m_em
}
