//! The build of a student's runner: cargo in the build sandbox, read
//! through its JSON messages (the program, or every compiler error with
//! its file and line), its build folder bounded in size.

use super::CourseError;
use super::building::{self, Building};
use super::process::{self, Ctx, Waited};
use super::sandbox::{self, Kind, Limits, Spec};
use super::status::Located;
use super::toolchain;
use super::workspace::{RUNNER_BIN, RUNNER_PACKAGE, Workspace};
use std::ffi::OsString;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Arc;

/// The most a build folder may hold: the stubs' build takes about 300 MB;
/// a 2 GiB `static` would write gigabytes.
pub const MAX_TARGET: u64 = 2 << 30;

/// What a build gave.
#[derive(Debug)]
pub(crate) enum Built {
    /// Each program built (its target's name and file).
    Programs(Vec<(String, PathBuf)>),
    /// The compiler's errors, in its order (the first of each place).
    Failed(Vec<Located>),
    /// The time ran out, or the grading was stopped.
    OutOfTime,
    /// It was stopped by a bound (its build folder's size).
    Bounded(String),
}

/// The cargo to run: the one running us (`CARGO`), else the one on `PATH`.
pub(crate) fn cargo_program() -> PathBuf {
    std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from)
}

/// The environment a build keeps (a build sees no other variable: no
/// instructor's token, no `RUSTFLAGS` that the warm build did not have).
fn build_env(ws: &Workspace) -> Vec<(String, OsString)> {
    let mut keep: Vec<(String, OsString)> = [
        "PATH",
        "HOME",
        "CARGO_HOME",
        "RUSTUP_HOME",
        "RUSTUP_TOOLCHAIN",
        "RUSTC",
    ]
    .iter()
    .filter_map(|k| std::env::var_os(k).map(|v| (k.to_string(), v)))
    .collect();
    keep.push(("CARGO_TARGET_DIR".into(), ws.target().into()));
    keep.push(("TMPDIR".into(), ws.tmp().into()));
    keep.push(("CARGO_TERM_COLOR".into(), "never".into()));
    keep
}

/// Builds the runner of the workspace `ws` (with the `solutions` feature
/// when asked), in the build sandbox through `launcher` when there is one,
/// within `ctx`'s time and `cpu_seconds` of CPU per process; cargo's
/// count of the units it compiles goes to `progress` when it is watched.
pub(crate) fn build_runner(
    ws: &Workspace,
    launcher: Option<&Path>,
    solutions: bool,
    cpu_seconds: u64,
    ctx: &Ctx,
    progress: Option<&Arc<Building>>,
) -> Result<Built, CourseError> {
    let mut args: Vec<OsString> = [
        "rustc",
        "--offline",
        "-p",
        RUNNER_PACKAGE,
        "--bin",
        RUNNER_BIN,
    ]
    .map(OsString::from)
    .to_vec();
    args.push("--manifest-path".into());
    args.push(ws.root().join("Cargo.toml").into());
    args.extend(["--message-format", "json", "--color", "never"].map(OsString::from));
    if solutions {
        args.extend(["--features", "spintop-lessons/solutions"].map(OsString::from));
    }
    // Linux: a runner linked statically, so that its empty root needs no
    // library (the flag is the final crate's alone: the warm build's
    // dependencies serve as they are).
    #[cfg(target_os = "linux")]
    args.extend(["--", "-C", "target-feature=+crt-static"].map(OsString::from));
    let spec = Spec {
        kind: Kind::Build {
            writable: ws.root().to_path_buf(),
        },
        limits: Limits::build(cpu_seconds),
    };
    let mut env = build_env(ws);
    if let Some(p) = progress {
        p.phase(building::Phase::Building);
        // cargo's progress line, written to the pipe (it reads no terminal).
        env.extend(
            building::CARGO_PROGRESS_ENV
                .iter()
                .map(|(k, v)| (k.to_string(), OsString::from(v))),
        );
    }
    let cargo = toolchain::find_cargo()?;
    let mut cmd = sandbox::command(launcher, &spec, &cargo, &args, &env);
    cmd.current_dir(ws.root());
    let target = ws.target();
    run_cargo(cmd, &spec.limits, ctx, progress.cloned(), move || {
        let size = tree_size(&target);
        (size > MAX_TARGET).then(|| {
            format!(
                "the build's files grew past {} GiB (a huge constant or static?) and it was stopped",
                MAX_TARGET >> 30
            )
        })
    })
}

