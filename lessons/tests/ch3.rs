//! Section 3 assignments: `cargo test -p spintop-lessons --test ch3`.
//!
//! Each test grades one assignment with fresh inputs (`SPINTOP_SEED=N` gives
//! the inputs of seed N again). `spintop course` runs each in a process of
//! its own, reads its verdict from structure, and first checks the source
//! rule (lessons/README.md, "No shortcut").

use spintop_grading::graded;
use spintop_lessons::ch3;

/// (3.3)
#[test]
fn eq_3_3_truncated_ale_rhs() {
    graded!(truncated_ale_rhs, ch3::truncated_ale_rhs);
}

/// (3.3) energy
#[test]
fn eq_3_3_energy_rate() {
    graded!(energy_rate, ch3::energy_rate);
}
