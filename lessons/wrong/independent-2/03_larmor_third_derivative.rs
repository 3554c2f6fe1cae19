//! assignment: larmor_rate
//! mistake: the third derivative d''' used in place of the second, -d' × d''' instead of -d' × d''
//! says: second derivative, d'', wrong factor
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [_, d1, _, d3] = jet;
    -d1.cross(d3)
}
