//! `spintop learn` against `less`, on a `TestBackend` with the real book:
//! search across the book from where the reader is, forward and backward;
//! half pages; the position and END; the contents paged and numbered;
//! `--chapter` by the header's number and by words in any case; links
//! followed; the mouse left to the terminal; the help scrolled at 60×20;
//! the scene beside the text from 80 columns; the book's pictures drawn;
//! details marked open; each chapter's words matching its scene; the
//! course panel at 80×24; the reader's place kept as it moves.

use super::learn::{book, draw, press};
use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use spintop_app::learn::markdown;
use spintop_app::learn::scene::Spec;
use spintop_app::learn::{Command, Learn, Mode, find_chapter};
use spintop_app::live::Top;
use spintop_app::term::session::Screen;

fn ctrl(learn: &mut Learn, c: char) {
    let event = Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::CONTROL));
    if let Some(command) = learn.command_for(&event) {
        learn.apply(command);
    }
}

/// Types `word` after `/` (or Ctrl-R) and Enter.
fn search(learn: &mut Learn, start: Command, word: &str) {
    learn.apply(start);
    for c in word.chars() {
        learn.apply(Command::SearchInput(c));
    }
    learn.apply(Command::SearchCommit);
}

fn file(learn: &Learn) -> &str {
    &learn.chapters()[learn.current()].file
}

fn message(learn: &Learn) -> String {
    learn.message().map(|m| m.0.clone()).unwrap_or_default()
}

/// A word in no chapter before Section 2 is found there from the preface,
/// and the status says where; `n` after `G` goes on from the end of the
/// page (the next chapter that has the word), never back to the top; `N`
/// and Ctrl-R go back.
#[test]
fn search_goes_across_the_book_from_where_the_reader_is() {
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 80, 24);
    search(&mut learn, Command::SearchStart, "twelve digits");
    assert_eq!(file(&learn), "section-2.md");
    let said = message(&learn);
    assert!(
        said.contains("in Section 2") && said.contains("chapter 3 of"),
        "{said}"
    );
    let page = learn.scroll()..learn.scroll() + 20;
    let s = learn.search().unwrap();
    assert!(
        page.contains(&s.matches[s.at.unwrap()].line()),
        "the match is on the page"
    );

    // "runaway" is in Section 2 and later chapters: from the end of
    // Section 2, n goes on to a later chapter.
    press(&mut learn, KeyCode::Char('g'));
    search(&mut learn, Command::SearchStart, "runaway");
    assert_eq!(file(&learn), "section-2.md");
    press(&mut learn, KeyCode::Char('G'));
    let end = learn.scroll();
    let last_here = learn.search().unwrap().matches.last().unwrap().line();
    press(&mut learn, KeyCode::Char('n'));
    if last_here < end {
        assert_ne!(file(&learn), "section-2.md", "{}", message(&learn));
        assert!(message(&learn).contains("(chapter"), "{}", message(&learn));
    } else {
        assert!(
            learn.scroll() + 1 >= end.min(last_here),
            "n from the end, not the top"
        );
    }
    let ahead = learn.current();
    // N goes back the other way: to an earlier match, here or before.
    press(&mut learn, KeyCode::Char('N'));
    assert!(learn.current() <= ahead);

    // Ctrl-R searches backward: from Section 3's top, "twelve digits" is
    // found behind, in Section 2.
    let mut learn = Learn::open(&book(), Some("§3")).unwrap();
    draw(&mut learn, 80, 24);
    ctrl(&mut learn, 'r');
    assert_eq!(learn.mode(), &Mode::Search(String::new(), false));
    for c in "twelve digits".chars() {
        learn.apply(Command::SearchInput(c));
    }
    learn.apply(Command::SearchCommit);
    assert_eq!(file(&learn), "section-2.md", "{}", message(&learn));
    // A word in no chapter is said to be nowhere.
    search(&mut learn, Command::SearchStart, "xyzzy-not-a-word");
    assert!(message(&learn).contains("nowhere in the book"));
}

