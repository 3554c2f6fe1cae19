//! assignment: rk4_step
//! mistake: weights 1/6, 1/3, 1/3, 1/6 mixed up as 1/8, 3/8, 3/8, 1/8 (the 3/8 rule's weights on RK4's stages)
//! says: other weights
use spintop::assignment::{DynField, Mat3, State, Vec3};

pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * h));
    y + (k1 + k2 * 3.0 + k3 * 3.0 + k4) * (h / 8.0)
}
