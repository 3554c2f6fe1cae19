//! The harness: grades a lessons crate and reads each grader's verdict from
//! structure, never from printed text.
//!
//! 1. The source rule ([`super::source_rule`]) is checked on the copy's
//!    files; a copy that breaks it is not compiled at all.
//! 2. `cargo test --no-run --message-format json` builds the graders' test
//!    programs; cargo's JSON names each program, and the first compiler
//!    error with its file and line.
//! 3. Each grader's test runs in a process of its own (`TEST --exact`) under
//!    a time limit, with a fresh seed, a verdict file and a random token (see
//!    [`spintop_grading::verdict`]). An assignment passes only when its
//!    process exits with success *and* the grader's verdict file, carrying
//!    the token, says so. What the student's code prints is never read.

use super::source_rule;
use super::{Assignment, COURSE};
use spintop_grading::verdict::{self, Verdict};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Where an assignment stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum State {
    /// The stub is untouched (it still panics with `todo!()`).
    NotStarted,
    /// The grader rejected the answer, or the copy breaks the source rule;
    /// the report.
    Failing(String),
    /// The grader accepted it.
    Passing,
    /// The lessons crate did not compile: `file:line: message`.
    DoesNotCompile(String),
    /// The grader did not finish within its time limit; why it was stopped.
    TimedOut(String),
    /// The grader did not report (not run).
    Unknown,
}

impl State {
    /// A short word for a status line.
    pub fn word(&self) -> &'static str {
        match self {
            State::NotStarted => "not started",
            State::Failing(_) => "failing",
            State::Passing => "passing",
            State::DoesNotCompile(_) => "does not compile",
            State::TimedOut(_) => "timed out",
            State::Unknown => "not graded",
        }
    }

    /// The report or the reason behind the word, if there is one.
    pub fn reason(&self) -> Option<&str> {
        match self {
            State::Failing(r) | State::DoesNotCompile(r) | State::TimedOut(r) => Some(r),
            _ => None,
        }
    }
}

/// A place in a file, and what is wrong there (a compile error, a
/// violation of the source rule).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// The file, as cargo or the rule names it.
    pub file: String,
    /// The line (1-based).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.message)
    }
}

/// The course's state after one grading run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    /// Each assignment of [`COURSE`] with its state, in course order.
    pub states: Vec<(Assignment, State)>,
    /// The seed the graders drew their inputs from.
    pub seed: u64,
    /// The first compile error, when the crate does not compile.
    pub compile_error: Option<Located>,
    /// The first violation of the source rule, when the copy breaks it.
    pub shortcut: Option<Located>,
}

impl Status {
    /// A status with each assignment's state from `state`.
    pub fn new(seed: u64, state: impl Fn(&Assignment) -> State) -> Self {
        Self {
            states: COURSE.iter().map(|a| (*a, state(a))).collect(),
            seed,
            compile_error: None,
            shortcut: None,
        }
    }

    /// How many pass.
    pub fn passing(&self) -> usize {
        self.states
            .iter()
            .filter(|(_, s)| *s == State::Passing)
            .count()
    }

    /// The first assignment in course order that does not pass.
    pub fn next(&self) -> Option<&(Assignment, State)> {
        self.states.iter().find(|(_, s)| *s != State::Passing)
    }

    /// The file to open next: where the crate does not compile or breaks the
    /// rule (`file:line`), else the next assignment's file.
    pub fn next_place(&self) -> Option<String> {
        if let Some(l) = self.compile_error.as_ref().or(self.shortcut.as_ref()) {
            return Some(format!("{}:{}", l.file, l.line));
        }
        None
    }

    /// Whether every assignment has a verdict of its own (none is "does not
    /// compile" or ungraded), so that a partial re-grade can build on it.
    pub fn complete(&self) -> bool {
        self.compile_error.is_none()
            && self.shortcut.is_none()
            && self
                .states
                .iter()
                .all(|(_, s)| !matches!(s, State::DoesNotCompile(_) | State::Unknown))
    }

