//! `spintop course`: the assignments in course order with their state, the
//! progress, and what to do next, from one grading run of
//! `cargo test -p spintop-lessons` (its build noise and backtraces hidden).
//! The engine is [`crate::course`]; this file only prints it.

use super::{CliError, bad};
use crate::course::{self, State};
use clap::Args;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;

/// The raw arguments of `course`.
#[derive(Debug, Default, Args)]
pub struct CourseArgs {
    /// Show the grader's whole report for one assignment (its function name,
    /// e.g. torque_rate, or its equation, e.g. 2.2).
    #[arg(long, value_name = "NAME")]
    assignment: Option<String>,
    /// Instructor: grade the reference solutions (lessons/src/solutions/)
    /// instead of the student's files; every assignment must pass.
    #[arg(long)]
    solutions: bool,
}

fn repository() -> Result<PathBuf, CliError> {
    let repo = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    if repo.join("lessons").join("Cargo.toml").is_file() {
        Ok(repo)
    } else {
        Err(bad(format!(
            "spintop course grades the assignments in the repository, and {} is missing; run it from a clone of spintop",
            repo.join("lessons").display()
        )))
    }
}

fn mark(state: &State) -> &'static str {
    match state {
        State::Passing => "✓",
        State::Failing(_) | State::DoesNotCompile(_) => "✗",
        State::NotStarted | State::Unknown => "·",
    }
}

/// Runs `spintop course`.
pub(crate) fn execute(args: CourseArgs, out: &mut impl Write) -> Result<(), CliError> {
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
    let repo = repository()?;
    if std::io::stderr().is_terminal() {
        eprint!("grading (cargo test -p spintop-lessons)…\r");
    }
    if args.solutions && !repo.join("lessons/src/solutions").is_dir() {
        return Err(bad(
            "--solutions: lessons/src/solutions/ is not here (a student's copy has none)",
        ));
    }
    let status = course::grade(&repo, args.solutions).map_err(bad)?;
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
            a.file,
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
                a.equation, a.function, a.file, a.chapter
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
            writeln!(
                out,
                "  grade it alone: cargo test -p spintop-lessons --test {} {}",
                a.binary, a.test
            )?;
        }
    }
    Ok(())
}