/// The bytes a folder's files take on disk, every folder deep (links not
/// followed); a sparse file counts what it holds.
pub(crate) fn tree_size(dir: &Path) -> u64 {
    let mut total = 0;
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let Ok(meta) = entry.metadata() else { continue };
            if meta.is_dir() {
                stack.push(entry.path());
            } else {
                #[cfg(unix)]
                {
                    total += std::os::unix::fs::MetadataExt::blocks(&meta) * 512;
                }
                #[cfg(not(unix))]
                {
                    total += meta.len();
                }
            }
        }
    }
    total
}

/// Runs the cargo command `cmd` (which prints JSON), reading the programs
/// it builds and its errors (and its progress, to `progress`); `watch` may
/// stop it.
fn run_cargo(
    mut cmd: Command,
    limits: &Limits,
    ctx: &Ctx,
    progress: Option<Arc<Building>>,
    watch: impl FnMut() -> Option<String>,
) -> Result<Built, CourseError> {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = process::spawn_group(&mut cmd).map_err(CourseError::Cargo)?;
    sandbox::bound_from_outside(&child, limits);
    let stdout = child.stdout.take();
    let artifacts = progress.clone();
    let reader = std::thread::spawn(move || read_messages(stdout, artifacts.as_deref()));
    let stderr = match progress {
        Some(p) => building::drain_cargo(child.stderr.take(), 64 * 1024, p),
        None => process::drain(child.stderr.take(), 64 * 1024),
    };
    let waited = process::wait_watched(&mut child, ctx.left(), ctx, watch);
    let (programs, errors) = reader.join().unwrap_or_default();
    let stderr = String::from_utf8_lossy(&stderr.join().unwrap_or_default()).into_owned();
    if let Waited::Exited(s) = &waited
        && let Some(why) = setup_failure(*s, &stderr)
    {
        return Err(CourseError::CannotGrade(why));
    }
    Ok(match waited {
        Waited::Killed(None) => Built::OutOfTime,
        Waited::Killed(Some(why)) => Built::Bounded(why),
        Waited::Exited(s) if s.success() => Built::Programs(programs),
        // No error with a place in the code: cargo, the toolchain or a
        // bound stopped the build, not the code.
        Waited::Exited(s) if errors.iter().all(|e| e.file == NOWHERE) => {
            match cargo_refused(&stderr, s, &errors) {
                Refused::Bounded(why) => Built::Bounded(why),
                Refused::Cargo(line) => {
                    return Err(CourseError::CannotGrade(toolchain::refusal(&line)));
                }
            }
        }
        Waited::Exited(_) => Built::Failed(errors),
    })
}

/// The launcher's own words when cargo never started in the sandbox (no
/// cargo on PATH, a sandbox that could not be set up): a failure of the
/// grading, not a state of the student's code.
pub(crate) fn setup_failure(status: std::process::ExitStatus, stderr: &str) -> Option<String> {
    if status.code() != Some(sandbox::SETUP_FAILED) {
        return None;
    }
    let line = stderr.lines().find(|l| l.contains(sandbox::SETUP_MARK))?;
    let words = line.trim();
    Some(
        words
            .strip_prefix("spintop course: ")
            .unwrap_or(words)
            .to_string(),
    )
}

/// Why a build that failed with no error in the code failed.
#[derive(Debug, PartialEq, Eq)]
enum Refused {
    /// A bound the build runs within stopped the compiler (its memory, CPU
    /// time or file size: a huge constant or static), or a signal did: the
    /// code's doing.
    Bounded(String),
    /// Cargo (or rustup, or the linker) refused before any code was
    /// judged: its first line.
    Cargo(String),
}

/// The file of a compiler error that names no place (a linker's, a
/// missing target's).
const NOWHERE: &str = "?";

