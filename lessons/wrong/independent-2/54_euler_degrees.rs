//! assignment: euler_from_rotation
//! mistake: the three angles returned in degrees (to_degrees) instead of radians
//! says: degrees, radians
use spintop::assignment::Mat3;

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    let (phi, psi) = if s < 1e-12 {
        (m[(1, 0)].atan2(m[(0, 0)]), 0.0)
    } else {
        (m[(0, 2)].atan2(-m[(1, 2)]), m[(2, 0)].atan2(m[(2, 1)]))
    };
    (phi.to_degrees(), theta.to_degrees(), psi.to_degrees())
}
