use spintop::math::Vec3;
use spintop::physics::balance::Jet;

/// Eq. (2.1).
pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [_, d1, d2, _] = jet;
    -d1.cross(d2)
}

/// Eq. (2.2).
pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, _, _, d3] = jet;
    d.cross(d3)
}

/// Eq. (2.4).
pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, _, d2, _] = jet;
    d.cross(d2)
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