/// `d` `u` and Ctrl-D Ctrl-U move half a page, Ctrl-F Ctrl-B a page; the
/// frame says where the reader is, and END at the end.
#[test]
fn half_pages_and_the_position_as_less_has_them() {
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("% lines 1–"), "{shown}");
    // 24 rows: the header, the frame's two borders, the status, the keys.
    let page = 19;
    press(&mut learn, KeyCode::Char('d'));
    assert_eq!(learn.scroll(), page / 2);
    press(&mut learn, KeyCode::Char('u'));
    assert_eq!(learn.scroll(), 0);
    ctrl(&mut learn, 'd');
    assert_eq!(learn.scroll(), page / 2);
    ctrl(&mut learn, 'u');
    ctrl(&mut learn, 'f');
    assert_eq!(learn.scroll(), page - 2);
    ctrl(&mut learn, 'b');
    assert_eq!(learn.scroll(), 0);
    press(&mut learn, KeyCode::Char('G'));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains(" END "), "{shown}");
}

/// less's other names for the same moves: `e` `y` and Ctrl-E Ctrl-N
/// Ctrl-Y Ctrl-P a line, `z` and Ctrl-V a page, `<` `>` the top and the
/// end, `Q` quits.
#[test]
fn less_s_other_names_for_a_line_a_page_the_ends_and_quit() {
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    draw(&mut learn, 80, 24);
    let page = 19;
    press(&mut learn, KeyCode::Char('e'));
    assert_eq!(learn.scroll(), 1, "e");
    press(&mut learn, KeyCode::Char('y'));
    assert_eq!(learn.scroll(), 0, "y");
    for (down, up) in [('e', 'y'), ('n', 'p'), ('j', 'k')] {
        ctrl(&mut learn, down);
        assert_eq!(learn.scroll(), 1, "^{down}");
        ctrl(&mut learn, up);
        assert_eq!(learn.scroll(), 0, "^{up}");
    }
    press(&mut learn, KeyCode::Char('z'));
    assert_eq!(learn.scroll(), page - 2);
    ctrl(&mut learn, 'v');
    assert_eq!(learn.scroll(), 2 * (page - 2));
    press(&mut learn, KeyCode::Char('<'));
    assert_eq!(learn.scroll(), 0);
    press(&mut learn, KeyCode::Char('>'));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains(" END "), "{shown}");
    assert!(!learn.should_quit());
    press(&mut learn, KeyCode::Char('Q'));
    assert!(learn.should_quit());
}

/// The contents page with PgDn and number their chapters as the header
/// does; typing a number goes to that chapter, Enter opens it.
#[test]
fn the_contents_page_and_take_the_chapters_number() {
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 80, 24);
    press(&mut learn, KeyCode::Char('c'));
    assert_eq!(learn.mode(), &Mode::Contents(0));
    press(&mut learn, KeyCode::PageDown);
    let Mode::Contents(after_page) = *learn.mode() else {
        panic!("still the contents")
    };
    assert!(
        after_page >= 10,
        "a page is more than one line: {after_page}"
    );
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("a number jumps"), "{shown}");
    press(&mut learn, KeyCode::Char('9'));
    press(&mut learn, KeyCode::Enter);
    assert_eq!(learn.current(), 8, "chapter 9 as the header counts");
    let shown = draw(&mut learn, 80, 24);
    assert!(
        shown.contains(" 9/") || shown.contains("chapter 9 of"),
        "{shown}"
    );
    // A number with no chapter is refused, and says the range.
    press(&mut learn, KeyCode::Char('c'));
    press(&mut learn, KeyCode::Char('9'));
    press(&mut learn, KeyCode::Char('9'));
    assert!(
        message(&learn).contains("no chapter 99"),
        "{}",
        message(&learn)
    );
}

/// `--chapter` takes the number the header shows, and names in any case.
#[test]
fn chapter_takes_the_headers_number_and_words_in_any_case() {
    let learn = Learn::open(&book(), Some("9")).unwrap();
    assert_eq!(learn.current(), 8);
    let chapters = learn.chapters();
    for (wanted, file) in [
        ("Where Methods Fail", "where-methods-fail.md"),
        ("NUMERICAL-METHODS", "numerical-methods.md"),
        ("#3", "section-2.md"),
        ("chapter 3", "section-2.md"),
        ("§3", "section-3.md"),
        ("SECTION 3", "section-3.md"),
        ("Section-3", "section-3.md"),
        ("§4.2", "section-4-2.md"),
        ("4.2", "section-4-2.md"),
        ("asymmetric", "asymmetric-top.md"),
    ] {
        let i = find_chapter(chapters, wanted).unwrap_or_else(|| panic!("--chapter {wanted}"));
        assert_eq!(chapters[i].file, file, "--chapter {wanted}");
    }
}

