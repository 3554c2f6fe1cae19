//! assignment: axial_schott_rate
//! mistake: divided by |d|^2 instead of |d|
//! says: normalised twice
use spintop::assignment::{Jet, Vec3};

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let d = jet[0];
    d.dot(&jet[1].cross(&jet[2])) / d.norm_squared()
}
