//! assignment: axial_schott_rate
//! mistake: projected on d'/|d'| instead of d/|d|
//! says: wrong vector
use spintop::assignment::{Jet, Vec3};

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let n = jet[1].normalize();
    n.dot(&(jet[1].cross(&jet[2]) + jet[0].cross(&jet[3])))
}
