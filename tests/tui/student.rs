//! What a reviewer found using `spintop learn` as a student at 80×24 and
//! 200×60 (issue 43, second pass): marks kept without colour, the hint seen
//! when asked, the scene's `v` telling the truth, the course panel's
//! scrolling after it shrinks.

use super::learn::{book, draw, press};
use crossterm::event::KeyCode;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use ratatui::{Terminal, backend::TestBackend};
use spintop_app::learn::{Command, Learn, Mode};
use spintop_app::term::theme;
use spintop_course::{Report, State, Status};

/// The screen as `NO_COLOR` puts it on the terminal: drawn, then every
/// colour taken out (the loop's way, [`theme::strip_colours`]).
fn draw_plain(learn: &mut Learn, width: u16, height: u16) -> Buffer {
    draw(learn, width, height);
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| {
            spintop_app::learn::view::draw(f, learn);
            theme::strip_colours(f.buffer_mut());
        })
        .unwrap();
    terminal.backend().buffer().clone()
}

fn row_text(buf: &Buffer, y: u16) -> String {
    (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect()
}

/// The cells of row `y` whose text is `word`, where it first stands.
fn cells_of(buf: &Buffer, word: &str) -> Option<Vec<ratatui::buffer::Cell>> {
    for y in 0..buf.area.height {
        let cells: Vec<_> = (0..buf.area.width).map(|x| buf[(x, y)].clone()).collect();
        let symbols: Vec<&str> = cells.iter().map(|c| c.symbol()).collect();
        let n = word.chars().count();
        for x in 0..cells.len().saturating_sub(n) {
            if symbols[x..x + n].concat() == word {
                return Some(cells[x..x + n].to_vec());
            }
        }
    }
    None
}

fn message(learn: &Learn) -> String {
    learn.message().map(|m| m.0.clone()).unwrap_or_default()
}

/// Under NO_COLOR no cell has a colour, and the marks that were drawn
/// with one still stand out: the contents' selection is reversed, the
/// search's match and the focused link keep a mark of their own.
#[test]
fn without_colour_the_selection_the_match_and_the_link_keep_their_marks() {
    let mut learn = Learn::open(&book(), Some("1")).unwrap().plain(true);
    draw(&mut learn, 80, 24);
    press(&mut learn, KeyCode::Char('c'));
    for _ in 0..3 {
        press(&mut learn, KeyCode::Down);
    }
    let buf = draw_plain(&mut learn, 80, 24);
    assert!(
        buf.content
            .iter()
            .all(|c| c.fg == Color::Reset && c.bg == Color::Reset),
        "no colour at all"
    );
    let reversed: Vec<u16> = (0..24)
        .filter(|&y| (0..80).any(|x| buf[(x, y)].modifier.contains(Modifier::REVERSED)))
        .collect();
    assert_eq!(reversed.len(), 1, "one selected entry: {reversed:?}");
    assert!(!row_text(&buf, reversed[0]).trim().is_empty());
    press(&mut learn, KeyCode::Esc);

    learn.apply(Command::SearchStart);
    for c in "Schott".chars() {
        learn.apply(Command::SearchInput(c));
    }
    learn.apply(Command::SearchCommit);
    let buf = draw_plain(&mut learn, 80, 24);
    let hit = cells_of(&buf, "Schott").expect("the match on screen");
    assert!(
        hit.iter().all(|c| !c.modifier.is_empty()),
        "the match is marked without colour"
    );
    press(&mut learn, KeyCode::Esc);

    learn.apply(Command::NextLink);
    assert!(message(&learn).contains("link"), "{}", message(&learn));
    let buf = draw_plain(&mut learn, 80, 24);
    let focused = buf
        .content
        .iter()
        .filter(|c| c.modifier.contains(Modifier::REVERSED))
        .count();
    let underlined = buf
        .content
        .iter()
        .filter(|c| c.modifier.contains(Modifier::UNDERLINED))
        .count();
    assert!(focused > 0, "the focused link is reversed");
    assert!(underlined > 0, "links are underlined");
}

/// The figures drawn in §4.1 and §4.2 name no colour without colour: their
/// titles name the glyphs, and the two curves of panel (d) differ in glyph.
#[test]
fn without_colour_the_figures_name_their_glyphs_not_colours() {
    for (chapter, number) in [("4.1", 1), ("4.2", 2)] {
        let plain = Learn::open(&book(), Some(chapter)).unwrap().plain(true);
        let text: String = plain
            .rendered()
            .lines
            .iter()
            .map(|l| {
                l.spans
                    .iter()
                    .map(|s| s.content.as_ref())
                    .collect::<String>()
                    + "\n"
            })
            .collect();
        let at = text
            .find(&format!("Figure {number}"))
            .expect("the figure's caption");
        let titles: Vec<&str> = text
            .lines()
            .filter(|l| {
                ["(a) Ω", "(b) the top", "(d) φ̇"]
                    .iter()
                    .any(|t| l.contains(t))
            })
            .collect();
        assert!(titles.len() >= 3, "the panels' titles: {titles:?}");
        for colour in ["yellow", "green", "in red", "pale"] {
            assert!(
                titles.iter().all(|t| !t.contains(colour)),
                "{colour} in §{chapter}'s figure without colour: {titles:?}"
            );
        }
        assert!(text.contains("(d) φ̇ •, ψ̇ braille"), "§{chapter}");
        assert!(text.contains("L: •") && text.contains("•: its shadows"));
        // The dots are drawn (the shadows, L, φ̇): a glyph braille is not.
        assert!(text[..at].matches('•').count() + text[at..].matches('•').count() > 20);
        let coloured = Learn::open(&book(), Some(chapter)).unwrap();
        let text: String = coloured
            .rendered()
            .lines
            .iter()
            .flat_map(|l| l.spans.iter().map(|s| s.content.to_string()))
            .collect();
        assert!(text.contains("φ̇ yellow, ψ̇ green"), "with colour, colours");
    }
}

/// `h` in the course panel at 80×24 shows its rung on screen (the panel
/// scrolls to it), and each press shows the next: in a student's copy with a
/// real grader's report of a wrong (2.1), where the hint falls below the
/// panel's first screen.
#[test]
fn a_hint_is_on_screen_when_asked_at_80x24() {
    use spintop_course::{Chosen, Course};
    let top = std::env::temp_dir().join(format!("spintop-hint-copy-{}", std::process::id()));
    let copy = top.join("a/rather/long/path/to/the/students/copy");
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
    for rung in 1..=3 {
        press(&mut learn, KeyCode::Char('h'));
        let shown = draw(&mut learn, 80, 24);
        let hint = learn.hint().expect("a hint");
        assert_eq!(hint.rung, rung);
        assert!(
            shown.contains(&format!("hint {rung} of 3")),
            "rung {rung} on screen:\n{shown}"
        );
        let first = hint
            .text
            .split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ");
        let flat = shown.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(flat.contains(&first), "its text {first:?}:\n{shown}");
    }
    // The rungs used were kept in the copy's progress file.
    std::fs::remove_dir_all(&top).ok();
}

/// A rung taken with `spintop course hint` in another terminal shows in the
/// open course panel at the next frame (it kept the rung of the last `h`).
#[test]
fn a_hint_taken_in_another_terminal_shows_in_the_open_panel() {
    use spintop_course::{Chosen, Course};
    let copy = std::env::temp_dir().join(format!("spintop-hint-elsewhere-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&copy);
    std::fs::create_dir_all(&copy).unwrap();
    let mut learn = Learn::open(&book(), Some("2")).unwrap();
    learn.watch_course(Course::at(&copy, Chosen::Found), None);
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Failing("larmor_rate, Eq. (2.1): wrong answer".into()),
        _ => State::NotStarted,
    });
    learn.course_report(Report::Graded(status));
    press(&mut learn, KeyCode::Char('a'));
    press(&mut learn, KeyCode::Char('h'));
    assert!(draw(&mut learn, 80, 24).contains("hint 1 of 3"));
    // Another terminal: `spintop course hint larmor_rate`, twice.
    let larmor = spintop_course::find("larmor_rate").unwrap();
    for _ in 0..2 {
        let mut progress = spintop_course::load_progress(&copy);
        spintop_course::next_hint(&mut progress, larmor);
        spintop_course::save_progress(&copy, &progress).unwrap();
    }
    learn.advance(std::time::Duration::ZERO);
    let hint = learn.hint().expect("a hint");
    assert_eq!((hint.assignment.function, hint.rung), ("larmor_rate", 3));
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("hint 3 of 3"), "{shown}");
    // And the next `h` there stays on the last rung, as the file says.
    press(&mut learn, KeyCode::Char('h'));
    assert_eq!(learn.hint().map(|h| h.rung), Some(3));
    drop(learn);
    let _ = std::fs::remove_dir_all(&copy);
}

