//! Appendix assignment: `cargo test -p spintop-lessons --test appendix`.

use spintop::grading::{self, assert_passes};
use spintop_lessons::appendix;

#[test]
fn eq_a_1_shell_acceleration() {
    assert_passes(grading::shell_acceleration(appendix::shell_acceleration));
}
