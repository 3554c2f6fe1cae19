//! Numerical methods (and the Euler angles of Section 3) assignments: `cargo test -p spintop-lessons --test numerics`.
//!
//! Each test grades one assignment with fresh inputs (`SPINTOP_SEED=N` gives
//! the inputs of seed N again). `spintop course` runs each in a process of
//! its own, reads its verdict from structure, and first checks the source
//! rule (lessons/README.md, "No shortcut").

use spintop_grading::graded;
use spintop_lessons::numerics;

/// (3.5)
#[test]
fn eq_3_5_euler_from_rotation() {
    graded!(euler_from_rotation, numerics::euler_from_rotation);
}

/// RK4
#[test]
fn rk4_step() {
    graded!(rk4_step, numerics::rk4_step);
}

/// DP5
#[test]
fn dp5_step() {
    graded!(dp5_step, numerics::dp5_step);
}

/// (4.12) RK4
#[test]
fn eq_4_12_reduced_rk4_takes_n_classical_steps() {
    graded!(reduced_rk4, numerics::reduced_rk4);
}
