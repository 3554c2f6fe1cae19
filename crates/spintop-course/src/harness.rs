//! The harness: one grading of a lessons crate.
//!
//! 1. **Snapshot.** The copy's `src/**/*.rs` is copied once into a private
//!    workspace ([`super::snapshot`], [`super::workspace`]): no link
//!    followed, sizes checked before reading. Everything after reads the
//!    snapshot.
//! 2. **The source rule** ([`super::source_rule`]) on the snapshot's files;
//!    a copy that breaks it is not compiled at all.
//! 3. **The build** of the runner (the student's crate and
//!    `spintop_runner`, no grader, no reference) in the build sandbox. A
//!    file of an assignment that does not compile is put back to its stub
//!    and the rest built again: its assignments say why, the others are
//!    graded.
//! 4. **The graders** run here, in this process; each calls the student's
//!    function in the runner, in its sandbox, over a pipe
//!    ([`super::runner`]). A runner that dies or hangs costs its assignment,
//!    and the next gets a new one. What the student's code prints is never
//!    read.

use super::compile::{self, Built};
use super::process::{self, Ctx};
use super::runner::{Lost, Runner};
use super::status::{Failure, Located, State, Status};
use super::workspace::Workspace;
use super::{Assignment, COURSE, CourseError, snapshot, source_rule};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// How to grade.
#[derive(Debug, Clone)]
pub struct Options {
    /// Grade the instructor's reference solutions (`--features solutions`).
    pub solutions: bool,
    /// The graders' test binaries whose assignments to grade (all when
    /// empty).
    pub binaries: Vec<&'static str>,
    /// The seed of the inputs (a fresh one when `None`).
    pub seed: Option<u64>,
    /// The `--course DIR` the reports' commands repeat (`None`: the
    /// repository's own lessons).
    pub course_arg: Option<String>,
    /// The private workspace to grade in (default: `spintop-grade/` in the
    /// course's own `target/`, kept between gradings so that a build reuses
    /// the last one).
    pub work: Option<PathBuf>,
    /// A warm build folder (the stubs' build) to start the workspace's
    /// from, when it has none yet.
    pub warm: Option<PathBuf>,
    /// The launcher of the sandbox: the `spintop` binary (`None`: no
    /// sandbox, only the limits a parent can set from outside).
    pub launcher: Option<PathBuf>,
    /// The longest one grader may run.
    pub test_limit: Duration,
    /// The longest the whole grading (build and graders) may take, counted
    /// from the start of its build.
    pub time_limit: Option<Duration>,
    /// Held while building, so that builds wait for each other before
    /// their clock starts.
    pub build_lock: Option<Arc<std::sync::Mutex<()>>>,
    /// Graders (and runners) at once.
    pub jobs: usize,
    /// Set to stop: the running build or runner is killed.
    pub stop: Option<Arc<AtomicBool>>,
    /// Where to report how far the grading has got (see [`super::building`]).
    pub progress: Option<Arc<super::building::Building>>,
    /// Which spintop crates the runner is built against.
    pub crates: Crates,
}

/// The spintop crates (the core, the wire) a runner is built against, and
/// the lock file that pins their dependencies.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Crates {
    /// Those the copy carries in its own `crates/` (an export handed to a
    /// student), so that `spintop course` grades it where the repository
    /// is not; the repository's when the copy carries none.
    #[default]
    CarriedOrRepository,
    /// The repository's, always: an instructor's grade never builds
    /// against crates a student's copy holds.
    Repository,
}

impl Crates {
    /// The folder whose `crates/` and `Cargo.lock` the runner of the copy
    /// in `dir` is built against.
    pub fn root(self, dir: &Path) -> PathBuf {
        let carried = dir.join("crates/spintop-runner/Cargo.toml").is_file()
            && dir.join("crates/spintop/Cargo.toml").is_file()
            && dir.join("Cargo.lock").is_file();
        match self {
            Crates::CarriedOrRepository if carried => dir.to_path_buf(),
            _ => super::repository().to_path_buf(),
        }
    }
}

