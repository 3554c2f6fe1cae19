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
extern "C" {
    fn write(fd: i32, buf: *const u8, n: usize) -> isize;
    fn prctl(option: i32, arg: u64, a3: u64, a4: u64, a5: u64) -> i32;
    fn syscall(number: i64, ...) -> i64;
    fn memfd_create(name: *const u8, flags: u32) -> i32;
}
fn errno() -> String { std::io::Error::last_os_error().to_string() }
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
            "pid" => Ok(std::process::id().to_string()),
            "fds" => Ok((3..=1023).filter(|&fd| unsafe { write(fd, b"LEAK\n".as_ptr(), 5) } == 5).map(|fd| fd.to_string()).collect::<Vec<_>>().join(" ")),
            "nodeath" => if unsafe { prctl(1, 0, 0, 0, 0) } == 0 { Ok(String::new()) } else { Err(errno()) },
            "sleep" => { std::thread::sleep(std::time::Duration::from_secs(arg.parse().unwrap())); Ok(String::new()) }
            "memfd" => { let fd = unsafe { memfd_create(b"x\0".as_ptr(), 0) }; if fd >= 0 { Ok(fd.to_string()) } else { Err(errno()) } }
            "fsopen" => { let fd = unsafe { syscall(430, b"tmpfs\0".as_ptr(), 0) }; if fd >= 0 { Ok(fd.to_string()) } else { Err(errno()) } }
            "open_tree" => { let fd = unsafe { syscall(428, -100i64, b"/\0".as_ptr(), 1) }; if fd >= 0 { Ok(fd.to_string()) } else { Err(errno()) } }
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

