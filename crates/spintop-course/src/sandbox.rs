//! The sandbox of a student's build and runner.
//!
//! Every build of a student's copy and every runner that answers for its
//! functions starts through a **launcher**: the `spintop` binary
//! re-executed with a hidden flag (`spintop course --sandbox SPEC PROGRAM
//! ARGS…`), which restricts itself and then becomes the program (`exec`).
//! The restrictions are set by the process itself, with safe calls, so the
//! crates need no `unsafe` (`pre_exec` would be), and they hold however the
//! parent ends (a limit set on a process stays with it).
//!
//! What each layer gives, where the kernel allows it (Linux; see
//! `lessons/README.md` for each platform):
//!
//! | layer | build (cargo, rustc) | runner (the student's code) |
//! |---|---|---|
//! | rlimits | memory, CPU time, file size, no core | the same, and few open files |
//! | user + network namespaces | no network | no network |
//! | mount namespace | every file system read-only but its own folder | an empty root holding the runner alone |
//! | seccomp | no internet socket, no `ptrace` | no socket, `ptrace`, signal or new process |
//! | Landlock | writes only below its own folder | reads the runner alone, writes nothing |
//!
//! As root, the runner first becomes `nobody` (65534), so that what a
//! missing layer leaves open is what nobody may do.

use serde::{Deserialize, Serialize};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

#[cfg(target_os = "linux")]
mod linux;

/// The hidden flag of `spintop course` that runs the launcher.
pub const FLAG: &str = "--sandbox";

/// The exit code of a launcher that could not restrict itself (the
/// program never started).
pub const SETUP_FAILED: i32 = 125;

/// The words that start the launcher's line when it could not restrict
/// itself.
pub const SETUP_MARK: &str = "the sandbox could not be set up";

/// What runs in the sandbox.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum Kind {
    /// A build: it may write below `writable` (its work folder) and
    /// nowhere else.
    Build {
        /// The build's own folder (sources, target, temporary files).
        writable: PathBuf,
    },
    /// A runner: it sees nothing but itself, writes nothing, opens no
    /// socket, starts no process.
    Run,
    /// No program: the launcher says which layers this machine allows (one
    /// JSON line, [`Layers`]) and exits.
    Probe,
}

/// The resource limits, per process.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Limits {
    /// Address space, in bytes.
    pub memory: u64,
    /// CPU time, in seconds (then SIGXCPU, and SIGKILL a second later).
    pub cpu_seconds: u64,
    /// The largest file it may write, in bytes.
    pub file_size: u64,
    /// Open files.
    pub open_files: u64,
}

impl Limits {
    /// A build's: 3 GiB of address space (a copy's build takes under 1; a
    /// 2 GiB `static` takes 7), `cpu_seconds` of CPU, files of at most
    /// 512 MiB.
    pub fn build(cpu_seconds: u64) -> Self {
        Self {
            memory: 3 << 30,
            cpu_seconds,
            file_size: 512 << 20,
            open_files: 1024,
        }
    }

    /// A runner's: 1 GiB of address space (no assignment needs a hundredth
    /// of it), `cpu_seconds` of CPU, no file written.
    pub fn run(cpu_seconds: u64) -> Self {
        Self {
            memory: 1 << 30,
            cpu_seconds,
            file_size: 0,
            open_files: 16,
        }
    }
}

/// A runner's wall-clock limit, in seconds, which the launcher sets as an
/// alarm that holds whether or not the grader is there to count: ten times
/// its CPU time and a minute (the grader's own limits come first; this is
/// the backstop), at most a day.
pub fn wall_seconds(limits: &Limits) -> u32 {
    let s = limits.cpu_seconds.saturating_mul(10).saturating_add(60);
    u32::try_from(s.min(24 * 3600)).unwrap_or(24 * 3600)
}

/// A sandbox: what runs, within what limits.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Spec {
    /// What runs.
    pub kind: Kind,
    /// Its limits.
    pub limits: Limits,
}

/// Which layers a launcher applied (or, probing, could apply): each `Ok`
/// with what it did, or `Err` with why not.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Layers {
    /// Resource limits.
    pub rlimits: Result<String, String>,
    /// User, mount and network namespaces.
    pub namespaces: Result<String, String>,
    /// The system-call filter.
    pub seccomp: Result<String, String>,
    /// The file system ruleset.
    pub landlock: Result<String, String>,
}

impl Layers {
    /// None applied, each for `why`.
    pub fn none(why: &str) -> Self {
        let no = || Err(why.to_string());
        Self {
            rlimits: no(),
            namespaces: no(),
            seccomp: no(),
            landlock: no(),
        }
    }
}

