//! Section 3 assignments: `cargo test -p spintop-lessons --test ch3`.

use spintop::grading::{self, assert_passes};
use spintop_lessons::ch3;

#[test]
fn eq_3_3_truncated_ale_rhs() {
    assert_passes(grading::truncated_ale_rhs(ch3::truncated_ale_rhs));
}
