//! assignment: schott_angular_momentum
//! mistake: d x d' instead of d x d''
//! says: one derivative short
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, d1, _, _] = *jet;
    d.cross(&d1)
}
