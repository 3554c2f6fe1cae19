//! The course's tests, in one binary: the graders really grade (`graders`:
//! every assignment of the catalogue, the reference passes, stubs and known
//! wrong answers fail with their diagnoses), and the source rule refuses
//! every shortcut trick on parsed syntax trees (`source_rule`). The harness
//! and the grade book on real copies of the course built by cargo are the
//! application's tests (`tests/course`), since they run `spintop course` as
//! an instructor does.

mod diagnoses;
mod graders;
mod source_rule;
mod wrong_answers;

/// The seeds every grader test runs at: the same assertions must hold for
/// any grading's inputs.
pub(crate) const SEEDS: [u64; 3] = [2026, 7, 918_273_645];
