//! assignment: larmor_rate
//! mistake: the constant κ = 2/(3c³) kept with c = 1, although the chapter's units set κ = 1, so the rate is 2/3 of the right one
//! says: factor, 2/3
use spintop::assignment::{Jet, Vec3};

pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [_, d1, d2, _] = jet;
    -d1.cross(d2) * (2.0 / 3.0)
}