    /// This status with the assignments graded by `binaries` (all when empty)
    /// taken from `fresh`. A compile error or a shortcut concerns the whole
    /// crate, so it is taken for every assignment.
    pub fn merged(&self, fresh: Status, binaries: &[&str]) -> Status {
        let whole = fresh.compile_error.is_some() || fresh.shortcut.is_some();
        let states = self
            .states
            .iter()
            .zip(fresh.states)
            .map(|((a, old), (_, new))| {
                let regraded = binaries.is_empty() || binaries.contains(&a.binary);
                if regraded || whole {
                    (*a, new)
                } else {
                    (*a, old.clone())
                }
            })
            .collect();
        Status {
            states,
            seed: fresh.seed,
            compile_error: fresh.compile_error,
            shortcut: fresh.shortcut,
        }
    }
}

/// How to grade.
#[derive(Debug, Clone)]
pub struct Options {
    /// Grade the instructor's reference solutions (`--features solutions`).
    pub solutions: bool,
    /// The graders' test binaries to run (all when empty).
    pub binaries: Vec<&'static str>,
    /// The seed of the inputs (a fresh one when `None`).
    pub seed: Option<u64>,
    /// The `--course DIR` the reports' commands repeat (`None`: the
    /// repository's own lessons).
    pub course_arg: Option<String>,
    /// The build folder (cargo's own choice when `None`).
    pub target_dir: Option<PathBuf>,
    /// The longest one grader may run.
    pub test_limit: Duration,
    /// The longest the whole grading (build and tests) may take, counted
    /// from the start of its build.
    pub time_limit: Option<Duration>,
    /// Held while building, so that builds sharing a build folder wait for
    /// each other before their clock starts.
    pub build_lock: Option<Arc<std::sync::Mutex<()>>>,
    /// Graders run at once.
    pub jobs: usize,
    /// Set to stop: the running cargo or test is killed.
    pub stop: Option<Arc<AtomicBool>>,
    /// Where to report how far the grading has got (see [`super::building`]).
    pub progress: Option<Arc<super::building::Building>>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            solutions: false,
            binaries: Vec::new(),
            seed: None,
            course_arg: None,
            target_dir: None,
            test_limit: Duration::from_secs(60),
            time_limit: None,
            build_lock: None,
            jobs: std::thread::available_parallelism().map_or(2, |n| n.get()),
            stop: None,
            progress: None,
        }
    }
}

/// One grading's options and its deadline.
pub(crate) struct Ctx<'a> {
    pub(crate) opts: &'a Options,
    pub(crate) deadline: Option<Instant>,
}

impl Ctx<'_> {
    fn stopped(&self) -> bool {
        self.opts
            .stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
    }

    /// The time left before the deadline (a long time without one).
    fn left(&self) -> Duration {
        self.deadline.map_or(Duration::from_secs(24 * 3600), |d| {
            d.saturating_duration_since(Instant::now())
        })
    }
}

