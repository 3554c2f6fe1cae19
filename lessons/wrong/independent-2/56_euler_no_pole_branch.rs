//! assignment: euler_from_rotation
//! mistake: no special case on the poles: with sin θ = 0, φ and ψ come from atan2(±0, ±0), and φ ± ψ is lost
//! says: pole
use spintop::assignment::Mat3;

pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    (
        m[(0, 2)].atan2(-m[(1, 2)]),
        theta,
        m[(2, 0)].atan2(m[(2, 1)]),
    )
}
