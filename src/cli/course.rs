//! `spintop course`: the assignments in course order with their state, the
//! progress, and what to do next, from one grading (each grader in its own
//! process, its verdict read from structure); and the instructor's tools:
//! `export`, `grade` (a whole class, CSV or Gradescope), `diagnose`.
//! The engine is [`spintop_course`]; this file validates and prints.

use super::gate::Gate;
use super::{CliError, bad, parse_number};
use clap::{Args, Subcommand};
use spintop_course::{self as course, Chosen, Course, Options, State};

mod grade;
use spintop_grading as grading;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The raw arguments of `course`.
#[derive(Debug, Default, Args)]
#[command(
    args_conflicts_with_subcommands = true,
    after_help = "Examples:\n  \
        spintop course                                   every assignment, its state and what to do next\n  \
        spintop course hint torque_rate                  the next rung of its hint ladder\n  \
        spintop course watch                             re-grade on every save\n\n\
        Exit codes: 0 graded (whatever the grades); 2 bad input (a flag, a course that is not one); \
        4 could not grade: the machine did not allow it (no cargo, a toolchain that refuses, crates \
        missing offline, a folder this user may not write), said with what to do, and nothing of the \
        code was judged; for `course grade`, 4 when some copy could not be fully graded (its rows say \
        why); 1 an output or a kept file (a hint's rung) could not be written."
)]
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
    /// The course to grade: a lessons crate or a student's copy made by
    /// `spintop course export` (default: the one the current folder is in,
    /// as cargo finds its manifest; else the repository's lessons/).
    #[arg(long, value_name = "DIR")]
    course: Option<PathBuf>,
    /// The status as text (default) or as JSON, for an instructor's scripts.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Draw the graders' inputs from this seed (a failure's report names its
    /// seed; the same seed gives the same inputs). Default: a fresh one.
    #[arg(long, value_name = "N")]
    seed: Option<u64>,
    /// The launcher of a student's build or runner: it restricts itself and
    /// becomes the program (see `spintop_course::sandbox`).
    #[arg(long = "sandbox", hide = true, num_args = 2.., allow_hyphen_values = true, value_name = "SPEC PROGRAM ARGS")]
    sandbox: Option<Vec<std::ffi::OsString>>,
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

/// How `spintop course grade` writes the grades.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum GradeFormat {
    /// One CSV row per student and assignment.
    #[default]
    Csv,
    /// Gradescope's autograder results.json (one per student).
    Gradescope,
}

/// Where an exported copy is graded on every push.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum CiChoice {
    /// GitHub Actions (.github/workflows/grade.yml).
    Github,
}

