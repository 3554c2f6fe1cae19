//! assignment: schott_rate
//! mistake: the second product-rule term subtracted
//! says: sign
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    jet[1].cross(&jet[2]) - jet[0].cross(&jet[3])
}
