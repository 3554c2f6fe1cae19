//! `spintop course`: the assignments in course order with their state, the
//! progress, and what to do next, from one grading run of
//! `cargo test -p spintop-lessons` (its build noise and backtraces hidden).
//! The engine is [`crate::course`]; this file only prints it.

use super::gate::Gate;
use super::{CliError, bad};
use crate::course::{self, State};
use clap::{Args, Subcommand};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;

/// The raw arguments of `course`.
#[derive(Debug, Default, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct CourseArgs {
    #[command(subcommand)]
    action: Option<CourseAction>,
    /// Show the grader's whole report for one assignment (its function name,
    /// e.g. torque_rate, or its equation, e.g. 2.2).
    #[arg(long, value_name = "NAME")]
    assignment: Option<String>,
    /// Instructor: grade the reference solutions (lessons/src/solutions/)
    /// instead of the student's files; every assignment must pass.
    #[arg(long)]
    solutions: bool,
    /// The course to grade: a lessons crate (default: the repository's
    /// lessons/; a student's copy made by `spintop course export` also works).
    #[arg(long, value_name = "DIR")]
    course: Option<PathBuf>,
    /// The status as text (default) or as JSON, for an instructor's scripts.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// How `spintop course` prints the status.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Format {
    /// One line per assignment, for people.
    #[default]
    Text,
    /// One JSON document, for scripts.
    Json,
}

/// What `course` can do besides printing the status.
#[derive(Debug, Subcommand)]
enum CourseAction {
    /// Re-grade on every save of a file of the course and print the verdict
    /// and the progress (Ctrl-C stops)
    Watch {
        /// The course to watch (default: the repository's lessons/)
        #[arg(long, value_name = "DIR")]
        course: Option<PathBuf>,
    },
    /// Instructor: write a self-contained student's copy of the course to a
    /// new folder (stubs, graders, the assignments page, a README; never the
    /// reference solutions)
    Export {
        /// The folder to create (it must not exist yet, or be empty)
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// The next rung of an assignment's hint ladder: where to look, then the
    /// idea, then the formula (one rung per call)
    Hint {
        /// The assignment: its function name (e.g. torque_rate) or equation (e.g. 2.2)
        name: String,
        /// The course whose progress keeps the rungs (default: the repository's lessons/)
        #[arg(long, value_name = "DIR")]
        course: Option<PathBuf>,
    },
    /// Instructor: grade students' copies with the repository's graders and
    /// write a CSV (student, assignment, equation, state, hint rungs used)
    Grade {
        /// The students' copies (folders made by `course export`), one per student
        #[arg(required = true, value_name = "DIR")]
        copies: Vec<PathBuf>,
        /// Write the CSV here instead of to standard output
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
    },
}

/// The lessons crate to grade: `--course DIR`, or the repository's.
pub(crate) fn lessons(chosen: Option<&PathBuf>) -> Result<PathBuf, CliError> {
    let dir = match chosen {
        Some(dir) => dir.clone(),
        None => {
            let dir = course::lessons_dir(std::path::Path::new(env!("CARGO_MANIFEST_DIR")));
            if !dir.join("Cargo.toml").is_file() {
                return Err(bad(format!(
                    "spintop course grades the assignments in the repository, and {} is missing; run it from a clone of spintop, or name a course with --course DIR",
                    dir.display()
                )));
            }
            dir
        }
    };
    course::check_lessons_dir(&dir).map_err(|e| bad(format!("--course: {e}")))?;
    Ok(dir)
}

fn mark(state: &State) -> &'static str {
    match state {
        State::Passing => "✓",
        State::Failing(_) | State::DoesNotCompile(_) => "✗",
        State::NotStarted | State::Unknown => "·",
    }
}

