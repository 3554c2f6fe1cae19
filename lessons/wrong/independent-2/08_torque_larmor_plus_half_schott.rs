//! assignment: torque_rate
//! mistake: built as (2.1) plus dL_S/dt with dL_S/dt missing its product-rule term d' × d'', so -d' × d'' + d × d''' is left
//! says: product rule, d' × d'', larmor
use spintop::assignment::{Jet, Vec3};

pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, d1, d2, d3] = jet;
    let larmor = -d1.cross(d2);
    let schott = d.cross(d3);
    larmor + schott
}
