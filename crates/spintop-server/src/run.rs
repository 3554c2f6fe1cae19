//! Compiling and running one snippet: a scratch Cargo project that depends on
//! the local spintop by path and shares the workspace's build folder, so a
//! warm run compiles only the snippet. Both the build and the run are
//! process trees under a supervisor ([`super::tree`]): bounded, one at a
//! time, and killed whole.

use super::bounds::Bounds;
use super::drain::{Capped, Drain, Lines, finish};
use super::tree::{Ended, Slot};
use super::unit::Containment;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The server's limits: of a request, and of one build and run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The largest request accepted.
    pub request_bytes: usize,
    /// The time a whole request (head and body) may take to arrive, from
    /// its first byte, however slowly the bytes come.
    pub request_time: Duration,
    /// The longest compile while the scratch project is cold (spintop and
    /// its dependencies are compiled once).
    pub compile: Duration,
    /// The longest compile once a build has succeeded (only the snippet is
    /// compiled then): a compile-time loop holds ▶ no longer than this.
    pub compile_warm: Duration,
    /// The longest run; then the program and everything it started are killed.
    pub run: Duration,
    /// The CPU time of each process of a run (then SIGXCPU).
    pub cpu: Duration,
    /// The address space (virtual memory) of each process of a run, in bytes.
    pub memory: u64,
    /// The largest file a run may write, in bytes (then SIGXFSZ).
    pub file_size: u64,
    /// How many processes and threads a run may start beyond those the
    /// reader has when it starts (RLIMIT_NPROC counts every task of a user,
    /// so it is set from that count): a fork bomb stops there, with the
    /// machine's other programs still able to start theirs. Within the
    /// reader's hard limit, and 96 below the soft one, which the server's
    /// threads need. The kernel does not hold root to it.
    pub processes: u64,
    /// The most output kept; the rest is dropped, with a note.
    pub output_bytes: usize,
    /// How long the first answer waits before saying "compiling…".
    pub answer_within: Duration,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            request_bytes: 64 * 1024,
            request_time: Duration::from_secs(10),
            compile: Duration::from_secs(900),
            compile_warm: Duration::from_secs(120),
            run: Duration::from_secs(10),
            cpu: Duration::from_secs(11),
            memory: 4 << 30,
            file_size: 64 << 20,
            processes: 512,
            output_bytes: 64 * 1024,
            answer_within: Duration::from_millis(4500),
        }
    }
}

/// The crates a snippet may use (the repository's `crates/NAME`): the core,
/// and for the course's chapters the graders and the course runner. A
/// snippet that names any other crate builds under `cargo test` (a doctest
/// sees every dependency) and fails under ▶.
pub const SNIPPET_CRATES: [&str; 3] = ["spintop", "spintop-grading", "spintop-course"];

/// Where snippets are compiled, and with what.
#[derive(Debug, Clone)]
pub struct Runner {
    /// The scratch project (created on first use).
    pub scratch: PathBuf,
    /// The repository whose crates the snippets use (`crates/spintop`, the
    /// core; `crates/spintop-grading` and `crates/spintop-course` for the
    /// course's chapters).
    pub spintop: PathBuf,
    /// The build folder shared with the workspace.
    pub target_dir: PathBuf,
    /// The spintop binary, which supervises each build and run
    /// (`spintop book --supervise`, see `crates/spintop-server/src/supervise.rs`).
    pub launcher: PathBuf,
    /// The limits.
    pub limits: Limits,
    /// The strongest way to end a tree as a unit that the server may use;
    /// it uses the strongest of those up to this one that the machine
    /// allows ([`super::Server::containment`]).
    pub containment: Containment,
}

/// What the builds and runs of one server share: the one process tree at a
/// time, and whether the scratch project has been built (then a compile
/// has [`Limits::compile_warm`]).
#[derive(Debug, Default)]
pub(crate) struct Shared {
    pub(crate) slot: Slot,
    pub(crate) warm: AtomicBool,
}

