//! `spintop learn`: the book's chapters in the terminal beside their live
//! scenes (the screen itself is [`crate::learn`]; this file validates,
//! chooses the course to grade, and says how the session ended).
//!
//! The course is the one the command stands in (a student's copy, or a
//! clone's lessons), as `spintop course` finds it, or the one `--course`
//! names: it is graded beside the book, and its book is read
//! ([`Book::beside`]: the `book/src` a copy made by `spintop course export`
//! carries, or a clone's, the same Markdown mdBook builds; else the book of
//! the repository this spintop was built from). Progress is one small file,
//! `target/spintop-learn.json` in the course's own folder (the repository's
//! when no course is found), kept as the reader reads.

use super::gate::Gate;
use super::{CliError, bad};
use crate::learn::scene::{Scene, Spec};
use crate::learn::{Learn, progress};
use crate::term::session;
use clap::Args;
use spintop_course::{Book, Course};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The raw arguments of `learn`.
#[derive(Debug, Default, Args)]
#[command(after_help = "Examples:\n  \
    spintop learn                                    the book in the terminal, where you left it\n  \
    spintop learn --chapter 9                        chapter 9, as the header counts (\"chapter 9 of …\")\n  \
    spintop learn --chapter 4.2                      Section 4.2 of the paper beside its scene\n  \
    spintop learn --chapter §5                       Section 5 (a bare 5 is chapter 5)\n  \
    spintop learn --list\n  \
    spintop learn --chapter 4.1 --list               Section 4.1 as plain text\n\n\
The book is the one the course you stand in carries (a copy made by `spintop course export`\n\
holds it in book/src), else the book of the spintop repository; --list names it.\n\n\
The reading place (the chapter, where in it, the chapters opened) is kept in\n\
target/spintop-learn.json of the course you stand in (a copy keeps its own, even\n\
when it carries no book; the repository's only when there is no course), written\n\
as you read and on every way out; --reset forgets it.")]
pub struct LearnArgs {
    /// Open this chapter: its number as the header shows it ("chapter 9 of
    /// …": 9), a section of the paper (§2, §3, 4.1, 4.2, §5, A; also
    /// 'section 5'), a file name of the book (section-5, numerical-methods)
    /// or words of its title (where methods fail), in any case.
    #[arg(long, value_name = "CHAPTER")]
    chapter: Option<String>,
    /// Print the chapters, their scenes and experiments, the progress and
    /// which book is read, as plain text, and exit; with --chapter, print
    /// that chapter's text instead (80 columns).
    #[arg(long)]
    list: bool,
    /// Forget the progress (the chapters opened) and exit.
    #[arg(long, conflicts_with_all = ["list", "chapter"])]
    reset: bool,
    /// Do not grade the course in the background (by default the course you
    /// stand in is graded at the start and again whenever one of its files
    /// is saved).
    #[arg(long)]
    no_grading: bool,
    /// The course to grade beside the book, whose book is read if it carries
    /// one: a lessons crate (default: the one the current folder is in, as
    /// cargo finds its manifest; else the repository's lessons/).
    #[arg(long, value_name = "DIR", conflicts_with = "no_grading")]
    course: Option<PathBuf>,
}

/// The course the command stands in (named, or found from the current
/// folder, else the repository's): the one graded beside the book, and the
/// one whose book is read.
fn chosen(args: &LearnArgs) -> Course {
    let cwd = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
    Course::choose(args.course.as_deref(), &cwd)
}

/// The book to read beside `course` ([`Book::beside`]: the one the course
/// carries, else the repository's).
fn book(course: &Course) -> Result<Book, CliError> {
    Book::beside(course, spintop_course::repository()).map_err(|e| {
        bad(format!(
            "spintop learn reads the book of the course it stands in: {e}; run it in a copy made by `spintop course export`, or from a clone of spintop (`cargo run --release -- learn`)"
        ))
    })
}

/// Where the reader's place is kept: in the `target/` of [`Book::home`]
/// (the course's own folder; the repository's when there is no course). The one rule;
/// `spintop learn --help` says it.
pub fn progress_file(book: &Book) -> PathBuf {
    // The tests point this elsewhere, so that they never touch a student's progress.
    match std::env::var_os("SPINTOP_LEARN_PROGRESS") {
        Some(path) if !path.is_empty() => PathBuf::from(path),
        _ => book.home.join("target").join("spintop-learn.json"),
    }
}

