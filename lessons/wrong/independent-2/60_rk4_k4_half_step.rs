//! assignment: rk4_step
//! mistake: the fourth stage's state advanced by h/2 instead of h (y + k3 h/2)
//! says: stage 4, full step
use spintop::assignment::{DynField, State};

pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * (h / 2.0)));
    y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
}
