//! Appendix assignments: `cargo test -p spintop-lessons --test appendix`.
//!
//! Each test grades one assignment with fresh inputs (`SPINTOP_SEED=N` gives
//! the inputs of seed N again). `spintop course` runs each in a process of
//! its own, reads its verdict from structure, and first checks the source
//! rule (lessons/README.md, "No shortcut").

use spintop_grading::graded;
use spintop_lessons::appendix;

/// (A.1) masses
#[test]
fn eq_a_1_shell_masses() {
    graded!(shell_masses, appendix::shell_masses);
}

/// (A.1)
#[test]
fn eq_a_1_shell_acceleration() {
    graded!(shell_acceleration, appendix::shell_acceleration);
}

/// (A.1) root
#[test]
fn eq_a_1_characteristic_root() {
    graded!(characteristic_root, appendix::characteristic_root);
}
