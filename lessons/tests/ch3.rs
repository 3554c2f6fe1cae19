//! Section 3 assignments: `cargo test -p spintop-lessons --test ch3`.
//!
//! Each grader also rejects a file that calls spintop's own answers (see
//! lessons/README.md, "No shortcut").

use spintop::{graded, grading};
use spintop_lessons::ch3;

/// (3.3)
#[test]
fn eq_3_3_truncated_ale_rhs() {
    graded!("ch3", grading::truncated_ale_rhs(ch3::truncated_ale_rhs));
}

/// (3.3) energy
#[test]
fn eq_3_3_energy_rate() {
    graded!("ch3", grading::energy_rate(ch3::energy_rate));
}
