//! Section 2 assignments: `cargo test -p spintop-lessons --test ch2`.

use spintop::grading::{self, assert_passes};
use spintop_lessons::ch2;

#[test]
fn eq_2_1_larmor_rate() {
    assert_passes(grading::larmor_rate(ch2::larmor_rate));
}

#[test]
fn eq_2_2_torque_rate() {
    assert_passes(grading::torque_rate(ch2::torque_rate));
}

#[test]
fn eq_2_4_schott_angular_momentum() {
    assert_passes(grading::schott_angular_momentum(
        ch2::schott_angular_momentum,
    ));
}

#[test]
fn eq_2_3_axial_schott_rate() {
    assert_passes(grading::axial_schott_rate(ch2::axial_schott_rate));
}
