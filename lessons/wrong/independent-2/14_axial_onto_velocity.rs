//! assignment: axial_schott_rate
//! mistake: projected on the direction of d' instead of n = d/|d|
//! says: projection, direction, d/|d|
use spintop::assignment::Jet;

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let [d, d1, d2, d3] = jet;
    let rate = d1.cross(d2) + d.cross(d3);
    let n = d1.norm();
    if n == 0.0 { 0.0 } else { d1.dot(&rate) / n }
}
