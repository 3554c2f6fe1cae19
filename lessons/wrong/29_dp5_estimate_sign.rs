//! assignment: dp5_step
//! mistake: the error estimate as y4 - y5
//! says: wrong sign
use spintop::assignment::{DynField, State};

pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    let (y5, e) = crate::numerics::dp5_step(f, t, y, h);
    (y5, -e)
}
