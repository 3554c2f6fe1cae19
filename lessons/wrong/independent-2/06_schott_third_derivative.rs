//! assignment: schott_angular_momentum
//! mistake: d × d''' (a term of the torque) handed in for L_S = d × d''
//! says: second derivative, d'', rate
use spintop::assignment::{Jet, Vec3};

pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, _, _, d3] = jet;
    d.cross(d3)
}
