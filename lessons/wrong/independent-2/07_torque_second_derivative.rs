//! assignment: torque_rate
//! mistake: the second derivative in place of the third, d × d'' (which is L_S) instead of d × d'''
//! says: third derivative, d''', schott angular momentum
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, _, d2, _] = jet;
    d.cross(d2)
}
