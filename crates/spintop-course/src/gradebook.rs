//! The grade book: a class of students' copies graded with the repository's
//! graders, one row per student and assignment whatever happens.
//!
//! Each copy gets a fresh export of the repository (its manifest and its
//! graders' tests) with the student's `src/` dropped in, so edited tests or a
//! changed manifest count for nothing, and is graded by the harness within a
//! time limit: a copy that does not compile, that hangs, that breaks the
//! source rule, or that is missing still gets its rows, each with a reason.

use super::harness::{self, Options, State, Status};
use super::{Assignment, COURSE, Progress, export, load_progress};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How to grade a class.
#[derive(Debug, Clone)]
pub struct ClassOptions {
    /// The longest one copy may take (its build and every grader).
    pub timeout: Duration,
    /// The longest one grader may take.
    pub test_limit: Duration,
    /// Copies graded at once.
    pub jobs: usize,
    /// The seed of the inputs (one fresh seed for the class when `None`).
    pub seed: Option<u64>,
    /// The build folder the copies share.
    pub target_dir: PathBuf,
    /// Where the fresh copies are put together (emptied first).
    pub work: PathBuf,
}

/// How one copy came out.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// Graded (each assignment has a state, "timed out" included).
    Graded(Status),
    /// No folder there.
    Missing(String),
    /// A folder, but not a course.
    NotACourse(String),
    /// It could not be put together or cargo could not be run: why.
    NotGraded(String),
}

/// One student's copy, graded.
#[derive(Debug, Clone)]
pub struct Copy {
    /// The student's name (the folder's name).
    pub student: String,
    /// The folder.
    pub folder: PathBuf,
    /// What came out.
    pub outcome: Outcome,
    /// The hint rungs the student used.
    pub progress: Progress,
    /// Seconds spent on it.
    pub seconds: f64,
}

impl Copy {
    /// Whether every assignment of the copy got a verdict (passing, failing,
    /// not started, does not compile): no timeout, no missing folder.
    pub fn fully_graded(&self) -> bool {
        match &self.outcome {
            Outcome::Graded(s) => s
                .states
                .iter()
                .all(|(_, st)| !matches!(st, State::TimedOut(_) | State::Unknown)),
            _ => false,
        }
    }

    /// The copy's state of `a`: its word and the reason behind it.
    pub fn row(&self, a: &Assignment) -> (&'static str, String) {
        match &self.outcome {
            Outcome::Graded(status) => {
                let state = status
                    .states
                    .iter()
                    .find(|(b, _)| b.test == a.test)
                    .map(|(_, s)| s.clone())
                    .unwrap_or(State::Unknown);
                (state.word(), reason(&state))
            }
            Outcome::Missing(why) => ("missing", why.clone()),
            Outcome::NotACourse(why) => ("not a course", why.clone()),
            Outcome::NotGraded(why) => ("not graded", why.clone()),
        }
    }

    /// The seed its graders used, if it was graded.
    pub fn seed(&self) -> Option<u64> {
        match &self.outcome {
            Outcome::Graded(s) => Some(s.seed),
            _ => None,
        }
    }
}

/// The one-line reason behind a state (the diagnosis of a failure, the
/// compiler's first error, what timed out). A report whose first line ends
/// in a colon is named with its next line too (a shortcut's file and line).
fn reason(state: &State) -> String {
    match state {
        State::Failing(report) => report
            .lines()
            .find_map(|l| l.trim().strip_prefix("diagnosis:").map(str::trim))
            .map(str::to_string)
            .unwrap_or_else(|| {
                let mut lines = report.lines().map(str::trim);
                let first = lines.next().unwrap_or_default();
                match (first.ends_with(':'), lines.next()) {
                    (true, Some(next)) => format!("{first} {next}"),
                    _ => first.to_string(),
                }
            }),
        State::DoesNotCompile(why) | State::TimedOut(why) => why.clone(),
        _ => String::new(),
    }
}

/// The student's name for `folder`: its last component.
pub fn student_name(folder: &Path) -> String {
    folder
        .canonicalize()
        .ok()
        .as_deref()
        .unwrap_or(folder)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| folder.display().to_string())
}

/// Two copies that [`student_name`] gives the same name (the same folder
/// twice, or `x/alice` and `y/alice`), said in one line: their rows (and
/// Gradescope's `STUDENT/results.json`) could not be told apart.
pub fn same_names(copies: &[PathBuf]) -> Option<String> {
    let names: Vec<String> = copies.iter().map(|c| student_name(c)).collect();
    (0..names.len()).find_map(|j| {
        let i = names[..j].iter().position(|n| *n == names[j])?;
        Some(format!(
            "{} and {} would both be graded as student `{}`: give each copy a folder of its own name",
            copies[i].display(),
            copies[j].display(),
            names[j]
        ))
    })
}