impl Default for Options {
    fn default() -> Self {
        Self {
            solutions: false,
            binaries: Vec::new(),
            seed: None,
            course_arg: None,
            work: None,
            warm: None,
            launcher: None,
            test_limit: Duration::from_secs(60),
            time_limit: None,
            build_lock: None,
            jobs: std::thread::available_parallelism().map_or(2, |n| n.get()),
            stop: None,
            progress: None,
            crates: Crates::default(),
        }
    }
}

/// The CPU seconds a build or runner may use: its wall-clock limit, and a
/// day without one.
fn cpu_seconds(limit: Option<Duration>) -> u64 {
    limit.map_or(24 * 3600, |l| l.as_secs().max(1) + 1)
}

/// Where the course in `dir` is graded when no workspace is given: next to
/// its progress file, in its own `target/`.
pub fn default_work(dir: &Path) -> PathBuf {
    super::progress_path(dir)
        .parent()
        .map_or_else(|| dir.join("target"), Path::to_path_buf)
        .join("spintop-grade")
}

/// Every assignment refused for one reason (a shortcut, a snapshot that
/// could not be taken), the first place named.
fn refusal(seed: u64, lines: &[String], place: Located) -> Status {
    let report = format!(
        "{}: your copy reaches past what an assignment may use, so no grader runs:\n  {}\n(lessons/README.md, \"No shortcut\", says what is allowed and why)",
        spintop_grading::NO_SHORTCUT,
        lines.join("\n  ")
    );
    let mut status = Status::new(seed, |_| State::Failing(Failure::plain(report.clone())));
    status.shortcut = Some(place);
    status
}

/// Holds the workspace at `root` for one grading (an exclusive `flock` on
/// its `grading.lock`, released when the file is dropped, or by the kernel
/// when the process dies), waiting for a grading that holds it.
fn lock_workspace(root: &Path) -> Result<std::fs::File, CourseError> {
    let path = root.join("grading.lock");
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(CourseError::io(&path))?;
    #[cfg(unix)]
    rustix::fs::flock(&file, rustix::fs::FlockOperation::LockExclusive)
        .map_err(|e| CourseError::io(&path)(e.into()))?;
    Ok(file)
}

