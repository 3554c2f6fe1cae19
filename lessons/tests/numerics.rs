//! Numerical methods (and the Euler angles of Section 3) assignments: `cargo test -p spintop-lessons --test numerics`.
//!
//! Each grader also rejects a file that calls spintop's own answers (see
//! lessons/README.md, "No shortcut").

use spintop::{graded, grading};
use spintop_lessons::numerics;

/// (3.5)
#[test]
fn eq_3_5_euler_from_rotation() {
    graded!(
        "numerics",
        grading::euler_from_rotation(numerics::euler_from_rotation)
    );
}

/// RK4
#[test]
fn rk4_step() {
    graded!("numerics", grading::rk4_step(numerics::rk4_step));
}

/// DP5
#[test]
fn dp5_step() {
    graded!("numerics", grading::dp5_step(numerics::dp5_step));
}

/// (4.12) RK4
#[test]
fn reduced_rk4_converges_at_order_4() {
    graded!("numerics", grading::reduced_rk4(numerics::reduced_rk4));
}
