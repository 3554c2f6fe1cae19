//! assignment: torque_rate
//! mistake: d' x d''' instead of d x d'''
//! says: you crossed d' with d'''
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    jet[1].cross(&jet[3])
}
