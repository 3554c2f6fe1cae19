//! The course's grading, end to end: the graders (`graders`), the source
//! rule against every shortcut trick (`source_rule`), and the harness and
//! the grade book on real copies of the course built by cargo (`harness`).

mod graders;
mod harness;
mod source_rule;

/// The seeds every grader test runs at: the same assertions must hold for
/// any grading's inputs.
pub(crate) const SEEDS: [u64; 3] = [2026, 7, 918_273_645];
