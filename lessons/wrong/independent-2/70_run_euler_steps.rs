//! assignment: reduced_rk4
//! mistake: explicit Euler steps y + h f(y) instead of classical RK4 steps
//! says: euler, order
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
    for i in 0..steps {
        let t = i as f64 * h;
        let k1 = rhs(t, &y);
        y += k1 * h;
    }
    y
}
