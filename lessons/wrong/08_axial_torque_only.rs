//! assignment: axial_schott_rate
//! mistake: only the d x d''' term projected
//! says: comes from its other term
use spintop::assignment::Jet;

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let n = jet[0] / jet[0].norm();
    n.dot(&jet[0].cross(&jet[3]))
}
