//! assignment: torque_rate
//! mistake: the rate of L_S (both product-rule terms) handed in for the torque
//! says: dL_S/dt
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    jet[0].cross(&jet[3]) + jet[1].cross(&jet[2])
}
