//! A grader's verdict, as the graders' tests (`lessons/tests/*.rs`) give it.
//!
//! A test calls its grader through [`graded!`](crate::graded), which draws a
//! seed (`SPINTOP_SEED`, or a fresh one), grades, and panics with the report
//! on a failure, as any test does: feedback on the student's machine, where
//! the grader runs in the test's own process. A grade an instructor counts
//! never comes from here: `spintop course` and `course grade` run the
//! graders in `spintop` itself and call the student's functions in a runner,
//! another process (`spintop_runner`), so no verdict file, token or folder
//! exists that the student's code could list or write.

use super::Grade;
use std::path::Path;

/// The seed of a grading (a whole number); a fresh one when unset.
pub const SEED_VAR: &str = "SPINTOP_SEED";

/// 64 bits nobody chose: the time, the process and the process's random
/// hash keys mixed.
pub fn fresh_u64() -> u64 {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    h.write_u128(now);
    h.write_u32(std::process::id());
    h.finish()
}

/// A seed nobody chose, of nine digits: short enough to type, far too many
/// to tabulate.
pub fn fresh_seed() -> u64 {
    fresh_u64() % 1_000_000_000
}

/// The seed of this grading: `SPINTOP_SEED` if set, else a fresh one.
fn seed() -> u64 {
    match std::env::var(SEED_VAR) {
        Ok(text) if !text.trim().is_empty() => text.trim().parse().unwrap_or_else(|_| {
            panic!("{SEED_VAR}={text}: a seed is a whole number, e.g. {SEED_VAR}=2026")
        }),
        _ => fresh_seed(),
    }
}

/// The `--course DIR` a report repeats: the lessons crate at `manifest_dir` unless it is the repository's own
/// (where `spintop course` looks by default).
fn course_arg(manifest_dir: &str) -> Option<String> {
    let own = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../lessons"));
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    };
    (!same(Path::new(manifest_dir), own)).then(|| manifest_dir.to_string())
}

/// The graders' tests' entry: grade with this grading's seed and panic with
/// the report unless the assignment passed. `manifest_dir` is the lessons crate's.
pub fn assert_graded(manifest_dir: &str, grade: impl FnOnce(u64) -> Grade) {
    let seed = seed();
    let grade = grade(seed).map_err(|mut failed| {
        failed.course = course_arg(manifest_dir);
        failed
    });
    if let Err(failed) = grade {
        panic!("\n{failed}\n");
    }
}

/// `graded!(larmor_rate, ch2::larmor_rate)`: the test of an assignment. It
/// grades the student's function with the grader of the same name (see
/// [`crate`]) at this grading's seed, and fails with the report.
#[macro_export]
macro_rules! graded {
    ($grader:ident, $student:expr) => {
        $crate::assert_graded(env!("CARGO_MANIFEST_DIR"), |seed| {
            $crate::$grader(seed, $student)
        })
    };
}