/// A bare number is the chapter the header numbers so, for every chapter
/// (`--chapter 5` opened Section 5, the seventh, while the messages said
/// chapter numbers are the header's); where the number is also a
/// section's, the note says which chapter that section is, and the way it
/// names opens it.
#[test]
fn a_bare_number_opens_the_chapter_the_header_numbers_so() {
    let count = Learn::open(&book(), None).unwrap().chapters().len();
    for n in 1..=count {
        let mut learn = Learn::open(&book(), Some(&n.to_string())).unwrap();
        assert_eq!(learn.current() + 1, n, "--chapter {n}");
        let shown = draw(&mut learn, 120, 30);
        assert!(
            shown.contains(&format!("chapter {n} of {count}")),
            "--chapter {n}: the header\n{shown}"
        );
    }
    let sections: Vec<String> = Learn::open(&book(), None)
        .unwrap()
        .chapters()
        .iter()
        .filter_map(|c| c.section())
        .filter(|s| s.parse::<usize>().is_ok())
        .map(str::to_string)
        .collect();
    assert!(sections.len() >= 3, "{sections:?}");
    for s in sections {
        let learn = Learn::open(&book(), Some(&s)).unwrap();
        let note = message(&learn);
        assert!(note.contains(&format!("chapter {s} of {count}")), "{note}");
        for way in [format!("§{s}"), format!("section-{s}")] {
            assert!(note.contains(&way), "{note}");
            let section = Learn::open(&book(), Some(&way)).unwrap();
            let said = format!("Section {s} is chapter {}", section.current() + 1);
            assert!(note.contains(&said), "{note}: want {said}");
            assert_eq!(
                section.chapters()[section.current()].section(),
                Some(s.as_str()),
                "--chapter {way}"
            );
        }
    }
    // The refusal of a name that is none lists the ways in the same words.
    let e = Learn::open(&book(), Some("9.9")).err().unwrap().to_string();
    assert!(
        e.contains(&format!(
            "the chapter's number as the header shows it (1 to {count})"
        )) && e.contains("§5"),
        "{e}"
    );
}

/// Tab from the top of a chapter whose first link is further down scrolls
/// to it, as a browser moves the focus; Shift-Tab before the first link,
/// and Tab after the last, say so.
#[test]
fn tab_scrolls_to_a_link_below_the_page() {
    let mut learn = Learn::open(&book(), Some("asymmetric-top")).unwrap();
    draw(&mut learn, 100, 30);
    let first = learn.rendered().links[0].parts[0].0;
    assert!(
        first > 28,
        "the first link is below the first page: {first}"
    );
    press(&mut learn, KeyCode::Tab);
    assert_eq!(learn.focused_link(), Some(0), "{}", message(&learn));
    assert!(
        learn.scroll() <= first && first < learn.scroll() + 26,
        "scrolled to it: {} for line {first}",
        learn.scroll()
    );
    press(&mut learn, KeyCode::BackTab);
    assert!(
        message(&learn).contains("no link further up"),
        "{}",
        message(&learn)
    );
    press(&mut learn, KeyCode::Char('G'));
    let last = learn.rendered().links.len() - 1;
    for _ in 0..=last {
        press(&mut learn, KeyCode::Tab);
    }
    assert!(
        message(&learn).contains("no link further down"),
        "{}",
        message(&learn)
    );
}

