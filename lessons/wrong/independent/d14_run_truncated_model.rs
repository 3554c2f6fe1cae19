//! assignment: reduced_rk4
//! mistake: the general top's truncated ALE (3.3) integrated (I = (1, 1, ratio), d along the axis) instead of the reduced model
//! says: truncated
use spintop::assignment::{DynField, Mat3, State, Vec3};

pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    let h = t_end / steps as f64;
    let inertia = Vec3::new(1.0, 1.0, ratio);
    let dipole = Vec3::new(0.0, 0.0, tau.sqrt());
    let rhs = |_t: f64, y: &State<3>| crate::ch3::truncated_ale_rhs(inertia, dipole, *y);
    let mut y = omega0;
    for i in 0..steps {
        y = crate::numerics::rk4_step(&rhs, i as f64 * h, &y, h);
    }
    y
}
