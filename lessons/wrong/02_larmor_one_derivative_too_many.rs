//! assignment: larmor_rate
//! mistake: d' crossed with d''' instead of d''
//! says: you crossed d' with d'''
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    -jet[1].cross(&jet[3])
}
