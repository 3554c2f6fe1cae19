//! assignment: schott_angular_momentum
//! mistake: d' x d'' in place of d x d''
//! says: Larmor
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    jet[1].cross(&jet[2])
}