/// Grades the lessons crate in `dir`. An error is a reason cargo could not
/// be run at all; everything else (a shortcut, a compile error, a hang) is a
/// state in the status.
pub fn grade(dir: &Path, opts: &Options) -> Result<Status, String> {
    // Absolute: cargo runs inside the copy, where a path relative to here
    // (`--course mine`) would name nothing.
    let absolute = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    let dir = absolute.as_path();
    let seed = opts.seed.unwrap_or_else(verdict::fresh_seed);
    report(opts, super::building::Building::start);
    let selected = |a: &Assignment| opts.binaries.is_empty() || opts.binaries.contains(&a.binary);
    // 1. The source rule, before anything is compiled. A file the parser
    // cannot read is left to the compiler, which says more about it; the
    // rule refuses it only if the crate builds without it.
    let violations = source_rule::check_copy(dir);
    let refusal = |violations: &[source_rule::Violation]| {
        let first = violations.first()?;
        let lines: Vec<String> = violations.iter().take(5).map(|v| v.to_string()).collect();
        let report = format!(
            "{}: your copy reaches past what an assignment may use, so no grader runs:\n  {}\n(lessons/README.md, \"No shortcut\", says what is allowed and why)",
            spintop_grading::NO_SHORTCUT,
            lines.join("\n  ")
        );
        let mut status = Status::new(seed, |_| State::Failing(report.clone()));
        status.shortcut = Some(Located {
            file: first.file.display().to_string(),
            line: first.line,
            message: first.what.clone(),
        });
        Some(status)
    };
    if violations.iter().any(|v| !v.unreadable) {
        let real: Vec<_> = violations
            .iter()
            .filter(|v| !v.unreadable)
            .cloned()
            .collect();
        return Ok(refusal(&real).unwrap_or_else(|| Status::new(seed, |_| State::Unknown)));
    }
    // 2. The graders' programs.
    let binaries: Vec<&'static str> = if opts.binaries.is_empty() {
        super::catalogue::binaries()
    } else {
        opts.binaries.clone()
    };
    let guard = opts
        .build_lock
        .as_ref()
        .map(|l| l.lock().unwrap_or_else(|e| e.into_inner()));
    let ctx = Ctx {
        opts,
        deadline: opts.time_limit.map(|t| Instant::now() + t),
    };
    let built = build(dir, &ctx, &binaries);
    drop(guard);
    let programs = match built? {
        Built::Programs(p) => p,
        Built::Failed(error) => {
            let why = error.to_string();
            let mut status = Status::new(seed, |a| {
                if selected(a) {
                    State::DoesNotCompile(why.clone())
                } else {
                    State::Unknown
                }
            });
            status.compile_error = Some(error);
            return Ok(status);
        }
        Built::OutOfTime => {
            let stopped = ctx.stopped();
            return Ok(Status::new(seed, |a| {
                if selected(a) && !stopped {
                    State::TimedOut(
                        "the build did not finish within the time limit and was stopped".into(),
                    )
                } else {
                    State::Unknown
                }
            }));
        }
    };
    if let Some(status) = refusal(&violations) {
        return Ok(status); // it builds, but a file of it cannot be read
    }
    // 3. Each grader in a process of its own.
    let token = format!("{:016x}{:016x}", verdict::fresh_u64(), verdict::fresh_u64());
    let verdicts = std::env::temp_dir().join(format!("spintop-verdicts-{token}"));
    std::fs::create_dir_all(&verdicts).map_err(|e| format!("{}: {e}", verdicts.display()))?;
    let todo: Vec<&Assignment> = COURSE.iter().filter(|a| selected(a)).collect();
    report(opts, |p| p.graders(todo.len()));
    let run = Run {
        dir,
        ctx: &ctx,
        seed,
        token: &token,
        verdicts: &verdicts,
    };
    let results = in_parallel(todo.len(), opts.jobs, |i| {
        let a = todo[i];
        let state = match programs.iter().find(|(b, _)| b == a.binary) {
            Some((_, exe)) => run.test(exe, a),
            None => State::Failing(format!(
                "cargo built no test program `{}`: is tests/{}.rs in the copy?",
                a.binary, a.binary
            )),
        };
        report(opts, super::building::Building::grader_done);
        state
    });
    let _ = std::fs::remove_dir_all(&verdicts);
    let mut status = Status::new(seed, |_| State::Unknown);
    for (a, result) in todo.iter().zip(results) {
        if let Some(slot) = status.states.iter_mut().find(|(b, _)| b.test == a.test) {
            slot.1 = result.unwrap_or(State::Unknown);
        }
    }
    Ok(status)
}

/// Tells the grading's progress, if it is watched.
fn report(opts: &Options, f: impl FnOnce(&super::building::Building)) {
    if let Some(p) = &opts.progress {
        f(p);
    }
}

