//! Compiling and running one snippet: a scratch Cargo project that depends on
//! the local spintop by path and shares the workspace's build folder, so a
//! warm run compiles only the snippet.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The limits of one run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The largest request accepted.
    pub request_bytes: usize,
    /// The longest compile (a cold first build of spintop included).
    pub compile: Duration,
    /// The longest run; then the process is killed.
    pub run: Duration,
    /// The most output kept; the rest is dropped, with a note.
    pub output_bytes: usize,
    /// How long the first answer waits before saying "compiling…".
    pub answer_within: Duration,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            request_bytes: 64 * 1024,
            compile: Duration::from_secs(900),
            run: Duration::from_secs(10),
            output_bytes: 64 * 1024,
            answer_within: Duration::from_millis(4500),
        }
    }
}

/// Where snippets are compiled.
#[derive(Debug, Clone)]
pub struct Runner {
    /// The scratch project (created on first use; nothing is written elsewhere).
    pub scratch: PathBuf,
    /// The spintop crate the snippets use.
    pub spintop: PathBuf,
    /// The build folder shared with the workspace.
    pub target_dir: PathBuf,
    /// The limits.
    pub limits: Limits,
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
    /// The compile took longer than allowed.
    CompileTimeout,
    /// The run took longer than allowed and was killed.
    RunTimeout,
    /// Cargo could not be started, or the scratch folder written.
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
                "[stopped: the run took longer than the time limit ({:.0} s) and was killed]",
                self.elapsed.as_secs_f64().max(1.0)
            )),
            OutcomeKind::CompileTimeout => {
                note("[stopped: the compile took longer than the time limit]".into())
            }
            OutcomeKind::Failed if self.output.trim().is_empty() => {
                note("[the program failed with no output]".into())
            }
            _ => {}
        }
        text
    }
}

/// Output kept up to a limit, the rest read and dropped (so a child that
/// prints forever never blocks on a full pipe).
#[derive(Default)]
struct Capped {
    text: Vec<u8>,
    truncated: bool,
}

fn pump(mut from: impl Read + Send + 'static, into: Arc<Mutex<Capped>>, limit: usize) {
    std::thread::spawn(move || {
        let mut buf = [0u8; 8192];
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            let mut c = into.lock().unwrap_or_else(|e| e.into_inner());
            let room = limit.saturating_sub(c.text.len());
            if n > room {
                c.truncated = true;
            }
            let take = n.min(room);
            c.text.extend_from_slice(&buf[..take]);
        }
    });
}

/// Waits for `child` up to `limit`, then kills it; its status if it ended in time.
fn wait_or_kill(child: &mut Child, limit: Duration) -> Option<std::process::ExitStatus> {
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Some(status),
            Ok(None) if start.elapsed() < limit => std::thread::sleep(Duration::from_millis(20)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return None;
            }
        }
    }
}

impl Runner {
    /// The snippet program's name: one per scratch folder, so that two
    /// servers sharing a build folder never run each other's program.
    fn binary_name(&self) -> String {
        format!(
            "spintop-snippet-{:08x}",
            crate::numbers::stable_key(&self.scratch.to_string_lossy())
        )
    }