/// Grades the lessons crate in `dir`. An error is a reason the grading
/// could not be done at all (cargo not run, the workspace not written);
/// everything the copy does (a shortcut, a compile error, a hang) is a
/// state in the status.
pub fn grade(dir: &Path, opts: &Options) -> Result<Status, CourseError> {
    let dir = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    let seed = opts
        .seed
        .unwrap_or_else(spintop_grading::verdict::fresh_seed);
    report(opts, super::building::Building::start);
    let ws = Workspace::at(&opts.work.clone().unwrap_or_else(|| default_work(&dir)));
    let crates = opts.crates.root(&dir);
    let refused = |e| workspace_refused(e, &dir);
    ws.lay_out(&crates).map_err(refused)?;
    let ws = Workspace::at(
        &ws.root()
            .canonicalize()
            .map_err(CourseError::io(ws.root()))?,
    );
    // One grading at a time in a workspace: a second grading of the same
    // copy (two `spintop course` at once, or one beside `learn`) waits here
    // for the first instead of clearing the sources under it.
    let _grading = lock_workspace(ws.root()).map_err(refused)?;
    ws.clear_sources().map_err(refused)?;
    // 1. The snapshot.
    let snap = match snapshot::take(&dir, &ws.course(), &snapshot::Limits::default()) {
        Ok(s) => s,
        Err(e @ (snapshot::SnapshotError::SrcNotAFolder | snapshot::SnapshotError::TooMuch(_))) => {
            let place = Located {
                file: "src".into(),
                line: 1,
                message: e.to_string(),
            };
            return Ok(refusal(seed, &[place.to_string()], place));
        }
        Err(e) => return Err(e.into()),
    };
    if let Some(first) = snap.refused.first() {
        let lines: Vec<String> = snap
            .refused
            .iter()
            .take(5)
            .map(|r| format!("{}:1: {}", r.path.display(), r.why))
            .collect();
        let place = Located {
            file: first.path.display().to_string(),
            line: 1,
            message: first.why.clone(),
        };
        return Ok(refusal(seed, &lines, place));
    }
    // 2. The rule, on the snapshot. A file the parser cannot read is left
    // to the compiler, which says more about it.
    let violations: Vec<_> = source_rule::check_copy(&ws.course())
        .into_iter()
        .filter(|v| !v.unreadable)
        .collect();
    if let Some(first) = violations.first() {
        let lines: Vec<String> = violations.iter().take(5).map(|v| v.to_string()).collect();
        let place = Located {
            file: first.file.display().to_string(),
            line: first.line,
            message: first.what.clone(),
        };
        return Ok(refusal(seed, &lines, place));
    }
    match &opts.warm {
        Some(warm) => super::warm::copy_into(warm, &ws.target())?,
        // A first grading here starts from the class's warm build, if any
        // (built against the repository's crates).
        None if crates == super::repository() => {
            super::warm::seed_from_cache(super::repository(), &ws.target())?
        }
        None => {}
    }
    // 3. The build.
    let ctx = Ctx {
        stop: opts.stop.clone(),
        deadline: None,
    };
    let guard = opts
        .build_lock
        .as_ref()
        .map(|l| l.lock().unwrap_or_else(|e| e.into_inner()));
    let ctx = Ctx {
        deadline: opts.time_limit.map(|t| Instant::now() + t),
        ..ctx
    };
    let built = build_with_stubs(&ws, opts, &ctx)?;
    drop(guard);
    let selected = |a: &Assignment| opts.binaries.is_empty() || opts.binaries.contains(&a.binary);
    let (exe, broken, compile_error) = match built {
        Outcome::Runner { exe, broken } => {
            let first = broken.first().map(|(_, l)| l.clone());
            (exe, broken, first)
        }
        Outcome::Whole(state, error) => {
            let mut status = Status::new(seed, |a| {
                if selected(a) && !ctx.stopped() {
                    state.clone()
                } else {
                    State::Unknown
                }
            });
            status.compile_error = error;
            return Ok(status);
        }
    };
    // 4. The graders, each with the student's functions in a runner.
    let mut status = Status::new(seed, |_| State::Unknown);
    status.compile_error = compile_error;
    let todo: Vec<&Assignment> = COURSE.iter().filter(|a| selected(a)).collect();
    report(opts, |p| p.graders(todo.len()));
    let graded = grade_all(&todo, &exe, &broken, seed, opts, &ctx);
    for (a, state) in todo.iter().zip(graded) {
        if let Some(slot) = status.states.iter_mut().find(|(b, _)| b.test == a.test) {
            slot.1 = state;
        }
    }
    Ok(status)
}

/// A workspace that could not be written (a course another user owns, a
/// read-only file system): which folder, why, and what to do; nothing of
/// the copy in `dir` was judged.
fn workspace_refused(e: CourseError, dir: &Path) -> CourseError {
    let CourseError::Io { path, source } = &e else {
        return e;
    };
    if !matches!(
        source.kind(),
        std::io::ErrorKind::PermissionDenied | std::io::ErrorKind::ReadOnlyFilesystem
    ) {
        return e;
    }
    CourseError::CannotGrade(format!(
        "the grader builds in {}, and it could not be written ({}). Grading needs a course you may write to: copy it to a folder of your own (cp -r {} ~/spintop-course) and work there; reading the book and its scenes need nothing written",
        path.display(),
        super::unwritable_why(path, source),
        dir.display()
    ))
}

/// Tells the grading's progress, if it is watched.
fn report(opts: &Options, f: impl FnOnce(&super::building::Building)) {
    if let Some(p) = &opts.progress {
        f(p);
    }
}

