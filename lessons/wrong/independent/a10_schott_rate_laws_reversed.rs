//! assignment: schott_rate
//! mistake: Larmor minus torque: the difference of the two laws taken the wrong way round
//! says: sign
use spintop::assignment::{Jet, Vec3};

pub fn schott_rate(jet: &Jet) -> Vec3 {
    let larmor = -jet[1].cross(&jet[2]);
    let torque = jet[0].cross(&jet[3]);
    larmor - torque
}
