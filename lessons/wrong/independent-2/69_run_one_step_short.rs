//! assignment: reduced_rk4
//! mistake: the loop runs from 1 to steps - 1 (for i in 1..steps), one step too few, so the run stops at t_end - h
//! says: one step too few, off-by-one, steps
use spintop::assignment::{State, Vec3};

pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    let rhs = |_t: f64, w: &State<3>| -> State<3> {
        let precession = (1.0 - ratio) * w.z;
        let damping = tau * (w.x * w.x + w.y * w.y + (ratio * w.z).powi(2));
        Vec3::new(
            precession * w.y - damping * w.x,
            -precession * w.x - damping * w.y,
            0.0,
        )
    };
    let h = t_end / steps as f64;
    let mut y = omega0;
    for i in 1..steps {
        let t = i as f64 * h;
        let k1 = rhs(t, &y);
        let k2 = rhs(t + h / 2.0, &(y + k1 * (h / 2.0)));
        let k3 = rhs(t + h / 2.0, &(y + k2 * (h / 2.0)));
        let k4 = rhs(t + h, &(y + k3 * h));
        y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
    }
    y
}