/// Tab puts the links of the page in focus one by one, Enter follows the
/// one in focus: another chapter, at the heading its anchor names.
#[test]
fn tab_and_enter_follow_a_link_to_its_chapter_and_heading() {
    let mut learn = Learn::open(&book(), Some("asymmetric-top")).unwrap();
    draw(&mut learn, 100, 30);
    let target = "scene-reference.md#what-auto-chooses";
    let link = learn
        .rendered()
        .links
        .iter()
        .position(|l| l.target == target)
        .expect("the chapter links to the scene reference");
    let line = learn.rendered().links[link].parts[0].0;
    learn.apply(Command::Scroll(line as i64));
    draw(&mut learn, 100, 30);
    for _ in 0..learn.rendered().links.len() {
        if learn.focused_link() == Some(link) {
            break;
        }
        press(&mut learn, KeyCode::Tab);
    }
    assert_eq!(learn.focused_link(), Some(link), "{}", message(&learn));
    assert!(message(&learn).contains(target));
    press(&mut learn, KeyCode::Enter);
    assert_eq!(file(&learn), "scene-reference.md");
    let heading = learn
        .rendered()
        .headings
        .iter()
        .find(|(_, _, h)| h == "What auto chooses")
        .expect("the heading")
        .0;
    assert!(learn.scroll() <= heading && heading < learn.scroll() + 28);
    // An address outside the book is shown to copy, not followed.
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 100, 30);
    if let Some(i) = learn
        .rendered()
        .links
        .iter()
        .position(|l| l.target.contains("://"))
    {
        let line = learn.rendered().links[i].parts[0].0;
        learn.apply(Command::Scroll(line as i64));
        while learn.focused_link() != Some(i) {
            press(&mut learn, KeyCode::Tab);
        }
        press(&mut learn, KeyCode::Enter);
        assert_eq!(learn.current(), 0);
        assert!(message(&learn).contains("outside the book"));
    }
}

/// The mouse is the terminal's (selecting text works) until M lets the
/// wheel scroll here; the help says so.
#[test]
fn the_mouse_is_left_to_the_terminal_until_m() {
    let mut learn = Learn::open(&book(), None).unwrap();
    assert!(!learn.wants_mouse());
    press(&mut learn, KeyCode::Char('M'));
    assert!(learn.wants_mouse());
    assert!(message(&learn).contains("Shift"));
    press(&mut learn, KeyCode::Char('M'));
    assert!(!learn.wants_mouse());
    assert!(message(&learn).contains("select"));
}

/// At 60×20 the help is taller than the screen: it scrolls, says where it
/// is, and its last line can be reached.
#[test]
fn the_help_scrolls_on_a_small_terminal() {
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 60, 20);
    press(&mut learn, KeyCode::Char('h'));
    let first = draw(&mut learn, 60, 20);
    assert!(first.contains("rows 1–"), "{first}");
    assert!(!first.contains("--chapter"), "{first}");
    press(&mut learn, KeyCode::End);
    let last = draw(&mut learn, 60, 20);
    assert!(
        last.contains("--chapter") && last.contains("end;"),
        "{last}"
    );
    press(&mut learn, KeyCode::Char('k'));
    assert!(matches!(learn.mode(), Mode::Help(n) if *n > 0));
    press(&mut learn, KeyCode::Char('x'));
    assert_eq!(learn.mode(), &Mode::Read);
}

/// From 80 columns the scene stands beside the text (Braille drawn), and
/// `w` gives the text the whole width; below 80 it is text alone.
#[test]
fn the_scene_stands_beside_the_text_from_80_columns() {
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    let shown = draw(&mut learn, 80, 24);
    let braille = shown
        .chars()
        .filter(|c| ('\u{2801}'..='\u{28FF}').contains(c))
        .count();
    assert!(shown.contains("scene:") && braille > 10, "{shown}");
    press(&mut learn, KeyCode::Char('w'));
    let wide = draw(&mut learn, 80, 24);
    assert!(!wide.contains("scene:"), "{wide}");
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    assert!(draw(&mut learn, 79, 24).contains("(s shows it, w beside the text)"));
}

