//! assignment: precessing_dipole_jet
//! mistake: the half-angle θ taken as degrees and converted to radians before sin and cos, although it is given in radians
//! says: degrees, radians, theta
use spintop::assignment::{Jet, Vec3};

pub fn precessing_dipole_jet(theta: f64, omega: f64, t: f64) -> Jet {
    let (st, ct) = theta.to_radians().sin_cos();
    let (s, c) = (omega * t).sin_cos();
    let w = omega;
    [
        Vec3::new(st * c, st * s, ct),
        Vec3::new(-w * st * s, w * st * c, 0.0),
        Vec3::new(-w * w * st * c, -w * w * st * s, 0.0),
        Vec3::new(w * w * w * st * s, -w * w * w * st * c, 0.0),
    ]
}