/// The course to grade beside the book, checked before the screen changes:
/// the one named, or the one the current folder stands in.
fn graded(args: &LearnArgs, course: &Course) -> Result<Option<Course>, CliError> {
    if args.no_grading {
        return Ok(None);
    }
    match spintop_course::check_lessons_dir(&course.dir) {
        Ok(()) => Ok(Some(course.clone())),
        Err(e) if args.course.is_some() => Err(bad(format!("--course: {e}"))),
        // No course here, and the repository's is missing: the book alone.
        Err(_) => Ok(None),
    }
}

/// Runs `spintop learn`.
pub(crate) fn execute(args: LearnArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let chosen = chosen(&args);
    let course = graded(&args, &chosen)?;
    let book = book(&chosen)?;
    let progress_path = progress_file(&book);
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
            Err(e) => {
                return Err(CliError::NotSaved(format!(
                    "learn --reset: your place in {} could not be forgotten: {}",
                    progress_path.display(),
                    spintop_course::unwritable_why(&progress_path, &e)
                )));
            }
        }
        return Ok(());
    }
    let opened = progress::open(&progress_path);
    let read = opened.progress.clone();
    let start = args
        .chapter
        .clone()
        .or(if args.list { None } else { read.last.clone() });
    // The scenes run on threads of their own: the screen never waits on them.
    let mut session = match Learn::open_in_background(&book.src, start.as_deref()) {
        Ok(s) => s,
        // A stale "last chapter" in the progress file falls back to the preface.
        Err(_) if args.chapter.is_none() => {
            Learn::open_in_background(&book.src, None).map_err(|e| bad(e.to_string()))?
        }
        Err(e) => return Err(bad(e.to_string())),
    }
    .plain(crate::term::theme::no_color());
    session.restore(&read);
    if args.list && args.chapter.is_some() {
        writeln!(out, "{}", session.chapter_text(TEXT_WIDTH).trim_end())?;
        return Ok(());
    }
    if args.list {
        if let Some(said) = &opened.said {
            writeln!(out, "spintop learn: {said}")?;
        }
        return list(&mut session, &read, &book, out);
    }
    session::check().map_err(|e| {
        bad(format!(
            "spintop learn {e}; `spintop learn --list` prints the course as text"
        ))
    })?;
    match course {
        Some(c) => session.watch_course(c, super::course::launcher()),
        None if args.no_grading => session.grading_off(
            "--no-grading turned the grader off; run spintop learn without it to grade the \
             assignments beside the book, or `spintop course` to grade them once",
        ),
        None => session.grading_off(
            "there is no course here to grade: run spintop learn in a copy made by \
             `spintop course export`, or name one with --course DIR",
        ),
    }
    if book.instead_of.is_some() {
        // Not the book one would expect where one stands: say whose it is.
        session.note(format!("reading {}", book.describe()));
    }
    if let Some(said) = opened.said {
        session.note(said);
    }
    if opened.keep {
        session.keep_progress(progress_path, read);
    }
    // However the session ends (q, a signal, a terminal gone), the place is
    // saved before anything else is said.
    let ran = crate::learn::run(&mut session);
    let saved = session.save_progress();
    let report = ran?;
    if let Err(e) = saved {
        return Err(CliError::NotSaved(e.to_string()));
    }
    if let Some(signal) = report.signal {
        return Err(CliError::Signal(signal, crate::term::signals::name(signal)));
    }
    Ok(())
}

/// The width `--chapter X --list` prints a chapter at (a terminal's).
const TEXT_WIDTH: u16 = 80;

fn list(
    session: &mut Learn,
    progress: &progress::Progress,
    book: &Book,
    out: &mut impl Write,
) -> Result<(), CliError> {
    let opened = progress.opened.len();
    writeln!(
        out,
        "spintop learn: {} chapters, {opened} opened; reading {}",
        session.chapters().len(),
        book.describe()
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
        let experiments = match experiments_of(&book.src, &c.file)? {
            0 => String::new(),
            1 => "; 1 experiment".into(),
            n => format!("; {n} experiments"),
        };
        writeln!(out, "           {}{experiments}", scene_line(&c.scene()))?;
    }
    writeln!(
        out,
        "open one with: spintop learn --chapter 9 (its number, as above), --chapter 4.2 or §5 (a section) or --chapter numerical-methods (a file); print one as text with --chapter 4.2 --list"
    )?;
    Ok(())
}

/// "scene: …", or "no scene: why".
fn scene_line(scene: &Scene) -> String {
    match scene.spec {
        Spec::None => scene.describe(),
        _ => format!("scene: {}", scene.about),
    }
}

fn experiments_of(book: &Path, file: &str) -> Result<usize, CliError> {
    let text = std::fs::read_to_string(book.join(file)).map_err(CliError::Io)?;
    Ok(crate::learn::markdown::render(&text, 80).experiments.len())
}