/// Runs `spintop course`.
pub(crate) fn execute(args: CourseArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    match args.action {
        Some(CourseAction::Export { out: dir }) => return export(&dir, out),
        Some(CourseAction::Watch { course }) => return watch(course.as_ref(), out),
        Some(CourseAction::Hint { name, course }) => return hint(&name, course.as_ref(), out),
        Some(CourseAction::Grade { copies, out: csv }) => {
            return grade_copies(&copies, csv.as_ref(), out);
        }
        None => {}
    }
    let wanted = args
        .assignment
        .as_deref()
        .map(|w| w.trim_start_matches('(').trim_end_matches(')').to_string());
    if let Some(w) = &wanted
        && !course::COURSE
            .iter()
            .any(|a| a.function == w || a.equation.trim_matches(['(', ')']) == w)
    {
        let names: Vec<&str> = course::COURSE.iter().map(|a| a.function).collect();
        return Err(bad(format!(
            "--assignment {w}: no such assignment; one of {}",
            names.join(", ")
        )));
    }
    let dir = lessons(args.course.as_ref())?;
    if args.solutions && !dir.join("src/solutions").is_dir() {
        return Err(bad(format!(
            "--solutions: {} is not here (a student's copy has none)",
            dir.join("src/solutions").display()
        )));
    }
    if std::io::stderr().is_terminal() {
        eprint!("grading (cargo test on {})…\r", dir.display());
    }
    let status = course::grade(&dir, args.solutions).map_err(bad)?;
    if !args.solutions {
        course::record_passes_now(&dir, &status);
    }
    let progress = course::load_progress(&dir);
    if args.format == Format::Json {
        let json = status_json(&status, &progress);
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&json).unwrap_or_default()
        )?;
        return Ok(());
    }
    // In the repository the files are under lessons/; in an export, at its top.
    let own = args.course.is_none();
    let file = |a: &course::Assignment| {
        if own {
            a.file.to_string()
        } else {
            a.file.trim_start_matches("lessons/").to_string()
        }
    };
    if std::io::stderr().is_terminal() {
        eprint!("{}\r", " ".repeat(48));
    }
    let n = status.states.len();
    writeln!(out, "spintop course: {} of {n} passing", status.passing())?;
    for (a, s) in &status.states {
        writeln!(
            out,
            "  {} {:<14} {:<18} {:<26} {:<24} {}",
            mark(s),
            a.equation,
            a.chapter,
            a.function,
            file(a),
            s.word()
        )?;
    }
    let show = match &wanted {
        Some(w) => status
            .states
            .iter()
            .find(|(a, _)| a.function == w || a.equation.trim_matches(['(', ')']) == w),
        None => status.next(),
    };
    match show {
        None => writeln!(out, "all {n} assignments pass: the course is done")?,
        Some((a, s)) => {
            let label = if wanted.is_some() {
                "assignment"
            } else {
                "next"
            };
            writeln!(
                out,
                "{label}: {} {} in {} ({})",
                a.equation,
                a.function,
                file(a),
                a.chapter
            )?;
            match s {
                State::NotStarted => writeln!(
                    out,
                    "  the stub is untouched: read {} in the book, then replace its todo!()",
                    a.chapter
                )?,
                State::Failing(report) => {
                    // The whole report for one assignment; its first lines for "next".
                    let limit = if wanted.is_some() { usize::MAX } else { 8 };
                    for line in report.lines().take(limit) {
                        writeln!(out, "  {line}")?;
                    }
                }
                State::DoesNotCompile(e) => writeln!(out, "  the lessons do not compile: {e}")?,
                State::Passing => writeln!(out, "  passing")?,
                State::Unknown => {
                    writeln!(out, "  its grader did not report; run it alone to see why")?
                }
            }
            let package = if own { " -p spintop-lessons" } else { "" };
            writeln!(
                out,
                "  grade it alone: cargo test{package} --test {} {}",
                a.binary, a.test
            )?;
            if !matches!(s, State::Passing | State::Failing(_)) {
                writeln!(
                    out,
                    "  stuck? spintop course hint {} (where to look, then the idea, then the formula)",
                    a.function
                )?;
            }
        }
    }
    Ok(())
}

/// `spintop course export --out DIR`.
fn export(dir: &std::path::Path, out: &mut impl Write) -> Result<(), CliError> {
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let written = course::export(repo, dir).map_err(|e| bad(format!("course export: {e}")))?;
    writeln!(
        out,
        "spintop course export: wrote {} files to {} (stubs, graders, the assignments page; no solutions)",
        written.files.len(),
        dir.display()
    )?;
    writeln!(
        out,
        "  hand it out; a student runs `cargo test` in it, or `spintop course --course {}`",
        dir.display()
    )?;
    Ok(())
}

/// One line for a changed verdict.
fn verdict_line(a: &course::Assignment, s: &State) -> String {
    format!("{} {} {} {}", mark(s), a.equation, a.function, s.word())
}