/// Why cargo failed with no compiler error that names a place (`errors`
/// are those that name none): a bound that stopped the compiler, or
/// cargo's refusal, in its own first error line.
fn cargo_refused(stderr: &str, status: std::process::ExitStatus, errors: &[Located]) -> Refused {
    let killed = stderr.lines().find_map(|l| {
        let l = l.trim();
        let signal = l
            .split_once("signal: ")
            .map(|(_, rest)| rest.trim_end_matches(')').to_string());
        if l.contains("memory allocation of") || l.contains("out of memory") {
            Some(None)
        } else {
            signal.map(Some)
        }
    });
    #[cfg(unix)]
    let killed = killed.or_else(|| {
        std::os::unix::process::ExitStatusExt::signal(&status).map(|s| Some(s.to_string()))
    });
    if let Some(signal) = killed {
        let sig = signal.unwrap_or_default();
        return Refused::Bounded(if sig.contains("XCPU") || sig.starts_with("24") {
            "the build used up the CPU time a build may take (a huge constant or static?)".into()
        } else if sig.contains("XFSZ") || sig.starts_with("25") {
            "the build wrote a file larger than a build may (a huge constant or static?)".into()
        } else if sig.is_empty()
            || sig.contains("KILL")
            || sig.contains("ABRT")
            || sig.starts_with('9')
            || sig.starts_with('6')
        {
            "the build ran out of the memory a build may take (a huge constant or static?)".into()
        } else {
            format!("the compiler was stopped by a signal ({sig}) while compiling the code")
        });
    }
    let line = errors
        .first()
        .map(|e| format!("error: {}", e.message))
        .or_else(|| {
            stderr
                .lines()
                .find(|l| l.trim_start().starts_with("error"))
                .or_else(|| stderr.lines().find(|l| !l.trim().is_empty()))
                .map(str::to_string)
        })
        .map(|l| l.trim().chars().take(300).collect::<String>());
    Refused::Cargo(line.unwrap_or_else(|| format!("cargo failed ({status}) and said nothing")))
}

/// Cargo's JSON messages: the programs built, and the first error of each
/// place, in order (each artifact counted in `progress`).
fn read_messages(
    stdout: Option<std::process::ChildStdout>,
    progress: Option<&Building>,
) -> (Vec<(String, PathBuf)>, Vec<Located>) {
    let mut programs = Vec::new();
    let mut errors: Vec<Located> = Vec::new();
    let Some(out) = stdout else {
        return (programs, errors);
    };
    for line in BufReader::new(out).lines().map_while(Result::ok) {
        let Ok(msg) = serde_json::from_str::<serde_json::Value>(&line) else {
            continue;
        };
        match msg["reason"].as_str() {
            Some("compiler-artifact") => {
                if let Some(p) = progress {
                    p.artifact();
                }
                if let (Some(name), Some(exe)) =
                    (msg["target"]["name"].as_str(), msg["executable"].as_str())
                {
                    programs.push((name.to_string(), PathBuf::from(exe)));
                }
            }
            Some("compiler-message") => {
                if let Some(e) = compile_error(&msg["message"])
                    && !errors.iter().any(|f| f.file == e.file)
                    && errors.len() < 64
                {
                    errors.push(e);
                }
            }
            _ => {}
        }
    }
    (programs, errors)
}

/// The first error of a rustc diagnostic, with its primary place (and, in
/// its message, the line's text when the place is the generated runner).
pub(crate) fn compile_error(message: &serde_json::Value) -> Option<Located> {
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
    let (file, line, source) = match primary {
        Some(sp) => (
            sp["file_name"].as_str().unwrap_or("?").to_string(),
            sp["line_start"].as_u64().unwrap_or(1) as usize,
            sp["text"][0]["text"]
                .as_str()
                .unwrap_or_default()
                .to_string(),
        ),
        None => (NOWHERE.to_string(), 1, String::new()),
    };
    let message = if file.ends_with("runner/main.rs") && !source.is_empty() {
        format!("{text} [{}]", source.trim())
    } else {
        text
    };
    Some(Located {
        file,
        line,
        message,
    })
}

