//! assignment: torque_rate
//! mistake: the minus sign of (2.1) carried over to (2.2)
//! says: sign
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    -jet[0].cross(&jet[3])
}
