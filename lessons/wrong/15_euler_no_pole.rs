//! assignment: euler_from_rotation
//! mistake: psi from atan2 of two zeros on the pole, divided by sin theta
//! says: not finite on or near a pole
use spintop::assignment::Mat3;

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    let phi = (m[(0, 2)] / s).atan2(-m[(1, 2)] / s);
    let psi = (m[(2, 0)] / s).atan2(m[(2, 1)] / s);
    (phi, theta, psi)
}
