//! assignment: schott_rate
//! mistake: the first term of the product rule counted twice
//! says: a factor 2 on one term
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    2.0 * jet[1].cross(&jet[2]) + jet[0].cross(&jet[3])
}
