//! assignment: torque_rate
//! mistake: the cross product in the wrong order, d''' × d instead of d × d'''
//! says: sign, order
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, _, _, d3] = jet;
    d3.cross(d)
}
