//! `spintop course grade DIR...`: a class graded with the repository's
//! graders, each copy in its sandbox, one row per student and assignment
//! whatever happens; a progress bar on a terminal that never holds up the
//! output. The grading itself is `spintop_course::gradebook`; this file
//! validates, shows progress and writes the files.

use super::super::gate::Gate;
use super::super::{CliError, bad};
use super::{GradeFormat, launcher};
use spintop_course::{self as course, gradebook};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The time limits and parallelism of `course grade`, validated.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    timeout: Duration,
    test_timeout: Duration,
    jobs: usize,
}

impl Limits {
    pub(crate) fn new(
        timeout: f64,
        test_timeout: f64,
        jobs: Option<usize>,
    ) -> Result<Self, CliError> {
        let seconds = |v: f64, flag: &str| {
            if v.is_finite() && v > 0.0 && v <= 86_400.0 {
                Ok(Duration::from_secs_f64(v))
            } else {
                Err(bad(format!(
                    "{flag} {}: give a number of seconds above 0 and at most a day",
                    spintop::numbers::fmt_value(v)
                )))
            }
        };
        let jobs = match jobs {
            Some(0) => return Err(bad("--jobs 0: give at least 1 copy at a time")),
            Some(n) if n > 256 => return Err(bad(format!("--jobs {n}: at most 256"))),
            Some(n) => n,
            None => std::thread::available_parallelism().map_or(2, |n| n.get()),
        };
        Ok(Self {
            timeout: seconds(timeout, "--timeout")?,
            test_timeout: seconds(test_timeout, "--test-timeout")?,
            jobs,
        })
    }
}

/// Where the grades go, checked before any copy is graded.
fn check_out(path: Option<&PathBuf>, format: GradeFormat, several: bool) -> Result<(), CliError> {
    let Some(p) = path else {
        if format == GradeFormat::Gradescope && several {
            return Err(bad(
                "--format gradescope with several copies writes one results.json each: give --out FOLDER",
            ));
        }
        return Ok(());
    };
    if format == GradeFormat::Gradescope && several {
        if p.exists() && !p.is_dir() {
            return Err(bad(format!(
                "--out {}: with several copies, Gradescope's results go to a folder (one STUDENT/results.json each)",
                p.display()
            )));
        }
        return Ok(());
    }
    let parent = p.parent().filter(|q| !q.as_os_str().is_empty());
    if parent.is_some_and(|q| !q.is_dir()) {
        return Err(bad(format!(
            "--out {}: the folder {} does not exist",
            p.display(),
            parent.map(|q| q.display().to_string()).unwrap_or_default()
        )));
    }
    if p.is_dir() {
        return Err(bad(format!("--out {}: a folder; give a file", p.display())));
    }
    Ok(())
}

/// `spintop course grade DIR...`: each copy graded with the repository's
/// graders, one row per student and assignment, whatever happens.
pub(crate) fn grade_copies(
    copies: &[PathBuf],
    path: Option<&PathBuf>,
    format: GradeFormat,
    limits: Limits,
    seed: Option<u64>,
    out: &mut Gate<'_>,
) -> Result<(), CliError> {
    let repo = course::repository();
    if !course::lessons_dir(repo).join("Cargo.toml").is_file() {
        return Err(bad(
            "spintop course grade needs the repository's graders (lessons/); run it from a clone of spintop",
        ));
    }
    if let Some(why) = gradebook::same_names(copies) {
        return Err(bad(why));
    }
    check_out(path, format, copies.len() > 1)?;
    let options = gradebook::ClassOptions {
        timeout: limits.timeout,
        test_limit: limits.test_timeout,
        jobs: limits.jobs,
        seed,
        work: repo.join("target").join("course-grade"),
        launcher: launcher(),
    };
    if let Some(warning) = seed.and_then(|s| course::sheet::seed_shown_before(&options.work, s)) {
        eprintln!("spintop course grade: warning: {warning}");
    }
    let class = grade_class(copies, &options)?;
    write_grades(&class, path, format, &options.work, out)?;
    ungraded(&class)
}

