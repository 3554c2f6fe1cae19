//! assignment: larmor_rate
//! mistake: the cross product written by hand, the middle component's two products swapped
//! says: y has the wrong sign
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let (a, b) = (jet[1], jet[2]);
    let c = Vec3::new(
        a.y * b.z - a.z * b.y,
        a.x * b.z - a.z * b.x,
        a.x * b.y - a.y * b.x,
    );
    -c
}