/// What `course` can do besides printing the status.
#[derive(Debug, Subcommand)]
enum CourseAction {
    /// Re-grade on every save of a file of the course and print the verdict
    /// and the progress (Ctrl-C stops)
    Watch {
        /// The course to watch (default: the one the current folder is in;
        /// else the repository's lessons/)
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
        /// Also add a workflow that grades the copy with `cargo test` on
        /// every push (and a copy of spintop's core, so that it builds there)
        #[arg(long, value_enum, value_name = "SERVICE")]
        ci: Option<CiChoice>,
    },
    /// The next rung of an assignment's hint ladder: where to look, then the
    /// idea, then the formula (one rung per call)
    Hint {
        /// The assignment: its function name (e.g. torque_rate) or equation (e.g. 2.2)
        name: String,
        /// The course whose progress keeps the rungs (default: the one the
        /// current folder is in; else the repository's lessons/)
        #[arg(long, value_name = "DIR")]
        course: Option<PathBuf>,
    },
    /// Instructor: grade students' copies with the repository's graders, each
    /// within a time limit, and write one row per student and assignment
    /// whatever happens (a missing folder, a copy that does not compile or
    /// hangs); exit 4 when a copy could not be fully graded
    Grade {
        /// The students' copies (folders made by `course export`), one per student
        #[arg(required = true, value_name = "DIR")]
        copies: Vec<PathBuf>,
        /// Write the CSV (or, with --format gradescope, results.json; a folder
        /// of STUDENT/results.json for several copies) here instead of to
        /// standard output
        #[arg(long, value_name = "PATH")]
        out: Option<PathBuf>,
        /// CSV rows, or Gradescope's results.json
        #[arg(long, value_enum, default_value_t = GradeFormat::Csv)]
        format: GradeFormat,
        /// The longest one copy may take, its build and every grader (seconds)
        #[arg(long, value_name = "SECONDS", default_value_t = 120.0, value_parser = parse_number, allow_hyphen_values = true)]
        timeout: f64,
        /// The longest one grader may take (seconds)
        #[arg(long, value_name = "SECONDS", default_value_t = 30.0, value_parser = parse_number, allow_hyphen_values = true)]
        test_timeout: f64,
        /// Copies graded at once (default: the number of cores)
        #[arg(long, value_name = "N", value_parser = spintop::numbers::parse_count::<usize>, allow_hyphen_values = true)]
        jobs: Option<usize>,
        /// Draw every grader's inputs from this seed (default: a fresh one for the class)
        #[arg(long, value_name = "N")]
        seed: Option<u64>,
    },
    /// Instructor: grade a folder of wrong answers (one `.rs` file each, its
    /// `//! assignment:` and `//! mistake:` in its header) and print each
    /// grader's diagnosis, to measure how often it names the mistake
    Diagnose {
        /// The folder of wrong answers
        #[arg(value_name = "DIR")]
        dir: PathBuf,
        /// The inputs' seed (default: a fresh one)
        #[arg(long, value_name = "N")]
        seed: Option<u64>,
        /// A table for people (default), or JSON lines for scripts
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
}

/// The course to grade: `--course DIR`, else the one the current folder
/// stands in (as cargo finds its manifest), else the repository's lessons.
pub(crate) fn lessons(chosen: Option<&PathBuf>) -> Result<Course, CliError> {
    let cwd = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
    let course = Course::choose(chosen.map(PathBuf::as_path), &cwd);
    if course.chosen == Chosen::Default && !course.dir.join("Cargo.toml").is_file() {
        return Err(bad(format!(
            "spintop course grades the course the current folder is in, and there is none here; the repository's lessons ({}) are missing too: run it in a copy made by `spintop course export`, or name one with --course DIR",
            course.dir.display()
        )));
    }
    course::check_lessons_dir(&course.dir).map_err(|e| bad(format!("--course: {e}")))?;
    Ok(course)
}

/// The `--course DIR` a printed command must repeat (as the user typed it).
fn given(chosen: Option<&PathBuf>) -> Option<String> {
    chosen.map(|d| d.display().to_string())
}

fn mark(state: &State) -> &'static str {
    match state {
        State::Passing => "✓",
        State::Failing(_) | State::DoesNotCompile(_) | State::TimedOut(_) => "✗",
        State::NotStarted | State::Unknown => "·",
    }
}

/// Runs `spintop course`.
pub(crate) fn execute(args: CourseArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    if let Some(launched) = &args.sandbox {
        // The launcher: it becomes the program, or exits saying why not.
        out.flush()?;
        std::process::exit(course::sandbox::launch(launched));
    }
    match args.action {
        Some(CourseAction::Export { out: dir, ci }) => export(&dir, ci, out),
        Some(CourseAction::Watch { course }) => watch(course.as_ref(), out),
        Some(CourseAction::Hint { name, course }) => hint(&name, course.as_ref(), out),
        Some(CourseAction::Grade {
            copies,
            out: path,
            format,
            timeout,
            test_timeout,
            jobs,
            seed,
        }) => {
            let limits = grade::Limits::new(timeout, test_timeout, jobs)?;
            grade::grade_copies(&copies, path.as_ref(), format, limits, seed, out)
        }
        Some(CourseAction::Diagnose { dir, seed, format }) => diagnose(&dir, seed, format, out),
        None => status(&args, out),
    }
}

/// The `spintop` binary that launches the sandbox of a student's build and
/// runner (this program).
pub(crate) fn launcher() -> Option<PathBuf> {
    std::env::current_exe().ok()
}

