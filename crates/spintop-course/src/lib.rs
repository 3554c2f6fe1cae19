//! The course: the assignments of `lessons/` in course order, and their state
//! as their graders judge them.
//!
//! A shared layer below the shells: `spintop course` prints it as text and
//! `spintop learn` shows it in its panel; neither reads the other's output.
//! It runs cargo and the graders' tests as child processes, so it is not part
//! of the pure core, and it is built only with the feature `app`: a student's
//! build (the core) never compiles it.
//!
//! | module | what |
//! |---|---|
//! | `catalogue` | the 22 assignments, their files, tests and hint ladders |
//! | `locate` | which course a command stands in, and its files and commands as named there |
//! | `building` | how far a grading has got (cargo's units, the graders), for a screen |
//! | `source_rule` | what a copy may not contain, on a parsed syntax tree |
//! | `harness` | one grading: the snapshot, the rule, the build, the graders calling the runner |
//! | `workspace` | the private folder one grading builds in, and its generated runner |
//! | `compile` | cargo in the build sandbox, read through its JSON |
//! | `toolchain` | the cargo a grading runs, and what to say when the machine refuses it |
//! | `runner` | the student's runner, reached over a pipe ([`spintop_grading::Remote`]) |
//! | `warm` | the stubs' build, shared by every class grading under a lock |
//! | `progress` | hint rungs used and first passes, in the course's own `target/` |
//! | `hints` | the hint ladder, one rung per request |
//! | `watch` | grading again on every save |
//! | `probe` | the student's function of time, sampled for `spintop learn` |
//! | `export` | a student's copy, optionally with a CI workflow |
//! | `gradebook` | a class graded: every row, within time limits, each run in a folder of its own |
//! | `sheet` | the CSV and Gradescope files, safe to open, with totals |
//! | `diagnose` | a folder of wrong answers graded, to measure the diagnoses |
//! | `snapshot` | a student's `src/` copied once, no link followed, sizes checked first |
//! | `sandbox` | the launcher that bounds a student's build and runner |

#![forbid(unsafe_code)]

pub mod building;
mod catalogue;
mod compile;
pub mod diagnose;
mod error;
pub mod export;
pub mod gradebook;
pub mod harness;
mod hints;
mod locate;
mod probe;
mod process;
mod progress;
pub mod runner;
pub mod sandbox;
pub mod sheet;
pub mod snapshot;
pub mod source_rule;
mod status;
mod toolchain;
mod warm;
mod watch;
pub mod workspace;

pub use catalogue::{Assignment, COURSE, COURSE_LEN, Hints, binaries, find};
pub use error::CourseError;
pub use export::{
    CARRIED_CRATES, Ci, Export, ExportOptions, Link, check_lessons_dir, export, export_with,
    lessons_dir, strip_solutions,
};
pub use harness::{Crates, Options, default_work, grade};
pub use hints::{Hint, hint_reached, next_hint};
pub use locate::{Book, Chosen, Course, NoBook, find_course, is_course};
pub use probe::{ProbeSpec, Probed, parse_probe, probe};
pub use progress::{
    Progress, load_progress, progress_path, read_progress, record_passes, record_passes_now,
    save_progress,
};
pub use status::{Failure, Located, State, Status};
pub use toolchain::{find_cargo, unwritable_why};
pub use watch::{Report, Watch, binaries_for, sources_stamps};

use std::path::Path;

/// The repository this spintop was built from: two folders above this
/// crate's (`crates/spintop-course`), named without `..` so that a path
/// shown to a user reads as the folder it is.
pub fn repository() -> &'static Path {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.parent().and_then(Path::parent).unwrap_or(here)
}

/// The `--course DIR` that commands printed for the course in `dir` must
/// repeat: none for the repository's own lessons (where `spintop course`
/// looks by default), the folder otherwise.
pub fn course_arg_for(dir: &Path) -> Option<String> {
    let own = lessons_dir(repository());
    let same = match (dir.canonicalize(), own.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => dir == own,
    };
    (!same).then(|| dir.display().to_string())
}

/// The book's course chapters (`book/src`): `cargo test` compiles and runs
/// every Rust block in them as a doctest against this crate and the graders
/// (the other chapters are the core's, `spintop::book`).
#[cfg(doctest)]
pub mod book {
    #[doc = include_str!("../../../book/src/assignments.md")]
    pub struct Assignments;
    #[doc = include_str!("../../../book/src/instructors.md")]
    pub struct Instructors;
}
