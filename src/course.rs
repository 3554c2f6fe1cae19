//! The course: the assignments of `lessons/` in course order, and their state
//! as `cargo test -p spintop-lessons` grades them.
//!
//! A shared layer below the shells: `spintop course` prints it as text and
//! `spintop learn` can show it in its panel; neither parses the other's output.
//! It runs cargo (a child process) and reads its output, so it is not part of
//! the pure core.
//!
//! The graders' verdicts come from the test harness's own lines
//! (`test eq_2_1_larmor_rate ... ok`) and, for a failure, from the grader's
//! report that the harness prints under `---- eq_2_1_larmor_rate stdout ----`:
//! the equation, the input, what was expected, what came back, and the hint.

use std::path::Path;
use std::process::Command;

/// One assignment: the grader's test, its place in the book and the file and
/// function the student fills in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Assignment {
    /// The grader's test binary (`lessons/tests/NAME.rs`).
    pub binary: &'static str,
    /// The grader's test function.
    pub test: &'static str,
    /// The equation, as the paper numbers it.
    pub equation: &'static str,
    /// The book chapter that explains it.
    pub chapter: &'static str,
    /// The file and function to fill in.
    pub file: &'static str,
    /// The function's name.
    pub function: &'static str,
}

/// The course, in the order the book teaches it.
pub const COURSE: [Assignment; 11] = [
    Assignment {
        binary: "ch2",
        test: "eq_2_1_larmor_rate",
        equation: "(2.1)",
        chapter: "Section 2",
        file: "lessons/src/ch2.rs",
        function: "larmor_rate",
    },
    Assignment {
        binary: "ch2",
        test: "eq_2_2_torque_rate",
        equation: "(2.2)",
        chapter: "Section 2",
        file: "lessons/src/ch2.rs",
        function: "torque_rate",
    },
    Assignment {
        binary: "ch2",
        test: "eq_2_4_schott_angular_momentum",
        equation: "(2.4)",
        chapter: "Section 2",
        file: "lessons/src/ch2.rs",
        function: "schott_angular_momentum",
    },
    Assignment {
        binary: "ch2",
        test: "eq_2_3_axial_schott_rate",
        equation: "(2.3)-(2.4)",
        chapter: "Section 2",
        file: "lessons/src/ch2.rs",
        function: "axial_schott_rate",
    },
    Assignment {
        binary: "ch3",
        test: "eq_3_3_truncated_ale_rhs",
        equation: "(3.3)",
        chapter: "Section 3",
        file: "lessons/src/ch3.rs",
        function: "truncated_ale_rhs",
    },
    Assignment {
        binary: "numerics",
        test: "eq_3_5_euler_from_rotation",
        equation: "(3.5)",
        chapter: "Section 3",
        file: "lessons/src/numerics.rs",
        function: "euler_from_rotation",
    },
    Assignment {
        binary: "ch4",
        test: "eq_4_11_precession_tilt",
        equation: "(4.11)",
        chapter: "Section 4.1",
        file: "lessons/src/ch4.rs",
        function: "precession_tilt",
    },
    Assignment {
        binary: "ch4",
        test: "eq_4_15_eq_4_16_reduced_closed_form",
        equation: "(4.15)-(4.16)",
        chapter: "Section 4.2",
        file: "lessons/src/ch4.rs",
        function: "reduced_closed_form",
    },
    Assignment {
        binary: "numerics",
        test: "rk4_step",
        equation: "RK4",
        chapter: "Numerical methods",
        file: "lessons/src/numerics.rs",
        function: "rk4_step",
    },
    Assignment {
        binary: "numerics",
        test: "dp5_step",
        equation: "DP5",
        chapter: "Numerical methods",
        file: "lessons/src/numerics.rs",
        function: "dp5_step",
    },
    Assignment {
        binary: "appendix",
        test: "eq_a_1_shell_acceleration",
        equation: "(A.1)",
        chapter: "Appendix",
        file: "lessons/src/appendix.rs",
        function: "shell_acceleration",
    },
];

/// Where an assignment stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum State {
    /// The stub is untouched (it still panics with `todo!()`).
    NotStarted,
    /// The grader rejected the answer; the grader's report.
    Failing(String),
    /// The grader accepted it.
    Passing,
    /// The lessons crate did not compile; the compiler's first error.
    DoesNotCompile(String),
    /// The grader's test did not report (not found in the output).
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
            State::Unknown => "not graded",
        }
    }
}

/// The course's state after one grading run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    /// Each assignment of [`COURSE`] with its state, in course order.
    pub states: Vec<(Assignment, State)>,
}

impl Status {
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
}