/// Every picture of the book is drawn in the terminal (Braille under its
/// caption), none left as a name, none failed; details are marked open.
#[test]
fn the_books_pictures_are_drawn_and_details_marked_open() {
    let learn = Learn::open(&book(), None).unwrap();
    let mut pictures = 0;
    for chapter in learn.chapters() {
        let source = std::fs::read_to_string(book().join(&chapter.file)).unwrap();
        let source = markdown::resolve_includes(&source, &book());
        let options = markdown::Options {
            images: Some(book()),
            ..Default::default()
        };
        let text = markdown::plain(&markdown::render_with(&source, 76, &options).lines);
        assert!(
            !text.contains("▣ diagram"),
            "{}: a picture not drawn",
            chapter.file
        );
        assert!(
            !text.contains("could not be drawn"),
            "{}:\n{text}",
            chapter.file
        );
        pictures += source.matches("](figures/").count();
        if source.contains("<details>") {
            assert!(
                text.contains("▾ "),
                "{}: details are shown open",
                chapter.file
            );
            assert!(!text.contains("▸ Derivation"), "{}", chapter.file);
        }
    }
    assert!(pictures >= 10, "only {pictures} pictures");
    // The top's frames in Section 3: Braille lines, and its axes' names each
    // once (a label is never printed twice, nor over another).
    let picture =
        spintop_app::learn::diagrams::lines(&book().join("figures/top-axes-dipole.svg"), 76);
    let text = markdown::plain(&picture);
    assert!(
        text.chars()
            .filter(|c| ('\u{2801}'..='\u{28FF}').contains(c))
            .count()
            > 50,
        "{text}"
    );
    for name in ["e₁", "e₂", "e₃", "x", "y", "z"] {
        assert_eq!(text.matches(name).count(), 1, "{name} in\n{text}");
    }
    assert!(picture.len() <= usize::from(spintop_app::learn::diagrams::MAX_ROWS));
}

/// Each chapter's words match its scene: the asymmetric top's chapter
/// names the top its scene runs, and says the catalogue's
/// `asymmetric-top` is another (with that scene's own numbers).
#[test]
fn the_asymmetric_chapter_names_the_top_its_scene_runs() {
    let learn = Learn::open(&book(), Some("asymmetric-top")).unwrap();
    let Spec::Top { settings, .. } = &learn.scene_info().spec else {
        panic!("a live-view scene")
    };
    let Top::General(top) = settings.top() else {
        panic!("a general top")
    };
    let v = |x: spintop::math::Vec3| {
        let f = spintop::numbers::fmt_param;
        format!("({}, {}, {})", f(x.x), f(x.y), f(x.z))
    };
    let text = markdown::plain(&learn.rendered().lines).replace('\n', " ");
    let runs = format!(
        "runs the top above, I = {}, d = {}",
        v(top.inertia()),
        v(top.dipole())
    );
    assert!(text.contains(&runs), "{runs}");
    let scene = spintop::scene::catalogue::find("asymmetric-top")
        .unwrap()
        .scene()
        .unwrap();
    let (other, _) = spintop_app::live::Settings::for_scene(&scene, None).unwrap();
    let Top::General(other) = other.top() else {
        panic!("the catalogue's asymmetric top is a general top")
    };
    let named = format!(
        "another one: I = {} and d = {}",
        v(other.inertia()),
        v(other.dipole())
    );
    assert!(text.contains(&named), "{named}");
}

/// At 80×24 the course panel puts the next failing assignment's diagnosis
/// first and its list below, and the arrows scroll it instead of closing it.
#[test]
fn the_course_panel_fits_80x24_diagnosis_first_and_scrolls() {
    use spintop_course::{Report, State, Status};
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    draw(&mut learn, 80, 24);
    let report = "torque_rate, Eq. (2.2): wrong answer at 3 of 300 inputs\n  expected 1.5, got -1.5\n  hint: the sign of the Schott term";
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Passing,
        "torque_rate" => State::Failing(report.into()),
        _ => State::NotStarted,
    });
    learn.course_report(Report::Graded(status));
    press(&mut learn, KeyCode::Char('a'));
    let shown = draw(&mut learn, 80, 24);
    let rows: Vec<&str> = shown.lines().collect();
    let diagnosis = rows
        .iter()
        .position(|r| r.contains("next: (2.2) torque_rate"))
        .unwrap_or_else(|| panic!("the diagnosis is on screen:\n{shown}"));
    assert!(diagnosis < 8, "the diagnosis comes first:\n{shown}");
    assert!(shown.contains("hint: the sign"), "{shown}");
    assert!(shown.contains("rows 1–"), "the panel scrolls:\n{shown}");
    // No row of the panel is wider than the screen (nothing wraps oddly).
    assert!(
        rows.iter()
            .all(|r| r.trim_matches('"').chars().count() <= 80)
    );
    press(&mut learn, KeyCode::Char('j'));
    assert_eq!(learn.mode(), &Mode::Course(1), "j scrolls, never closes");
    press(&mut learn, KeyCode::End);
    let end = draw(&mut learn, 80, 24);
    assert!(end.contains("re-grades it"), "the list's end:\n{end}");
    assert!(end.contains("reduced_rk4"), "the last assignment:\n{end}");
}

