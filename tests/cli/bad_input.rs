//! The bad-input corpus: several hundred bad, edge and numerically hard
//! invocations of the command line (`tests/cli/corpus.toml`), each with the
//! exit code and a fragment of the message a user should get.
//!
//! Every case must hold the command-line contract: it ends; a refusal or
//! failure prints exactly one line on stderr, starting `spintop: error:`,
//! naming what was wrong; the exit code is the documented one (2 bad input,
//! 3 numerical failure, 1 output not writable, 0 success); nothing panics or
//! aborts; and no output, on success or failure, holds a NaN, an infinity or
//! a JSON `null` standing for one.
//!
//! The cases run in this process, through `spintop_app::cli::run_code` (the
//! function `main` calls), on threads: several hundred of them take well
//! under a second. A handful run as real processes of the `spintop` binary
//! as well: what needs a process (no terminal: `spintop` and `spintop learn`
//! refuse to start their screens; the output on a full disk, `/dev/full`),
//! and a sample of the rest, which must answer exactly as they do in
//! process.

use std::io::{self, Read, Write};
use std::path::Path;
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
    /// Stdout goes to a full disk instead of a pipe.
    full: bool,
}

/// The corpus file's cases, with `{dir}` read as `dir`, after writing its
/// files there.
fn corpus(dir: &Path) -> Vec<Case> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cli/corpus.toml");
    let data: toml::Table = std::fs::read_to_string(&path)
        .expect("the corpus file")
        .parse()
        .expect("the corpus parses");
    let dir_text = dir.display().to_string();
    for file in data["file"].as_array().expect("[[file]]") {
        let name = file["name"].as_str().expect("a file's name");
        let text = file["text"].as_str().expect("a file's text");
        std::fs::write(dir.join(name), text).expect("a corpus file written");
    }
    data["case"]
        .as_array()
        .expect("[[case]]")
        .iter()
        .map(|c| Case {
            args: c["args"]
                .as_array()
                .expect("args")
                .iter()
                .map(|a| a.as_str().expect("an argument").replace("{dir}", &dir_text))
                .collect(),
            code: c["code"].as_integer().expect("code") as i32,
            fragment: c["says"]
                .as_str()
                .expect("says")
                .replace("{dir}", &dir_text),
            full: c.get("stdout").and_then(|s| s.as_str()) == Some("full"),
        })
        .collect()
}

/// A writer that is a full disk: every write fails as /dev/full's does.
struct Full;

impl Write for Full {
    fn write(&mut self, _: &[u8]) -> io::Result<usize> {
        Err(io::Error::from_raw_os_error(28))
    }
    fn flush(&mut self) -> io::Result<()> {
        Err(io::Error::from_raw_os_error(28))
    }
}

/// Runs a case in this process; returns (exit code, stdout, stderr).
fn run_in_process(c: &Case) -> Result<(i32, String, String), String> {
    let args = std::iter::once("spintop".to_string()).chain(c.args.iter().cloned());
    let mut stdout = Vec::new();
    let mut stderr = Vec::new();
    let code = if c.full {
        spintop_app::cli::run_code(args, &mut Full, &mut stderr)
    } else {
        spintop_app::cli::run_code(args, &mut stdout, &mut stderr)
    };
    Ok((
        i32::from(code),
        String::from_utf8_lossy(&stdout).into_owned(),
        String::from_utf8_lossy(&stderr).into_owned(),
    ))
}

/// Whether a case needs a process of its own: the live view and `learn`
/// without a subcommand look for a terminal (in process they would find the
/// test's own, if it has one).
fn needs_a_process(c: &Case) -> bool {
    matches!(c.args.first().map(String::as_str), Some("tui" | "learn"))
        && !c
            .args
            .iter()
            .skip(1)
            .any(|a| a.starts_with('-') || a.contains('.'))
        || c.args.is_empty()
}

/// Runs a case with a time limit; returns (exit code, stdout, stderr).
fn run_process(c: &Case) -> Result<(i32, String, String), String> {
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
fn check(c: &Case, in_process: bool) -> Option<String> {
    let ran = if in_process {
        run_in_process(c)
    } else {
        run_process(c)
    };
    let (code, stdout, stderr) = match ran {
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

#[test]
fn the_bad_input_corpus_holds_the_command_line_contract() {
    let dir = std::env::temp_dir().join(format!("spintop-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let cases = corpus(&dir);
    assert!(cases.len() >= 500, "the corpus has {} cases", cases.len());
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
                    .filter_map(|c| {
                        check(c, !needs_a_process(c))
                            .map(|p| format!("spintop {}: {p}", c.args.join(" ")))
                    })
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

/// The real binary answers as the function does: every case that writes to
/// a full disk (a real /dev/full) and one case in twenty of the rest, run
/// as processes, give the same exit code, stdout and stderr as in process.
#[test]
fn the_binary_answers_the_corpus_as_the_function_does() {
    let dir = std::env::temp_dir().join(format!("spintop-corpus-bin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let cases = corpus(&dir);
    let sample: Vec<&Case> = cases
        .iter()
        .enumerate()
        .filter(|(i, c)| (c.full || i % 20 == 0) && !needs_a_process(c))
        .map(|(_, c)| c)
        .collect();
    assert!(sample.len() >= 25, "{}", sample.len());
    let mut differ = Vec::new();
    for c in sample {
        if let Some(p) = check(c, false) {
            differ.push(format!("spintop {}: {p}", c.args.join(" ")));
            continue;
        }
        let (a, b) = (run_process(c), run_in_process(c));
        // The full disk's output is not read back; the rest must agree byte for byte.
        if a != b && !(c.full && a.as_ref().map(|r| (r.0, &r.2)) == b.as_ref().map(|r| (r.0, &r.2)))
        {
            differ.push(format!(
                "spintop {}: process {a:?}, in process {b:?}",
                c.args.join(" ")
            ));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(differ.is_empty(), "{}", differ.join("\n"));
}
