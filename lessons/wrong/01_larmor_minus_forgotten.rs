//! assignment: larmor_rate
//! mistake: the minus sign of the law forgotten
//! says: sign flip
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    jet[1].cross(&jet[2])
}
