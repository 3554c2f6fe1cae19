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

/// The lessons crate of the repository at `repo` (where `spintop course`
/// and `spintop learn` look unless told otherwise).
pub fn lessons_dir(repo: &Path) -> std::path::PathBuf {
    repo.join("lessons")
}

/// Why `dir` is not a lessons crate spintop can grade, if it is not.
pub fn check_lessons_dir(dir: &Path) -> Result<(), String> {
    if !dir.join("Cargo.toml").is_file() || !dir.join("src").is_dir() {
        return Err(format!(
            "{} is not a course: it needs a Cargo.toml and a src/ folder (the repository's lessons/, or a copy made by `spintop course export`)",
            dir.display()
        ));
    }
    Ok(())
}

/// The cargo command that grades the lessons crate in `dir`: the graders of
/// the given test binaries, or all of them when `binaries` is empty; with
/// `solutions`, the instructor's reference solutions.
fn grade_command(dir: &Path, solutions: bool, binaries: &[&str]) -> Command {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(dir)
        .arg("test")
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--no-fail-fast", "--color", "never"]);
    if solutions {
        cmd.args(["--features", "solutions"]);
    }
    for b in binaries {
        cmd.args(["--test", b]);
    }
    cmd.args(["--", "--color", "never"])
        .env("RUST_BACKTRACE", "0");
    cmd
}

/// Grades the course of the lessons crate in `dir` (see [`lessons_dir`]):
/// runs `cargo test --no-fail-fast` on it (no backtraces, no colour) and reads
/// its output; with `solutions`, the instructor's reference solutions are
/// graded instead of the student's files. An error is a reason cargo could
/// not be run at all.
pub fn grade(dir: &Path, solutions: bool) -> Result<Status, String> {
    let out = grade_command(dir, solutions, &[])
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let text = format!(
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(parse(&text))
}

/// The modification time of each of the student's files (`src/*.rs` of the
/// lessons crate in `dir`), by file name.
pub fn sources_stamps(dir: &Path) -> std::collections::BTreeMap<String, std::time::SystemTime> {
    std::fs::read_dir(dir.join("src"))
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "rs"))
        .filter_map(|e| {
            let time = e.metadata().ok()?.modified().ok()?;
            Some((e.file_name().to_string_lossy().into_owned(), time))
        })
        .collect()
}

/// The test binaries whose graders can change when the files `changed` (names
/// under `src/`) do: those of the assignments in them, or every one (an empty
/// list) when another file changed (`lib.rs`, a helper).
pub fn binaries_for(changed: &[String]) -> Vec<&'static str> {
    let mut binaries = Vec::new();
    for file in changed {
        let mut owners = COURSE
            .iter()
            .filter(|a| a.file.rsplit('/').next() == Some(file.as_str()))
            .map(|a| a.binary)
            .peekable();
        if owners.peek().is_none() {
            return Vec::new();
        }
        binaries.extend(owners);
    }
    binaries.sort_unstable();
    binaries.dedup();
    binaries
}

impl Status {
    /// Whether every assignment has a verdict of its own (none is "does not
    /// compile" or ungraded), so that a partial re-grade can build on it.
    pub fn complete(&self) -> bool {
        self.states
            .iter()
            .all(|(_, s)| !matches!(s, State::DoesNotCompile(_) | State::Unknown))
    }