/// The first PgUp after the course panel got shorter moves it.
#[test]
fn page_up_moves_at_once_after_the_course_panel_shrinks() {
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    draw(&mut learn, 80, 24);
    // Rows that wrap at 80 columns: fixing the assignment takes more rows
    // off the panel than a page.
    let long = (1..=9)
        .map(|i| {
            format!(
                "  line {i} of the diagnosis, {}",
                "long words again ".repeat(8)
            )
        })
        .collect::<Vec<_>>()
        .join("\n");
    let failing = format!("torque_rate, Eq. (2.2): wrong answer\n{long}");
    let status = |torque: State| {
        Status::new(0, move |a| match a.function {
            "torque_rate" => torque.clone(),
            _ => State::Passing,
        })
    };
    learn.course_report(Report::Graded(status(State::Failing(
        failing.as_str().into(),
    ))));
    press(&mut learn, KeyCode::Char('a'));
    press(&mut learn, KeyCode::End);
    let Mode::Course(end) = *learn.mode() else {
        panic!("the course panel")
    };
    // Fixed: the diagnosis goes, the panel is shorter.
    learn.course_report(Report::Graded(status(State::Passing)));
    let before = draw(&mut learn, 80, 24);
    let rows = |s: &str| {
        s.split("rows ")
            .nth(1)
            .map(|r| r[..r.find(' ').unwrap()].to_string())
    };
    press(&mut learn, KeyCode::PageUp);
    let Mode::Course(after) = *learn.mode() else {
        panic!("the course panel")
    };
    assert!(after < end);
    let shown = draw(&mut learn, 80, 24);
    assert_ne!(
        rows(&before),
        rows(&shown),
        "PgUp moved:\n{before}\n{shown}"
    );
}

