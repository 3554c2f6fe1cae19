//! `spintop learn`: the book's chapters in the terminal beside their live
//! scenes (the screen itself is [`crate::tui::learn`]; this file validates,
//! keeps the progress file and restores the terminal).
//!
//! The chapters are read from the repository's `book/src` (one source: the
//! same Markdown mdBook builds), so `spintop learn` needs the repository, as
//! the course does. Progress is one small file, `target/spintop-learn.json`.

use super::gate::Gate;
use super::{CliError, bad};
use crate::tui::learn::{Learn, Progress};
use crate::tui::session::{self, Session};
use clap::Args;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The raw arguments of `learn`.
#[derive(Debug, Default, Args)]
#[command(after_help = "Examples:\n  \
    spintop learn                                    the book in the terminal, where you left it\n  \
    spintop learn --chapter 4.2                      Section 4.2 beside its scene\n  \
    spintop learn --list")]
pub struct LearnArgs {
    /// Open this chapter: a section of the paper (2, 3, 4.1, 4.2, 5, A) or a
    /// file name of the book (section-4-2, numerical-methods, …).
    #[arg(long, value_name = "CHAPTER")]
    chapter: Option<String>,
    /// Print the chapters, their scenes and experiments, and the progress, as
    /// plain text, and exit.
    #[arg(long)]
    list: bool,
    /// Forget the progress (the chapters opened) and exit.
    #[arg(long, conflicts_with_all = ["list", "chapter"])]
    reset: bool,
    /// Do not grade the course in the background (by default the assignments
    /// are graded at the start and again whenever a file in lessons/src is saved).
    #[arg(long)]
    no_grading: bool,
    /// The course to grade beside the book: a lessons crate (default: the
    /// repository's lessons/; a student's copy made by `spintop course export`
    /// also works).
    #[arg(long, value_name = "DIR", conflicts_with = "no_grading")]
    course: Option<PathBuf>,
}

fn repository() -> PathBuf {
    spintop_course::repository().to_path_buf()
}

fn book_dir(repo: &Path) -> Result<PathBuf, CliError> {
    let book = repo.join("book").join("src");
    if book.join("SUMMARY.md").is_file() {
        Ok(book)
    } else {
        Err(bad(format!(
            "spintop learn reads the book from the repository, and {} is missing; run it from a clone of spintop (`cargo run --release -- learn`)",
            book.join("SUMMARY.md").display()
        )))
    }
}

fn progress_file(repo: &Path) -> PathBuf {
    // The tests point this elsewhere, so that they never touch a student's progress.
    match std::env::var_os("SPINTOP_LEARN_PROGRESS") {
        Some(path) if !path.is_empty() => PathBuf::from(path),
        _ => repo.join("target").join("spintop-learn.json"),
    }
}

fn read_progress(path: &Path) -> Progress {
    // A missing or unreadable file is a fresh start, never an error.
    std::fs::read(path)
        .ok()
        .filter(|b| b.len() < 1 << 20)
        .and_then(|b| serde_json::from_slice(&b).ok())
        .unwrap_or_default()
}

