//! The grade book: a class of students' copies graded with the
//! repository's graders, one row per student and assignment whatever
//! happens.
//!
//! Each run of `course grade` works in a private folder of its own
//! ([`Run`]: unique, 0700, removed at the end), and each copy in its own
//! workspace below it, with its own build folder started from the run's
//! warm build ([`super::warm`]): two runs at once share nothing but the
//! warm cache, which a lock guards. Each copy is snapshotted, checked,
//! built and graded by the harness in its sandbox, within a time limit: a
//! copy that does not compile, hangs, breaks the rule, or is missing still
//! gets its rows, each with a reason.

use super::harness::{self, Options};
use super::process::{self, Ctx};
use super::status::{State, Status};
use super::workspace::private_dir;
use super::{Assignment, CourseError, Progress, export};
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
    /// Where runs put their private folders (the warm cache is the
    /// repository's: `target/course-grade/cache`).
    pub work: PathBuf,
    /// The sandbox's launcher (the `spintop` binary; `None`: no sandbox).
    pub launcher: Option<PathBuf>,
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
    /// It could not be graded at all: why.
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
    /// The hint rungs the student used, as their copy recorded them, or why
    /// that record could not be read (a link, a FIFO, too large).
    pub progress: Result<Progress, String>,
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

    /// The copy's state of `a`, if it was graded.
    pub fn state(&self, a: &Assignment) -> Option<&State> {
        match &self.outcome {
            Outcome::Graded(status) => status
                .states
                .iter()
                .find(|(b, _)| b.test == a.test)
                .map(|(_, s)| s),
            _ => None,
        }
    }

    /// The copy's state of `a`: its word and the one-line reason behind it.
    pub fn row(&self, a: &Assignment) -> (&'static str, String) {
        match &self.outcome {
            Outcome::Graded(_) => {
                let state = self.state(a).cloned().unwrap_or(State::Unknown);
                (state.word(), state.one_line())
            }
            Outcome::Missing(why) => ("missing", why.clone()),
            Outcome::NotACourse(why) => ("not a course", why.clone()),
            Outcome::NotGraded(why) => ("not graded", why.clone()),
        }
    }

    /// How many of its assignments pass.
    pub fn passing(&self) -> usize {
        match &self.outcome {
            Outcome::Graded(s) => s.passing(),
            _ => 0,
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

/// One run's private folder: unique (its process and 64 random bits),
/// 0700, removed with everything in it when the run ends. Its lock file
/// (`run-….lock` beside it, made and locked before the folder) is held
/// for the run's life: a run that finds another's lock free knows that run
/// is gone (SIGKILLed, its folder left behind) and removes its folder.
#[derive(Debug)]
pub struct Run {
    dir: PathBuf,
    lock: Option<(PathBuf, std::fs::File)>,
}

impl Run {
    /// A new run folder below `base` (made private if it is new), after
    /// removing the folders of runs that are no longer alive.
    pub fn new(base: &Path) -> Result<Self, CourseError> {
        private_dir(base)?;
        remove_dead_runs(base);
        loop {
            let name = format!(
                "run-{}-{:016x}",
                std::process::id(),
                spintop_grading::verdict::fresh_u64()
            );
            let dir = base.join(&name);
            let lock = match hold_lock(&base.join(format!("{name}.lock")))? {
                Some(lock) => lock,
                // Removed by a cleaner between its creation and its lock.
                None => continue,
            };
            let mut builder = std::fs::DirBuilder::new();
            #[cfg(unix)]
            std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
            // Not `recursive`: a folder already there (another run's) is an error.
            builder.create(&dir).map_err(CourseError::io(&dir))?;
            return Ok(Self {
                dir,
                lock: Some(lock),
            });
        }
    }

    /// Its folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Its warm build folder (once [`warm_up`] made it).
    fn warm(&self) -> PathBuf {
        self.dir.join("warm")
    }
}

/// Creates and locks `path`: `None` when the file was removed before the
/// lock held (then the caller tries another name).
fn hold_lock(path: &Path) -> Result<Option<(PathBuf, std::fs::File)>, CourseError> {
    let file = std::fs::OpenOptions::new()
        .create_new(true)
        .write(true)
        .open(path)
        .map_err(CourseError::io(path))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        rustix::fs::flock(&file, rustix::fs::FlockOperation::LockExclusive)
            .map_err(|e| CourseError::io(path)(e.into()))?;
        let held = file.metadata().map_err(CourseError::io(path))?;
        match std::fs::symlink_metadata(path) {
            Ok(now) if now.ino() == held.ino() && now.dev() == held.dev() => {}
            _ => return Ok(None),
        }
    }
    Ok(Some((path.to_path_buf(), file)))
}

/// Removes the folders of runs below `base` whose lock no one holds (their
/// run ended without its `Drop`: a SIGKILL), and folders of runs that kept
/// no lock. A lock file is removed last, while this run holds it.
fn remove_dead_runs(base: &Path) {
    #[cfg(unix)]
    {
        let Ok(entries) = std::fs::read_dir(base) else {
            return;
        };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
            if !name.starts_with("run-") || name.ends_with(".lock") || !is_dir {
                continue;
            }
            let lock_path = base.join(format!("{name}.lock"));
            // A lock file comes before its folder and goes after it: a
            // folder without one was left by a run that kept none.
            let lock = match std::fs::OpenOptions::new().write(true).open(&lock_path) {
                Ok(f) => Some(f),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                Err(_) => continue,
            };
            if let Some(f) = &lock {
                use rustix::fs::FlockOperation::NonBlockingLockExclusive;
                if rustix::fs::flock(f, NonBlockingLockExclusive).is_err() {
                    continue; // its run is alive
                }
            }
            let _ = std::fs::remove_dir_all(entry.path());
            if lock.is_some() {
                let _ = std::fs::remove_file(&lock_path);
            }
        }
    }
    #[cfg(not(unix))]
    let _ = base;
}