/// What a build or run reports while it goes on.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Stage<'a> {
    /// Its turn came: cargo starts.
    Compiling,
    /// One of cargo's progress lines ("Compiling nalgebra v0.35.0").
    Line(&'a str),
    /// Compiled: the program runs.
    Running,
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Outcome {
    /// What happened.
    pub kind: OutcomeKind,
    /// Standard output and error, in order of arrival, within the limit.
    pub output: String,
    /// Whether output was dropped at the limit.
    pub truncated: bool,
    /// The wall time of the run (compile and execution).
    pub elapsed: Duration,
    /// The time limit it met (a timeout), else `None`. Not `elapsed`: the
    /// tree may take a while to kill (its supervisor stopped by the
    /// snippet: the 2 s grace), and the note states the limit.
    pub limit: Option<Duration>,
}

/// The kinds of [`Outcome`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutcomeKind {
    /// The program ran and exited 0.
    Success,
    /// It ran and failed (a panic, a failed assertion: exit code non-zero).
    Failed,
    /// It did not compile.
    CompileError,
    /// The compile took longer than allowed (cargo and every compiler it
    /// started were killed).
    CompileTimeout,
    /// The run took longer than allowed and was killed, with everything it
    /// started.
    RunTimeout,
    /// Cargo could not be started, the scratch folder written, or the
    /// server is stopping.
    Internal,
}

impl Outcome {
    /// Whether the snippet compiled and ran to a successful end.
    pub fn success(&self) -> bool {
        self.kind == OutcomeKind::Success
    }

    /// The `error` field of the answer: none for a success.
    pub fn error_kind(&self) -> Option<&'static str> {
        match self.kind {
            OutcomeKind::Success => None,
            OutcomeKind::Failed => Some("failed"),
            OutcomeKind::CompileError => Some("compile error"),
            OutcomeKind::CompileTimeout => Some("compile time limit"),
            OutcomeKind::RunTimeout => Some("time limit"),
            OutcomeKind::Internal => Some("internal"),
        }
    }

    /// What the page shows under the snippet.
    pub fn shown(&self) -> String {
        let mut text = self.output.clone();
        let mut note = |s: String| {
            if !text.is_empty() && !text.ends_with('\n') {
                text.push('\n');
            }
            text.push_str(&s);
        };
        if self.truncated {
            note("[output truncated: only the first part is shown]".into());
        }
        match self.kind {
            OutcomeKind::RunTimeout => note(format!(
                "[stopped: the run took longer than the time limit ({} s) and was killed, with every process it started]",
                seconds(self.limit.unwrap_or(self.elapsed))
            )),
            OutcomeKind::CompileTimeout => note(format!(
                "[stopped: the compile took longer than the time limit ({} s) and was killed]",
                seconds(self.limit.unwrap_or(self.elapsed))
            )),
            OutcomeKind::Failed if self.output.trim().is_empty() => {
                note("[the program failed with no output]".into())
            }
            _ => {}
        }
        text
    }
}

/// The trivial program the background build compiles: it makes cargo
/// build spintop and its dependencies, so that a reader's first ▶ compiles
/// only the snippet.
const WARM_UP: &str = "fn main() {}\n";

impl Runner {
    /// The snippet program's name: one per scratch folder, so that two
    /// servers sharing a build folder never run each other's program.
    fn binary_name(&self) -> String {
        format!(
            "spintop-snippet-{:08x}",
            spintop::numbers::stable_key(&self.scratch.to_string_lossy())
        )
    }

    /// The scratch project's manifest.
    fn manifest(&self, edition: &str) -> String {
        format!(
            "[package]\nname = \"{}\"\nversion = \"0.0.0\"\nedition = \"{edition}\"\npublish = false\n\n# The book's snippets, one at a time; not part of any workspace.\n[workspace]\n\n[dependencies]\nspintop = {{ path = {:?} }}\nspintop-grading = {{ path = {:?} }}\nspintop-course = {{ path = {:?} }}\n",
            self.binary_name(),
            self.spintop.join("crates/spintop").display().to_string(),
            self.spintop
                .join("crates/spintop-grading")
                .display()
                .to_string(),
            self.spintop
                .join("crates/spintop-course")
                .display()
                .to_string(),
        )
    }

    fn prepare(&self, code: &str, edition: &str) -> std::io::Result<()> {
        std::fs::create_dir_all(self.scratch.join("src"))?;
        let manifest = self.manifest(edition);
        let path = self.scratch.join("Cargo.toml");
        if std::fs::read_to_string(&path).ok().as_deref() != Some(manifest.as_str()) {
            std::fs::write(&path, manifest)?;
        }
        let lock = self.scratch.join("Cargo.lock");
        if !lock.exists()
            && let Ok(text) = std::fs::read_to_string(self.spintop.join("Cargo.lock"))
        {
            std::fs::write(&lock, text)?;
        }
        std::fs::write(self.scratch.join("src/main.rs"), code)
    }

    /// The supervisor's command, in folder `dir`.
    fn supervised(&self, dir: &Path) -> Command {
        let mut command = Command::new(&self.launcher);
        command
            .current_dir(dir)
            .env("CARGO_TARGET_DIR", &self.target_dir);
        command
    }