/// What the build came to.
enum Outcome {
    /// A runner; the files put back to their stubs, each with its error.
    Runner {
        exe: PathBuf,
        broken: Vec<(&'static str, Located)>,
    },
    /// No runner: every assignment gets this state (and the error, if it is
    /// the compiler's).
    Whole(State, Option<Located>),
}

/// The assignment file (`ch2`, …) an error is in: its own file, or the
/// runner's line that calls one of its functions (a signature of the
/// student's own); `None` for any other file.
fn module_of(error: &Located) -> Option<&'static str> {
    const MODULES: [&str; 5] = ["ch2", "ch3", "ch4", "numerics", "appendix"];
    let file = Path::new(&error.file);
    if file.ends_with("runner/main.rs") {
        return MODULES
            .into_iter()
            .find(|m| error.message.contains(&format!("{m}::")));
    }
    let name = file.file_stem()?.to_str()?;
    let in_src = file
        .parent()
        .is_some_and(|p| p.ends_with("course/src") || p.ends_with("src"));
    MODULES.into_iter().find(|m| *m == name && in_src)
}

/// An error as the student knows the file: `src/ch3.rs`, not the
/// workspace's `course/src/ch3.rs`.
fn as_student_sees(mut error: Located) -> Located {
    if let Some(rest) = error.file.strip_prefix("course/") {
        error.file = rest.to_string();
    }
    if error.file.ends_with("runner/main.rs") {
        error.message = format!(
            "a function's signature is not the stub's (the course calls each as its stub declares it): {}",
            error.message
        );
    }
    error
}

