//! assignment: schott_angular_momentum
//! mistake: d x d' : one derivative too few on the second factor
//! says: derivative
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    jet[0].cross(&jet[1])
}
