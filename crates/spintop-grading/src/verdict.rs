//! A grader's verdict, as the graders' tests (`lessons/tests/*.rs`) give it.
//!
//! A test calls its grader through [`graded!`](crate::graded), which draws a
//! seed (`SPINTOP_SEED`, or a fresh one), grades, and panics with the report
//! on a failure, as any test does. When `spintop course` runs the test it
//! also names a file (`SPINTOP_GRADE_OUT`) and a random token
//! (`SPINTOP_GRADE_NONCE`): the grader writes its [`Verdict`] there, with the
//! token. The course reads a pass only from that file *and* the test's exit
//! status; nothing the student's code prints counts, and the student's code
//! can neither read the token nor write the file (the source rule forbids
//! `std::env`, `std::fs`, `std::process` and `unsafe`).

use super::Grade;
use std::path::Path;

/// The seed of a grading (a whole number); a fresh one when unset.
pub const SEED_VAR: &str = "SPINTOP_SEED";
/// Where the grader writes its verdict (set by `spintop course`).
pub const OUT_VAR: &str = "SPINTOP_GRADE_OUT";
/// The token the verdict must carry (set by `spintop course`).
pub const NONCE_VAR: &str = "SPINTOP_GRADE_NONCE";
/// The `--course DIR` a report's commands repeat (set by `spintop course`;
/// empty for none).
pub const COURSE_VAR: &str = "SPINTOP_GRADE_COURSE";

/// One grader's verdict, as written for `spintop course`.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Verdict {
    /// The token of the run that asked for it.
    pub nonce: String,
    /// The assignment (its function's name).
    pub assignment: String,
    /// The seed of the inputs.
    pub seed: u64,
    /// Whether every input was answered right.
    pub passed: bool,
    /// Whether the function is still the `todo!()` stub.
    pub stub: bool,
    /// Inputs checked, when it passed.
    pub cases: usize,
    /// What is wrong, when it failed.
    pub diagnosis: String,
    /// The whole report, when it failed.
    pub report: String,
}

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

/// The `--course DIR` a report repeats: the one `spintop course` was given,
/// else the lessons crate at `manifest_dir` unless it is the repository's own
/// (where `spintop course` looks by default).
fn course_arg(manifest_dir: &str) -> Option<String> {
    if let Ok(given) = std::env::var(COURSE_VAR) {
        return (!given.is_empty()).then_some(given);
    }
    let own = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../lessons"));
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    };
    (!same(Path::new(manifest_dir), own)).then(|| manifest_dir.to_string())
}

/// The graders' tests' entry: grade with this grading's seed, write the
/// verdict when `spintop course` asked for one, and panic with the report
/// unless the assignment passed. `manifest_dir` is the lessons crate's.
pub fn assert_graded(manifest_dir: &str, grade: impl FnOnce(u64) -> Grade) {
    let seed = seed();
    let grade = grade(seed).map_err(|mut failed| {
        failed.course = course_arg(manifest_dir);
        failed
    });
    if let Some(path) = std::env::var_os(OUT_VAR) {
        let verdict = match &grade {
            Ok(p) => Verdict {
                nonce: std::env::var(NONCE_VAR).unwrap_or_default(),
                assignment: p.assignment.into(),
                seed,
                passed: true,
                stub: false,
                cases: p.cases,
                diagnosis: String::new(),
                report: String::new(),
            },
            Err(f) => Verdict {
                nonce: std::env::var(NONCE_VAR).unwrap_or_default(),
                assignment: f.assignment.into(),
                seed,
                passed: false,
                stub: f.is_stub(),
                cases: 0,
                diagnosis: f.diagnosis.clone(),
                report: f.to_string(),
            },
        };
        let json = serde_json::to_vec(&verdict).unwrap_or_default();
        if let Err(e) = std::fs::write(&path, json) {
            panic!(
                "cannot write the verdict to {}: {e}",
                Path::new(&path).display()
            );
        }
    }
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