    /// The scratch project's manifest.
    fn manifest(&self, edition: &str) -> String {
        format!(
            "[package]\nname = \"{}\"\nversion = \"0.0.0\"\nedition = \"{edition}\"\npublish = false\n\n# The book's snippets, one at a time; not part of any workspace.\n[workspace]\n\n[dependencies]\nspintop = {{ path = {:?} }}\n",
            self.binary_name(),
            self.spintop.display().to_string()
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

    /// Compiles and runs `code`, reporting cargo's progress lines to
    /// `progress`. Code without `fn main` is wrapped in one, as rustdoc and
    /// mdBook do (mdBook leaves editable snippets unwrapped).
    pub fn run(&self, code: &str, edition: &str, progress: &mut dyn FnMut(&str)) -> Outcome {
        let start = Instant::now();
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
        let internal = |msg: String, start: Instant| Outcome {
            kind: OutcomeKind::Internal,
            output: msg,
            truncated: false,
            elapsed: start.elapsed(),
        };
        if let Err(e) = self.prepare(code, edition) {
            return internal(format!("cannot write the scratch project: {e}"), start);
        }
        // 1. Compile, with cargo's progress passed on line by line.
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let mut build = match Command::new(&cargo)
            .current_dir(&self.scratch)
            .args(["build", "--color", "never", "--message-format", "short"])
            .env("CARGO_TARGET_DIR", &self.target_dir)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
        {
            Ok(child) => child,
            Err(e) => return internal(format!("cannot run cargo: {e}"), start),
        };
        let (tx, rx) = std::sync::mpsc::channel::<String>();
        if let Some(err) = build.stderr.take() {
            std::thread::spawn(move || {
                for line in BufReader::new(err).lines().map_while(Result::ok) {
                    if tx.send(line).is_err() {
                        break;
                    }
                }
            });
        }
        let mut errors = Vec::new();
        let status = loop {
            for line in rx.try_iter() {
                let t = line.trim();
                if t.starts_with("Compiling") || t.starts_with("Checking") {
                    progress(&format!("{t} ({:.0} s)", start.elapsed().as_secs_f64()));
                } else if !t.starts_with("Finished") && !t.starts_with("Blocking") && !t.is_empty()
                {
                    errors.push(line);
                }
            }
            match build.try_wait() {
                Ok(Some(status)) => break Some(status),
                Ok(None) if start.elapsed() < self.limits.compile => {
                    std::thread::sleep(Duration::from_millis(50))
                }
                _ => {
                    let _ = build.kill();
                    let _ = build.wait();
                    break None;
                }
            }
        };
        // The last lines, after the exit.
        std::thread::sleep(Duration::from_millis(20));
        for line in rx.try_iter() {
            let t = line.trim();
            if !(t.starts_with("Compiling") || t.starts_with("Finished") || t.is_empty()) {
                errors.push(line);
            }
        }
        match status {
            None => {
                return Outcome {
                    kind: OutcomeKind::CompileTimeout,
                    output: String::new(),
                    truncated: false,
                    elapsed: start.elapsed(),
                };
            }
            Some(s) if !s.success() => {
                let mut text = errors.join("\n");
                let truncated = text.len() > self.limits.output_bytes;
                if truncated {
                    let mut cut = self.limits.output_bytes;
                    while !text.is_char_boundary(cut) {
                        cut -= 1;
                    }
                    text.truncate(cut);
                }
                return Outcome {
                    kind: OutcomeKind::CompileError,
                    output: text,
                    truncated,
                    elapsed: start.elapsed(),
                };
            }
            Some(_) => {}
        }
        // 2. Run, with the time and output limits.
        progress("running");
        let binary = self.target_dir.join("debug").join(self.binary_name());
        let mut child = match Command::new(&binary)
            .current_dir(&self.scratch)
            .env("RUST_BACKTRACE", "0")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
        {
            Ok(c) => c,
            Err(e) => return internal(format!("cannot start {}: {e}", binary.display()), start),
        };
        let captured = Arc::new(Mutex::new(Capped::default()));
        if let Some(out) = child.stdout.take() {
            pump(out, Arc::clone(&captured), self.limits.output_bytes);
        }
        if let Some(err) = child.stderr.take() {
            pump(err, Arc::clone(&captured), self.limits.output_bytes);
        }
        let run_start = Instant::now();
        let status = wait_or_kill(&mut child, self.limits.run);
        // Let the pumps drain what is left in the pipes.
        std::thread::sleep(Duration::from_millis(50));
        let c = captured.lock().unwrap_or_else(|e| e.into_inner());
        let output = String::from_utf8_lossy(&c.text).into_owned();
        let kind = match status {
            None => OutcomeKind::RunTimeout,
            Some(s) if s.success() => OutcomeKind::Success,
            Some(_) => OutcomeKind::Failed,
        };
        Outcome {
            kind,
            output,
            truncated: c.truncated,
            elapsed: if kind == OutcomeKind::RunTimeout {
                run_start.elapsed()
            } else {
                start.elapsed()
            },
        }
    }
}

/// The scratch folder and build folder `spintop book` uses in `repo`.
pub fn default_runner(repo: &Path) -> Runner {
    let target_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo.join("target"));
    Runner {
        scratch: repo.join("target").join("spintop-book").join("scratch"),
        spintop: repo.to_path_buf(),
        target_dir,
        limits: Limits::default(),
    }
}