/// Grades the class in a run folder of its own, with a progress bar over
/// the copies on a terminal (drawn from the grading threads, never holding
/// the output).
fn grade_class(
    copies: &[PathBuf],
    options: &gradebook::ClassOptions,
) -> Result<gradebook::Class, CliError> {
    let run = gradebook::Run::new(&options.work)
        .map_err(|e| CliError::CannotGrade(format!("course grade: {e}")))?;
    let terminal = std::io::stderr().is_terminal();
    // Spintop itself is built once, before any copy's clock starts (only when
    // some copy will be built at all).
    if copies.iter().any(|c| course::check_lessons_dir(c).is_ok()) {
        if terminal {
            eprint!("preparing the graders (the first build of spintop can take a minute)…\r");
        }
        // A failed warm-up is said, not fatal: each copy then builds cold.
        if let Err(e) = gradebook::warm_up(course::repository(), options, &run) {
            eprintln!("spintop course grade: preparing the graders failed: {e}");
        }
        if terminal {
            eprint!("{}\r", " ".repeat(72));
        }
    }
    let bar = terminal.then(|| {
        let bar = indicatif::ProgressBar::new(copies.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "grading {bar:30} {pos}/{len} copies, {elapsed} ({msg})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.enable_steady_tick(Duration::from_millis(250));
        bar
    });
    let class = gradebook::grade_class(copies, options, &run, &|copy| {
        if let Some(bar) = &bar {
            bar.set_message(copy.student.clone());
            bar.inc(1);
        }
    });
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    Ok(class)
}

/// Writes the CSV, or the Gradescope results (noting their seed as shown
/// to students).
fn write_grades(
    class: &gradebook::Class,
    path: Option<&PathBuf>,
    format: GradeFormat,
    work: &Path,
    out: &mut Gate<'_>,
) -> Result<(), CliError> {
    let write = |p: &Path, text: &str| {
        std::fs::write(p, text).map_err(|e| bad(format!("course grade --out {}: {e}", p.display())))
    };
    match format {
        GradeFormat::Csv => {
            let text = class.csv();
            match path {
                Some(p) => {
                    write(p, &text)?;
                    writeln!(
                        out,
                        "spintop course grade: {} students, {} rows written to {} (inputs from seed {})",
                        class.copies.len(),
                        class.copies.len() * (course::COURSE_LEN + 1),
                        p.display(),
                        class.seed
                    )?;
                }
                None => write!(out, "{text}")?,
            }
        }
        GradeFormat::Gradescope => {
            let several = class.copies.len() > 1;
            for copy in &class.copies {
                let json = serde_json::to_string_pretty(&class.gradescope(copy))
                    .unwrap_or_default()
                    + "\n";
                match (path, several) {
                    (None, _) => write!(out, "{json}")?,
                    (Some(p), false) => write(p, &json)?,
                    (Some(p), true) => {
                        let folder = p.join(&copy.student);
                        std::fs::create_dir_all(&folder)
                            .map_err(|e| bad(format!("{}: {e}", folder.display())))?;
                        write(&folder.join("results.json"), &json)?;
                    }
                }
            }
            course::sheet::record_shown_seed(work, class.seed);
            if let Some(p) = path {
                writeln!(
                    out,
                    "spintop course grade: Gradescope results for {} students written to {}",
                    class.copies.len(),
                    p.display()
                )?;
            }
        }
    }
    Ok(())
}

/// Exit 4 (could not grade) naming the copies that could not be fully
/// graded, if any.
fn ungraded(class: &gradebook::Class) -> Result<(), CliError> {
    let count = class.ungraded();
    if count == 0 {
        return Ok(());
    }
    let names: Vec<String> = class
        .copies
        .iter()
        .filter(|c| !c.fully_graded())
        .map(|c| {
            let words: Vec<&str> = course::COURSE
                .iter()
                .map(|a| c.row(a).0)
                .filter(|w| {
                    !matches!(
                        *w,
                        "passing" | "failing" | "not started" | "does not compile"
                    )
                })
                .collect();
            format!(
                "{} ({})",
                c.student,
                words.first().copied().unwrap_or("not graded")
            )
        })
        .collect();
    Err(CliError::CannotGrade(format!(
        "course grade: {count} of {} copies could not be fully graded: {}; their rows say why",
        class.copies.len(),
        names.join(", ")
    )))
}

/// Runs `grade` with a line on a terminal that says how far one grading of
/// one course has got (its build, then its graders), redrawn four times a
/// second and cleared at the end; off a terminal, no line and no progress.
/// (`spintop course` on a terminal had said nothing for the minutes of a
/// first build.)
pub(crate) fn with_progress<T>(
    what: &str,
    grade: impl FnOnce(Option<std::sync::Arc<course::building::Building>>) -> T,
) -> T {
    if !std::io::stderr().is_terminal() {
        return grade(None);
    }
    let building = course::building::Building::shared();
    let line = indicatif::ProgressBar::new_spinner();
    line.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    line.set_message(format!("grading {what}"));
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let drawer = {
        let (line, building, stop) = (line.clone(), building.clone(), stop.clone());
        std::thread::spawn(move || {
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                line.set_message(building.snapshot().describe());
                line.tick();
                std::thread::sleep(Duration::from_millis(250));
            }
        })
    };
    let result = grade(Some(building));
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let _ = drawer.join();
    line.finish_and_clear();
    result
}
