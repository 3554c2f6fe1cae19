//! assignment: larmor_rate
//! mistake: d used where d' belongs: -d x d''
//! says: crossed d with d''
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    -jet[0].cross(&jet[2])
}
