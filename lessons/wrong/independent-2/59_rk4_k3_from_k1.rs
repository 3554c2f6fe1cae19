//! assignment: rk4_step
//! mistake: the third stage built from k1 instead of k2 (y + k1 h/2, a copy of the line above)
//! says: stage 3, k2
use spintop::assignment::{DynField, State};

pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * h));
    y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
}
