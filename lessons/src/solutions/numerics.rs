use spintop::assignment::{DynField, Mat3, State, Vec3};

/// Classical RK4.
pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
    let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
    let k4 = f(t + h, &(y + k3 * h));
    y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
}

/// Dormand–Prince 5(4) (Hairer–Nørsett–Wanner I, Table II.5.2).
pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    let k1 = f(t, y);
    let k2 = f(t + h / 5.0, &(y + k1 * (h / 5.0)));
    let k3 = f(
        t + 3.0 * h / 10.0,
        &(y + (k1 * (3.0 / 40.0) + k2 * (9.0 / 40.0)) * h),
    );
    let k4 = f(
        t + 4.0 * h / 5.0,
        &(y + (k1 * (44.0 / 45.0) - k2 * (56.0 / 15.0) + k3 * (32.0 / 9.0)) * h),
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

/// z-x-z Euler angles, θ by atan2, ψ = 0 on the poles.
pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let theta = s.atan2(m[(2, 2)]);
    if s < 1e-12 {
        return (m[(1, 0)].atan2(m[(0, 0)]), theta, 0.0);
    }
    (
        m[(0, 2)].atan2(-m[(1, 2)]),
        theta,
        m[(2, 0)].atan2(m[(2, 1)]),
    )
}

/// `steps` RK4 steps of (4.12)-(4.14), with this crate's own step and rate.
pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    let h = t_end / steps as f64;
    let rhs = |_t: f64, y: &State<3>| crate::ch4::reduced_ale_rhs(ratio, tau, *y);
    let mut y = omega0;
    for i in 0..steps {
        y = rk4_step(&rhs, i as f64 * h, &y, h);
    }
    y
}