/// `work(0)`, …, `work(count − 1)` on at most `jobs` threads at once, each
/// taking the next index when it is free; each result in its place (`None`
/// if its thread died).
pub(crate) fn in_parallel<T: Send>(
    count: usize,
    jobs: usize,
    work: impl Fn(usize) -> T + Sync,
) -> Vec<Option<T>> {
    let slots: Vec<std::sync::Mutex<Option<T>>> =
        (0..count).map(|_| std::sync::Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, count.max(1)) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= count {
                        break;
                    }
                    let result = work(i);
                    if let Ok(mut slot) = slots[i].lock() {
                        *slot = Some(result);
                    }
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|s| s.into_inner().ok().flatten())
        .collect()
}

/// What a build gave.
pub(crate) enum Built {
    /// Each test binary's name and program.
    Programs(Vec<(String, PathBuf)>),
    /// The first error.
    Failed(Located),
    /// The time ran out, or the grading was stopped.
    OutOfTime,
}

fn cargo() -> Command {
    Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
}

/// Starts `cmd` in a process group of its own (so that a time limit ends it
/// and every process it started).
pub(crate) fn spawn_group(cmd: &mut Command) -> std::io::Result<Child> {
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        cmd.process_group(0);
    }
    cmd.spawn()
}

/// Ends `child` and its process group.
fn kill_group(child: &mut Child) {
    #[cfg(unix)]
    {
        let pid = rustix::process::Pid::from_child(child);
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// Waits for `child` until `limit`, or until the grading is stopped; `None`
/// when it had to be killed.
pub(crate) fn wait_within(child: &mut Child, limit: Duration, ctx: &Ctx) -> Option<ExitStatus> {
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Some(status),
            Ok(None) if start.elapsed() < limit && !ctx.stopped() => {
                std::thread::sleep(Duration::from_millis(10))
            }
            _ => {
                kill_group(child);
                return None;
            }
        }
    }
}

/// Reads at most `cap` bytes of `from` in a thread, dropping the rest.
pub(crate) fn drain(
    from: Option<impl Read + Send + 'static>,
    cap: usize,
) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut kept = Vec::new();
        let Some(mut from) = from else { return kept };
        let mut buf = [0u8; 8192];
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            let room = cap.saturating_sub(kept.len());
            kept.extend_from_slice(&buf[..n.min(room)]);
        }
        kept
    })
}

/// `cargo test --no-run` of the graders' programs, read through cargo's JSON.
fn build(dir: &Path, ctx: &Ctx, binaries: &[&str]) -> Result<Built, String> {
    let mut args: Vec<&str> = vec!["test", "--no-run"];
    if ctx.opts.solutions {
        args.extend(["--features", "solutions"]);
    }
    for b in binaries {
        args.extend(["--test", b]);
    }
    cargo_json(dir, &args, ctx, |msg| {
        msg["profile"]["test"].as_bool() == Some(true)
            && msg["target"]["kind"]
                .as_array()
                .is_some_and(|k| k.iter().any(|x| x == "test"))
    })
}

