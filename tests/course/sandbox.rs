//! The sandbox, tried the way an attacker would try it: a program of the
//! attacker's own (any code at all, as a student's runner is once safe Rust
//! is broken through rust-lang/rust#25860) started through the launcher
//! exactly as a runner or a build is, asked to list, read, write, connect,
//! start processes, and outlast its limits. Where this kernel lacks a layer
//! (user namespaces, Landlock, seccomp), the test says so and checks what
//! the other layers still hold.

use spintop_course::sandbox::{self, Kind, Layers, Limits, Spec};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// The attacker's program: each argument pair an action, each answered
/// with one line, `ok …` or `err …`.
const PROBE: &str = r#"
use std::io::Write;
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut out = std::io::stdout();
    for pair in args.chunks(2) {
        let (what, arg) = (pair[0].as_str(), pair.get(1).map(String::as_str).unwrap_or(""));
        let result: Result<String, String> = match what {
            "list" => std::fs::read_dir(arg).map(|d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect::<Vec<_>>().join(" ")).map_err(|e| e.to_string()),
            "read" => std::fs::read(arg).map(|b| b.len().to_string()).map_err(|e| e.to_string()),
            "write" => std::fs::write(arg, b"x").map(|()| String::new()).map_err(|e| e.to_string()),
            "tcp" => std::net::TcpListener::bind("127.0.0.1:0").map(|_| String::new()).map_err(|e| e.to_string()),
            "udp" => std::net::UdpSocket::bind("127.0.0.1:0").map(|_| String::new()).map_err(|e| e.to_string()),
            "spawn" => std::process::Command::new(arg).status().map(|s| s.to_string()).map_err(|e| e.to_string()),
            "thread" => std::thread::Builder::new().spawn(|| 1).map(|h| format!("{:?}", h.join())).map_err(|e| e.to_string()),
            "alloc" => {
                let n: usize = arg.parse().unwrap();
                let v = std::hint::black_box(vec![1u8; std::hint::black_box(n)]);
                Ok(v.len().to_string())
            }
            "spin" => loop { std::hint::black_box(0u64); },
            _ => Err("unknown".into()),
        };
        let line = match result { Ok(s) => format!("ok {what} {s}"), Err(e) => format!("err {what} {e}") };
        writeln!(out, "{line}").unwrap();
        out.flush().unwrap();
    }
}
"#;

fn spintop() -> &'static Path {
    Path::new(env!("CARGO_BIN_EXE_spintop"))
}

/// The probe, compiled once (statically linked, as a runner is).
fn probe() -> &'static Path {
    static PROGRAM: OnceLock<PathBuf> = OnceLock::new();
    PROGRAM.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("spintop-probe-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("probe.rs"), PROBE).unwrap();
        let exe = dir.join("probe");
        let ok = Command::new("rustc")
            .args([
                "-O",
                "--edition",
                "2021",
                "-C",
                "target-feature=+crt-static",
                "-o",
            ])
            .arg(&exe)
            .arg(dir.join("probe.rs"))
            .status()
            .unwrap();
        assert!(ok.success(), "the probe compiles");
        exe
    })
}

/// What this machine's launcher can apply.
fn layers() -> Layers {
    sandbox::probe(spintop()).expect("the launcher answers a probe")
}

/// The probe's answers, run through the launcher in `spec`.
fn run(spec: &Spec, args: &[&str]) -> (Vec<String>, std::process::ExitStatus, Duration) {
    let start = Instant::now();
    let args: Vec<std::ffi::OsString> = args.iter().map(Into::into).collect();
    let out = sandbox::command(Some(spintop()), spec, probe(), &args, &[])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let lines = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(String::from)
        .collect();
    (lines, out.status, start.elapsed())
}

fn answer<'a>(lines: &'a [String], what: &str) -> &'a str {
    lines
        .iter()
        .find(|l| l.split(' ').nth(1) == Some(what))
        .map(String::as_str)
        .unwrap_or_else(|| panic!("no answer to {what}: {lines:?}"))
}

