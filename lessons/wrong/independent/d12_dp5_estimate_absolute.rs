//! assignment: dp5_step
//! mistake: the error estimate made positive component by component (abs)
//! says: wrong sign
use spintop::assignment::{DynField, Mat3, State, Vec3};

fn stages(f: DynField, t: f64, y: &State<3>, h: f64, c2: f64) -> [State<3>; 6] {
    let k1 = f(t, y);
    let k2 = f(t + c2 * h, &(y + k1 * (c2 * h)));
    let k3 = f(t + 3.0 * h / 10.0, &(y + (k1 * (3.0 / 40.0) + k2 * (9.0 / 40.0)) * h));
    let k4 = f(t + 4.0 * h / 5.0, &(y + (k1 * (44.0 / 45.0) - k2 * (56.0 / 15.0) + k3 * (32.0 / 9.0)) * h));
    let k5 = f(
        t + 8.0 * h / 9.0,
        &(y + (k1 * (19372.0 / 6561.0) - k2 * (25360.0 / 2187.0) + k3 * (64448.0 / 6561.0)
            - k4 * (212.0 / 729.0))
            * h),
    );
    let k6 = f(
        t + h,
        &(y + (k1 * (9017.0 / 3168.0) - k2 * (355.0 / 33.0) + k3 * (46732.0 / 5247.0)
            + k4 * (49.0 / 176.0)
            - k5 * (5103.0 / 18656.0))
            * h),
    );
    [k1, k2, k3, k4, k5, k6]
}

fn fifth(y: &State<3>, k: &[State<3>; 6], h: f64) -> State<3> {
    y + (k[0] * (35.0 / 384.0) + k[2] * (500.0 / 1113.0) + k[3] * (125.0 / 192.0)
        - k[4] * (2187.0 / 6784.0)
        + k[5] * (11.0 / 84.0))
        * h
}

fn fourth(y: &State<3>, k: &[State<3>; 6], k7: State<3>, h: f64) -> State<3> {
    y + (k[0] * (5179.0 / 57600.0) + k[2] * (7571.0 / 16695.0) + k[3] * (393.0 / 640.0)
        - k[4] * (92097.0 / 339200.0)
        + k[5] * (187.0 / 2100.0)
        + k7 * (1.0 / 40.0))
        * h
}

pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    let k = stages(f, t, y, h, 0.2);
    let y5 = fifth(y, &k, h);
    let y4 = fourth(y, &k, f(t + h, &y5), h);
    (y5, (y5 - y4).abs())
}