/// `spintop course`: grades the course once and prints every assignment's
/// state and what to do next.
fn status(args: &CourseArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let wanted = match args.assignment.as_deref() {
        Some(w) => Some(course::find(w).ok_or_else(|| {
            let names: Vec<&str> = course::COURSE.iter().map(|a| a.function).collect();
            bad(format!(
                "--assignment {w}: no such assignment; one of {}",
                names.join(", ")
            ))
        })?),
        None => None,
    };
    let chosen = lessons(args.course.as_ref())?;
    let dir = chosen.dir.clone();
    if args.solutions && !dir.join("src/solutions").is_dir() {
        return Err(bad(format!(
            "--solutions: {} is not here (a student's copy has none)",
            dir.join("src/solutions").display()
        )));
    }
    let course_arg = given(args.course.as_ref());
    if std::io::stderr().is_terminal() {
        eprintln!("spintop course: grading {}…", chosen.describe());
    }
    let status = grade::with_progress(&chosen.describe(), |progress| {
        let options = Options {
            solutions: args.solutions,
            seed: args.seed,
            course_arg: course_arg.clone(),
            launcher: launcher(),
            progress,
            ..Options::default()
        };
        course::grade(&dir, &options)
    })
    // Whatever stopped it, nothing of the code was judged: exit 4.
    .map_err(|e| CliError::CannotGrade(format!("course: {e}")))?;
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
    print_status(&chosen, &status, wanted, course_arg.as_deref(), out)
}

/// The status as text: the table, then what to fix or do next, named as
/// the course names its files (in the repository under lessons/; in a
/// copy, at its top).
fn print_status(
    chosen: &Course,
    status: &course::Status,
    wanted: Option<&course::Assignment>,
    course_arg: Option<&str>,
    out: &mut Gate<'_>,
) -> Result<(), CliError> {
    let n = status.states.len();
    writeln!(
        out,
        "spintop course: {} of {n} passing (inputs from seed {})",
        status.passing(),
        status.seed
    )?;
    writeln!(out, "  graded: {}", chosen.describe())?;
    for line in table(chosen, status) {
        writeln!(out, "{line}")?;
    }
    // A compile error or a shortcut comes first.
    if let Some(place) = status.next_place() {
        let what = status.whole_copy_reason().unwrap_or_default();
        let detail = status
            .compile_error
            .as_ref()
            .or(status.shortcut.as_ref())
            .map(|l| l.message.clone())
            .unwrap_or_default();
        writeln!(out, "next: fix {place} ({what})")?;
        writeln!(out, "  {detail}")?;
        if wanted.is_none() {
            return Ok(());
        }
    }
    let show = match wanted {
        Some(w) => status.states.iter().find(|(a, _)| a.function == w.function),
        None => status.next(),
    };
    match show {
        None => writeln!(out, "all {n} assignments pass: the course is done")?,
        Some((a, s)) => print_next(chosen, a, s, wanted.is_some(), course_arg, out)?,
    }
    Ok(())
}

/// The status's table, each line at most 80 columns wide: a heading per
/// chapter, then one row per assignment (its equation, function, file
/// under the course's `src/`, state), the columns as wide as the course's
/// longest entries. (The chapter and the path as columns made rows of 102.)
fn table(chosen: &Course, status: &course::Status) -> Vec<String> {
    let folder = format!("in {}/", chosen.path("src"));
    let name = |a: &course::Assignment| {
        Path::new(a.file)
            .file_name()
            .map_or_else(|| a.file.to_string(), |n| n.to_string_lossy().into_owned())
    };
    let widest =
        |f: &dyn Fn(&course::Assignment) -> usize| course::COURSE.iter().map(f).max().unwrap_or(0);
    let eq = widest(&|a| a.equation.chars().count()).max("equation".len());
    let function = widest(&|a| a.function.chars().count());
    let file = widest(&|a| name(a).chars().count()).max(folder.chars().count());
    let mut lines = vec![format!(
        "      {:<eq$} {:<function$} {:<file$} state",
        "equation", "assignment", folder
    )];
    let mut chapter = "";
    for (a, s) in &status.states {
        if a.chapter != chapter {
            chapter = a.chapter;
            lines.push(format!("  {chapter}"));
        }
        lines.push(format!(
            "    {} {:<eq$} {:<function$} {:<file$} {}",
            mark(s),
            a.equation,
            a.function,
            name(a),
            status.word_of(s)
        ));
    }
    lines
}

