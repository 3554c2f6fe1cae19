//! assignment: rk4_step
//! mistake: the second stage evaluated at time t instead of t + h/2 (its state is right)
//! says: stage 2, time
use spintop::assignment::{DynField, State};

pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * h));
    y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
}
