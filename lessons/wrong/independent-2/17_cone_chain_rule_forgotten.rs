//! assignment: precessing_dipole_jet
//! mistake: the chain rule forgotten: the derivatives of cos ωt and sin ωt lack their factors ω, ω², ω³
//! says: chain rule, omega, factor
use spintop::assignment::{Jet, Vec3};

pub fn precessing_dipole_jet(theta: f64, omega: f64, t: f64) -> Jet {
    let (st, ct) = theta.sin_cos();
    let (s, c) = (omega * t).sin_cos();
    [
        Vec3::new(st * c, st * s, ct),
        Vec3::new(-st * s, st * c, 0.0),
        Vec3::new(-st * c, -st * s, 0.0),
        Vec3::new(st * s, -st * c, 0.0),
    ]
}