/// `spec`'s probe started the way `exec 7>>LEAK 8>>LEAK; spintop course
/// grade` starts it: a shell opens descriptors the grader inherits.
fn through_shell(spec: &Spec, args: &[&str], env: &[(String, std::ffi::OsString)]) -> Command {
    let args: Vec<std::ffi::OsString> = args.iter().map(Into::into).collect();
    let inner = sandbox::command(Some(spintop()), spec, probe(), &args, env);
    let mut shell = Command::new("bash");
    std::os::unix::process::CommandExt::process_group(&mut shell, 0);
    shell
        .arg("-c")
        // Not `exec`ed by the shell: it stays the program's parent.
        .arg("exec 7>>\"$LEAK\" 8>>\"$LEAK\"; \"$@\"; r=$?; exit $r")
        .arg("bash")
        .arg(inner.get_program())
        .args(inner.get_args())
        .env_clear()
        .envs(env.iter().map(|(k, v)| (k.clone(), v.clone())))
        .stdin(Stdio::null());
    shell
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn no_descriptor_the_grader_inherited_reaches_a_runner_or_a_build() {
    let work = std::env::temp_dir().join(format!("spintop-fds-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let leak = work.join("leak");
    std::fs::write(&leak, "").unwrap();
    let env = [("LEAK".to_string(), leak.clone().into_os_string())];
    let build = Spec {
        kind: Kind::Build {
            writable: work.clone(),
        },
        limits: Limits::build(10),
    };
    for spec in [runner(), build] {
        let out = through_shell(&spec, &["fds", ""], &env).output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        // Writes to 0..2 only: nothing from 3 to 1023 is open.
        assert_eq!(text.trim_end(), "ok fds", "{spec:?}: {text}");
    }
    assert_eq!(std::fs::read_to_string(&leak).unwrap(), "");
    std::fs::remove_dir_all(&work).unwrap();
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_runner_mounts_nothing_and_makes_no_memory_file() {
    if layers().seccomp.is_err() {
        eprintln!("SKIPPED: no seccomp on this kernel");
        return;
    }
    let (lines, status, _) = run(&runner(), &["memfd", "", "fsopen", "", "open_tree", ""]);
    assert!(status.success(), "{status:?} {lines:?}");
    for what in ["memfd", "fsopen", "open_tree"] {
        assert!(answer(&lines, what).starts_with("err"), "{lines:?}");
    }
}

/// Whether process `pid` is alive (a zombie is not).
fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .ok()
        .and_then(|s| {
            s.rsplit(')')
                .next()
                .map(|r| !r.trim_start().starts_with(['Z', 'X']))
        })
        .unwrap_or(false)
}

/// Starts a stand-in grader (a shell) whose child is `spec`'s probe with
/// `args`, and the probe's first answer line.
fn under_a_grader(
    spec: &Spec,
    args: &[&str],
) -> (
    std::process::Child,
    std::io::Lines<std::io::BufReader<std::process::ChildStdout>>,
) {
    use std::io::BufRead;
    let mut grader = through_shell(spec, args, &[("LEAK".into(), "/dev/null".into())])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = std::io::BufReader::new(grader.stdout.take().unwrap()).lines();
    (grader, lines)
}

#[test]
#[ignore = "end-to-end: compiles a probe program"]
fn a_runner_that_drops_its_parent_death_signal_still_dies_with_the_grader() {
    let spec = Spec {
        kind: Kind::Run,
        limits: Limits::run(5),
    };
    let (mut grader, mut lines) =
        under_a_grader(&spec, &["pid", "", "nodeath", "", "sleep", "600"]);
    let pid: u32 = lines.next().unwrap().unwrap()["ok pid ".len()..]
        .parse()
        .unwrap();
    let nodeath = lines.next().unwrap().unwrap();
    assert!(alive(pid));
    if layers().seccomp.is_ok() {
        assert!(nodeath.starts_with("err"), "{nodeath}");
    }
    grader.kill().unwrap();
    grader.wait().unwrap();
    std::thread::sleep(Duration::from_secs(2));
    assert!(!alive(pid), "the runner {pid} outlived its grader");
}

#[test]
#[ignore = "end-to-end: compiles a probe program and a slow constant"]
fn a_build_dies_with_the_grader_rustc_included() {
    let work = std::env::temp_dir().join(format!("spintop-slow-build-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let source = work.join("slow_const.rs");
    std::fs::write(
        &source,
        "#[allow(long_running_const_eval)]\npub const X: u64 = { let mut i = 0u64; let mut s = 0u64; \
         while i < 1 << 50 { s = s.wrapping_add(i * i); i += 1; } s };\npub fn f() -> u64 { X }\n",
    )
    .unwrap();
    let spec = Spec {
        kind: Kind::Build {
            writable: work.clone(),
        },
        limits: Limits::build(600),
    };
    // As cargo does: rustc is a grandchild of the launcher (`sh` between).
    let script = format!(
        "rustc --crate-type lib --out-dir {} {}; true",
        work.display(),
        source.display()
    );
    let env: Vec<(String, std::ffi::OsString)> = [
        "PATH",
        "HOME",
        "RUSTUP_HOME",
        "CARGO_HOME",
        "RUSTUP_TOOLCHAIN",
    ]
    .into_iter()
    .filter_map(|k| Some((k.to_string(), std::env::var_os(k)?)))
    .chain([("LEAK".to_string(), "/dev/null".into())])
    .collect();
    let inner = sandbox::command(
        Some(spintop()),
        &spec,
        Path::new("/bin/sh"),
        &["-c".into(), script.into()],
        &env,
    );
    let mut grader = Command::new("bash");
    std::os::unix::process::CommandExt::process_group(&mut grader, 0);
    let mut grader = grader
        .arg("-c")
        .arg("\"$@\"; r=$?; exit $r")
        .arg("bash")
        .arg(inner.get_program())
        .args(inner.get_args())
        .env_clear()
        .envs(env.iter().map(|(k, v)| (k.clone(), v.clone())))
        .stdin(Stdio::null())
        .spawn()
        .unwrap();
    let compiling = || -> Vec<u32> {
        std::fs::read_dir("/proc")
            .unwrap()
            .flatten()
            .filter_map(|e| e.file_name().to_str()?.parse::<u32>().ok())
            .filter(|pid| {
                std::fs::read(format!("/proc/{pid}/cmdline"))
                    .is_ok_and(|c| String::from_utf8_lossy(&c).contains("slow_const.rs"))
                    && alive(*pid)
            })
            .collect()
    };
    let start = Instant::now();
    while compiling().len() < 2 && start.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(100));
    }
    std::thread::sleep(Duration::from_secs(3));
    let before = compiling();
    assert!(!before.is_empty(), "rustc is compiling the slow constant");
    grader.kill().unwrap();
    grader.wait().unwrap();
    std::thread::sleep(Duration::from_secs(2));
    assert_eq!(
        compiling(),
        Vec::<u32>::new(),
        "the build outlived its grader (was {before:?})"
    );
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