/// `spintop course watch`: grades once, then again on every save, printing
/// the assignments whose verdict changed and the progress line.
fn watch(chosen: Option<&PathBuf>, out: &mut impl Write) -> Result<(), CliError> {
    let dir = lessons(chosen)?;
    writeln!(
        out,
        "spintop course watch: grading {} now and on every save under {} (Ctrl-C stops)",
        dir.display(),
        dir.join("src").display()
    )?;
    out.flush()?;
    let watch = course::Watch::start(&dir);
    let mut last: Option<course::Status> = None;
    loop {
        for report in watch.poll() {
            match report {
                course::Report::Grading => {
                    if last.is_some() {
                        writeln!(out, "grading…")?;
                    }
                }
                course::Report::Failed(e) => writeln!(out, "spintop course watch: {e}")?,
                course::Report::Graded(status) => {
                    course::record_passes_now(&dir, &status);
                    for (i, (a, s)) in status.states.iter().enumerate() {
                        let changed = last.as_ref().is_none_or(|l| l.states[i].1 != *s);
                        if changed && (last.is_some() || *s != State::NotStarted) {
                            writeln!(out, "  {}", verdict_line(a, s))?;
                            if let State::Failing(report) | State::DoesNotCompile(report) = s {
                                for line in report.lines().take(6) {
                                    writeln!(out, "      {line}")?;
                                }
                            }
                        }
                    }
                    let next = status
                        .next()
                        .map(|(a, _)| format!("; next: {} {}", a.equation, a.function))
                        .unwrap_or_default();
                    writeln!(
                        out,
                        "{} of {} passing{next}",
                        status.passing(),
                        status.states.len()
                    )?;
                    last = Some(status);
                }
            }
            out.flush()?;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}

/// The status as one JSON value.
fn status_json(status: &course::Status, progress: &course::Progress) -> serde_json::Value {
    let assignments: Vec<serde_json::Value> = status
        .states
        .iter()
        .map(|(a, s)| {
            let report = match s {
                State::Failing(r) | State::DoesNotCompile(r) => Some(r.clone()),
                _ => None,
            };
            serde_json::json!({
                "function": a.function,
                "equation": a.equation,
                "chapter": a.chapter,
                "file": a.file,
                "test": format!("{}::{}", a.binary, a.test),
                "state": s.word(),
                "report": report,
                "hint_rungs_used": progress.hints.get(a.function).copied().unwrap_or(0),
                "first_passed_unix": progress.first_passed.get(a.function),
            })
        })
        .collect();
    serde_json::json!({
        "passing": status.passing(),
        "total": status.states.len(),
        "next": status.next().map(|(a, _)| a.function),
        "assignments": assignments,
    })
}

/// `spintop course hint NAME`: the next rung of the ladder.
fn hint(name: &str, chosen: Option<&PathBuf>, out: &mut impl Write) -> Result<(), CliError> {
    let Some(a) = course::find(name) else {
        let names: Vec<&str> = course::COURSE.iter().map(|a| a.function).collect();
        return Err(bad(format!(
            "course hint {name}: no such assignment; one of {}",
            names.join(", ")
        )));
    };
    let dir = lessons(chosen)?;
    let mut progress = course::load_progress(&dir);
    let h = course::next_hint(&mut progress, a);
    course::save_progress(&dir, &progress).map_err(|e| bad(format!("course hint: {e}")))?;
    let n = a.hints.len();
    let label = h.label();
    writeln!(
        out,
        "{} {} - hint {} of {n} ({label}):",
        a.equation, a.function, h.rung
    )?;
    writeln!(out, "  {}", h.text)?;
    if h.is_last() {
        writeln!(out, "  (that was the last rung)")?;
    } else {
        writeln!(
            out,
            "  (run `spintop course hint {}` again for the next rung)",
            a.function
        )?;
    }
    Ok(())
}

/// A CSV field, quoted when it needs to be.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `spintop course grade DIR...`: each copy graded with the repository's
/// graders, one CSV row per student and assignment.
fn grade_copies(
    copies: &[PathBuf],
    csv: Option<&PathBuf>,
    out: &mut impl Write,
) -> Result<(), CliError> {
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    if !course::lessons_dir(repo).join("Cargo.toml").is_file() {
        return Err(bad(
            "spintop course grade needs the repository's graders (lessons/); run it from a clone of spintop",
        ));
    }
    for dir in copies {
        course::check_lessons_dir(dir).map_err(|e| bad(format!("course grade: {e}")))?;
    }
    let work = repo.join("target").join("course-grade");
    // The repository's own build folder: spintop is already compiled there.
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo.join("target"));
    let mut rows = vec!["student,assignment,equation,state,hint_rungs_used".to_string()];
    for (i, dir) in copies.iter().enumerate() {
        let student = dir
            .canonicalize()
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| dir.display().to_string());
        if std::io::stderr().is_terminal() {
            eprint!("grading {student} ({} of {})…\r", i + 1, copies.len());
        }
        let status = course::grade_submission(repo, dir, &work.join("copy"), &target)
            .map_err(|e| bad(format!("course grade {}: {e}", dir.display())))?;
        let progress = course::load_progress(dir);
        for (a, s) in &status.states {
            rows.push(
                [
                    csv_field(&student),
                    a.function.to_string(),
                    csv_field(a.equation),
                    s.word().to_string(),
                    progress
                        .hints
                        .get(a.function)
                        .copied()
                        .unwrap_or(0)
                        .to_string(),
                ]
                .join(","),
            );
        }
    }
    let text = rows.join("\n") + "\n";
    match csv {
        Some(path) => {
            std::fs::write(path, &text)
                .map_err(|e| bad(format!("course grade --out {}: {e}", path.display())))?;
            writeln!(
                out,
                "spintop course grade: {} students, {} rows written to {}",
                copies.len(),
                rows.len() - 1,
                path.display()
            )?;
        }
        None => write!(out, "{text}")?,
    }
    Ok(())
}