/// Why a sandbox could not be started.
#[derive(Debug, thiserror::Error)]
pub enum SandboxError {
    /// The launcher could not be run.
    #[error("cannot start {program}: {source}")]
    Spawn {
        /// The program.
        program: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The probe said nothing readable.
    #[error("the sandbox's probe gave no answer: {0}")]
    Probe(String),
}

/// The command that runs `program args…` inside `spec`: through the
/// launcher when there is one (the `spintop` binary), else the program
/// itself, bounded from outside once started ([`bound_from_outside`]).
/// Its environment is cleared but for `keep` (a runner gets none at all).
pub fn command(
    launcher: Option<&Path>,
    spec: &Spec,
    program: &Path,
    args: &[OsString],
    keep: &[(String, OsString)],
) -> Command {
    let mut cmd = match launcher {
        Some(l) => {
            let mut cmd = Command::new(l);
            let spec = serde_json::to_string(spec).unwrap_or_default();
            cmd.arg("course").arg(FLAG).arg(spec).arg(program);
            cmd
        }
        None => Command::new(program),
    };
    cmd.args(args).env_clear();
    for (k, v) in keep {
        cmd.env(k, v);
    }
    cmd
}

/// Puts `limits` on a process just started without a launcher (Linux's
/// `prlimit`; elsewhere nothing): it lands while the program is starting.
pub fn bound_from_outside(child: &std::process::Child, limits: &Limits) {
    #[cfg(target_os = "linux")]
    {
        use rustix::process::{Pid, Resource, Rlimit, prlimit};
        let pid = Pid::from_child(child);
        for (resource, v) in [
            (Resource::As, limits.memory),
            (Resource::Cpu, limits.cpu_seconds),
            (Resource::Core, 0),
        ] {
            let limit = Rlimit {
                current: Some(v),
                maximum: Some(v),
            };
            let _ = prlimit(Some(pid), resource, limit);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (child, limits);
}

/// What this machine's launcher allows: runs `launcher` with
/// [`Kind::Probe`] and reads its answer.
pub fn probe(launcher: &Path) -> Result<Layers, SandboxError> {
    let spec = Spec {
        kind: Kind::Probe,
        limits: Limits::run(10),
    };
    let out = command(Some(launcher), &spec, Path::new("-"), &[], &[])
        .output()
        .map_err(|source| SandboxError::Spawn {
            program: launcher.to_path_buf(),
            source,
        })?;
    let text = String::from_utf8_lossy(&out.stdout);
    serde_json::from_str(text.trim()).map_err(|_| {
        SandboxError::Probe(format!(
            "{}{}",
            text.trim(),
            String::from_utf8_lossy(&out.stderr).trim()
        ))
    })
}

/// The launcher's `main`: `args` are what followed [`FLAG`] (`SPEC PROGRAM
/// ARGS…`). It restricts itself and becomes the program; it returns only
/// when it could not (the exit code, [`SETUP_FAILED`], after a line on
/// stderr), or after a probe (0).
pub fn launch(args: &[OsString]) -> i32 {
    let parsed = args.split_first().and_then(|(spec, rest)| {
        let spec: Spec = serde_json::from_str(spec.to_str()?).ok()?;
        let (program, rest) = rest.split_first()?;
        Some((spec, PathBuf::from(program), rest))
    });
    let Some((spec, program, rest)) = parsed else {
        eprintln!("spintop course {FLAG}: expected SPEC PROGRAM [ARGS…]");
        return 2;
    };
    imp_launch(&spec, &program, rest)
}

#[cfg(target_os = "linux")]
fn imp_launch(spec: &Spec, program: &Path, args: &[OsString]) -> i32 {
    linux::launch(spec, program, args)
}

#[cfg(all(unix, not(target_os = "linux")))]
fn imp_launch(spec: &Spec, program: &Path, args: &[OsString]) -> i32 {
    use std::os::unix::process::CommandExt;
    let rlimits = set_rlimits(&spec.limits);
    if spec.kind == Kind::Probe {
        let mut layers = Layers::none("not on this system (Linux only)");
        layers.rlimits = rlimits.map(|()| "set".into()).map_err(|e| e.to_string());
        println!("{}", serde_json::to_string(&layers).unwrap_or_default());
        return 0;
    }
    if let Err(e) = rlimits {
        eprintln!("spintop course: cannot bound the student's program: {e}");
        return SETUP_FAILED;
    }
    let e = Command::new(program).args(args).exec();
    eprintln!("cannot start {}: {e}", program.display());
    SETUP_FAILED
}

#[cfg(not(unix))]
fn imp_launch(spec: &Spec, program: &Path, args: &[OsString]) -> i32 {
    if spec.kind == Kind::Probe {
        let layers = Layers::none("not on this system (Linux only)");
        println!("{}", serde_json::to_string(&layers).unwrap_or_default());
        return 0;
    }
    match Command::new(program).args(args).status() {
        Ok(s) => s.code().unwrap_or(SETUP_FAILED),
        Err(e) => {
            eprintln!("cannot start {}: {e}", program.display());
            SETUP_FAILED
        }
    }
}

/// Sets `limits` on this process (and what it starts): no core dumps.
#[cfg(unix)]
pub(crate) fn set_rlimits(limits: &Limits) -> std::io::Result<()> {
    use rustix::process::{Resource, Rlimit, getrlimit, setrlimit};
    // Lowered only: a limit already below the one asked for stays (raising
    // a hard limit takes a privilege).
    let set = |resource, soft: u64, hard: u64| {
        let now = getrlimit(resource).maximum.unwrap_or(u64::MAX);
        setrlimit(
            resource,
            Rlimit {
                current: Some(soft.min(now)),
                maximum: Some(hard.min(now)),
            },
        )
    };
    set(Resource::Core, 0, 0)?;
    set(Resource::As, limits.memory, limits.memory)?;
    // The soft limit sends SIGXCPU; the hard one, a second later, SIGKILL.
    set(Resource::Cpu, limits.cpu_seconds, limits.cpu_seconds + 1)?;
    set(Resource::Fsize, limits.file_size, limits.file_size)?;
    set(Resource::Nofile, limits.open_files, limits.open_files)?;
    Ok(())
}
