//! assignment: axial_schott_rate
//! mistake: the projection divided by |d|² instead of |d| (normalised twice)
//! says: normalise, |d|, twice
use spintop::assignment::Jet;

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let [d, d1, d2, d3] = jet;
    let rate = d1.cross(d2) + d.cross(d3);
    let n2 = d.norm_squared();
    if n2 == 0.0 { 0.0 } else { d.dot(&rate) / n2 }
}