fn runner() -> Spec {
    Spec {
        kind: Kind::Run,
        limits: Limits::run(5),
    }
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_runner_lists_reads_and_writes_nothing_outside_itself() {
    let layers = layers();
    if layers.namespaces.is_err() && layers.landlock.is_err() {
        eprintln!(
            "SKIPPED: this kernel allows neither user namespaces ({:?}) nor Landlock ({:?}): a runner reads what its user may read",
            layers.namespaces, layers.landlock
        );
        return;
    }
    let solution = spintop_course::repository().join("lessons/src/solutions/ch2.rs");
    let solution = solution.canonicalize().unwrap();
    assert!(solution.is_file());
    let (lines, status, _) = run(
        &runner(),
        &[
            "list",
            "/",
            "read",
            solution.to_str().unwrap(),
            "read",
            "/etc/passwd",
            "list",
            std::env::temp_dir().to_str().unwrap(),
            "write",
            "/runner-was-here",
            "write",
            std::env::temp_dir()
                .join("spintop-runner-was-here")
                .to_str()
                .unwrap(),
        ],
    );
    assert!(status.success(), "{status:?} {lines:?}");
    // Nothing to see but the runner itself.
    let listed = answer(&lines, "list");
    assert!(
        listed.starts_with("err") || listed == "ok list runner",
        "{listed}"
    );
    for line in lines.iter().filter(|l| !l.contains(" list ")) {
        assert!(line.starts_with("err"), "{line}");
    }
    assert!(
        !std::env::temp_dir()
            .join("spintop-runner-was-here")
            .exists()
    );
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_runner_opens_no_socket_and_starts_no_process_or_thread() {
    let layers = layers();
    if layers.seccomp.is_err() && layers.namespaces.is_err() {
        eprintln!(
            "SKIPPED: neither seccomp ({:?}) nor namespaces ({:?}) on this kernel",
            layers.seccomp, layers.namespaces
        );
        return;
    }
    let (lines, status, _) = run(
        &runner(),
        &["tcp", "", "udp", "", "spawn", "/bin/true", "thread", ""],
    );
    assert!(status.success(), "{status:?} {lines:?}");
    for what in ["tcp", "udp", "spawn", "thread"] {
        let line = answer(&lines, what);
        if (what == "spawn" || what == "thread") && layers.seccomp.is_err() {
            eprintln!(
                "SKIPPED {what}: no seccomp on this kernel ({:?})",
                layers.seccomp
            );
            continue;
        }
        assert!(line.starts_with("err"), "{line}");
    }
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_runner_cannot_outlast_its_cpu_time_or_its_memory() {
    let spec = Spec {
        kind: Kind::Run,
        limits: Limits::run(1),
    };
    let (lines, status, elapsed) = run(&spec, &["alloc", &(2usize << 30).to_string()]);
    assert!(
        !status.success() && lines.is_empty(),
        "{status:?} {lines:?}"
    );
    let (_, status, elapsed2) = run(&spec, &["spin", ""]);
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        // SIGXCPU at its 1 s of CPU, or SIGKILL a second later.
        assert!(matches!(status.signal(), Some(24 | 9)), "{status:?}");
    }
    assert!(elapsed < Duration::from_secs(10), "{elapsed:?}");
    assert!(elapsed2 < Duration::from_secs(10), "{elapsed2:?}");
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_build_writes_only_in_its_own_folder_and_reaches_no_network() {
    let layers = layers();
    let work = std::env::temp_dir().join(format!("spintop-build-box-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let outside = spintop_course::repository()
        .join("target")
        .join("spintop-build-was-here");
    let spec = Spec {
        kind: Kind::Build {
            writable: work.clone(),
        },
        limits: Limits::build(10),
    };
    let inside = work.join("inside");
    let (lines, status, _) = run(
        &spec,
        &[
            "write",
            inside.to_str().unwrap(),
            "write",
            outside.to_str().unwrap(),
            "tcp",
            "",
        ],
    );
    assert!(status.success(), "{status:?} {lines:?}");
    assert!(lines[0].starts_with("ok") && inside.is_file(), "{lines:?}");
    if layers.namespaces.is_ok() || layers.landlock.is_ok() {
        assert!(
            lines[1].starts_with("err") && !outside.exists(),
            "{lines:?}"
        );
    } else {
        eprintln!("SKIPPED: no namespaces or Landlock: a build may write where its user may");
    }
    if layers.namespaces.is_ok() || layers.seccomp.is_ok() {
        assert!(lines[2].starts_with("err"), "{lines:?}");
    }
    let _ = std::fs::remove_file(&outside);
    std::fs::remove_dir_all(&work).unwrap();
}

/// What the launcher applies on this machine, printed for the record (and
/// each layer named, applied or not).
#[test]
fn the_launcher_says_which_layers_this_machine_allows() {
    let layers = layers();
    eprintln!("{layers:#?}");
    assert!(layers.rlimits.is_ok(), "{layers:?}");
    #[cfg(target_os = "linux")]
    assert!(
        layers.seccomp.is_ok(),
        "seccomp is in every Linux this course supports: {layers:?}"
    );
}
