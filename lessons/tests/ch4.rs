//! Sections 4.1 and 4.2 assignments: `cargo test -p spintop-lessons --test ch4`.
//!
//! Each test grades one assignment with fresh inputs (`SPINTOP_SEED=N` gives
//! the inputs of seed N again). `spintop course` runs each in a process of
//! its own, reads its verdict from structure, and first checks the source
//! rule (lessons/README.md, "No shortcut").

use spintop_grading::graded;
use spintop_lessons::ch4;

/// (4.5)-(4.6)
#[test]
fn eq_4_6_truncated_omega_perp() {
    graded!(truncated_omega_perp, ch4::truncated_omega_perp);
}

/// (4.7)
#[test]
fn eq_4_7_truncated_closed_form() {
    graded!(truncated_closed_form, ch4::truncated_closed_form);
}

/// (4.6) inv.
#[test]
fn eq_4_6_truncated_time_to_factor() {
    graded!(truncated_time_to_factor, ch4::truncated_time_to_factor);
}

/// (4.11)
#[test]
fn eq_4_11_precession_tilt() {
    graded!(precession_tilt, ch4::precession_tilt);
}

/// (4.12)-(4.14)
#[test]
fn eq_4_12_reduced_ale_rhs() {
    graded!(reduced_ale_rhs, ch4::reduced_ale_rhs);
}

/// (4.16) sigma
#[test]
fn eq_4_16_reduced_decay_time() {
    graded!(reduced_decay_time, ch4::reduced_decay_time);
}

/// (4.15)-(4.16)
#[test]
fn eq_4_15_eq_4_16_reduced_closed_form() {
    graded!(reduced_closed_form, ch4::reduced_closed_form);
}