    /// This status with the assignments graded by `binaries` (all when empty)
    /// taken from `fresh`. A compile error concerns the whole crate, so it is
    /// taken for every assignment.
    pub fn merged(&self, fresh: Status, binaries: &[&str]) -> Status {
        let broken = fresh
            .states
            .iter()
            .any(|(_, s)| matches!(s, State::DoesNotCompile(_)));
        let states = self
            .states
            .iter()
            .zip(fresh.states)
            .map(|((a, old), (_, new))| {
                let regraded = binaries.is_empty() || binaries.contains(&a.binary);
                if regraded || broken {
                    (*a, new)
                } else {
                    (*a, old.clone())
                }
            })
            .collect();
        Status { states }
    }
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
/// time a file under `src/` of the lessons crate is saved (polled every
/// 200 ms); a save re-grades only the graders of the assignments in the saved
/// file (see [`binaries_for`]). The grading runs stop with the watch:
/// dropping it ends the thread and kills a cargo still running.
pub struct Watch {
    reports: std::sync::mpsc::Receiver<Report>,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Watch {
    /// Starts watching the lessons crate in `dir`.
    pub fn start(dir: &Path) -> Self {
        use std::sync::atomic::Ordering;
        let (tx, reports) = std::sync::mpsc::channel();
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let stop_thread = std::sync::Arc::clone(&stop);
        let dir = dir.to_path_buf();
        let thread = std::thread::spawn(move || {
            let mut graded: Option<(std::collections::BTreeMap<_, _>, Status)> = None;
            while !stop_thread.load(Ordering::Relaxed) {
                let stamps = sources_stamps(&dir);
                let binaries = match &graded {
                    None => Some(Vec::new()),
                    // After a compile error or a failed run, everything again.
                    Some((old, status)) if *old != stamps && !status.complete() => Some(Vec::new()),
                    Some((old, _)) if *old != stamps => {
                        let changed: Vec<String> = stamps
                            .iter()
                            .filter(|(f, t)| old.get(*f) != Some(t))
                            .map(|(f, _)| f.clone())
                            .chain(old.keys().filter(|f| !stamps.contains_key(*f)).cloned())
                            .collect();
                        Some(binaries_for(&changed))
                    }
                    Some(_) => None,
                };
                if let Some(binaries) = binaries {
                    if tx.send(Report::Grading).is_err() {
                        return;
                    }
                    let report = match grade_cancellable(&dir, &binaries, &stop_thread) {
                        Ok(Some(fresh)) => {
                            let status = match &graded {
                                Some((_, old)) => old.merged(fresh, &binaries),
                                None => fresh,
                            };
                            graded = Some((stamps, status.clone()));
                            Report::Graded(status)
                        }
                        Ok(None) => return,
                        Err(e) => {
                            // Try again on the next save, from scratch.
                            graded = Some((stamps, parse("")));
                            Report::Failed(e)
                        }
                    };
                    if tx.send(report).is_err() {
                        return;
                    }
                }
                std::thread::sleep(std::time::Duration::from_millis(200));
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

/// [`grade`] of the graders in `binaries` (all when empty) as a child
/// process that is killed when `stop` is set; `None` when it was.
fn grade_cancellable(
    dir: &Path,
    binaries: &[&str],
    stop: &std::sync::atomic::AtomicBool,
) -> Result<Option<Status>, String> {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = grade_command(dir, false, binaries)
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

/// A student's file with the instructor's solutions taken out: the
/// `#[cfg(not(feature = "solutions"))]` attributes (always true once the
/// feature is gone), each `#[cfg(feature = "solutions")]` item, and the
/// comment that announces it.
pub fn strip_solutions(source: &str) -> String {
    let mut out = Vec::new();
    let mut skip_next = false;
    for line in source.lines() {
        let t = line.trim();
        if skip_next {
            skip_next = false;
            continue;
        }
        if t == "#[cfg(not(feature = \"solutions\"))]" {
            continue;
        }
        if t == "#[cfg(feature = \"solutions\")]" {
            skip_next = true;
            continue;
        }
        if t.starts_with("// The instructor's reference solutions")
            || (t.starts_with("// src/solutions/") && t.contains("handing out"))
        {
            continue;
        }
        out.push(line);
    }
    let mut text = out.join("\n").trim_end().to_string();
    text.push('\n');
    text
}

/// What [`export`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Export {
    /// Every file written, relative to the export's folder.
    pub files: Vec<std::path::PathBuf>,
}

/// The student's copy's manifest: the lessons package on its own (its own
/// workspace), depending on spintop at `spintop` (an absolute path).
fn export_manifest(spintop: &Path) -> String {
    format!(
        r#"[package]
name = "spintop-lessons"
version = "0.1.0"
edition = "2024"
publish = false
description = "Course assignments on Duviryak's polarized spinning top, graded by cargo test."

# A course of its own, not a member of any other workspace.
[workspace]

[lib]
path = "src/lib.rs"

[dependencies]
spintop = {{ path = {path:?} }}
"#,
        path = spintop.display().to_string()
    )
}

const EXPORT_README: &str = "# The spintop course

Assignments on A. Duviryak's polarized spinning top, graded by `cargo test`.
Every function under `src/` is a stub that ends in `todo!()`; the chapter of
the book it comes from is named in its doc comment (the assignments page is in
`book/`).

Two commands:

```sh
cargo test                     # grade every assignment
cargo test --test ch2          # grade one chapter's assignments
```

With spintop installed, `spintop course --course .` lists the assignments in
course order with their state and what to do next, and
`spintop learn --course .` opens the book in the terminal and re-grades on
every save.
";

/// Writes a self-contained student's copy of the course in `repo` to `out`
/// (a folder that must not exist yet, or be empty): the stubs without the
/// reference solutions, the graders, the book's assignments page, a README
/// and a manifest that builds on its own against the spintop in `repo`.
pub fn export(repo: &Path, out: &Path) -> Result<Export, String> {
    let lessons = lessons_dir(repo);
    check_lessons_dir(&lessons)?;
    if out.exists() {
        let empty = std::fs::read_dir(out)
            .map_err(|e| format!("{}: {e}", out.display()))?
            .next()
            .is_none();
        if !empty {
            return Err(format!(
                "{} is not empty; give a new folder, so that nothing is overwritten",
                out.display()
            ));
        }
    }
    let spintop = repo
        .canonicalize()
        .map_err(|e| format!("{}: {e}", repo.display()))?;
    let mut files: Vec<(std::path::PathBuf, String)> = vec![
        ("Cargo.toml".into(), export_manifest(&spintop)),
        ("README.md".into(), EXPORT_README.to_string()),
        (".gitignore".into(), "/target\n".to_string()),
    ];
    for (from, to, strip) in [("src", "src", true), ("tests", "tests", false)] {
        let mut entries: Vec<_> = std::fs::read_dir(lessons.join(from))
            .map_err(|e| format!("{}: {e}", lessons.join(from).display()))?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "rs"))
            .collect();
        entries.sort();
        for path in entries {
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let text = if strip { strip_solutions(&text) } else { text };
            let name = path.file_name().unwrap_or_default();
            files.push((Path::new(to).join(name), text));
        }
    }
    let page = repo.join("book/src/assignments.md");
    if let Ok(text) = std::fs::read_to_string(&page) {
        files.push(("book/assignments.md".into(), text));
    }
    if let Ok(lock) = std::fs::read_to_string(repo.join("Cargo.lock")) {
        files.push(("Cargo.lock".into(), lock));
    }
    for (rel, text) in &files {
        let path = out.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        }
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(Export {
        files: files.into_iter().map(|(p, _)| p).collect(),
    })
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

    #[test]
    fn a_save_regrades_only_the_graders_of_the_saved_file() {
        assert_eq!(binaries_for(&["ch2.rs".into()]), vec!["ch2"]);
        // numerics.rs holds three assignments of one grader binary.
        assert_eq!(binaries_for(&["numerics.rs".into()]), vec!["numerics"]);
        assert_eq!(
            binaries_for(&["ch4.rs".into(), "ch2.rs".into()]),
            vec!["ch2", "ch4"]
        );
        // lib.rs (or any file without an assignment) can change every grader.
        assert!(binaries_for(&["lib.rs".into()]).is_empty());
        assert!(binaries_for(&["ch2.rs".into(), "helpers.rs".into()]).is_empty());
    }

    #[test]
    fn a_partial_regrade_keeps_the_other_verdicts() {
        let before = parse(SAMPLE);
        assert_eq!(before.passing(), 2);
        // A run of the ch4 graders alone: one passes, ch2's tests are absent.
        let fresh = parse("test eq_4_11_precession_tilt ... ok\n");
        let after = before.merged(fresh.clone(), &["ch4"]);
        assert_eq!(after.passing(), 3);
        let tilt = after
            .states
            .iter()
            .find(|(a, _)| a.test == "eq_4_11_precession_tilt");
        assert_eq!(tilt.unwrap().1, State::Passing);
        // Merging it as if every grader had run forgets ch2's verdicts.
        assert_eq!(before.merged(fresh, &[]).passing(), 1);
        // A compile error concerns every assignment.
        let broken = parse("error[E0308]: mismatched types\n");
        assert!(!before.merged(broken.clone(), &["ch4"]).complete());
        assert_eq!(before.merged(broken, &["ch4"]).passing(), 0);
    }

    #[test]
    fn an_export_holds_the_stubs_and_graders_and_no_solution() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let out = std::env::temp_dir().join(format!("spintop-export-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        let written = export(root, &out).unwrap();
        for a in COURSE {
            let file = a.file.trim_start_matches("lessons/");
            let text = std::fs::read_to_string(out.join(file)).unwrap();
            let start = text.find(&format!("pub fn {}(", a.function)).unwrap();
            let body = &text[start..start + text[start..].find("\n}").unwrap()];
            assert!(
                body.contains("todo!("),
                "{}: the stub, not a solution",
                a.function
            );
            assert!(out.join("tests").join(format!("{}.rs", a.binary)).is_file());
        }
        for rel in &written.files {
            let text = std::fs::read_to_string(out.join(rel)).unwrap();
            if rel.starts_with("src") || rel.ends_with("Cargo.toml") {
                assert!(
                    !text.contains("solutions"),
                    "{} mentions the solutions",
                    rel.display()
                );
            }
        }
        assert!(!out.join("src/solutions").exists());
        // Every solution's body is absent from every exported source file.
        for entry in std::fs::read_dir(root.join("lessons/src/solutions")).unwrap() {
            let solution = std::fs::read_to_string(entry.unwrap().path()).unwrap();
            for body in solution.split("\npub fn ").skip(1) {
                let body = &body[body.find('{').unwrap()..];
                let body = &body[..body.find("\n}").unwrap_or(body.len())];
                if body.lines().count() < 3 {
                    continue;
                }
                for rel in written.files.iter().filter(|p| p.starts_with("src")) {
                    let text = std::fs::read_to_string(out.join(rel)).unwrap();
                    assert!(!text.contains(body), "{} holds a solution", rel.display());
                }
            }
        }
        let manifest = std::fs::read_to_string(out.join("Cargo.toml")).unwrap();
        assert!(manifest.contains("[workspace]") && manifest.contains("spintop = { path"));
        // A second export into the same folder is refused, nothing overwritten.
        assert!(export(root, &out).unwrap_err().contains("not empty"));
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn stripping_the_solutions_keeps_the_stub() {
        let text = "use a;\n#[cfg(not(feature = \"solutions\"))]\npub fn f() {\n    todo!()\n}\n\n#[cfg(feature = \"solutions\")]\npub use crate::solutions::ch2::*;\n";
        assert_eq!(
            strip_solutions(text),
            "use a;\npub fn f() {\n    todo!()\n}\n"
        );
    }
}
