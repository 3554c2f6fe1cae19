//! assignment: precessing_dipole_jet
//! mistake: d''' with the wrong sign
//! says: d''' has the wrong sign
use spintop::assignment::{Jet, Vec3};

pub fn precessing_dipole_jet(theta: f64, omega: f64, t: f64) -> Jet {
    let (s, c) = (omega * t).sin_cos();
    let st = theta.sin();
    [
        Vec3::new(st * c, st * s, theta.cos()),
        omega * st * Vec3::new(-s, c, 0.0),
        -omega * omega * st * Vec3::new(c, s, 0.0),
        omega.powi(3) * st * Vec3::new(-s, c, 0.0),
    ]
}
