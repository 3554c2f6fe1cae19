//! assignment: rk4_step
//! mistake: the weights of the 3/8 rule (1, 3, 3, 1)/8 combined with the classical stages instead of (1, 2, 2, 1)/6
//! says: weights
use spintop::assignment::{DynField, State};

pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * h));
    y + (k1 + k2 * 3.0 + k3 * 3.0 + k4) * (h / 8.0)
}
