//! `spintop learn`'s keys as `less` has them, on a `TestBackend` with the
//! real book: `?` searches backward (help is `h` and F1), `q` closes an
//! overlay or panel and quits only from the text, Esc never quits, and a
//! paste is text for the search prompt, never keys.

use super::learn::{book, draw, press};
use crossterm::event::{Event, KeyCode};
use spintop_app::learn::{Learn, Mode};

fn open() -> Learn {
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    draw(&mut learn, 80, 24);
    learn
}

/// `?polhode` is a backward search for "polhode": no letter of it is run
/// as a command (`p` pauses the scene, `l` logs time, `h` opens the help).
#[test]
fn question_mark_searches_backward_and_its_letters_are_the_query() {
    let mut learn = open();
    press(&mut learn, KeyCode::Char('?'));
    for c in "polhode".chars() {
        press(&mut learn, KeyCode::Char(c));
    }
    assert_eq!(learn.mode(), &Mode::Search("polhode".into(), false));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("?polhode"), "{shown}");
    press(&mut learn, KeyCode::Enter);
    assert_eq!(learn.mode(), &Mode::Read);
    let search = learn.search().expect("a search made");
    assert_eq!(search.query, "polhode");
}

#[test]
fn h_and_f1_open_the_help_and_the_footer_says_so() {
    for code in [KeyCode::Char('h'), KeyCode::F(1)] {
        let mut learn = open();
        press(&mut learn, code);
        assert!(matches!(learn.mode(), Mode::Help(_)), "{code:?}");
    }
    let mut learn = open();
    let shown = draw(&mut learn, 80, 24);
    let footer = shown.lines().next_back().unwrap_or_default();
    assert!(footer.contains("h help"), "{shown}");
    // The course key stays in the footer at 80 columns, beside a scene.
    assert!(footer.contains("a course"), "{footer}");
}

/// As in `less`, q closes the help (and the contents, the course panel);
/// it quits only from the text. Esc never quits.
#[test]
fn q_closes_every_overlay_and_quits_only_from_the_text() {
    for opener in [KeyCode::Char('h'), KeyCode::Char('c'), KeyCode::Char('a')] {
        let mut learn = open();
        press(&mut learn, opener);
        assert_ne!(learn.mode(), &Mode::Read, "{opener:?} opens something");
        press(&mut learn, KeyCode::Char('q'));
        assert_eq!(learn.mode(), &Mode::Read, "{opener:?}: q closed it");
        assert!(!learn.should_quit(), "{opener:?}: q did not quit");
        for _ in 0..3 {
            press(&mut learn, KeyCode::Esc);
        }
        assert!(!learn.should_quit(), "Esc never quits");
        press(&mut learn, KeyCode::Char('q'));
        assert!(learn.should_quit(), "q quits from the text");
    }
}

/// A paste into the search prompt is its text (line breaks left out, never
/// Enter); a paste while reading runs none of its letters.
#[test]
fn a_paste_is_search_text_and_elsewhere_ignored() {
    let mut learn = open();
    let paste = |learn: &mut Learn, text: &str| {
        let command = learn.command_for(&Event::Paste(text.into())).unwrap();
        learn.apply(command);
    };
    paste(&mut learn, "q\nq");
    assert!(!learn.should_quit());
    assert_eq!(learn.mode(), &Mode::Read);
    assert!(
        learn
            .message()
            .is_some_and(|m| m.0.contains("paste ignored"))
    );
    press(&mut learn, KeyCode::Char('/'));
    paste(&mut learn, "polhode\nq");
    assert_eq!(learn.mode(), &Mode::Search("polhodeq".into(), true));
    assert!(!learn.should_quit());
}

/// "graded N s ago" is the latest grading's: a run that ends in a compile
/// error, or in cargo failing to run, is a grading too.
#[test]
fn the_time_of_grading_is_the_latest_runs() {
    use spintop_course::{Report, State, Status};
    let mut learn = open();
    learn.course_report(Report::Graded(Status::new(0, |_| State::Passing)));
    let first = learn.course_panel().graded_at().expect("graded");
    learn.course_report(Report::Grading);
    learn.course_report(Report::Failed("cargo could not be run".into()));
    let second = learn.course_panel().graded_at().expect("graded");
    assert!(second > first, "the failed run's time is shown");
    press(&mut learn, KeyCode::Char('a'));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("graded 0 s ago"), "{shown}");
    // The grades a run that could not grade leaves are the last ones, said so.
    assert_eq!(
        learn.course().map(Status::passing),
        Some(spintop_course::COURSE_LEN)
    );
    let flat = shown.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("the grades below (22 of 22 passing) are the last grading's"),
        "{shown}"
    );
}

/// Enter on a search says "searching…" first (the loop draws it before the
/// search runs, which across the whole book may take a moment), and the
/// answer replaces it.
#[test]
fn a_search_is_announced_before_it_runs() {
    use spintop_app::learn::Command;
    use spintop_app::term::session::Screen;
    let mut learn = open();
    press(&mut learn, KeyCode::Char('/'));
    for c in "qwxzzy".chars() {
        press(&mut learn, KeyCode::Char(c));
    }
    assert!(Screen::announce(&mut learn, &Command::SearchCommit));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("searching for “qwxzzy”…"), "{shown}");
    learn.apply(Command::SearchCommit);
    let shown = draw(&mut learn, 80, 24);
    assert!(!shown.contains("searching"), "{shown}");
    assert!(shown.contains("nowhere in the book"), "{shown}");
    // Keys that search nothing are not announced.
    assert!(!Screen::announce(&mut learn, &Command::PageDown));
}

/// A status message longer than the line is shown whole at 80 columns,
/// over the rows above it, not cut with "…".
#[test]
fn a_long_status_message_is_shown_whole_at_80_columns() {
    let mut learn = open();
    press(&mut learn, KeyCode::Char('M'));
    let message = learn.message().expect("M says what it did").0.clone();
    assert!(message.chars().count() > 78, "a long message: {message}");
    let shown = draw(&mut learn, 80, 24);
    let flat: String = shown
        .lines()
        .map(|l| l.trim_matches('"').trim())
        .collect::<Vec<_>>()
        .join(" ");
    let last_words: Vec<&str> = message.split_whitespace().rev().take(3).collect();
    for w in last_words {
        assert!(flat.contains(w), "“{w}” of “{message}” shown:\n{shown}");
    }
}
