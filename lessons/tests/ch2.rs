//! Section 2 assignments: `cargo test -p spintop-lessons --test ch2`.
//!
//! Each test grades one assignment with fresh inputs (`SPINTOP_SEED=N` gives
//! the inputs of seed N again). `spintop course` runs each in a process of
//! its own, reads its verdict from structure, and first checks the source
//! rule (lessons/README.md, "No shortcut").

use spintop_grading::graded;
use spintop_lessons::ch2;

/// (2.1)
#[test]
fn eq_2_1_larmor_rate() {
    graded!(larmor_rate, ch2::larmor_rate);
}

/// (2.4)
#[test]
fn eq_2_4_schott_angular_momentum() {
    graded!(schott_angular_momentum, ch2::schott_angular_momentum);
}

/// (2.2)
#[test]
fn eq_2_2_torque_rate() {
    graded!(torque_rate, ch2::torque_rate);
}

/// (2.3)
#[test]
fn eq_2_3_schott_rate() {
    graded!(schott_rate, ch2::schott_rate);
}

/// (2.3)-(2.4)
#[test]
fn eq_2_3_axial_schott_rate() {
    graded!(axial_schott_rate, ch2::axial_schott_rate);
}

/// Sec. 2 cone
#[test]
fn precessing_dipole_jet() {
    graded!(precessing_dipole_jet, ch2::precessing_dipole_jet);
}
