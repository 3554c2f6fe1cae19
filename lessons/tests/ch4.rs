//! Section 4 assignments: `cargo test -p spintop-lessons --test ch4`.

use spintop::grading::{self, assert_passes};
use spintop_lessons::ch4;

#[test]
fn eq_4_15_eq_4_16_reduced_closed_form() {
    assert_passes(grading::reduced_closed_form(ch4::reduced_closed_form));
}

#[test]
fn eq_4_11_precession_tilt() {
    assert_passes(grading::precession_tilt(ch4::precession_tilt));
}