/// Runs `spintop learn`.
pub(crate) fn execute(args: LearnArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let repo = repository();
    let progress_path = progress_file(&repo);
    if args.reset {
        match std::fs::remove_file(&progress_path) {
            Ok(()) => writeln!(
                out,
                "spintop learn: progress forgotten ({})",
                progress_path.display()
            )?,
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                writeln!(out, "spintop learn: no progress to forget")?
            }
            Err(e) => return Err(CliError::Io(e)),
        }
        return Ok(());
    }
    let book = book_dir(&repo)?;
    // The course to grade beside the book, checked before the screen changes.
    let course = if !args.no_grading
        && (args.course.is_some()
            || spintop_course::lessons_dir(&repo)
                .join("Cargo.toml")
                .is_file())
    {
        Some(super::course::lessons(args.course.as_ref())?)
    } else {
        None
    };
    let progress = read_progress(&progress_path);
    let start = args.chapter.clone().or(if args.list {
        None
    } else {
        progress.last.clone()
    });
    // The scenes run on threads of their own: the screen never waits on them.
    let mut session = match Learn::open_in_background(&book, start.as_deref()) {
        Ok(s) => s,
        // A stale "last chapter" in the progress file falls back to the preface.
        Err(_) if args.chapter.is_none() => Learn::open_in_background(&book, None).map_err(bad)?,
        Err(e) => return Err(bad(e)),
    };
    session.restore(&progress);
    if args.list {
        return list(&mut session, &progress, out);
    }
    session::check().map_err(|e| {
        bad(format!(
            "spintop learn {e}; `spintop learn --list` prints the course as text"
        ))
    })?;
    match course {
        Some(dir) => session.watch_course(&dir),
        None if args.no_grading => session.grading_off(
            "--no-grading turned the grader off; run spintop learn without it to grade the \
             assignments beside the book, or `spintop course` to grade them once",
        ),
        None => session.grading_off(
            "there is no lessons/ crate here to grade; a copy made by `spintop course export` \
             is graded with --course DIR",
        ),
    }
    let signal = Session::start(true)?.run(&mut session, None)?.signal;
    let progress = Progress::of(&session);
    if let Some(dir) = progress_path.parent() {
        // Progress is a convenience: failing to save it is reported, not fatal.
        let saved = std::fs::create_dir_all(dir).and_then(|()| {
            std::fs::write(
                &progress_path,
                serde_json::to_vec_pretty(&progress).unwrap_or_default(),
            )
        });
        if let Err(e) = saved {
            writeln!(
                out,
                "spintop learn: progress not saved to {}: {e}",
                progress_path.display()
            )?;
        }
    }
    if let Some(signal) = signal {
        return Err(CliError::Signal(signal, crate::tui::signals::name(signal)));
    }
    Ok(())
}

fn list(session: &mut Learn, progress: &Progress, out: &mut impl Write) -> Result<(), CliError> {
    let opened = progress.opened.len();
    writeln!(
        out,
        "spintop learn: {} chapters, {opened} opened",
        session.chapters().len()
    )?;
    let chapters = session.chapters().to_vec();
    let mut part = None;
    for (i, c) in chapters.iter().enumerate() {
        if c.part != part {
            part = c.part.clone();
            if let Some(p) = &part {
                writeln!(out, "{p}")?;
            }
        }
        let mark = if progress.opened.contains(&c.file) {
            "✓"
        } else {
            " "
        };
        let section = c.section().map(|s| format!("§{s}")).unwrap_or_default();
        writeln!(
            out,
            "  {mark} {:>2} {section:<5} {} ({})",
            i + 1,
            c.title,
            c.file.trim_end_matches(".md")
        )?;
        let experiments = match experiments_of(session, i)? {
            0 => String::new(),
            1 => "; 1 experiment".into(),
            n => format!("; {n} experiments"),
        };
        writeln!(out, "           {}{experiments}", scene_line(&c.scene()))?;
    }
    writeln!(
        out,
        "open one with: spintop learn --chapter 4.2 (a section) or --chapter numerical-methods (a file)"
    )?;
    Ok(())
}

/// "scene: …", or "no scene: why".
fn scene_line(scene: &crate::tui::learn::scene::Scene) -> String {
    match scene.spec {
        crate::tui::learn::scene::Spec::None => scene.describe(),
        _ => format!("scene: {}", scene.about),
    }
}

fn experiments_of(session: &Learn, index: usize) -> Result<usize, CliError> {
    let book = book_dir(&repository())?;
    let file = &session.chapters()[index].file;
    let text = std::fs::read_to_string(book.join(file)).map_err(CliError::Io)?;
    Ok(crate::tui::learn::markdown::render(&text, 80)
        .experiments
        .len())
}