/// `cargo ARGS` on the crate in `dir`, read through cargo's JSON messages:
/// the programs built whose artifact message `wanted` accepts (by target
/// name), or the first compile error with its place.
pub(crate) fn cargo_json(
    dir: &Path,
    args: &[&str],
    ctx: &Ctx,
    wanted: fn(&serde_json::Value) -> bool,
) -> Result<Built, String> {
    let opts = ctx.opts;
    let mut cmd = cargo();
    cmd.current_dir(dir)
        .args(args)
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--message-format", "json", "--color", "never"]);
    if let Some(t) = &opts.target_dir {
        cmd.env("CARGO_TARGET_DIR", t);
    }
    if let Some(p) = &opts.progress {
        p.phase(super::building::Phase::Building);
        cmd.envs(super::building::CARGO_PROGRESS_ENV);
    }
    let progress = opts.progress.clone();
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = spawn_group(&mut cmd).map_err(|e| format!("cannot run cargo: {e}"))?;
    let stdout = child.stdout.take();
    let reader = std::thread::spawn(move || {
        let mut programs = Vec::new();
        let mut first_error = None;
        let Some(out) = stdout else {
            return (programs, first_error);
        };
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            let Ok(msg) = serde_json::from_str::<serde_json::Value>(&line) else {
                continue;
            };
            match msg["reason"].as_str() {
                Some("compiler-artifact") => {
                    if let Some(p) = &progress {
                        p.artifact();
                    }
                    if let (true, Some(name), Some(exe)) = (
                        wanted(&msg),
                        msg["target"]["name"].as_str(),
                        msg["executable"].as_str(),
                    ) {
                        programs.push((name.to_string(), PathBuf::from(exe)));
                    }
                }
                Some("compiler-message") if first_error.is_none() => {
                    first_error = compile_error(&msg["message"]);
                }
                _ => {}
            }
        }
        (programs, first_error)
    });
    let stderr = match &opts.progress {
        Some(p) => super::building::drain_cargo(child.stderr.take(), 64 * 1024, Arc::clone(p)),
        None => drain(child.stderr.take(), 64 * 1024),
    };
    let status = wait_within(&mut child, ctx.left(), ctx);
    let (programs, first_error) = reader.join().unwrap_or_default();
    let stderr = String::from_utf8_lossy(&stderr.join().unwrap_or_default()).into_owned();
    match status {
        None => Ok(Built::OutOfTime),
        Some(s) if s.success() => Ok(Built::Programs(programs)),
        Some(_) => Ok(Built::Failed(first_error.unwrap_or_else(|| {
            // Cargo itself refused (a broken manifest, a missing file): its last word.
            let line = stderr
                .lines()
                .rev()
                .find(|l| l.trim_start().starts_with("error"))
                .or_else(|| stderr.lines().rev().find(|l| !l.trim().is_empty()))
                .unwrap_or("cargo failed")
                .trim()
                .to_string();
            Located {
                file: "Cargo.toml".into(),
                line: 1,
                message: line,
            }
        }))),
    }
}

/// The first error of a rustc diagnostic, with its primary place.
fn compile_error(message: &serde_json::Value) -> Option<Located> {
    if message["level"].as_str() != Some("error") {
        return None;
    }
    let text = message["message"].as_str()?.to_string();
    let spans = message["spans"].as_array();
    let primary = spans.and_then(|s| {
        s.iter()
            .find(|sp| sp["is_primary"].as_bool() == Some(true))
            .or(s.first())
    });
    let (file, line) = match primary {
        Some(sp) => (
            sp["file_name"].as_str().unwrap_or("?").to_string(),
            sp["line_start"].as_u64().unwrap_or(1) as usize,
        ),
        None => ("?".to_string(), 1),
    };
    Some(Located {
        file,
        line,
        message: text,
    })
}

/// One grading's runs of single graders.
struct Run<'a> {
    dir: &'a Path,
    ctx: &'a Ctx<'a>,
    seed: u64,
    token: &'a str,
    verdicts: &'a Path,
}

