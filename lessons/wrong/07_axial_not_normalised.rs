//! assignment: axial_schott_rate
//! mistake: projected on d, not on d/|d|
//! says: not normalised
use spintop::assignment::Jet;

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    jet[0].dot(&(jet[1].cross(&jet[2]) + jet[0].cross(&jet[3])))
}
