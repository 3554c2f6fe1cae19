//! Appendix assignments: `cargo test -p spintop-lessons --test appendix`.
//!
//! Each grader also rejects a file that calls spintop's own answers (see
//! lessons/README.md, "No shortcut").

use spintop::{graded, grading};
use spintop_lessons::appendix;

/// (A.1) masses
#[test]
fn eq_a_1_shell_masses() {
    graded!("appendix", grading::shell_masses(appendix::shell_masses));
}

/// (A.1)
#[test]
fn eq_a_1_shell_acceleration() {
    graded!(
        "appendix",
        grading::shell_acceleration(appendix::shell_acceleration)
    );
}

/// (A.1) root
#[test]
fn eq_a_1_characteristic_root() {
    graded!(
        "appendix",
        grading::characteristic_root(appendix::characteristic_root)
    );
}
