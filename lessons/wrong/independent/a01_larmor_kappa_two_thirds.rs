//! assignment: larmor_rate
//! mistake: kappa = 2/3 kept although the units set it to 1
//! says: 2/3
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let kappa = 2.0 / 3.0;
    -kappa * jet[1].cross(&jet[2])
}
