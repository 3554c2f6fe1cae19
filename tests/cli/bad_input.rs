//! The bad-input corpus: several hundred bad, edge and numerically hard
//! invocations of the real binary, each with the exit code and a fragment of
//! the message a user should get.
//!
//! Every case must hold the command-line contract: it ends within a time
//! limit; a refusal or failure prints exactly one line on stderr, starting
//! `spintop: error:`, naming what was wrong; the exit code is the documented
//! one (2 bad input, 3 numerical failure, 1 output not writable, 0 success);
//! nothing panics or aborts; and no output, on success or failure, holds a
//! NaN, an infinity or a JSON `null` standing for one.
//!
//! The cases are data: a table of scalar flags crossed with malformed numbers
//! (each must be refused naming the flag), a table of out-of-range values
//! with the quantity each must name, broken scene files, numerical failures,
//! and edge values that must succeed.

use std::io::Read;
use std::process::{Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

/// One invocation and what it must give.
#[derive(Clone, Debug)]
struct Case {
    args: Vec<String>,
    code: i32,
    /// A fragment the message (stderr) must hold; for exit 0, stdout.
    fragment: String,
    /// Stdout goes to /dev/full instead of a pipe.
    full: bool,
}

fn case(args: &[&str], code: i32, fragment: &str) -> Case {
    Case {
        args: args.iter().map(|s| s.to_string()).collect(),
        code,
        fragment: fragment.to_string(),
        full: false,
    }
}

/// Runs a case with a time limit; returns (exit code, stdout, stderr).
fn run(c: &Case) -> Result<(i32, String, String), String> {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_spintop"));
    cmd.args(&c.args)
        .stdin(Stdio::null())
        .stderr(Stdio::piped());
    // Tests must never touch a student's progress file.
    cmd.env("SPINTOP_LEARN_PROGRESS", "/dev/null");
    if c.full {
        cmd.stdout(
            std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .map_err(|e| e.to_string())?,
        );
    } else {
        cmd.stdout(Stdio::piped());
    }
    let mut child = cmd.spawn().map_err(|e| e.to_string())?;
    // Drain the pipes on threads so a chatty child never blocks.
    let mut out = child.stdout.take();
    let mut err = child.stderr.take();
    let t_out = thread::spawn(move || {
        let mut s = Vec::new();
        if let Some(o) = out.as_mut() {
            let _ = o.take(1 << 24).read_to_end(&mut s);
        }
        s
    });
    let t_err = thread::spawn(move || {
        let mut s = Vec::new();
        if let Some(e) = err.as_mut() {
            let _ = e.take(1 << 20).read_to_end(&mut s);
        }
        s
    });
    let limit = Duration::from_secs(30);
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("no answer within {limit:?}"));
        }
        thread::sleep(Duration::from_millis(5));
    };
    let stdout = String::from_utf8_lossy(&t_out.join().unwrap_or_default()).into_owned();
    let stderr = String::from_utf8_lossy(&t_err.join().unwrap_or_default()).into_owned();
    let code = status
        .code()
        .ok_or_else(|| format!("killed by a signal: {status:?}; stderr: {stderr}"))?;
    Ok((code, stdout, stderr))
}

/// What is wrong with a case's result, if anything.
///
/// With `SPINTOP_CORPUS_DUMP=FILE`, every case's command, exit code and
/// message are appended to FILE, for reading them all as a user would.
fn check(c: &Case) -> Option<String> {
    let (code, stdout, stderr) = match run(c) {
        Ok(r) => r,
        Err(e) => return Some(e),
    };
    if let Some(path) = std::env::var_os("SPINTOP_CORPUS_DUMP") {
        use std::io::Write;
        if let Ok(mut f) = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
        {
            let _ = writeln!(
                f,
                "spintop {}\n  -> {code}: {}",
                c.args.join(" "),
                stderr.trim()
            );
        }
    }
    let mut problems = Vec::new();
    if code != c.code {
        problems.push(format!("exit {code}, expected {}", c.code));
    }
    if stderr.contains("panicked")
        || stderr.contains("RUST_BACKTRACE")
        || code == 101
        || code == 134
    {
        problems.push("a panic or an abort".into());
    }
    if code != 0 {
        let lines: Vec<&str> = stderr.lines().collect();
        if lines.len() != 1 || !lines[0].starts_with("spintop: error: ") {
            problems.push(format!(
                "stderr is not one `spintop: error:` line: {stderr:?}"
            ));
        }
    }
    // A number in a message is written short: never a double's three
    // hundred digits (`1e300`, not `1000…0`).
    let longest_digits = |text: &str| {
        text.split(|c: char| !c.is_ascii_digit())
            .map(str::len)
            .max()
            .unwrap_or(0)
    };
    if longest_digits(&stderr) > 24 {
        problems.push(format!(
            "a number of {} digits in the message",
            longest_digits(&stderr)
        ));
    }
    // Nor in the output: its warnings and headers included.
    if longest_digits(&stdout) > 24 {
        problems.push(format!(
            "a number of {} digits in the output",
            longest_digits(&stdout)
        ));
    }
    // A scene's message names the scene's keys, never a flag of another
    // command (`run` itself takes --format).
    if c.args.first().is_some_and(|a| a == "run")
        && stderr
            .split_whitespace()
            .any(|w| w.starts_with("--") && !w.starts_with("--format") && !w.starts_with("--help"))
    {
        problems.push("a command-line flag named in a scene's message".into());
    }
    // No number in a message is `inf` or `NaN` unless the user typed it
    // (echoed as typed, with "is not a finite number").
    let non_finite = stderr
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .any(|w| matches!(w, "inf" | "NaN" | "nan" | "infinity"));
    if non_finite && !stderr.contains("is not a finite number") {
        problems.push("a non-finite number computed in the message".into());
    }
    let haystack = if code == 0 { &stdout } else { &stderr };
    if !haystack.contains(&c.fragment) {
        problems.push(format!("no {:?} in the message", c.fragment));
    }
    // No NaN, infinity or null anywhere in the output (the command names
    // themselves hold none of these words).
    // In JSON, `null` is allowed only where a value is undefined by
    // definition: the Euler rates at the pole.
    let stdout_checked = stdout.replace("\"euler_rates\":null", "");
    for word in ["NaN", "nan,", " inf", "-inf", ",inf", "null", "infinity"] {
        if stdout_checked.contains(word) {
            problems.push(format!("{word:?} in stdout"));
        }
    }
    if problems.is_empty() {
        None
    } else {
        Some(format!(
            "{} | stderr: {}",
            problems.join("; "),
            stderr.trim()
        ))
    }
}