impl Run<'_> {
    /// Runs the grader of `a` alone, in program `exe`, and reads its verdict.
    fn test(&self, exe: &Path, a: &Assignment) -> State {
        if self.ctx.stopped() {
            return State::Unknown;
        }
        let limit = self.ctx.opts.test_limit.min(self.ctx.left());
        if limit.is_zero() {
            return State::TimedOut(
                "the copy's time limit ran out before this grader could start".into(),
            );
        }
        let out = self.verdicts.join(format!("{}.json", a.test));
        let mut cmd = Command::new(exe);
        cmd.current_dir(self.dir)
            .args([a.test, "--exact", "--test-threads", "1", "--color", "never"])
            .env(verdict::SEED_VAR, self.seed.to_string())
            .env(verdict::OUT_VAR, &out)
            .env(verdict::NONCE_VAR, self.token)
            .env(
                verdict::COURSE_VAR,
                self.ctx.opts.course_arg.as_deref().unwrap_or(""),
            )
            .env("RUST_BACKTRACE", "0")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        let mut child = match spawn_group(&mut cmd) {
            Ok(c) => c,
            Err(e) => return State::Failing(format!("cannot run {}: {e}", exe.display())),
        };
        limit_memory(&child);
        let stderr = drain(child.stderr.take(), 16 * 1024);
        let status = wait_within(&mut child, limit, self.ctx);
        let stderr = String::from_utf8_lossy(&stderr.join().unwrap_or_default()).into_owned();
        let Some(status) = status else {
            if self.ctx.stopped() {
                return State::Unknown;
            }
            return State::TimedOut(format!(
                "the grader gave no verdict within {} s and was stopped: a loop that never ends, or an answer far too slow?",
                limit.as_secs()
            ));
        };
        let verdict = read_verdict(&out, self.token, a.function);
        match verdict {
            Some(v) if v.passed && status.success() => State::Passing,
            Some(v) if v.passed => State::Failing(format!(
                "the grader accepted the answers, but the test process then failed ({}): {}",
                how(status),
                last_words(&stderr)
            )),
            Some(v) if v.stub => State::NotStarted,
            Some(v) => State::Failing(v.report),
            None if status.success() => State::Failing(
                "the test ended without a verdict from the course's grader: is it still the course's own test (graded!)?".into(),
            ),
            None => State::Failing(format!(
                "the test process ended without a verdict ({}): {}. A recursion without end (a stack overflow), more than the {} GiB of memory a grader may take, or an abort?",
                how(status),
                last_words(&stderr),
                MEMORY_LIMIT >> 30
            )),
        }
    }
}

/// The most memory (address space) one grader's process may take. No
/// assignment needs more than a few megabytes; a copy that allocates without
/// bound must fail alone, not take the machine, and the class's grading with
/// it (there is no swap to slow it down first).
pub(crate) const MEMORY_LIMIT: u64 = 2 << 30;

/// Puts [`MEMORY_LIMIT`] on a grader's process just started (Linux; an
/// allocation beyond it fails, and the process aborts). Set from outside,
/// since the crate has no `unsafe` for a `pre_exec`: the test program is
/// still starting when it lands, long before any grader runs.
fn limit_memory(child: &Child) {
    #[cfg(target_os = "linux")]
    {
        use rustix::process::{Pid, Resource, Rlimit, prlimit};
        let limit = Rlimit {
            current: Some(MEMORY_LIMIT),
            maximum: Some(MEMORY_LIMIT),
        };
        let _ = prlimit(Some(Pid::from_child(child)), Resource::As, limit);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = child;
}

/// The verdict at `path`, if the grader of `function` wrote it in this run.
fn read_verdict(path: &Path, token: &str, function: &str) -> Option<Verdict> {
    let bytes = std::fs::read(path).ok().filter(|b| b.len() < 1 << 20)?;
    let v: Verdict = serde_json::from_slice(&bytes).ok()?;
    (v.nonce == token && v.assignment == function).then_some(v)
}

/// How a process ended, in words.
fn how(status: ExitStatus) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = status.signal() {
            return format!("killed by signal {sig}");
        }
    }
    match status.code() {
        Some(c) => format!("exit code {c}"),
        None => "no exit code".into(),
    }
}

/// The last meaningful line a process wrote to its error stream (a `NaN` in
/// it spelt out, so that the CLI prints the report).
fn last_words(stderr: &str) -> String {
    let line: String = stderr
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with("note:"))
        .unwrap_or("it wrote nothing")
        .chars()
        .take(300)
        .collect();
    spintop::numbers::non_finite_in_words(&line)
}