    /// The background build: the scratch project with a trivial program,
    /// under the cold compile limit. Its outcome is a success once spintop
    /// is built for the snippets.
    pub(crate) fn warm_up(&self, shared: &Shared, progress: &mut dyn FnMut(Stage<'_>)) -> Outcome {
        let _turn = shared.slot.turn();
        let start = Instant::now();
        progress(Stage::Compiling);
        if let Err(e) = self.prepare(WARM_UP, "2024") {
            return internal(format!("cannot write the scratch project: {e}"), start);
        }
        match self.build(shared, self.limits.compile, start, progress) {
            Ok(()) => Outcome {
                kind: OutcomeKind::Success,
                output: String::new(),
                truncated: false,
                elapsed: start.elapsed(),
                limit: None,
            },
            Err(outcome) => outcome,
        }
    }

    /// Compiles and runs `code` when no other tree runs, reporting its
    /// stages to `progress`. Code without `fn main` is wrapped in one, as
    /// rustdoc and mdBook do (mdBook leaves editable snippets unwrapped).
    pub(crate) fn run(
        &self,
        code: &str,
        edition: &str,
        shared: &Shared,
        progress: &mut dyn FnMut(Stage<'_>),
    ) -> Outcome {
        let wrapped;
        let code = if code.contains("fn main") {
            code
        } else {
            wrapped = format!("#![allow(unused)]\nfn main() {{\n{code}\n}}\n");
            wrapped.as_str()
        };
        let edition = match edition {
            "2015" | "2018" | "2021" | "2024" => edition,
            _ => "2024",
        };
        let _turn = shared.slot.turn();
        let start = Instant::now();
        progress(Stage::Compiling);
        if let Err(e) = self.prepare(code, edition) {
            return internal(format!("cannot write the scratch project: {e}"), start);
        }
        let limit = if shared.warm.load(Ordering::SeqCst) {
            self.limits.compile_warm
        } else {
            self.limits.compile
        };
        if let Err(outcome) = self.build(shared, limit, start, progress) {
            return outcome;
        }
        progress(Stage::Running);
        self.execute(shared, start)
    }

    /// 1. Compile, with cargo's progress passed on line by line.
    fn build(
        &self,
        shared: &Shared,
        limit: Duration,
        start: Instant,
        progress: &mut dyn FnMut(Stage<'_>),
    ) -> Result<(), Outcome> {
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        // NOTE: cargo reads `.cargo/config.toml` in the folder it runs in
        // and in every folder above it, whoever wrote them, whatever
        // `--config` or CARGO_HOME say; not above the manifest. So it runs
        // in `/` (whose config only root can write), and finds the scratch
        // project by its path: a `rustc-wrapper` planted above a scratch
        // folder under /tmp is never read (`tests/book/folders.rs`).
        let mut command = self.supervised(Path::new("/"));
        command.stdout(Stdio::null()).stderr(Stdio::piped());
        let manifest = self.scratch.join("Cargo.toml");
        let args: [&OsStr; 7] = [
            "build".as_ref(),
            "--manifest-path".as_ref(),
            manifest.as_os_str(),
            "--color".as_ref(),
            "never".as_ref(),
            "--message-format".as_ref(),
            "short".as_ref(),
        ];
        // Core dumps off; cargo and rustc need their memory and CPU.
        let bounds = (Bounds::default(), limit, self.containment);
        let mut build = match shared.slot.start(command, bounds, &cargo, &args) {
            Ok(s) => s,
            Err(e) => {
                return Err(internal(
                    format!("cannot run cargo: {}", why_not(&e)),
                    start,
                ));
            }
        };
        let mut stderr = Drain::new(build.stderr());
        let (mut lines, mut errors) = (Lines::default(), Vec::new());
        let mut take = |bytes: &[u8], errors: &mut Vec<String>| {
            for line in lines.feed(bytes) {
                let t = line.trim();
                if t.starts_with("Compiling") || t.starts_with("Checking") {
                    progress(Stage::Line(t));
                } else if !t.starts_with("Finished") && !t.starts_with("Blocking") && !t.is_empty()
                {
                    errors.push(line);
                }
            }
        };
        let ended = build.wait(&shared.slot, limit, || {
            let mut bytes = Vec::new();
            stderr.pull(&mut bytes);
            take(&bytes, &mut errors);
        });
        // The last lines, after the exit (the pipe is closed by now, or soon).
        let mut bytes = Vec::new();
        finish(std::slice::from_mut(&mut stderr), &mut bytes);
        take(&bytes, &mut errors);
        errors.extend(lines.rest());
        let status = match ended {
            Ended::Exited(status) => status,
            Ended::TimedOut => {
                return Err(Outcome {
                    kind: OutcomeKind::CompileTimeout,
                    output: String::new(),
                    truncated: false,
                    elapsed: start.elapsed(),
                    limit: Some(limit),
                });
            }
            Ended::Stopped => return Err(internal("the server is stopping".into(), start)),
        };
        if !status.success() {
            let mut text = errors.join("\n");
            let truncated = text.len() > self.limits.output_bytes;
            if truncated {
                let mut cut = self.limits.output_bytes;
                while !text.is_char_boundary(cut) {
                    cut -= 1;
                }
                text.truncate(cut);
            }
            return Err(Outcome {
                kind: OutcomeKind::CompileError,
                output: text,
                truncated,
                elapsed: start.elapsed(),
                limit: None,
            });
        }
        shared.warm.store(true, Ordering::SeqCst);
        Ok(())
    }

    /// 2. Run, under the time, output and resource limits.
    fn execute(&self, shared: &Shared, start: Instant) -> Outcome {
        let binary = self.target_dir.join("debug").join(self.binary_name());
        let mut command = self.supervised(&self.scratch);
        command
            .env("RUST_BACKTRACE", "0")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        let whole_seconds = |d: Duration| d.as_secs() + u64::from(d.subsec_nanos() > 0);
        let bounds = Bounds {
            address_space: Some(self.limits.memory),
            cpu_seconds: Some(whole_seconds(self.limits.cpu).max(1)),
            file_size: Some(self.limits.file_size),
            processes: Some(self.limits.processes),
        };
        let spec = (bounds, self.limits.run, self.containment);
        let mut run = match shared.slot.start(command, spec, binary.as_os_str(), &[]) {
            Ok(r) => r,
            Err(e) => {
                return internal(
                    format!("cannot start {}: {}", binary.display(), why_not(&e)),
                    start,
                );
            }
        };
        let mut captured = Capped::new(self.limits.output_bytes);
        let mut pipes = [Drain::new(run.stdout()), Drain::new(run.stderr())];
        let run_start = Instant::now();
        let ended = run.wait(&shared.slot, self.limits.run, || {
            for pipe in &mut pipes {
                pipe.pull(&mut captured);
            }
        });
        // The tree is gone, so the pipes are closed: read what is left.
        finish(&mut pipes, &mut captured);
        let output = String::from_utf8_lossy(&captured.text).into_owned();
        let kind = match ended {
            Ended::TimedOut => OutcomeKind::RunTimeout,
            Ended::Exited(s) if s.success() => OutcomeKind::Success,
            Ended::Exited(_) => OutcomeKind::Failed,
            Ended::Stopped => return internal("the server is stopping".into(), start),
        };
        Outcome {
            kind,
            output,
            truncated: captured.truncated,
            elapsed: if kind == OutcomeKind::RunTimeout {
                run_start.elapsed()
            } else {
                start.elapsed()
            },
            limit: (kind == OutcomeKind::RunTimeout).then_some(self.limits.run),
        }
    }
}

/// Why a process could not be started, in the reader's terms where the
/// system's words are obscure.
fn why_not(e: &std::io::Error) -> String {
    if e.raw_os_error() == Some(rustix::io::Errno::AGAIN.raw_os_error()) {
        format!(
            "{e}: the system refused another process (your process limit, or the machine's, is reached); press ▶ again once other programs have ended"
        )
    } else {
        e.to_string()
    }
}

/// A duration in seconds as a note gives it: whole seconds as such
/// (`10`), else to a tenth (`0.5`).
fn seconds(d: Duration) -> String {
    if d.subsec_nanos() == 0 {
        d.as_secs().to_string()
    } else {
        format!("{:.1}", d.as_secs_f64())
    }
}

fn internal(msg: String, start: Instant) -> Outcome {
    Outcome {
        kind: OutcomeKind::Internal,
        output: msg,
        truncated: false,
        elapsed: start.elapsed(),
        limit: None,
    }
}

/// The scratch folder, build folder and launcher `spintop book` uses in
/// `repo`: the launcher is the running binary itself.
pub fn default_runner(repo: &Path) -> Runner {
    let target_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo.join("target"));
    Runner {
        scratch: repo.join("target").join("spintop-book").join("scratch"),
        spintop: repo.to_path_buf(),
        target_dir,
        launcher: std::env::current_exe().unwrap_or_else(|_| PathBuf::from("spintop")),
        limits: Limits::default(),
        containment: Containment::Namespace,
    }
}
