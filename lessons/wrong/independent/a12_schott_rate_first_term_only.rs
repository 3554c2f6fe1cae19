//! assignment: schott_rate
//! mistake: only d' x d'': the d x d''' term forgotten
//! says: half of the product rule
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    jet[1].cross(&jet[2])
}
