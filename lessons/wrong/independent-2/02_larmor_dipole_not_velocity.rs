//! assignment: larmor_rate
//! mistake: the dipole d itself crossed with d'' in place of its first derivative d'
//! says: first derivative, d', wrong factor
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [d, _, d2, _] = jet;
    -d.cross(d2)
}
