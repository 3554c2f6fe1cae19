//! assignment: schott_rate
//! mistake: only the derivative of the second factor
//! says: only half of the product rule
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    jet[0].cross(&jet[3])
}