impl Drop for Run {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
        if let Some((path, file)) = self.lock.take() {
            let _ = std::fs::remove_file(path);
            drop(file);
        }
    }
}

/// Builds the course's stubs once (in the shared cache under
/// `options.work`, under its lock) and gives `run` its warm build, so that
/// no copy's time limit pays for compiling spintop.
pub fn warm_up(repo: &Path, options: &ClassOptions, run: &Run) -> Result<(), CourseError> {
    let ctx = Ctx {
        stop: None,
        deadline: Some(Instant::now() + Duration::from_secs(3600)),
    };
    super::warm::prepare(
        repo,
        &super::warm::cache_dir(repo),
        &run.warm(),
        options.launcher.as_deref(),
        &ctx,
    )
}

/// Grades one student's copy (`submission`, a folder made by
/// [`export::export`]) in the workspace `work`.
pub fn grade_submission(submission: &Path, options: &Options) -> Outcome {
    if !submission.exists() {
        return Outcome::Missing(format!("no folder at {}", submission.display()));
    }
    if let Err(e) = export::check_lessons_dir(submission) {
        return Outcome::NotACourse(e);
    }
    match harness::grade(submission, options) {
        Ok(status) => Outcome::Graded(status),
        Err(e) => Outcome::NotGraded(e.to_string()),
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

/// Grades every copy in `copies` with the repository's graders, in `run`;
/// `done` hears of each copy as it is finished. Never fails: a copy that
/// cannot be graded gets its rows with the reason.
pub fn grade_class(
    copies: &[PathBuf],
    options: &ClassOptions,
    run: &Run,
    done: &(dyn Fn(&Copy) + Sync),
) -> Class {
    let seed = options
        .seed
        .unwrap_or_else(spintop_grading::verdict::fresh_seed);
    let build_lock = Arc::new(Mutex::new(()));
    let warm = run.warm();
    let graded = process::in_parallel(copies.len(), options.jobs, |i| {
        let folder = &copies[i];
        let start = Instant::now();
        let opts = Options {
            seed: Some(seed),
            work: Some(run.dir().join(format!("{i:03}"))),
            warm: warm.is_dir().then(|| warm.clone()),
            launcher: options.launcher.clone(),
            test_limit: options.test_limit.min(options.timeout),
            time_limit: Some(options.timeout),
            build_lock: Some(Arc::clone(&build_lock)),
            jobs: 1,
            crates: harness::Crates::Repository,
            ..Options::default()
        };
        let outcome = grade_submission(folder, &opts);
        if let Some(work) = &opts.work {
            let _ = std::fs::remove_dir_all(work);
        }
        let copy = Copy {
            student: student_name(folder),
            folder: folder.clone(),
            progress: super::progress::read_progress(folder),
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
                progress: Err("not read".into()),
                seconds: 0.0,
            })
        })
        .collect();
    Class { copies, seed }
}

impl Class {
    /// Copies that could not be fully graded (missing, not a course, timed
    /// out, cargo not run).
    pub fn ungraded(&self) -> usize {
        self.copies.iter().filter(|c| !c.fully_graded()).count()
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

    #[test]
    fn two_runs_get_two_private_folders_removed_at_their_end() {
        let base = std::env::temp_dir().join(format!("spintop-runs-{}", std::process::id()));
        let (a, b) = (Run::new(&base).unwrap(), Run::new(&base).unwrap());
        assert_ne!(a.dir(), b.dir());
        #[cfg(unix)]
        for dir in [&base, &a.dir().to_path_buf()] {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(dir).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode, 0o700, "{}", dir.display());
        }
        let kept = a.dir().to_path_buf();
        std::fs::write(kept.join("x"), "x").unwrap();
        drop(a);
        assert!(!kept.exists());
        assert!(b.dir().is_dir());
        drop(b);
        std::fs::remove_dir_all(&base).unwrap();
    }

    /// A run SIGKILLed leaves its folder and its lock file, no longer
    /// held: the next run removes them; a live run's folder (its lock
    /// held, here by this test) and a folder that is not a run's stay.
    #[test]
    #[cfg(unix)]
    fn a_new_run_removes_the_folders_of_dead_runs_only() {
        let base = std::env::temp_dir().join(format!("spintop-dead-runs-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        private_dir(&base).unwrap();
        let dead = base.join("run-1-dead");
        std::fs::create_dir_all(dead.join("warm/target")).unwrap();
        std::fs::write(base.join("run-1-dead.lock"), "").unwrap();
        let legacy = base.join("run-2-kept-no-lock");
        std::fs::create_dir(&legacy).unwrap();
        let alive = base.join("run-3-alive");
        std::fs::create_dir(&alive).unwrap();
        let held = std::fs::File::create(base.join("run-3-alive.lock")).unwrap();
        rustix::fs::flock(&held, rustix::fs::FlockOperation::LockExclusive).unwrap();
        let other = base.join("warm-up");
        std::fs::create_dir(&other).unwrap();
        let run = Run::new(&base).unwrap();
        assert!(!dead.exists() && !base.join("run-1-dead.lock").exists());
        assert!(!legacy.exists());
        assert!(alive.is_dir() && base.join("run-3-alive.lock").is_file());
        assert!(other.is_dir() && run.dir().is_dir());
        let lock = PathBuf::from(format!("{}.lock", run.dir().display()));
        assert!(lock.is_file());
        drop(run);
        assert!(!lock.exists());
        drop(held);
        std::fs::remove_dir_all(&base).unwrap();
    }
}
