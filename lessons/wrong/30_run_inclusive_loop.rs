//! assignment: reduced_rk4
//! mistake: for i in 0..=steps: one step too many
//! says: one step too many
use spintop::assignment::{State, Vec3};

pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    let h = t_end / steps as f64;
    let rhs = |_t: f64, y: &State<3>| crate::ch4::reduced_ale_rhs(ratio, tau, *y);
    let mut y = omega0;
    for i in 0..=steps {
        y = crate::numerics::rk4_step(&rhs, i as f64 * h, &y, h);
    }
    y
}
