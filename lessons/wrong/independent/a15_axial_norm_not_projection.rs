//! assignment: axial_schott_rate
//! mistake: the length of dL_S/dt instead of its projection on n
//! says: size of dL_S/dt
use spintop::assignment::{Jet, Vec3};

pub fn axial_schott_rate(jet: &Jet) -> f64 {
    (jet[1].cross(&jet[2]) + jet[0].cross(&jet[3])).norm()
}
