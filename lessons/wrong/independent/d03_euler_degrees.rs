//! assignment: euler_from_rotation
//! mistake: all three angles in degrees
//! says: degrees
use spintop::assignment::{DynField, Mat3, State, Vec3};

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    if s < 1e-12 {
        return (m[(1, 0)].atan2(m[(0, 0)]).to_degrees(), theta.to_degrees(), 0.0);
    }
    (
        m[(0, 2)].atan2(-m[(1, 2)]).to_degrees(),
        theta.to_degrees(),
        m[(2, 0)].atan2(m[(2, 1)]).to_degrees(),
    )
}