/// Malformed numbers: each must be refused by name of the flag.
const MALFORMED: [&str; 10] = [
    "nan", "NaN", "inf", "-inf", "abc", "", "1e400", "1,,2", "0x10", "1e",
];

/// Scalar numeric flags, each with a valid command it can be added to.
fn scalar_flags() -> Vec<(Vec<&'static str>, &'static str)> {
    let sim = vec![
        "simulate",
        "--model",
        "reduced",
        "--t-end",
        "10",
        "--samples",
        "3",
    ];
    let rk4 = vec![
        "simulate",
        "--model",
        "reduced",
        "--method",
        "rk4",
        "--t-end",
        "1",
        "--samples",
        "2",
    ];
    let bal = vec!["balance", "--dipole", "precessing", "--times", "0,1"];
    let orb = vec![
        "orbit",
        "--potential",
        "coulomb",
        "--tau0",
        "0.001",
        "--times",
        "1",
    ];
    let orb_no_tau = vec!["orbit", "--potential", "coulomb", "--times", "1"];
    let shell_no_tau = vec!["shell", "--delay", "0.03", "--times", "1"];
    let shell_no_delay = vec!["shell", "--tau0", "0.001", "--times", "1"];
    let plot = vec!["plot"];
    let tui = vec!["tui"];
    vec![
        (sim.clone(), "--ratio"),
        (
            vec!["simulate", "--model", "reduced", "--samples", "3"],
            "--t-end",
        ),
        (sim.clone(), "--rtol"),
        (rk4, "--step"),
        (bal.clone(), "--cone"),
        (bal.clone(), "--rate"),
        (vec!["balance", "--dipole", "loop", "--times", "0,1"], "--b"),
        (
            vec!["balance", "--dipole", "loop", "--times", "0,1"],
            "--eps",
        ),
        (
            vec!["balance", "--dipole", "dumbbell", "--times", "0,1"],
            "--length",
        ),
        (orb_no_tau, "--tau0"),
        (orb.clone(), "--r0"),
        (orb.clone(), "--eccentricity"),
        (orb, "--rtol"),
        (shell_no_tau, "--tau0"),
        (shell_no_delay, "--delay"),
        (plot.clone(), "--ratio"),
        (plot, "--t-end"),
        (tui.clone(), "--ratio"),
        (tui.clone(), "--warp"),
        (tui, "--bench"),
    ]
}

/// Flags of three numbers, with malformed values for them.
fn vector_flags() -> Vec<(Vec<&'static str>, &'static str, &'static [&'static str])> {
    const TRIPLE: &[&str] = &[
        "1,2", "1,2,3,4", "a,b,c", "nan,0,0", "0,inf,0", "", ",,", "1;2;3",
    ];
    const PAIR: &[&str] = &["1", "1,2,3", "a,b", "nan,1", "1,inf", "", ",", "1;2"];
    const LIST: &[&str] = &["", ",,", "a,b", "nan", "1,inf", "1;2", "1e400", "0,,1"];
    vec![
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--t-end",
                "1",
                "--samples",
                "2",
            ],
            "--omega",
            TRIPLE,
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--t-end",
                "1",
                "--samples",
                "2",
            ],
            "--euler",
            TRIPLE,
        ),
        (
            vec![
                "simulate",
                "--model",
                "general",
                "--dipole",
                "0,0,1",
                "--t-end",
                "1",
                "--samples",
                "2",
            ],
            "--inertia",
            TRIPLE,
        ),
        (
            vec![
                "simulate",
                "--model",
                "general",
                "--inertia",
                "1,2,3",
                "--t-end",
                "1",
                "--samples",
                "2",
            ],
            "--dipole",
            TRIPLE,
        ),
        (vec!["simulate", "--model", "reduced"], "--times", LIST),
        (vec!["balance", "--dipole", "precessing"], "--times", LIST),
        (
            vec!["balance", "--dipole", "dumbbell", "--times", "0"],
            "--charges",
            PAIR,
        ),
        (
            vec!["balance", "--dipole", "dumbbell", "--times", "0"],
            "--masses",
            PAIR,
        ),
        (
            vec!["orbit", "--potential", "harmonic", "--tau0", "0.01"],
            "--times",
            LIST,
        ),
        (
            vec!["shell", "--tau0", "0.001", "--delay", "0.03"],
            "--times",
            LIST,
        ),
        (vec!["plot"], "--omega", TRIPLE),
        (vec!["tui"], "--omega", TRIPLE),
    ]
}

fn with(base: &[&str], extra: &[&str]) -> Vec<String> {
    base.iter().chain(extra).map(|s| s.to_string()).collect()
}

/// A scene file with `body` written to a temporary folder; returns its path.
fn scene_file(dir: &std::path::Path, name: &str, body: &str) -> String {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, body).expect("a temporary scene file");
    path.display().to_string()
}

