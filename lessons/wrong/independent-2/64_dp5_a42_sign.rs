//! assignment: dp5_step
//! mistake: the coefficient of k2 in the fourth stage with the wrong sign, +56/15 instead of -56/15
//! says: sign, stage 4, coefficient
use spintop::assignment::{DynField, State};

pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    let k1 = f(t, y);
    let k2 = f(t + h / 5.0, &(y + k1 * (h / 5.0)));
    let k3 = f(
        t + 3.0 * h / 10.0,
        &(y + (k1 * (3.0 / 40.0) + k2 * (9.0 / 40.0)) * h),
    );
    let k4 = f(
        t + 4.0 * h / 5.0,
        &(y + (k1 * (44.0 / 45.0) + k2 * (56.0 / 15.0) + k3 * (32.0 / 9.0)) * h),
    );
    let k5 = f(
        t + 8.0 * h / 9.0,
        &(y + (k1 * (19372.0 / 6561.0) - k2 * (25360.0 / 2187.0) + k3 * (64448.0 / 6561.0)
            - k4 * (212.0 / 729.0))
            * h),
    );
    let k6 = f(
        t + h,
        &(y + (k1 * (9017.0 / 3168.0) - k2 * (355.0 / 33.0)
            + k3 * (46732.0 / 5247.0)
            + k4 * (49.0 / 176.0)
            - k5 * (5103.0 / 18656.0))
            * h),
    );
    let y5 = y
        + (k1 * (35.0 / 384.0) + k3 * (500.0 / 1113.0) + k4 * (125.0 / 192.0)
            - k5 * (2187.0 / 6784.0)
            + k6 * (11.0 / 84.0))
            * h;
    let k7 = f(t + h, &y5);
    let y4 = y
        + (k1 * (5179.0 / 57600.0) + k3 * (7571.0 / 16695.0) + k4 * (393.0 / 640.0)
            - k5 * (92097.0 / 339200.0)
            + k6 * (187.0 / 2100.0)
            + k7 * (1.0 / 40.0))
            * h;
    (y5, y5 - y4)
}
