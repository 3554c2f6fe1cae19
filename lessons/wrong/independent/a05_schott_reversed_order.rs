//! assignment: schott_angular_momentum
//! mistake: d'' x d: the factors of the cross product reversed
//! says: sign
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    jet[2].cross(&jet[0])
}