/// `cargo ARGS` on the crate in `dir` (no sandbox: the instructor's own
/// folder of wrong answers), read through cargo's JSON messages: the
/// programs it built (those with an executable), or its errors.
pub(crate) fn cargo_json(
    dir: &Path,
    args: &[&str],
    target_dir: Option<&Path>,
    ctx: &Ctx,
) -> Result<Built, CourseError> {
    let mut cmd = Command::new(toolchain::find_cargo()?);
    cmd.current_dir(dir)
        .args(args)
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--message-format", "json", "--color", "never"]);
    if let Some(t) = target_dir {
        cmd.env("CARGO_TARGET_DIR", t);
    }
    run_cargo(cmd, &Limits::build(3600), ctx, None, || None)
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    /// `run_cargo` on a stand-in for cargo: a shell that says `stderr`
    /// (and `stdout`) and exits with `code`.
    fn stand_in(stdout: &str, stderr: &str, code: i32) -> Result<Built, CourseError> {
        let mut cmd = Command::new("/bin/sh");
        cmd.arg("-c")
            .arg("printf '%s' \"$1\"; printf '%s' \"$2\" >&2; exit $3")
            .arg("sh")
            .arg(stdout)
            .arg(stderr)
            .arg(code.to_string());
        let ctx = Ctx {
            stop: None,
            deadline: None,
        };
        run_cargo(cmd, &Limits::build(60), &ctx, None, || None)
    }

    #[test]
    fn a_toolchain_that_refuses_is_a_grading_failure_in_cargos_words() {
        // rustup's proxy with no default toolchain: exit 1, no JSON.
        let rustup = "error: rustup could not choose a version of cargo to run, because one wasn't specified explicitly, and no default is configured.\nhelp: run 'rustup default stable' to download the latest stable release of Rust and set it as your default toolchain.\n";
        match stand_in("", rustup, 1) {
            Err(CourseError::CannotGrade(why)) => {
                assert!(why.contains("rustup could not choose a version"), "{why}");
                assert!(why.contains("rustup default stable"), "{why}");
            }
            other => panic!("not a grading failure: {other:?}"),
        }
        // Offline without the crates in cargo's cache.
        let offline = "    Updating crates.io index\nerror: no matching package named `nalgebra` found\nlocation searched: crates.io index\nrequired by package `spintop v0.1.0`\nAs a reminder, you're using offline mode (--offline)\n";
        match stand_in("", offline, 101) {
            Err(CourseError::CannotGrade(why)) => {
                assert!(
                    why.contains("no matching package named `nalgebra`"),
                    "{why}"
                );
                assert!(why.contains("cargo fetch"), "{why}");
            }
            other => panic!("not a grading failure: {other:?}"),
        }
        // A linker's error names no place in the code: the machine's, too.
        let linker = r#"{"reason":"compiler-message","message":{"level":"error","message":"linker `cc` not found","spans":[]}}"#;
        match stand_in(
            &format!("{linker}\n"),
            "error: could not compile `runner`\n",
            101,
        ) {
            Err(CourseError::CannotGrade(why)) => assert!(why.contains("C linker"), "{why}"),
            other => panic!("not a grading failure: {other:?}"),
        }
    }

    #[test]
    fn a_compiler_stopped_by_its_bound_is_the_codes_doing() {
        for (signal, words) in [
            ("signal: 9, SIGKILL: kill", "memory"),
            ("signal: 24, SIGXCPU: CPU time limit exceeded", "CPU time"),
            ("signal: 6, SIGABRT: process abort signal", "memory"),
        ] {
            let stderr = format!(
                "error: could not compile `spintop-lessons` (lib)\n\nCaused by:\n  process didn't exit successfully: `rustc --crate-name spintop_lessons` ({signal})\n"
            );
            match stand_in("", &stderr, 101) {
                Ok(Built::Bounded(why)) => assert!(why.contains(words), "{signal}: {why}"),
                other => panic!("{signal}: {other:?}"),
            }
        }
        let alloc = "memory allocation of 2147483648 bytes failed\nerror: could not compile `spintop-lessons`\n";
        assert!(matches!(stand_in("", alloc, 101), Ok(Built::Bounded(w)) if w.contains("memory")));
    }

    #[test]
    fn an_error_with_a_place_is_the_codes() {
        let msg = r#"{"reason":"compiler-message","message":{"level":"error","message":"mismatched types","spans":[{"file_name":"course/src/ch2.rs","line_start":7,"is_primary":true,"text":[{"text":"  1"}]}]}}"#;
        match stand_in(&format!("{msg}\n"), "error: could not compile\n", 101) {
            Ok(Built::Failed(errors)) => {
                assert_eq!(errors.len(), 1);
                assert_eq!(
                    (errors[0].file.as_str(), errors[0].line),
                    ("course/src/ch2.rs", 7)
                );
            }
            other => panic!("{other:?}"),
        }
    }
}
