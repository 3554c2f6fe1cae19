//! Section 2 assignments: `cargo test -p spintop-lessons --test ch2`.
//!
//! Each grader also rejects a file that calls spintop's own answers (see
//! lessons/README.md, "No shortcut").

use spintop::{graded, grading};
use spintop_lessons::ch2;

/// (2.1)
#[test]
fn eq_2_1_larmor_rate() {
    graded!("ch2", grading::larmor_rate(ch2::larmor_rate));
}

/// (2.4)
#[test]
fn eq_2_4_schott_angular_momentum() {
    graded!(
        "ch2",
        grading::schott_angular_momentum(ch2::schott_angular_momentum)
    );
}

/// (2.2)
#[test]
fn eq_2_2_torque_rate() {
    graded!("ch2", grading::torque_rate(ch2::torque_rate));
}

/// (2.3)
#[test]
fn eq_2_3_schott_rate() {
    graded!("ch2", grading::schott_rate(ch2::schott_rate));
}

/// (2.3)-(2.4)
#[test]
fn eq_2_3_axial_schott_rate() {
    graded!("ch2", grading::axial_schott_rate(ch2::axial_schott_rate));
}

/// Sec. 2 cone
#[test]
fn precessing_dipole_jet() {
    graded!(
        "ch2",
        grading::precessing_dipole_jet(ch2::precessing_dipole_jet)
    );
}
