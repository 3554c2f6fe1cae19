//! assignment: schott_rate
//! mistake: the product rule on d × d'' applied to the second factor only: d × d''' kept, d' × d'' missing
//! says: product rule, missing term, d' × d''
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    let [d, _, _, d3] = jet;
    d.cross(d3)
}
