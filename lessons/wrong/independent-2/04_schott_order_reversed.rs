//! assignment: schott_angular_momentum
//! mistake: the factors of the cross product in the wrong order, d'' × d instead of d × d''
//! says: sign, order
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, _, d2, _] = jet;
    d2.cross(d)
}