/// In a student's copy at 80×24, a real grader's report of a wrong (2.1)
/// (17-digit numbers, a seed, a hint command) leaves the command that grades
/// it alone on the panel's first screen, and names the copy's paths.
#[test]
fn a_real_failure_keeps_its_command_on_the_first_screen_at_80x24() {
    use spintop_course::{Chosen, Course, Report, State, Status};
    let copy = std::env::temp_dir().join(format!(
        "spintop-panel-copy-{}/a/rather/long/path/to/the/students/copy",
        std::process::id()
    ));
    let failed = spintop_grading::larmor_rate(553_308_490, |[_, d1, d2, _]| d1.cross(d2))
        .expect_err("a wrong Larmor rate fails");
    let report = failed.to_string();
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    learn.watch_course(Course::at(&copy, Chosen::Found), None);
    draw(&mut learn, 80, 24);
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Failing(report.as_str().into()),
        _ => State::NotStarted,
    });
    learn.course_report(Report::Graded(status));
    press(&mut learn, KeyCode::Char('a'));
    let shown = draw(&mut learn, 80, 24);
    for needed in [
        "next: (2.1) larmor_rate in src/ch2.rs",
        "is not right yet",
        "diagnosis:",
        "grade it alone:",
        "cargo test --test ch2 eq_2_1_larmor_rate",
    ] {
        assert!(
            shown.contains(needed),
            "{needed:?} on the first screen:\n{shown}"
        );
    }
    assert!(!shown.contains("lessons/src"), "{shown}");
    // The command line's hint is a key here.
    assert!(!shown.contains("spintop course hint"), "{shown}");
    press(&mut learn, KeyCode::End);
    let end = draw(&mut learn, 80, 24);
    assert!(end.contains("reduced_rk4"), "the list's end:\n{end}");
}

/// A wrong answer in another chapter comes before the stubs of the chapter
/// on screen: the student broke it, its diagnosis is what they need.
#[test]
fn a_failing_answer_elsewhere_comes_before_this_chapters_stubs() {
    use spintop_course::{Report, State, Status};
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    draw(&mut learn, 80, 24);
    let report =
        "larmor_rate, Eq. (2.1): wrong answer at 1 of 300 inputs\n  diagnosis: a sign flip";
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Failing(report.into()),
        _ => State::NotStarted,
    });
    learn.course_report(Report::Graded(status));
    assert_eq!(learn.hint_target().unwrap().function, "larmor_rate");
    press(&mut learn, KeyCode::Char('a'));
    let shown = draw(&mut learn, 80, 24);
    assert!(
        shown.contains("next: (2.1) larmor_rate") && shown.contains("a sign flip"),
        "{shown}"
    );
    // Once nothing fails, the chapter's own next assignment.
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Passing,
        _ => State::NotStarted,
    });
    learn.course_report(Report::Graded(status));
    assert_eq!(learn.hint_target().unwrap().chapter, "Section 4.1");
}

/// The place is written to the progress file as the reader moves, before
/// any quit: a terminal that goes away loses nothing.
#[test]
fn the_place_is_kept_in_the_file_as_the_reader_moves() {
    let path =
        std::env::temp_dir().join(format!("spintop-reader-keep-{}.json", std::process::id()));
    let _ = std::fs::remove_file(&path);
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    draw(&mut learn, 80, 24);
    learn.keep_progress(path.clone(), Default::default());
    for _ in 0..3 {
        press(&mut learn, KeyCode::Char(' '));
    }
    learn.advance(std::time::Duration::ZERO);
    let kept = spintop_app::learn::progress::read(&path);
    assert_eq!(kept.last.as_deref(), Some("section-4-1.md"));
    assert_eq!(kept.positions["section-4-1.md"].0, learn.scroll());
    assert!(learn.scroll() > 0);
    let _ = std::fs::remove_file(&path);
}
