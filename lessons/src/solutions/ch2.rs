use spintop::assignment::{Jet, Vec3};

/// Eq. (2.1).
pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [_, d1, d2, _] = jet;
    -d1.cross(d2)
}

/// Eq. (2.4).
pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, _, d2, _] = jet;
    d.cross(d2)
}

/// Eq. (2.2).
pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, _, _, d3] = jet;
    d.cross(d3)
}

/// Eq. (2.3): the product rule on L_S = d × d''.
pub fn schott_rate(jet: &Jet) -> Vec3 {
    let [d, d1, d2, d3] = jet;
    d1.cross(d2) + d.cross(d3)
}

/// Eqs. (2.3)-(2.4): n · (d' × d'' + d × d'''); the second term is ⊥ d.
pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let [d, d1, d2, _] = jet;
    let n = d.norm();
    if n == 0.0 {
        0.0
    } else {
        d.dot(&d1.cross(d2)) / n
    }
}

/// d(t) = (sin θ cos ωt, sin θ sin ωt, cos θ) and three derivatives.
pub fn precessing_dipole_jet(theta: f64, omega: f64, t: f64) -> Jet {
    let (st, ct) = theta.sin_cos();
    let (s, c) = (omega * t).sin_cos();
    let w = omega;
    [
        Vec3::new(st * c, st * s, ct),
        Vec3::new(-w * st * s, w * st * c, 0.0),
        Vec3::new(-w * w * st * c, -w * w * st * s, 0.0),
        Vec3::new(w * w * w * st * s, -w * w * w * st * c, 0.0),
    ]
}
