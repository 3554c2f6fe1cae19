//! assignment: axial_schott_rate
//! mistake: n . dL/dt of the Larmor law projected instead of n . dL_S/dt
//! says: sign
use spintop::assignment::{Jet, Vec3};

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    let n = jet[0].normalize();
    n.dot(&(-jet[1].cross(&jet[2])))
}