/// `v` in a scene of one model says so and names the model drawn; with
/// two models both on the screen it names `v`, not the live view's Tab.
#[test]
fn v_tells_the_truth_about_the_models_drawn() {
    for (w, h) in [(80, 24), (200, 60)] {
        let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
        draw(&mut learn, w, h);
        press(&mut learn, KeyCode::Char('v'));
        let said = message(&learn);
        assert!(
            said.contains("one model") && said.contains("reduced"),
            "{said}"
        );
        assert!(
            !said.contains("truncated") && !said.contains("Tab"),
            "{said}"
        );
    }
    let mut learn = Learn::open(&book(), Some("§5")).unwrap();
    draw(&mut learn, 200, 60);
    press(&mut learn, KeyCode::Char('v'));
    let said = message(&learn);
    assert!(!said.contains("Tab"), "{said}");
}

/// In the search prompt Ctrl-U clears the field (as in the live view's
/// editor), and a full field says its limit.
#[test]
fn the_search_prompt_clears_on_ctrl_u_and_says_its_limit() {
    use crossterm::event::{Event, KeyEvent, KeyModifiers};
    let mut learn = Learn::open(&book(), Some("1")).unwrap();
    draw(&mut learn, 80, 24);
    press(&mut learn, KeyCode::Char('/'));
    for c in "x".repeat(100).chars() {
        press(&mut learn, KeyCode::Char(c));
    }
    let shown = draw(&mut learn, 80, 24);
    let limit = spintop_app::learn::search::LONGEST;
    assert!(
        shown.contains(&format!("(full: {limit} characters; Ctrl-U clears)")),
        "{shown}"
    );
    let ctrl_u = Event::Key(KeyEvent::new(KeyCode::Char('u'), KeyModifiers::CONTROL));
    let command = learn.command_for(&ctrl_u).expect("Ctrl-U is taken");
    learn.apply(command);
    assert_eq!(learn.mode(), &Mode::Search(String::new(), true));
}