/// Reads the harness's output of `cargo test -p spintop-lessons` into the
/// course's state. `output` is stdout and stderr together.
pub fn parse(output: &str) -> Status {
    let compile_error = output
        .lines()
        .find(|l| l.starts_with("error[") || l.starts_with("error: could not compile"))
        .map(|first| {
            // The first real compiler error, not cargo's summary, if there is one.
            output
                .lines()
                .find(|l| {
                    l.starts_with("error[")
                        || (l.starts_with("error:") && !l.contains("could not compile"))
                })
                .unwrap_or(first)
                .to_string()
        });
    let states = COURSE
        .iter()
        .map(|a| {
            let ok = format!("test {} ... ok", a.test);
            let failed = format!("test {} ... FAILED", a.test);
            let state = if output.lines().any(|l| l.trim() == ok) {
                State::Passing
            } else if output.lines().any(|l| l.trim() == failed) {
                let report = report(output, a.test);
                if report.contains("not yet implemented") || report.contains("not implemented") {
                    State::NotStarted
                } else {
                    State::Failing(report)
                }
            } else if let Some(e) = &compile_error {
                State::DoesNotCompile(e.clone())
            } else {
                State::Unknown
            };
            (*a, state)
        })
        .collect();
    Status { states }
}

/// The grader's report for `test`: the lines under `---- TEST stdout ----`
/// up to the next section, without the harness's own noise.
fn report(output: &str, test: &str) -> String {
    let header = format!("---- {test} stdout ----");
    let Some(start) = output.find(&header) else {
        return String::new();
    };
    let body = &output[start + header.len()..];
    let end = [
        body.find("\n---- "),
        body.find("\nfailures:"),
        body.find("\n\nfailures:"),
    ]
    .into_iter()
    .flatten()
    .min()
    .unwrap_or(body.len());
    body[..end]
        .lines()
        .filter(|l| {
            let t = l.trim();
            !(t.starts_with("thread '")
                || t.starts_with("note: run with")
                || t.starts_with("stack backtrace"))
        })
        .collect::<Vec<_>>()
        .join("\n")
        .trim()
        .to_string()
}

/// Grades the course in the repository at `repo`: runs
/// `cargo test -p spintop-lessons --no-fail-fast` (no backtraces, no colour)
/// and reads its output; with `solutions`, the instructor's reference
/// solutions are graded instead of the student's files. An error is a reason
/// cargo could not be run at all.
pub fn grade(repo: &Path, solutions: bool) -> Result<Status, String> {
    let mut args = vec![
        "test",
        "-p",
        "spintop-lessons",
        "--no-fail-fast",
        "--color",
        "never",
    ];
    if solutions {
        args.extend(["--features", "solutions"]);
    }
    args.extend(["--", "--color", "never"]);
    let out = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .current_dir(repo)
        .args(&args)
        .env("RUST_BACKTRACE", "0")
        .env_remove("CARGO_TARGET_DIR")
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let text = format!(
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(parse(&text))
}

/// The newest modification time of the student's files (`lessons/src/*.rs`).
pub fn sources_stamp(repo: &Path) -> Option<std::time::SystemTime> {
    std::fs::read_dir(repo.join("lessons").join("src"))
        .ok()?
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "rs"))
        .filter_map(|e| e.metadata().ok()?.modified().ok())
        .max()
}

/// What a [`Watch`] reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Report {
    /// A grading run started (a file was saved, or the watch began).
    Grading,
    /// A grading run ended.
    Graded(Status),
    /// Cargo could not be run.
    Failed(String),
}