/// The next assignment (or the one asked for), its state and what to do.
fn print_next(
    chosen: &Course,
    a: &course::Assignment,
    s: &State,
    asked: bool,
    course_arg: Option<&str>,
    out: &mut Gate<'_>,
) -> Result<(), CliError> {
    let label = if asked { "assignment" } else { "next" };
    writeln!(
        out,
        "{label}: {} {} in {} ({})",
        a.equation,
        a.function,
        chosen.file(a),
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
            let limit = if asked { usize::MAX } else { 9 };
            for line in report.lines().take(limit) {
                writeln!(out, "  {line}")?;
            }
        }
        State::DoesNotCompile(e) => writeln!(out, "  the lessons do not compile: {e}")?,
        State::TimedOut(why) => writeln!(out, "  {why}")?,
        State::Passing => writeln!(out, "  passing")?,
        State::Unknown => writeln!(out, "  its grader did not report; run it alone to see why")?,
    }
    writeln!(out, "  grade it alone: {}", chosen.test_command(a))?;
    if !matches!(s, State::Passing | State::Failing(_)) {
        writeln!(
            out,
            "  stuck? {}\n    (one rung a call: where to look, then the idea, then the formula)",
            grading::hint_command(a.function, course_arg)
        )?;
    }
    Ok(())
}

/// `spintop course export --out DIR [--ci github]`.
fn export(dir: &Path, ci: Option<CiChoice>, out: &mut impl Write) -> Result<(), CliError> {
    let options = course::ExportOptions {
        ci: ci.map(|CiChoice::Github| course::Ci::Github),
        link: course::Link::Carried,
    };
    let written = course::export_with(course::repository(), dir, &options)
        .map_err(|e| bad(format!("course export: {e}")))?;
    writeln!(
        out,
        "spintop course export: wrote {} files to {} (stubs, graders' tests, the assignments page, spintop's core and graders in crates/, the book in book/src; no solutions)",
        written.files.len(),
        dir.display()
    )?;
    if ci.is_some() {
        writeln!(
            out,
            "  {} grades it with `cargo test` on every push",
            course::export::GITHUB_WORKFLOW
        )?;
    }
    writeln!(
        out,
        "  hand it out; a student runs `cargo test`, `spintop course` or `spintop learn` in it \
         (they find the course they stand in), or `spintop course{}` from elsewhere",
        grading::course_arg(Some(&dir.display().to_string()))
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
    let course = lessons(chosen)?;
    let dir = course.dir.clone();
    writeln!(
        out,
        "spintop course watch: grading {} now and on every save under {} (Ctrl-C stops)",
        course.describe(),
        dir.join("src").display()
    )?;
    out.flush()?;
    let course_arg = given(chosen);
    let watch = course::Watch::with_options(
        &dir,
        Options {
            course_arg: course_arg.clone(),
            launcher: launcher(),
            ..Options::default()
        },
    );
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
                            if let Some(report) = s.reason() {
                                for line in report.lines().take(7) {
                                    writeln!(out, "      {line}")?;
                                }
                            }
                        }
                    }
                    let next = match (status.next_place(), status.next()) {
                        (Some(place), _) => format!("; next: fix {place}"),
                        (None, Some((a, _))) => format!(
                            "; next: {} {} (stuck? {})",
                            a.equation,
                            a.function,
                            grading::hint_command(a.function, course_arg.as_deref())
                        ),
                        (None, None) => String::new(),
                    };
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
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// The status as one JSON value.
fn status_json(status: &course::Status, progress: &course::Progress) -> serde_json::Value {
    let assignments: Vec<serde_json::Value> = status
        .states
        .iter()
        .map(|(a, s)| {
            serde_json::json!({
                "function": a.function,
                "equation": a.equation,
                "chapter": a.chapter,
                "file": a.file,
                "test": format!("{}::{}", a.binary, a.test),
                "state": s.word(),
                "report": s.reason(),
                "hint_rungs_used": progress.hints.get(a.function).copied().unwrap_or(0),
                "first_passed_unix": progress.first_passed.get(a.function),
            })
        })
        .collect();
    let place = |l: &course::Located| serde_json::json!({"file": l.file, "line": l.line, "message": l.message});
    serde_json::json!({
        "passing": status.passing(),
        "total": status.states.len(),
        "seed": status.seed,
        "next": status.next().map(|(a, _)| a.function),
        "compile_error": status.compile_error.as_ref().map(place),
        "shortcut": status.shortcut.as_ref().map(place),
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
    let dir = lessons(chosen)?.dir;
    let mut progress = course::load_progress(&dir);
    let h = course::next_hint(&mut progress, a);
    // The rung is shown even where it cannot be kept (a course another user
    // owns): said after it, exit 1.
    let kept = course::save_progress(&dir, &progress);
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
            "  (run `{}` again for the next rung)",
            grading::hint_command(a.function, given(chosen).as_deref())
        )?;
    }
    kept.map_err(|e| {
        CliError::NotSaved(format!(
            "course hint: the rung shown was not kept ({e}), so the next call shows it again"
        ))
    })
}