/// A link to a bibliography entry (an anchor written `<a id="…">`) lands
/// on the entry, not at the top of the page.
#[test]
fn links_to_html_anchors_land_on_them() {
    let mut learn = Learn::open(&book(), Some("numerical-methods")).unwrap();
    draw(&mut learn, 80, 24);
    let k = learn
        .rendered()
        .links
        .iter()
        .position(|l| l.target == "bibliography.md#hairer-2")
        .expect("a link to the bibliography");
    for _ in 0..=k {
        learn.apply(Command::NextLink);
    }
    learn.apply(Command::FollowLink);
    let said = message(&learn);
    assert!(!said.contains("no heading"), "{said}");
    let shown = draw(&mut learn, 80, 24);
    assert!(
        shown.contains("Hairer and Wanner") || shown.contains("Hairer, E."),
        "{shown}"
    );
    let line = learn
        .rendered()
        .anchors
        .iter()
        .find(|(_, id)| id == "hairer-2")
        .map(|(l, _)| *l)
        .expect("the anchor");
    assert!(line > 0);
}

/// A message that wraps to two rows leaves the text's frame line, with the
/// position on it, in sight.
#[test]
fn a_two_row_message_leaves_the_position_in_sight() {
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    draw(&mut learn, 80, 24);
    press(&mut learn, KeyCode::Char('v'));
    let said = message(&learn);
    assert!(said.chars().count() > 80, "a message of two rows: {said}");
    let shown = draw(&mut learn, 80, 24);
    let flat = shown.split_whitespace().collect::<Vec<_>>().join(" ");
    let tail: String = said
        .split_whitespace()
        .rev()
        .take(3)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(flat.contains(&tail), "the message whole:\n{shown}");
    assert!(
        shown
            .lines()
            .any(|r| r.contains("% lines ") && r.contains('╰')),
        "the frame line with the position:\n{shown}"
    );
}

/// The words of the text of a chapter as rendered (code left out: it is
/// broken with a mark of its own).
fn prose_words(learn: &Learn) -> Vec<String> {
    let code = spintop_app::learn::markdown::code_style();
    learn
        .rendered()
        .lines
        .iter()
        .flat_map(|l| l.spans.iter().filter(|s| s.style != code))
        .flat_map(|s| {
            s.content
                .split(|c: char| !c.is_alphanumeric())
                .filter(|w| w.len() > 2)
                .map(str::to_string)
                .collect::<Vec<_>>()
        })
        .collect()
}

/// At 80 columns with the scene beside the text, the tables of *Where
/// methods fail* break their cells at words (a table too wide for that
/// is drawn row by row): every word drawn narrow is a word drawn wide.
#[test]
fn tables_beside_the_scene_wrap_at_words() {
    let mut narrow = Learn::open(&book(), Some("where methods fail")).unwrap();
    draw(&mut narrow, 80, 24);
    let mut wide = Learn::open(&book(), Some("where methods fail")).unwrap();
    draw(&mut wide, 300, 60);
    let whole: std::collections::HashSet<String> = prose_words(&wide).into_iter().collect();
    let words = prose_words(&narrow);
    assert!(words.len() > 500, "the chapter's words");
    let cut: Vec<&String> = words.iter().filter(|w| !whole.contains(*w)).collect();
    assert!(cut.is_empty(), "words cut: {cut:?}");
    for needed in ["equation", "integrate", "runaway"] {
        assert!(words.iter().any(|w| w == needed), "{needed}");
    }
}

