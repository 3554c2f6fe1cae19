//! Numerical-methods assignments: `cargo test -p spintop-lessons --test numerics`.

use spintop::grading::{self, assert_passes};
use spintop_lessons::numerics;

#[test]
fn rk4_step() {
    assert_passes(grading::rk4_step(numerics::rk4_step));
}

#[test]
fn dp5_step() {
    assert_passes(grading::dp5_step(numerics::dp5_step));
}

#[test]
fn eq_3_5_euler_from_rotation() {
    assert_passes(grading::euler_from_rotation(numerics::euler_from_rotation));
}
