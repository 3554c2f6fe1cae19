//! assignment: reduced_rk4
//! mistake: the loop takes forward Euler steps instead of RK4 steps
//! says: euler
use spintop::assignment::{DynField, Mat3, State, Vec3};

pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    let h = t_end / steps as f64;
    let mut y = omega0;
    for _ in 0..steps {
        y += crate::ch4::reduced_ale_rhs(ratio, tau, y) * h;
    }
    y
}
