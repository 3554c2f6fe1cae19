//! assignment: euler_from_rotation
//! mistake: rows and columns swapped when reading the matrix (the angles of the transpose, the inverse rotation)
//! says: transpose, row, column, inverse
use spintop::assignment::Mat3;

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(2, 0)].hypot(m[(2, 1)]);
    let theta = s.atan2(m[(2, 2)]);
    if s < 1e-12 {
        return (m[(0, 1)].atan2(m[(0, 0)]), theta, 0.0);
    }
    (
        m[(2, 0)].atan2(-m[(2, 1)]),
        theta,
        m[(0, 2)].atan2(m[(1, 2)]),
    )
}