/// Builds the runner; the files of assignments that do not compile are put
/// back to their stubs (at most three rounds), so that the others are
/// graded.
fn build_with_stubs(ws: &Workspace, opts: &Options, ctx: &Ctx) -> Result<Outcome, CourseError> {
    let mut broken: Vec<(&'static str, Located)> = Vec::new();
    for _round in 0..4 {
        let built = compile::build_runner(
            ws,
            opts.launcher.as_deref(),
            opts.solutions,
            cpu_seconds(opts.time_limit),
            ctx,
            opts.progress.as_ref(),
        )?;
        let errors = match built {
            Built::Programs(_) => {
                return Ok(Outcome::Runner {
                    exe: ws.runner(),
                    broken,
                });
            }
            Built::OutOfTime if ctx.stopped() => return Ok(Outcome::Whole(State::Unknown, None)),
            Built::OutOfTime => {
                return Ok(Outcome::Whole(
                    State::TimedOut(
                        "the build did not finish within the time limit and was stopped".into(),
                    ),
                    None,
                ));
            }
            Built::Bounded(why) => return Ok(Outcome::Whole(State::DoesNotCompile(why), None)),
            Built::Failed(errors) => errors,
        };
        let errors: Vec<Located> = errors.into_iter().map(as_student_sees).collect();
        let modules: Vec<Option<&'static str>> = errors.iter().map(module_of).collect();
        let fresh = modules
            .iter()
            .flatten()
            .any(|m| !broken.iter().any(|(b, _)| b == m));
        if modules.iter().any(Option::is_none) || !fresh {
            // An error outside an assignment's file (lib.rs, a helper, the
            // manifest): nothing can be graded.
            let first = errors
                .iter()
                .zip(&modules)
                .find(|(_, m)| m.is_none())
                .map(|(e, _)| e.clone())
                .or_else(|| errors.first().cloned());
            let why = first.as_ref().map(|e| e.to_string()).unwrap_or_default();
            return Ok(Outcome::Whole(State::DoesNotCompile(why), first));
        }
        for (error, module) in errors.into_iter().zip(modules) {
            let Some(module) = module else { continue };
            if broken.iter().any(|(b, _)| *b == module) {
                continue;
            }
            put_back_stub(ws, module)?;
            broken.push((module, error));
        }
    }
    let why = broken
        .first()
        .map(|(_, e)| e.to_string())
        .unwrap_or_default();
    Ok(Outcome::Whole(
        State::DoesNotCompile(why),
        broken.first().map(|(_, e)| e.clone()),
    ))
}

/// The course's assignment files as this spintop was built with them (the
/// stubs, and the solutions' switch that an export strips), so that a
/// student's copy is graded where the repository is not.
const STUBS: [(&str, &str); 5] = [
    ("ch2", include_str!("../../../lessons/src/ch2.rs")),
    ("ch3", include_str!("../../../lessons/src/ch3.rs")),
    ("ch4", include_str!("../../../lessons/src/ch4.rs")),
    ("numerics", include_str!("../../../lessons/src/numerics.rs")),
    ("appendix", include_str!("../../../lessons/src/appendix.rs")),
];

/// Puts the stub of the assignment file `module` in place of the
/// student's (the course's own stub, as an export writes it).
fn put_back_stub(ws: &Workspace, module: &str) -> Result<(), CourseError> {
    let to = ws.course().join("src").join(format!("{module}.rs"));
    let Some((_, text)) = STUBS.iter().find(|(m, _)| *m == module) else {
        return Err(CourseError::Export(format!("no stub for {module}")));
    };
    std::fs::write(&to, super::strip_solutions(text)).map_err(CourseError::io(&to))
}

/// Grades `todo` with the runner `exe`, on `opts.jobs` runners at once
/// (each thread its own runner, started anew when one is lost).
fn grade_all(
    todo: &[&Assignment],
    exe: &Path,
    broken: &[(&'static str, Located)],
    seed: u64,
    opts: &Options,
    ctx: &Ctx,
) -> Vec<State> {
    let jobs = opts.jobs.clamp(1, todo.len().max(1));
    let chunks = process::in_parallel(jobs, jobs, |k| {
        let mut runner: Option<Runner> = None;
        todo.iter()
            .enumerate()
            .filter(|(i, _)| i % jobs == k)
            .map(|(i, a)| {
                let state = grade_one(a, exe, broken, seed, opts, ctx, &mut runner);
                report(opts, super::building::Building::grader_done);
                (i, state)
            })
            .collect::<Vec<_>>()
    });
    let mut states = vec![State::Unknown; todo.len()];
    for (i, state) in chunks.into_iter().flatten().flatten() {
        states[i] = state;
    }
    states
}

/// Grades one assignment with a runner (started, or started again).
fn grade_one(
    a: &Assignment,
    exe: &Path,
    broken: &[(&'static str, Located)],
    seed: u64,
    opts: &Options,
    ctx: &Ctx,
    runner: &mut Option<Runner>,
) -> State {
    if let Some((_, error)) = broken.iter().find(|(m, _)| *m == a.binary) {
        return State::DoesNotCompile(error.to_string());
    }
    if ctx.stopped() {
        return State::Unknown;
    }
    let limit = opts.test_limit.min(ctx.left());
    if limit.is_zero() {
        return State::TimedOut(
            "the copy's time limit ran out before this grader could start".into(),
        );
    }
    if runner.as_ref().is_none_or(|r| r.lost().is_some()) {
        *runner = None;
        match Runner::start(exe, opts.launcher.as_deref(), cpu_seconds(opts.time_limit)) {
            Ok(r) => *runner = Some(r),
            Err(lost) => return State::Failing(Failure::plain(lost.reason())),
        }
    }
    let Some(r) = runner.as_ref() else {
        return State::Unknown;
    };
    r.allow(limit);
    let grade = spintop_grading::grade_remote(a.function, seed, r);
    if let Some(lost) = r.lost() {
        return match lost {
            _ if ctx.stopped() => State::Unknown,
            Lost::TimedOut(_) => State::TimedOut(lost.reason()),
            _ => State::Failing(Failure::plain(lost.reason())),
        };
    }
    match grade {
        None => State::Failing(Failure::plain(format!("no grader for {}", a.function))),
        Some(Ok(_)) => State::Passing,
        Some(Err(failed)) if failed.is_stub() => State::NotStarted,
        Some(Err(mut failed)) => {
            failed.course = opts.course_arg.clone();
            State::Failing(Failure::of(&failed))
        }
    }
}
