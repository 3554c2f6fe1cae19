//! assignment: schott_angular_momentum
//! mistake: the first derivative d' in place of d as the first factor, d' × d'' instead of d × d''
//! says: first factor, d, derivative
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [_, d1, d2, _] = jet;
    d1.cross(d2)
}