/// Puts together `scratch`: a fresh export of `repo` with the student's
/// `src/**/*.rs` from `submission` in place of the stubs. Like an export, it
/// leaves out `src/solutions/` (the instructor's, never a student's work);
/// a symbolic link is kept as a link, so that the source rule names it.
fn prepare(repo: &Path, submission: &Path, scratch: &Path) -> Result<(), String> {
    if scratch.exists() {
        std::fs::remove_dir_all(scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    }
    let src = submission.join("src");
    if std::fs::symlink_metadata(&src).is_ok_and(|m| m.file_type().is_symlink()) {
        // Not walked: it may stand for any folder of the machine.
        return Err(format!(
            "{}: src/ is a symbolic link, not the student's own folder",
            submission.display()
        ));
    }
    export::export_with(
        repo,
        scratch,
        &export::ExportOptions {
            ci: None,
            link: export::Link::Repository,
        },
    )?;
    let skip = ["solutions"];
    let place = |path: &Path| -> Result<PathBuf, String> {
        let to = scratch
            .join("src")
            .join(path.strip_prefix(&src).unwrap_or(path));
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        }
        Ok(to)
    };
    for path in export::rust_files(&src, &skip) {
        std::fs::copy(&path, place(&path)?).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    for link in export::symbolic_links(&src, &skip) {
        #[cfg(unix)]
        if let Ok(target) = std::fs::read_link(&link) {
            let to = place(&link)?;
            let _ = std::fs::remove_file(&to);
            std::os::unix::fs::symlink(target, &to)
                .map_err(|e| format!("{}: {e}", to.display()))?;
        }
    }
    Ok(())
}

/// Grades one student's copy (`submission`, a folder made by
/// [`export::export`]) with `repo`'s graders in `scratch`.
pub fn grade_submission(
    repo: &Path,
    submission: &Path,
    scratch: &Path,
    options: &Options,
) -> Outcome {
    if !submission.exists() {
        return Outcome::Missing(format!("no folder at {}", submission.display()));
    }
    if let Err(e) = export::check_lessons_dir(submission) {
        return Outcome::NotACourse(e);
    }
    if let Err(e) = prepare(repo, submission, scratch) {
        return Outcome::NotGraded(e);
    }
    // The student's own files are what the rule checks (the scratch holds
    // them, with the repository's tests and manifest).
    match harness::grade(scratch, options) {
        Ok(status) => Outcome::Graded(status),
        Err(e) => Outcome::NotGraded(e),
    }
}

/// The class, graded.
#[derive(Debug, Clone)]
pub struct Class {
    /// Each copy, in the order given.
    pub copies: Vec<Copy>,
    /// The seed the graders used.
    pub seed: u64,
}

/// Builds spintop itself once in the shared build folder (an export of the
/// stubs), so that no copy's time limit pays for it.
pub fn warm_up(repo: &Path, options: &ClassOptions) -> Result<(), String> {
    let scratch = options.work.join("warm-up");
    if scratch.exists() {
        std::fs::remove_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    }
    export::export_with(
        repo,
        &scratch,
        &export::ExportOptions {
            ci: None,
            link: export::Link::Repository,
        },
    )?;
    let opts = Options {
        target_dir: Some(options.target_dir.clone()),
        time_limit: Some(Duration::from_secs(3600)),
        binaries: vec![COURSE[0].binary],
        ..Options::default()
    };
    let status = harness::grade(&scratch, &opts)?;
    match status.compile_error {
        Some(e) => Err(format!("the course's own stubs do not build: {e}")),
        None => Ok(()),
    }
}

/// Grades every copy in `copies` with `repo`'s graders; `done` hears of each
/// copy as it is finished. Never fails: a copy that cannot be graded gets
/// its rows with the reason.
pub fn grade_class(
    repo: &Path,
    copies: &[PathBuf],
    options: &ClassOptions,
    done: &(dyn Fn(&Copy) + Sync),
) -> Class {
    let seed = options
        .seed
        .unwrap_or_else(spintop_grading::verdict::fresh_seed);
    let build_lock = Arc::new(Mutex::new(()));
    let graded = harness::in_parallel(copies.len(), options.jobs, |i| {
        let folder = &copies[i];
        let start = Instant::now();
        let student = student_name(folder);
        let scratch = options.work.join(format!("{i:03}-{student}"));
        let opts = Options {
            seed: Some(seed),
            target_dir: Some(options.target_dir.clone()),
            test_limit: options.test_limit.min(options.timeout),
            time_limit: Some(options.timeout),
            build_lock: Some(Arc::clone(&build_lock)),
            jobs: 1,
            ..Options::default()
        };
        let outcome = grade_submission(repo, folder, &scratch, &opts);
        let _ = std::fs::remove_dir_all(&scratch);
        let copy = Copy {
            student,
            folder: folder.clone(),
            progress: load_progress(folder),
            outcome,
            seconds: start.elapsed().as_secs_f64(),
        };
        done(&copy);
        copy
    });
    let copies = graded
        .into_iter()
        .zip(copies)
        .map(|(copy, folder)| {
            copy.unwrap_or_else(|| Copy {
                student: student_name(folder),
                folder: folder.clone(),
                outcome: Outcome::NotGraded("its grading thread ended early".into()),
                progress: Progress::default(),
                seconds: 0.0,
            })
        })
        .collect();
    Class { copies, seed }
}

/// A CSV field, quoted when it needs to be.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The CSV header.
pub const CSV_HEADER: &str = "student,assignment,equation,state,hint_rungs_used,seed,reason";

impl Class {
    /// Copies that could not be fully graded (missing, not a course, timed
    /// out, cargo not run).
    pub fn ungraded(&self) -> usize {
        self.copies.iter().filter(|c| !c.fully_graded()).count()
    }

    /// One CSV row per student and assignment, after the header.
    pub fn csv(&self) -> String {
        let mut rows = vec![CSV_HEADER.to_string()];
        for copy in &self.copies {
            let seed = copy.seed().map(|s| s.to_string()).unwrap_or_default();
            for a in &COURSE {
                let (word, why) = copy.row(a);
                let rungs = copy.progress.hints.get(a.function).copied().unwrap_or(0);
                rows.push(
                    [
                        csv_field(&copy.student),
                        a.function.to_string(),
                        csv_field(a.equation),
                        word.to_string(),
                        rungs.to_string(),
                        seed.clone(),
                        csv_field(&why),
                    ]
                    .join(","),
                );
            }
        }
        rows.join("\n") + "\n"
    }

    /// Gradescope's `results.json` for one copy: one test per assignment
    /// (1 point each), its status and output, the score, the time spent.
    /// The fields are those of Gradescope's autograder specification.
    pub fn gradescope(&self, copy: &Copy) -> serde_json::Value {
        let tests: Vec<serde_json::Value> = COURSE
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let (word, why) = copy.row(a);
                let report = match &copy.outcome {
                    Outcome::Graded(s) => s
                        .states
                        .iter()
                        .find(|(b, _)| b.test == a.test)
                        .and_then(|(_, st)| st.reason().map(str::to_string)),
                    _ => None,
                };
                let passed = word == "passing";
                let output = match report {
                    Some(r) => format!("{word}\n\n{r}"),
                    None if why.is_empty() => word.to_string(),
                    None => format!("{word}: {why}"),
                };
                serde_json::json!({
                    "name": format!("{} {}", a.equation, a.function),
                    "number": (i + 1).to_string(),
                    "score": if passed { 1.0 } else { 0.0 },
                    "max_score": 1.0,
                    "status": if passed { "passed" } else { "failed" },
                    "output": output,
                    "visibility": "visible",
                })
            })
            .collect();
        let passing = tests.iter().filter(|t| t["status"] == "passed").count();
        let summary = match &copy.outcome {
            Outcome::Graded(s) => format!(
                "spintop course grade: {passing} of {} passing (inputs from seed {}; the same inputs again: spintop course --seed {})",
                COURSE.len(),
                s.seed,
                s.seed
            ),
            Outcome::Missing(why) | Outcome::NotACourse(why) | Outcome::NotGraded(why) => {
                format!("spintop course grade: not graded: {why}")
            }
        };
        serde_json::json!({
            "score": passing as f64,
            "execution_time": copy.seconds.round() as u64,
            "output": summary,
            "tests": tests,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_copies_of_one_name_are_named_and_distinct_ones_pass() {
        let copies = |names: &[&str]| names.iter().map(PathBuf::from).collect::<Vec<_>>();
        let why = same_names(&copies(&["x/alice", "bob", "y/alice"])).expect("a clash");
        assert!(
            why.starts_with("x/alice and y/alice would both be graded as student `alice`"),
            "{why}"
        );
        assert!(same_names(&copies(&["bob", "bob"])).is_some());
        assert_eq!(same_names(&copies(&["x/alice", "x/bob", "carol"])), None);
    }
}
