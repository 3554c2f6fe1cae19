//! assignment: schott_rate
//! mistake: the product rule on d × d'' applied to one factor only: d' × d'' kept, d × d''' missing
//! says: product rule, missing term, d × d'''
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    let [_, d1, d2, _] = jet;
    d1.cross(d2)
}