/// Grades the course in the background, once at the start and again each
/// time a file under `lessons/src` is saved (polled every half second). The
/// grading runs stop with the watch: dropping it ends the thread and kills a
/// cargo still running.
pub struct Watch {
    reports: std::sync::mpsc::Receiver<Report>,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Watch {
    /// Starts watching the course in `repo`.
    pub fn start(repo: &Path) -> Self {
        use std::sync::atomic::Ordering;
        let (tx, reports) = std::sync::mpsc::channel();
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let stop_thread = std::sync::Arc::clone(&stop);
        let repo = repo.to_path_buf();
        let thread = std::thread::spawn(move || {
            let mut graded_stamp = None;
            while !stop_thread.load(Ordering::Relaxed) {
                let stamp = sources_stamp(&repo);
                if graded_stamp.is_none() || stamp != graded_stamp.flatten() {
                    graded_stamp = Some(stamp);
                    if tx.send(Report::Grading).is_err() {
                        return;
                    }
                    let report = match grade_cancellable(&repo, &stop_thread) {
                        Ok(Some(status)) => Report::Graded(status),
                        Ok(None) => return,
                        Err(e) => Report::Failed(e),
                    };
                    if tx.send(report).is_err() {
                        return;
                    }
                }
                std::thread::sleep(std::time::Duration::from_millis(500));
            }
        });
        Watch {
            reports,
            stop,
            thread: Some(thread),
        }
    }

    /// The reports since the last call, oldest first.
    pub fn poll(&self) -> Vec<Report> {
        self.reports.try_iter().collect()
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// [`grade`] as a child process that is killed when `stop` is set; `None`
/// when it was.
fn grade_cancellable(
    repo: &Path,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<Option<Status>, String> {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .current_dir(repo)
        .args([
            "test",
            "-p",
            "spintop-lessons",
            "--no-fail-fast",
            "--color",
            "never",
            "--",
            "--color",
            "never",
        ])
        .env("RUST_BACKTRACE", "0")
        .env_remove("CARGO_TARGET_DIR")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let mut out = child.stdout.take();
    let mut err = child.stderr.take();
    let t_out = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(o) = out.as_mut() {
            let _ = o.read_to_string(&mut s);
        }
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(e) = err.as_mut() {
            let _ = e.read_to_string(&mut s);
        }
        s
    });
    loop {
        if stop.load(std::sync::atomic::Ordering::Relaxed) {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(None);
        }
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) => std::thread::sleep(std::time::Duration::from_millis(50)),
            Err(e) => return Err(e.to_string()),
        }
    }
    let text = format!(
        "{}\n{}",
        t_out.join().unwrap_or_default(),
        t_err.join().unwrap_or_default()
    );
    Ok(Some(parse(&text)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What libtest printed for a run with one pass, one stub and one wrong
    /// answer (the shape of its output, written out by hand).
    const SAMPLE: &str = "\
running 4 tests
test eq_2_1_larmor_rate ... ok
test eq_2_2_torque_rate ... FAILED
test eq_2_4_schott_angular_momentum ... FAILED
test eq_2_3_axial_schott_rate ... ok

failures:

---- eq_2_2_torque_rate stdout ----

thread 'eq_2_2_torque_rate' panicked at lessons/src/ch2.rs:20:5:
not yet implemented
note: run with `RUST_BACKTRACE=1` environment variable to display a backtrace

---- eq_2_4_schott_angular_momentum stdout ----

thread 'eq_2_4_schott_angular_momentum' panicked at src/grading.rs:88:9:

schott_angular_momentum, Eq. (2.4): wrong answer
  input: ...
  expected: (0, 0, 1)
  got: (0, 0, -1)
  hint: check the sign


failures:
    eq_2_2_torque_rate
    eq_2_4_schott_angular_momentum

test result: FAILED. 2 passed; 2 failed; 0 ignored; 0 measured; 0 filtered out
";

    #[test]
    fn the_harness_output_becomes_one_state_per_assignment() {
        let status = parse(SAMPLE);
        let state = |name: &str| {
            status
                .states
                .iter()
                .find(|(a, _)| a.test == name)
                .unwrap()
                .1
                .clone()
        };
        assert_eq!(state("eq_2_1_larmor_rate"), State::Passing);
        assert_eq!(state("eq_2_2_torque_rate"), State::NotStarted);
        let State::Failing(report) = state("eq_2_4_schott_angular_momentum") else {
            panic!("failing")
        };
        assert!(
            report.starts_with("schott_angular_momentum, Eq. (2.4)") && report.contains("hint:"),
            "{report}"
        );
        assert!(!report.contains("thread '"), "{report}");
        assert_eq!(state("eq_3_3_truncated_ale_rhs"), State::Unknown);
        assert_eq!(status.passing(), 2);
        assert_eq!(status.next().unwrap().0.test, "eq_2_2_torque_rate");
    }

    #[test]
    fn a_compile_error_is_reported_for_every_ungraded_assignment() {
        let status = parse(
            "error[E0308]: mismatched types\n --> lessons/src/ch2.rs:3:5\nerror: could not compile `spintop-lessons`\n",
        );
        assert!(
            status
                .states
                .iter()
                .all(|(_, s)| matches!(s, State::DoesNotCompile(e) if e.contains("E0308")))
        );
        assert_eq!(status.passing(), 0);
    }

    #[test]
    fn every_assignment_names_a_real_test_and_function() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for a in COURSE {
            let tests = std::fs::read_to_string(
                root.join("lessons/tests").join(format!("{}.rs", a.binary)),
            )
            .unwrap();
            assert!(tests.contains(&format!("fn {}()", a.test)), "{a:?}");
            let src = std::fs::read_to_string(root.join(a.file)).unwrap();
            assert!(src.contains(&format!("pub fn {}", a.function)), "{a:?}");
        }
        let count: usize = std::fs::read_dir(root.join("lessons/tests"))
            .unwrap()
            .map(|e| {
                std::fs::read_to_string(e.unwrap().path())
                    .unwrap()
                    .matches("#[test]")
                    .count()
            })
            .sum();
        assert_eq!(count, COURSE.len(), "every grader is in the course, once");
    }
}
