//! assignment: schott_rate
//! mistake: the first product-rule term written d'' × d', so it enters with the wrong sign
//! says: sign, first term, d' × d''
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    let [d, d1, d2, d3] = jet;
    d2.cross(d1) + d.cross(d3)
}