fn corpus(dir: &std::path::Path) -> Vec<Case> {
    let mut cases = Vec::new();
    // 1. Malformed numbers in every scalar flag: refused, naming the flag.
    for (base, flag) in scalar_flags() {
        for value in MALFORMED {
            cases.push(Case {
                args: with(&base, &[flag, value]),
                code: 2,
                fragment: flag.into(),
                full: false,
            });
        }
    }
    // 2. Malformed vectors and lists.
    for (base, flag, values) in vector_flags() {
        for value in values.iter().copied() {
            cases.push(Case {
                args: with(&base, &[flag, value]),
                code: 2,
                fragment: flag.into(),
                full: false,
            });
        }
    }
    // 3. Out of range: the message names the quantity.
    let sim = [
        "simulate",
        "--model",
        "reduced",
        "--t-end",
        "10",
        "--samples",
        "3",
    ];
    let ranges: Vec<(Vec<String>, &str)> = vec![
        (with(&sim, &["--ratio", "0"]), "I3/I1"),
        (with(&sim, &["--ratio", "-0.4"]), "I3/I1"),
        (with(&sim, &["--ratio=-0.4"]), "I3/I1"),
        (with(&sim, &["--ratio", "2.5"]), "I3/I1"),
        (with(&sim, &["--ratio", "1e300"]), "I3/I1"),
        (with(&sim, &["--rtol", "0"]), "rtol"),
        (with(&sim, &["--rtol", "-1e-8"]), "rtol"),
        (with(&sim, &["--rtol", "1"]), "rtol"),
        (with(&sim, &["--rtol", "1e-15"]), "--rtol 1e-15 is below"),
        (with(&sim, &["--omega", "1e101,0,0"]), "1e100"),
        (
            with(
                &["simulate", "--model", "reduced", "--samples", "3"],
                &["--t-end", "-1"],
            ),
            "t-end",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--t-end", "1"],
                &["--samples", "0"],
            ),
            "samples",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--t-end", "1"],
                &["--samples", "-3"],
            ),
            "samples",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--t-end", "1"],
                &["--samples", "1e12"],
            ),
            "samples",
        ),
        (
            with(&["simulate", "--model", "reduced"], &["--times", "3,2,1"]),
            "times",
        ),
        (
            with(&["simulate", "--model", "reduced"], &["--times", "-1,2"]),
            "times",
        ),
        (
            with(
                &[
                    "simulate", "--model", "reduced", "--method", "rk4", "--t-end", "1",
                ],
                &["--step", "0"],
            ),
            "step",
        ),
        (
            with(
                &[
                    "simulate", "--model", "reduced", "--method", "rk4", "--t-end", "1",
                ],
                &["--step", "-0.1"],
            ),
            "step",
        ),
        (
            with(
                &[
                    "simulate", "--model", "general", "--dipole", "0,0,1", "--t-end", "1",
                ],
                &["--inertia", "1,1,3"],
            ),
            "not a rigid body",
        ),
        (
            with(
                &[
                    "simulate", "--model", "general", "--dipole", "0,0,1", "--t-end", "1",
                ],
                &["--inertia", "0,1,1"],
            ),
            "moment I1",
        ),
        (
            with(
                &[
                    "simulate", "--model", "general", "--dipole", "0,0,1", "--t-end", "1",
                ],
                &["--inertia", "-1,1,1"],
            ),
            "moment I1",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "general",
                    "--inertia",
                    "1,2,3",
                    "--t-end",
                    "1",
                ],
                &["--dipole", "0,0,0"],
            ),
            "dipole",
        ),
        (
            vec![
                "simulate".into(),
                "--model".into(),
                "general".into(),
                "--t-end".into(),
                "1".into(),
            ],
            "--inertia",
        ),
        (with(&sim, &["--inertia", "1,2,3"]), "--inertia"),
        (with(&sim, &["--method", "forward"]), "forward"),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "general",
                    "--inertia",
                    "1,2,3",
                    "--dipole",
                    "0,0,1",
                    "--t-end",
                    "1",
                ],
                &["--method", "exact"],
            ),
            "closed form",
        ),
        (
            with(
                &["simulate", "--model", "full", "--t-end", "1"],
                &["--method", "rk4"],
            ),
            "full",
        ),
        (
            with(
                &["simulate", "--model", "full", "--t-end", "1"],
                &["--method", "dopri5"],
            ),
            "full",
        ),
        (
            with(
                &["balance", "--dipole", "precessing", "--times", "0"],
                &["--cone", "4"],
            ),
            "cone",
        ),
        (
            with(
                &["balance", "--dipole", "precessing", "--times", "0"],
                &["--cone", "-0.1"],
            ),
            "cone",
        ),
        (
            with(
                &["balance", "--dipole", "precessing", "--times", "0"],
                &["--rate", "0"],
            ),
            "rate",
        ),
        (
            with(
                &["balance", "--dipole", "dumbbell", "--times", "0"],
                &["--masses", "0,1"],
            ),
            "m1",
        ),
        (
            with(
                &["balance", "--dipole", "dumbbell", "--times", "0"],
                &["--masses", "-1,1"],
            ),
            "m1",
        ),
        (
            with(
                &["balance", "--dipole", "dumbbell", "--times", "0"],
                &["--length", "0"],
            ),
            "length",
        ),
        (
            with(
                &["orbit", "--potential", "coulomb", "--times", "1"],
                &["--tau0", "0"],
            ),
            "tau0",
        ),
        (
            with(
                &["orbit", "--potential", "coulomb", "--times", "1"],
                &["--tau0", "-1"],
            ),
            "tau0",
        ),
        (
            with(
                &["orbit", "--potential", "coulomb", "--times", "1"],
                &["--tau0", "1"],
            ),
            "lower tau0",
        ),
        (
            with(
                &[
                    "orbit",
                    "--potential",
                    "coulomb",
                    "--tau0",
                    "0.001",
                    "--times",
                    "1",
                ],
                &["--r0", "0"],
            ),
            "r0",
        ),
        (
            with(
                &[
                    "orbit",
                    "--potential",
                    "coulomb",
                    "--tau0",
                    "0.001",
                    "--times",
                    "1",
                ],
                &["--r0", "-1"],
            ),
            "r0",
        ),
        (
            with(
                &[
                    "orbit",
                    "--potential",
                    "coulomb",
                    "--tau0",
                    "0.001",
                    "--times",
                    "1",
                ],
                &["--eccentricity", "1"],
            ),
            "eccentricity",
        ),
        (
            with(
                &[
                    "orbit",
                    "--potential",
                    "coulomb",
                    "--tau0",
                    "0.001",
                    "--times",
                    "1",
                ],
                &["--eccentricity", "-0.1"],
            ),
            "eccentricity",
        ),
        (
            with(
                &["orbit", "--potential", "coulomb", "--tau0", "0.001"],
                &["--times", "2,1"],
            ),
            "times",
        ),
        (
            with(
                &["shell", "--delay", "0.03", "--times", "1"],
                &["--tau0", "0"],
            ),
            "tau0",
        ),
        (
            with(
                &["shell", "--tau0", "0.001", "--times", "1"],
                &["--delay", "0"],
            ),
            "delay",
        ),
        (
            with(
                &["shell", "--tau0", "0.001", "--times", "1"],
                &["--delay", "-1"],
            ),
            "delay",
        ),
        (
            with(
                &["shell", "--tau0", "0.01", "--times", "1"],
                &["--delay", "1e300"],
            ),
            "shorter --delay",
        ),
        (
            with(
                &["shell", "--tau0", "0.001", "--delay", "0.03"],
                &["--times", "1e12"],
            ),
            "RK4 steps",
        ),
        (
            with(
                &["shell", "--delay", "1", "--times", "0,1"],
                &["--tau0", "1e308"],
            ),
            "use a smaller --tau0 or --delay",
        ),
        (
            with(
                &["shell", "--delay", "1", "--times", "0,1"],
                &["--tau0", "1e-320"],
            ),
            "use a larger --tau0",
        ),
        (
            // t_last/tau0 overflows: said in words, never `inf`.
            with(
                &[
                    "orbit",
                    "--potential",
                    "coulomb",
                    "--tau0",
                    "0.01",
                    "--force",
                    "al",
                ],
                &["--times", "0,1e308"],
            ),
            "t_last/tau0, more than 1e308, exceeds",
        ),
        (with(&["plot"], &["--ratio", "0"]), "I3/I1"),
        (with(&["plot"], &["--t-end", "0"]), "t-end"),
        (with(&["plot"], &["--t-end", "-5"]), "t-end"),
        (with(&["plot"], &["--width", "3"]), "width"),
        (with(&["plot"], &["--width", "100000"]), "width"),
        (with(&["plot"], &["--width", "-3"]), "width"),
        (with(&["plot"], &["--height", "1"]), "height"),
        (with(&["plot"], &["--height", "1000"]), "height"),
        // A chart is drawn in single precision: beyond its range a curve was
        // inf (exit 3 after the header) or flat at 0 (exit 0).
        (
            with(&["plot"], &["--omega", "0,1e39,0"]),
            "single precision",
        ),
        (
            with(&["plot"], &["--omega", "0,1e-46,0"]),
            "single precision",
        ),
        (with(&["plot"], &["--t-end", "3.5e38"]), "single precision"),
        (with(&["plot"], &["--t-end", "1e-50"]), "single precision"),
        (
            with(
                &["bench", "--quick"],
                &["--out", "/nonexistent-spintop-dir/rows.csv"],
            ),
            "cannot write --out",
        ),
        (
            with(&["bench", "--quick"], &["--repeats", "2.5"]),
            "not a whole number",
        ),
        (with(&["tui"], &["--warp", "3"]), "warp"),
        (with(&["tui"], &["--ratio", "5"]), "I3/I1"),
        (with(&["tui"], &["--bench", "0"]), "bench"),
        (with(&["tui"], &["--bench", "1e9"]), "bench"),
        (with(&["tui"], &["--bench", "1e308"]), "bench"),
        (with(&["tui"], &["nosuch-scene"]), "nosuch-scene"),
        (with(&["tui"], &["coulomb-collapse"]), "top scenes"),
        (with(&["tui"], &[]), "terminal"),
        (with(&["stability"], &["--row", "0"]), "row"),
        (with(&["stability"], &["--row", "7"]), "row"),
        (with(&["stability"], &["--row", "x"]), "--row"),
        (with(&["figure"], &["3"]), "Figures 1 and 2"),
        (with(&["figure"], &["x"]), "Figures 1 and 2"),
        (
            with(&["figure"], &["1", "--svg", "/nonexistent-dir/f.svg"]),
            "nonexistent-dir",
        ),
        (with(&["bench", "--quick"], &["--width", "2"]), "width"),
        (with(&["bench", "--quick"], &["--height", "0"]), "height"),
        (
            with(&["bench"], &["--join", "/nonexistent.csv"]),
            "nonexistent.csv",
        ),
        (
            with(&["bench"], &["--join", "/dev/zero"]),
            "not a regular file",
        ),
        (with(&["bench"], &["--join", "/tmp"]), "folder"),
        (with(&["run"], &["/tmp"]), "folder"),
        (with(&["run"], &["/dev/zero"]), "not a regular file"),
        (with(&["run"], &["/dev/null"]), "not a regular file"),
        (with(&["run"], &["nosuch"]), "no such scene"),
        (
            with(&["run"], &["figure-1", "--format", "xml"]),
            "is not known; expected one of",
        ),
        (with(&["learn"], &["--chapter", "9.9"]), "no such chapter"),
        (with(&["learn"], &[]), "terminal"),
        (with(&["learn"], &["--course", "/tmp"]), "is not a course"),
        // --reset forgets the progress and exits: with --list it used to do
        // only the reset, silently.
        (
            with(&["learn"], &["--reset", "--list"]),
            "cannot be used with",
        ),
        (
            with(&["learn"], &["--course", "/tmp", "--no-grading"]),
            "cannot be used with",
        ),
        (with(&["course"], &["--course", "/tmp"]), "is not a course"),
        (
            with(&["course"], &["--course", "/nonexistent-course"]),
            "nonexistent-course",
        ),
        (
            with(&["course", "watch"], &["--course", "/tmp"]),
            "is not a course",
        ),
        (with(&["course", "export"], &["--out", "/tmp"]), "not empty"),
        (with(&["course", "export"], &[]), "--out"),
        (with(&["course", "hint"], &["nosuch"]), "no such assignment"),
        (with(&["course", "hint"], &[]), "<NAME>"),
        (
            with(&["course", "hint"], &["2.1", "--course", "/tmp"]),
            "is not a course",
        ),
        (with(&["course", "grade"], &[]), "<DIR>"),
        (
            with(&["course", "grade"], &["/tmp", "--jobs", "0"]),
            "--jobs",
        ),
        (
            with(&["course", "grade"], &["/tmp", "--timeout", "0"]),
            "--timeout",
        ),
        (
            with(&["course", "grade"], &["/tmp", "--test-timeout", "nan"]),
            "--test-timeout",
        ),
        (
            with(&["course", "grade"], &["/tmp", "--timeout", "1e300"]),
            "--timeout 1e300",
        ),
        (
            with(&["course", "grade"], &["/tmp", "--timeout", "-1"]),
            "--timeout -1",
        ),
        (
            with(
                &["course", "grade"],
                &["/tmp", "--out", "/nonexistent-dir/g.csv"],
            ),
            "nonexistent-dir",
        ),
        (
            with(
                &["course", "grade"],
                &["/tmp", "/var", "--format", "gradescope"],
            ),
            "--out",
        ),
        (
            with(
                &["course", "export"],
                &["--out", "/tmp/x", "--ci", "gitlab"],
            ),
            "is not known; expected one of",
        ),
        (
            with(&["course", "diagnose"], &["/nonexistent-wrong"]),
            "nonexistent-wrong",
        ),
        (with(&["course"], &["--seed", "x"]), "--seed"),
        (
            with(&["course"], &["--format", "xml"]),
            "is not known; expected one of",
        ),
        (with(&["book"], &["--port", "99999"]), "--port"),
        (
            with(
                &["simulate", "--model", "reduced", "--times", "1"],
                &["--inertia", "1,1,0.4"],
            ),
            "--dipole",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--times", "1"],
                &[
                    "--inertia",
                    "1,1,0.4",
                    "--dipole",
                    "0,0,1",
                    "--ratio",
                    "0.4",
                ],
            ),
            "--ratio",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--times", "1"],
                &[
                    "--inertia",
                    "1,1,0.4",
                    "--dipole",
                    "0,0,1",
                    "--method",
                    "exact",
                ],
            ),
            "no closed form",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "full",
                    "--times",
                    "1",
                    "--dipole",
                    "1,0.5,0.2",
                ],
                &["--inertia", "1,1,3"],
            ),
            "not a rigid body",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "full",
                    "--times",
                    "1",
                    "--inertia",
                    "1,2,2.5",
                ],
                &["--dipole", "0,0,0"],
            ),
            "dipole",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "full",
                    "--times",
                    "1",
                    "--inertia",
                    "1,2,2.5",
                ],
                &["--dipole", "nan,0,1"],
            ),
            "--dipole",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "reduced",
                    "--times",
                    "1",
                    "--dipole",
                    "1,0.5,0.2",
                ],
                &["--inertia", "1,1,3"],
            ),
            "not a rigid body",
        ),
        (
            with(
                &[
                    "simulate",
                    "--model",
                    "full",
                    "--times",
                    "1",
                    "--inertia",
                    "1,2,2.5",
                ],
                &["--dipole", "1,0.5,0.2", "--method", "dopri5"],
            ),
            "model (3.4) takes method auto",
        ),
        (
            with(
                &["simulate", "--model", "full", "--times", "1"],
                &["--inertia", "1,2,2.5"],
            ),
            "--dipole",
        ),
        // The live view and plot check a method against their models by the
        // same rule as simulate (sim::Model::check_method).
        (
            with(&["plot"], &["--method", "forward"]),
            "method forward is for the full model (3.4) only",
        ),
        (
            with(&["tui"], &["--method", "forward"]),
            "method forward is for the full model (3.4) only",
        ),
        (with(&["book"], &["--port", "x"]), "--port"),
        (with(&["nosuch-command"], &[]), "unrecognized subcommand"),
        (
            with(&["simulate"], &["--model", "reduced", "--t_end", "5"]),
            "--t-end",
        ),
        (
            with(&["simulate"], &["--model", "xml"]),
            "is not known; expected one of",
        ),
        (
            with(
                &["simulate", "--model", "reduced", "--t-end", "1"],
                &["--format", "xml"],
            ),
            "is not known; expected one of",
        ),
        (with(&["simulate"], &["--t-end", "5"]), "--model"),
        (with(&["balance"], &[]), "--dipole"),
        (with(&["orbit"], &["--potential", "coulomb"]), "--tau0"),
        (with(&["shell"], &["--tau0", "0.001"]), "--delay"),
    ];
    for (args, fragment) in ranges {
        cases.push(Case {
            args,
            code: 2,
            fragment: fragment.into(),
            full: false,
        });
    }
    // A model refuses the methods it would otherwise ignore.
    for method in ["exact", "dop853", "dopri5", "rk4"] {
        cases.push(case(
            &[
                "simulate", "--model", "full", "--t-end", "1", "--method", method,
            ],
            2,
            "the full model (3.4) takes method auto",
        ));
    }
    // 4. Costs checked before running: refused up front with the estimate.
    for args in [
        vec![
            "simulate",
            "--model",
            "full",
            "--t-end",
            "1e300",
            "--samples",
            "2",
        ],
        vec![
            "simulate",
            "--model",
            "full",
            "--omega",
            "0,1e50,1e50",
            "--t-end",
            "10",
        ],
        vec!["simulate", "--model", "full", "--t-end", "1e8"],
        vec![
            "simulate", "--model", "full", "--method", "forward", "--t-end", "1e9",
        ],
        vec!["simulate", "--model", "reduced", "--times", "1e308"],
        vec![
            "simulate", "--model", "reduced", "--method", "rk4", "--t-end", "1e6",
        ],
        vec![
            "simulate", "--model", "reduced", "--method", "rk4", "--step", "1e-9", "--t-end", "1",
        ],
        vec![
            "simulate",
            "--model",
            "reduced",
            "--method",
            "dop853",
            "--omega",
            "0,1e4,2e4",
            "--t-end",
            "100",
        ],
        vec![
            "simulate",
            "--model",
            "reduced",
            "--method",
            "dopri5",
            "--omega",
            "0,100,200",
            "--t-end",
            "1e4",
        ],
        vec![
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,2,3",
            "--dipole",
            "1,1,1",
            "--omega",
            "1e60,0,0",
            "--t-end",
            "10",
        ],
        vec![
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,2,3",
            "--dipole",
            "1,1,1",
            "--t-end",
            "1e12",
        ],
        vec![
            "simulate",
            "--model",
            "truncated",
            "--method",
            "dop853",
            "--t-end",
            "1e300",
        ],
        vec!["plot", "--log-time", "--t-end", "1e300"],
        vec!["plot", "--method", "rk4", "--t-end", "1e6"],
    ] {
        let fragment = "more than the 1e7 allowed";
        cases.push(Case {
            args: args.iter().map(|s| s.to_string()).collect(),
            code: 2,
            fragment: fragment.into(),
            full: false,
        });
    }
    // 5. Numerical failures: exit 3 with the time and advice that applies.
    let failures: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "simulate", "--model", "reduced", "--method", "rk4", "--step", "1000", "--omega",
                "0,1,2",
            ],
            "smaller --step",
        ),
        (
            vec![
                "simulate", "--model", "reduced", "--method", "rk4", "--step", "1000", "--omega",
                "0,1,2", "--format", "json",
            ],
            "at t =",
        ),
        (
            vec![
                "simulate", "--model", "reduced", "--method", "rk4", "--step", "1000", "--omega",
                "0,1,2", "--format", "csv",
            ],
            "at t =",
        ),
        (
            vec![
                "simulate", "--model", "reduced", "--method", "rk4", "--step", "0.5", "--omega",
                "0,10,20", "--t-end", "10",
            ],
            "--method exact",
        ),
        (
            vec![
                "simulate",
                "--model",
                "truncated",
                "--method",
                "rk4",
                "--step",
                "0.5",
                "--omega",
                "0,10,20",
                "--t-end",
                "10",
            ],
            "smaller --step",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0,1",
                "--rate",
                "1e308",
            ],
            "--rate",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0,1",
                "--rate",
                "1e200",
                "--format",
                "json",
            ],
            "--rate",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0,1",
                "--rate",
                "1e200",
                "--format",
                "csv",
            ],
            "--rate",
        ),
        (
            vec![
                "orbit",
                "--potential",
                "coulomb",
                "--tau0",
                "0.01",
                "--r0",
                "1e300",
                "--times",
                "1",
            ],
            "--r0",
        ),
        (
            vec![
                "simulate",
                "--model",
                "truncated",
                "--omega",
                "0,0,1e100",
                "--t-end",
                "1e300",
                "--samples",
                "3",
            ],
            "at t = 5.0000e299",
        ),
    ];
    for (args, fragment) in failures {
        cases.push(Case {
            args: args.iter().map(|s| s.to_string()).collect(),
            code: 3,
            fragment: fragment.into(),
            full: false,
        });
    }
    // A forward run of (3.4) writes the samples before its runaway and exits
    // 3 in every format, saying how many were omitted.
    for format in ["table", "csv", "json"] {
        cases.push(case(
            &[
                "simulate",
                "--model",
                "full",
                "--method",
                "forward",
                "--times",
                "0,1,2,5,10",
                "--format",
                format,
            ],
            3,
            "2 of 5 samples omitted",
        ));
    }
    // 6. Output that cannot be written: exit 1, one line.
    for args in [
        vec![
            "simulate",
            "--model",
            "reduced",
            "--t-end",
            "10",
            "--samples",
            "3",
        ],
        vec!["scenes"],
        vec!["figure", "1"],
        vec!["stability", "--row", "5"],
        vec!["balance", "--dipole", "loop", "--times", "0,1"],
        // The help too (it was written with its error dropped: exit 0).
        vec!["--help"],
        vec!["simulate", "--help"],
    ] {
        let mut c = case(&args, 1, "cannot write output");
        c.full = true;
        cases.push(c);
    }
    // 7. Broken scene files: refused with the file, the line and the key.
    let good_top = "[scene]\nname = \"x\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"reduced\"\nratio = 0.4\nomega = [0.0, 0.1, 0.2]\n\n[solve]\nt_end = 10.0\nsamples = 3\n";
    let broken: Vec<(&str, String, &str)> = vec![
        ("not-toml", "this is = = not toml".into(), "not-toml"),
        ("empty", String::new(), "scene"),
        ("no-kind", good_top.replace("kind = \"top\"\n", ""), "kind"),
        ("bad-kind", good_top.replace("kind = \"top\"", "kind = \"planet\""), "kind"),
        ("bad-model", good_top.replace("model = \"reduced\"", "model = \"magic\""), "model"),
        ("bad-ratio", good_top.replace("ratio = 0.4", "ratio = 3.0"), "ratio"),
        ("neg-ratio", good_top.replace("ratio = 0.4", "ratio = -0.4"), "ratio"),
        ("nan-ratio", good_top.replace("ratio = 0.4", "ratio = nan"), "ratio"),
        ("inf-ratio", good_top.replace("ratio = 0.4", "ratio = inf"), "ratio"),
        ("str-ratio", good_top.replace("ratio = 0.4", "ratio = \"big\""), "ratio"),
        ("short-omega", good_top.replace("omega = [0.0, 0.1, 0.2]", "omega = [0.0, 0.1]"), "expected 3 numbers, got 2"),
        ("long-omega", good_top.replace("omega = [0.0, 0.1, 0.2]", "omega = [0.0, 0.1, 0.2, 0.3]"), "expected 3 numbers, got 4"),
        ("huge-omega", good_top.replace("omega = [0.0, 0.1, 0.2]", "omega = [0.0, 1e200, 0.2]"), "omega"),
        ("neg-tend", good_top.replace("t_end = 10.0", "t_end = -10.0"), "t_end"),
        ("zero-samples", good_top.replace("samples = 3", "samples = 0"), "samples"),
        ("float-samples", good_top.replace("samples = 3", "samples = 1e308"), "samples: invalid type: floating point `1e308`"),
        ("huge-tend-rk4", good_top.replace("[solve]\n", "[solve]\nmethod = \"rk4\"\n").replace("t_end = 10.0", "t_end = 1e9"), "steps"),
        ("unknown-key", good_top.replace("ratio = 0.4", "ratio = 0.4\nspin = 3"), "spin"),
        ("unknown-table", format!("{good_top}\n[extra]\na = 1\n"), "extra"),
        ("bad-method", good_top.replace("[solve]\n", "[solve]\nmethod = \"euler\"\n"), "method"),
        ("dup-key", good_top.replace("ratio = 0.4", "ratio = 0.4\nratio = 0.5"), "duplicate key"),
        ("bad-times", good_top.replace("t_end = 10.0\nsamples = 3", "times = [3.0, 1.0]"), "times"),
        ("both-times", good_top.replace("t_end = 10.0", "t_end = 10.0\ntimes = [1.0]"), "times"),
        ("shell-neg-delay", "[scene]\nname = \"s\"\nkind = \"shell\"\ndescription = \"d\"\n\n[shell]\ntau0 = 1e-3\ndelay = -0.03\n\n[solve]\ntimes = [1.0]\n".into(), "delay"),
        ("shell-zero-tau", "[scene]\nname = \"s\"\nkind = \"shell\"\ndescription = \"d\"\n\n[shell]\ntau0 = 0.0\ndelay = 0.03\n\n[solve]\ntimes = [1.0]\n".into(), "tau0"),
    ];
    for (name, body, fragment) in broken {
        let path = scene_file(dir, name, &body);
        cases.push(Case {
            args: vec!["run".into(), path],
            code: 2,
            fragment: fragment.into(),
            full: false,
        });
    }
    // 8. Edge values that are valid: exit 0, finite output.
    let edges: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--ratio",
                "2",
                "--t-end",
                "10",
                "--samples",
                "3",
            ],
            "reduced",
        ),
        (
            vec![
                "simulate",
                "--model",
                "truncated",
                "--ratio",
                "1e-6",
                "--t-end",
                "10",
                "--samples",
                "3",
            ],
            "truncated",
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--omega",
                "0,0,0",
                "--t-end",
                "10",
                "--samples",
                "3",
            ],
            "reduced",
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--omega",
                "1e-300,0,1e-300",
                "--t-end",
                "10",
                "--samples",
                "3",
            ],
            "reduced",
        ),
        (
            vec![
                "simulate", "--model", "reduced", "--times", "0", "--format", "json",
            ],
            "samples",
        ),
        (
            vec![
                "simulate", "--model", "reduced", "--times", "0,0,0", "--format", "csv",
            ],
            "omega1",
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--euler",
                "0,0,0",
                "--t-end",
                "10",
                "--samples",
                "2",
            ],
            "reduced",
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--euler",
                "0,3.141592653589793,0",
                "--t-end",
                "10",
                "--samples",
                "2",
            ],
            "reduced",
        ),
        (
            vec![
                "simulate",
                "--model",
                "general",
                "--inertia",
                "1e300,1e300,1e300",
                "--dipole",
                "1,0,0",
                "--t-end",
                "10",
                "--samples",
                "2",
            ],
            "general",
        ),
        (
            vec![
                "simulate",
                "--model",
                "full",
                "--t-end",
                "10",
                "--samples",
                "3",
                "--format",
                "json",
            ],
            "physical",
        ),
        (
            vec![
                "simulate", "--model", "full", "--method", "forward", "--times", "0,1,2",
            ],
            "forward",
        ),
        (
            vec![
                "simulate",
                "--model",
                "reduced",
                "--rtol",
                "1e-14",
                "--t-end",
                "10",
                "--samples",
                "2",
                "--method",
                "dop853",
            ],
            "dop853",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0",
                "--cone",
                "0",
            ],
            "precessing",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0",
                "--cone",
                "3.141592653589793",
            ],
            "precessing",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0",
                "--rate",
                "-1",
            ],
            "precessing",
        ),
        (
            vec![
                "balance",
                "--dipole",
                "precessing",
                "--times",
                "0",
                "--rate",
                "1e50",
                "--format",
                "json",
            ],
            "precessing",
        ),
        (
            vec![
                "orbit",
                "--potential",
                "harmonic",
                "--tau0",
                "1e-12",
                "--times",
                "1",
                "--force",
                "al",
            ],
            "harmonic",
        ),
        (
            vec![
                "orbit",
                "--potential",
                "coulomb",
                "--tau0",
                "1e-6",
                "--eccentricity",
                "0.99",
                "--times",
                "1",
            ],
            "coulomb",
        ),
        (vec!["plot", "--width", "16", "--height", "2"], "plot"),
        (vec!["plot", "--log-time", "--t-end", "1e6"], "plot"),
        (vec!["scenes"], "figure-1"),
        (vec!["run", "figure-2", "--format", "json"], "figure-2"),
        (vec!["learn", "--list"], "Section 4.2"),
        (vec!["--version"], "spintop"),
    ];
    for (args, fragment) in edges {
        cases.push(case(&args, 0, fragment));
    }
    cases.extend(extremes(dir));
    cases
}