/// `spintop course diagnose DIR`: the graders' diagnoses of a folder of
/// wrong answers.
fn diagnose(
    dir: &Path,
    seed: Option<u64>,
    format: Format,
    out: &mut impl Write,
) -> Result<(), CliError> {
    let repo = course::repository();
    let answers =
        course::diagnose::read_folder(dir).map_err(|e| bad(format!("course diagnose: {e}")))?;
    let seed = seed.unwrap_or_else(grading::verdict::fresh_seed);
    if std::io::stderr().is_terminal() {
        eprint!("building {} wrong answers…\r", answers.len());
    }
    let results = course::diagnose::run(
        repo,
        &answers,
        seed,
        &repo.join("target").join("course-diagnose"),
    )
    .map_err(|e| CliError::CannotGrade(format!("course diagnose: {e}")))?;
    match format {
        Format::Json => {
            for r in &results {
                writeln!(
                    out,
                    "{}",
                    serde_json::to_string(&r.json()).unwrap_or_default()
                )?;
            }
        }
        Format::Text => {
            for r in &results {
                writeln!(out, "{}", r.text())?;
            }
            let failed = results.iter().filter(|r| !r.passed).count();
            let expected: Vec<_> = results.iter().filter(|r| r.answer.says.is_some()).collect();
            let said = expected
                .iter()
                .filter(|r| r.says_it() == Some(true))
                .count();
            writeln!(
                out,
                "spintop course diagnose: {} wrong answers, {failed} rejected (seed {seed}); {said} of {} diagnoses contain the words their file expects",
                results.len(),
                expected.len()
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every line of the table fits 80 columns, whatever the states (the
    /// longest words included) and wherever the course is (the repository
    /// names its files under lessons/), and each assignment has its row.
    #[test]
    fn the_status_table_fits_80_columns() {
        let states = [
            State::DoesNotCompile("x".into()),
            State::Failing("y".into()),
            State::TimedOut("z".into()),
            State::Unknown,
            State::NotStarted,
            State::Passing,
        ];
        let k = std::cell::Cell::new(0);
        let mut status = course::Status::new(0, |_| {
            k.set(k.get() + 1);
            states[k.get() % states.len()].clone()
        });
        let repository = Course::at(&course::lessons_dir(course::repository()), Chosen::Default);
        let copy = Course::at(Path::new("/home/student/course"), Chosen::Found);
        for shortcut in [false, true] {
            status.shortcut = shortcut.then(|| course::Located {
                file: "src/ch2.rs".into(),
                line: 1,
                message: "std::fs".into(),
            });
            for chosen in [&repository, &copy] {
                let lines = table(chosen, &status);
                for l in &lines {
                    assert!(
                        l.chars().count() <= 80,
                        "{} columns: {l}",
                        l.chars().count()
                    );
                }
                for (a, s) in &status.states {
                    let row = lines
                        .iter()
                        .find(|l| l.contains(&format!(" {} ", a.function)))
                        .unwrap_or_else(|| panic!("{}: {lines:#?}", a.function));
                    assert!(row.ends_with(status.word_of(s)), "{row}");
                    assert!(row.contains(a.equation), "{row}");
                }
                let folder = format!("in {}/", chosen.path("src"));
                assert!(lines[0].contains(&folder), "{}", lines[0]);
            }
        }
    }
}
