//! assignment: axial_schott_rate
//! mistake: the magnitude |dL_S/dt| handed in instead of its projection on n = d/|d|
//! says: projection, magnitude, norm
use spintop::assignment::Jet;

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let [d, d1, d2, d3] = jet;
    (d1.cross(d2) + d.cross(d3)).norm()
}
