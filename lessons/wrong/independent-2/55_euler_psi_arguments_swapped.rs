//! assignment: euler_from_rotation
//! mistake: the two arguments of atan2 for ψ swapped, atan2(m₃₂, m₃₁) instead of atan2(m₃₁, m₃₂), so ψ comes out as π/2 - ψ
//! says: psi, swapped, atan2
use spintop::assignment::Mat3;

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    if s < 1e-12 {
        return (m[(1, 0)].atan2(m[(0, 0)]), theta, 0.0);
    }
    (
        m[(0, 2)].atan2(-m[(1, 2)]),
        theta,
        m[(2, 1)].atan2(m[(2, 0)]),
    )
}