/// Extreme values a user can type: each echoed short in its message (never
/// three hundred digits), refused or answered with advice that fits what
/// was asked, in one line.
fn extremes(dir: &std::path::Path) -> Vec<Case> {
    let sim = |extra: &[&str]| with(&["simulate", "--model", "reduced"], extra);
    let mut cases = vec![
        // Each value is echoed in exponent form.
        Case {
            args: sim(&["--rtol", "1e300"]),
            ..case(&[], 2, "1e300")
        },
        Case {
            args: sim(&["--rtol", "-1e-300"]),
            ..case(&[], 2, "-1e-300")
        },
        Case {
            args: sim(&["--method", "rk4", "--step", "-1e300"]),
            ..case(&[], 2, "-1e300")
        },
        Case {
            args: sim(&["--times", "5,-1e300"]),
            ..case(&[], 2, "-1e300")
        },
        Case {
            args: sim(&["--times", "5,1e-300"]),
            ..case(&[], 2, "1e-300")
        },
        Case {
            args: sim(&["--t-end", "-1e300"]),
            ..case(&[], 2, "-1e300")
        },
        case(&["plot", "--t-end", "-1e300"], 2, "-1e300"),
        case(
            &[
                "orbit",
                "--potential",
                "coulomb",
                "--tau0",
                "1e-3",
                "--rtol",
                "1e300",
                "--times",
                "1",
            ],
            2,
            "1e300",
        ),
        // The step count of a run to t = 1e308 overflows: said in words, the
        // time in exponent form.
        case(
            &[
                "shell", "--tau0", "1e-3", "--delay", "0.03", "--times", "0,1e308",
            ],
            2,
            "1e308",
        ),
        case(&["tui", "--bench", "1e300"], 2, "1e300"),
        // A delay of 1e300 needs 5e302 steps per delay, not the 1.8e19 of a
        // saturated integer.
        case(
            &[
                "shell", "--tau0", "1e-3", "--delay", "1e300", "--times", "0,1",
            ],
            2,
            "(5.0e302 per delay",
        ),
        // Evenly spaced times up to a last time near the largest double: the
        // spacing does not overflow on the way.
        case(
            &[
                "simulate",
                "--model",
                "truncated",
                "--t-end",
                "1e306",
                "--samples",
                "200",
            ],
            0,
            "truncated",
        ),
        // The oscillator under the Landau-Lifshitz force is overdamped for
        // tau0 >= 2: no orbit, and its closed-form mode does not exist.
        case(
            &[
                "orbit",
                "--potential",
                "harmonic",
                "--tau0",
                "3",
                "--times",
                "0,1",
            ],
            2,
            "tau0",
        ),
        case(
            &[
                "orbit",
                "--potential",
                "harmonic",
                "--tau0",
                "2",
                "--times",
                "0,1",
                "--format",
                "json",
            ],
            2,
            "tau0",
        ),
        // An unstable shell that runs away: one line, the error.
        case(
            &[
                "shell", "--tau0", "1e-3", "--delay", "1.5e-3", "--times", "0,1,20",
            ],
            3,
            "unstable",
        ),
        // A closed form asked for a time near the largest double, the top at
        // rest: the advice is an earlier time (a smaller omega cannot help).
        case(
            &[
                "simulate",
                "--model",
                "truncated",
                "--omega",
                "0,0,0",
                "--times",
                "1e308",
            ],
            3,
            "earlier",
        ),
        // A general top's overflow names its own inputs and units.
        case(
            &[
                "simulate",
                "--model",
                "general",
                "--inertia",
                "1,1,1",
                "--dipole",
                "1e300,0,0",
                "--t-end",
                "1",
            ],
            3,
            "--dipole",
        ),
        // The full ALE of a general top whose linearisation overflows: a
        // numerical failure at once, never an eigenvalue search for ever.
        case(
            &[
                "simulate",
                "--model",
                "full",
                "--inertia",
                "1,1,1",
                "--dipole",
                "1e100,0,0",
                "--t-end",
                "1",
            ],
            3,
            "--dipole",
        ),
        // A rate so slow that its period overflows a double is refused.
        case(
            &[
                "balance",
                "--dipole",
                "precessing",
                "--rate",
                "1e-308",
                "--times",
                "0",
            ],
            2,
            "rate",
        ),
        case(
            &[
                "balance", "--dipole", "dumbbell", "--rate", "5e-324", "--times", "0",
            ],
            2,
            "rate",
        ),
    ];
    // Runs refused for their cost whose estimate overflows a double: the
    // count is said in words, never `inf`.
    cases.extend([
        case(
            &[
                "simulate", "--model", "reduced", "--method", "rk4", "--step", "1e-320", "--t-end",
                "1",
            ],
            2,
            "more than 1e308 steps",
        ),
        case(
            &[
                "simulate", "--model", "reduced", "--method", "dopri5", "--t-end", "1e308",
            ],
            2,
            "more than 1e308 steps",
        ),
        case(
            &["simulate", "--model", "full", "--t-end", "1e308"],
            2,
            "more than 1e308 steps",
        ),
    ]);
    let scenes = [
        (
            "extreme-rk4-step",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"reduced\"\n\n[solve]\ntimes = [1e300]\nmethod = \"rk4\"\nstep = 1e-300\n",
            2,
            "more than 1e308 steps",
        ),
        // An asymmetric top asked about t = 1e300: the advice is the longest
        // run stepping holds (about 1.2e3 u here), not `times up to 0`.
        (
            "extreme-general-far",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"general\"\ninertia = [1.0, 2.0, 3.0]\ndipole = [1.0, 0.0, 0.0]\n\n[solve]\ntimes = [1e300]\n",
            2,
            "ask for times up to 1",
        ),
        (
            "extreme-times",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"truncated\"\n\n[solve]\ntimes = [1.0, -1e300]\n",
            2,
            "-1e300",
        ),
        (
            "extreme-shell",
            "[scene]\nname = \"s\"\nkind = \"shell\"\ndescription = \"d\"\n\n[shell]\ntau0 = 1e-3\ndelay = 0.03\n\n[solve]\ntimes = [0.0, 1e308]\n",
            2,
            "1e308",
        ),
        (
            // No characteristic root: bad input named in the scene's words
            // (was exit 3, "try a smaller --delay").
            "extreme-shell-tau0",
            "[scene]\nname = \"s\"\nkind = \"shell\"\ndescription = \"d\"\n\n[shell]\ntau0 = 1e308\ndelay = 1.0\n\n[solve]\ntimes = [0.0, 1.0]\n",
            2,
            "use a smaller [shell] tau0 or [shell] delay",
        ),
        (
            // A spin that is 0 in units of tau: refused, not run as a top at
            // rest whose report contradicted the scene's tilt.
            "extreme-slow-spin",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"auto\"\n\n[units]\nshape = \"cylinder\"\nradius_nm = 50.0\nlength_nm = 200.0\ndensity_kg_m3 = 2200.0\ndipole_debye = 1e3\nspin_hz = 1e-300\n",
            2,
            "spin_hz = 1e-300 is 0 in the model's unit of time",
        ),
        (
            // The same for a general particle's omega_hz.
            "extreme-slow-omega-hz",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"auto\"\n\n[units]\nshape = \"ellipsoid\"\nsemi_axes_nm = [20.0, 30.0, 50.0]\ndensity_kg_m3 = 2200.0\ndipole_vector_debye = [0.0, 0.0, 1e3]\nomega_hz = [1e-300, 1e-300, 1e-300]\n",
            2,
            "omega_hz is 0 in the model's unit of time",
        ),
        (
            // A delay longer than the run: a shorter delay, not a longer one.
            "extreme-shell-delay",
            "[scene]\nname = \"s\"\nkind = \"shell\"\ndescription = \"d\"\n\n[shell]\ntau0 = 1e-3\ndelay = 1e300\n\n[solve]\ntimes = [0.0, 1.0]\n",
            2,
            "expected a shorter [shell] delay",
        ),
        (
            "extreme-oscillator",
            "[scene]\nname = \"s\"\nkind = \"orbit\"\ndescription = \"d\"\n\n[orbit]\npotential = \"harmonic\"\ntau0 = 3.0\nforce = \"ll\"\n\n[solve]\ntimes = [0.0, 1.0]\n",
            2,
            "tau0",
        ),
        (
            "extreme-rate",
            "[scene]\nname = \"s\"\nkind = \"balance\"\ndescription = \"d\"\n\n[balance]\ndipole = \"precessing\"\nrate = 1e-308\n\n[solve]\ntimes = [0.0, 1.0]\n",
            2,
            "rate",
        ),
        // A result that overflows: the advice is said once, after the gate's
        // own sentence.
        (
            "extreme-torque",
            "[scene]\nname = \"s\"\nkind = \"balance\"\ndescription = \"d\"\n\n[balance]\ndipole = \"precessing\"\nrate = 1e200\n\n[solve]\ntimes = [0.0, 1.0]\n",
            3,
            "computation; ask for smaller rates",
        ),
        (
            "extreme-evenly",
            "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"truncated\"\n\n[solve]\nt_end = 1e306\nsamples = 200\n",
            0,
            "truncated",
        ),
    ];
    for (name, body, code, fragment) in scenes {
        let path = scene_file(dir, name, body);
        cases.push(case(&["run", &path, "--format", "json"], code, fragment));
    }
    // A general top whose radiation share overflows: said in words.
    let share = scene_file(
        dir,
        "extreme-share",
        "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"auto\"\ninertia = [1e-300, 1.0, 1.0]\ndipole = [1e300, 0.0, 0.0]\n",
    );
    cases.push(case(&["run", &share], 2, "more than 1e308 per radian"));
    // A reduced top spun to 1e100 and asked about t = 1e-200: its
    // warnings (tau k, the Euler pole) write both numbers short.
    let spun = scene_file(
        dir,
        "extreme-warnings",
        "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"reduced\"\nomega = [0.0, 0.0, 1e100]\n\n[solve]\ntimes = [1e-200]\n",
    );
    cases.push(case(&["run", &spun], 0, "tau k = 4.000e99"));
    // A forward run of (2.5) that runs away: the advice names the scene's
    // key, not the command line's flag.
    let forward = scene_file(
        dir,
        "extreme-orbit-forward",
        "[scene]\nname = \"s\"\nkind = \"orbit\"\ndescription = \"d\"\n\n[orbit]\npotential = \"coulomb\"\ntau0 = 1e-3\nforce = \"al-forward\"\n\n[solve]\ntimes = [0.0, 1.0, 1e4]\n",
    );
    cases.push(case(&["run", &forward], 3, "[orbit] force = \"al\""));
    cases
}

#[test]
fn the_bad_input_corpus_holds_the_command_line_contract() {
    let dir = std::env::temp_dir().join(format!("spintop-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let cases = corpus(&dir);
    assert!(cases.len() >= 250, "the corpus has {} cases", cases.len());
    // Two workers per core at most: the cases are small processes.
    let workers = thread::available_parallelism()
        .map_or(2, |n| n.get())
        .clamp(2, 8);
    let chunks: Vec<Vec<Case>> = (0..workers)
        .map(|w| cases.iter().skip(w).step_by(workers).cloned().collect())
        .collect();
    let handles: Vec<_> = chunks
        .into_iter()
        .map(|chunk| {
            thread::spawn(move || {
                chunk
                    .iter()
                    .filter_map(|c| check(c).map(|p| format!("spintop {}: {p}", c.args.join(" "))))
                    .collect::<Vec<_>>()
            })
        })
        .collect();
    let failures: Vec<String> = handles
        .into_iter()
        .flat_map(|h| h.join().expect("a worker"))
        .collect();
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        failures.is_empty(),
        "{} of {} cases break the contract:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