/// The scenes' words fit the scene at 80 and 100 columns with the value or
/// the verdict kept: the appendix's panels say stable and unstable, §2's
/// collapse time has its number, a chapter without a scene names its command
/// whole, and §2's header keeps the course.
#[test]
fn scene_words_keep_their_point_at_80_and_100_columns() {
    let mut appendix = Learn::open(&book(), Some("A")).unwrap();
    let shown = draw(&mut appendix, 80, 24);
    assert!(
        shown.contains(" stable") && shown.contains("unstable"),
        "{shown}"
    );
    assert!(
        !shown.contains("the shell again") && !shown.contains("point charg…"),
        "{shown}"
    );

    let mut two = Learn::open(&book(), Some("§2")).unwrap();
    let shown = draw(&mut two, 100, 40);
    let at = shown.find("t_c = ").expect("the collapse time");
    let after = &shown[at + "t_c = ".len()..];
    let after = after.split(" = ").last().unwrap_or(after);
    assert!(
        after.trim_start().starts_with(|c: char| c.is_ascii_digit()),
        "t_c has its value: {}",
        &shown[at..at + 60.min(shown.len() - at)]
    );

    let mut scales = Learn::open(&book(), Some("question and its scales")).unwrap();
    let shown = draw(&mut scales, 80, 24);
    assert!(
        shown.contains("spintop run nanoparticle-1e3-debye"),
        "the command whole:\n{shown}"
    );

    let status = Status::new(0, |a| match a.function {
        "larmor_rate" => State::Passing,
        _ => State::NotStarted,
    });
    two.course_report(Report::Graded(status));
    let shown = draw(&mut two, 80, 24);
    let header = shown.lines().next().unwrap_or_default();
    assert!(
        header.contains("course"),
        "the header keeps the course: {header}"
    );
}

/// The real binary under `NO_COLOR=1` in tmux at 80×24: the contents'
/// selection is drawn in reverse video and the matched word is marked, as
/// the terminal shows them (crossterm's colours under NO_COLOR reset every
/// attribute, so a frame with colour in it lost its marks).
#[test]
#[ignore = "end-to-end: tmux"]
fn no_color_keeps_reverse_video_in_a_real_terminal() {
    let progress = std::env::temp_dir().join(format!(
        "spintop-student-nocolor-{}.json",
        std::process::id()
    ));
    let env = format!("NO_COLOR=1 SPINTOP_LEARN_PROGRESS='{}'", progress.display());
    let Some(tmux) =
        super::tmux::launch_sized("nocolor", &env, "learn --no-grading --chapter 1", (80, 24))
    else {
        return;
    };
    let limit = std::time::Duration::from_secs(30);
    tmux.wait_for("the reader", limit, |s| s.contains("spintop learn"));
    let styled = || {
        let out = tmux.run(&["capture-pane", "-e", "-p", "-t", "spintop"]);
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    // Reverse video is SGR 7, alone or among others (`ESC[7m`, `ESC[1;7m`).
    let reversed = |s: &str| {
        s.split("\u{1b}[").skip(1).any(|seq| {
            seq.split_once('m')
                .is_some_and(|(codes, _)| codes.split(';').any(|c| c == "7"))
        })
    };
    let colour = |s: &str| {
        s.split("\u{1b}[").skip(1).any(|seq| {
            seq.split_once('m').is_some_and(|(codes, _)| {
                codes.split(';').any(|c| {
                    c.parse::<u16>().is_ok_and(|n| {
                        (30..=37).contains(&n)
                            || (40..=47).contains(&n)
                            || (90..=107).contains(&n)
                            || n == 38
                            || n == 48
                    })
                })
            })
        })
    };
    tmux.keys("c");
    tmux.keys("Down");
    tmux.keys("Down");
    tmux.wait_for("the contents", limit, |s| s.contains("contents:"));
    let start = std::time::Instant::now();
    let mut screen = styled();
    while !reversed(&screen) && start.elapsed() < std::time::Duration::from_secs(3) {
        std::thread::sleep(std::time::Duration::from_millis(100));
        screen = styled();
    }
    assert!(
        reversed(&screen),
        "the selection in reverse video:\n{screen}"
    );
    assert!(!colour(&screen), "no colour under NO_COLOR:\n{screen}");
    tmux.keys("q");
    let _ = std::fs::remove_file(&progress);
}
