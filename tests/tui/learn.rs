//! `spintop learn`: every chapter of the book rendered for the terminal.
//!
//! The chapters come from `book/src` itself, so these tests read the real
//! book: every chapter (and every page of it, scrolled through) is drawn on a
//! `TestBackend` at 80×24 and 160×48, and the screen must hold no raw TeX, no
//! mdBook directive and no Markdown markup outside code. Every experiment
//! comment in the book must parse and apply to its chapter's scene. Two
//! screens of Section 4.2 are pinned by insta snapshots (reviewed by hand).

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::{Terminal, backend::TestBackend};
use spintop_app::learn::markdown::{self, code_style};
use spintop_app::learn::scene::Spec;
use spintop_app::learn::{Command, Experiment, Learn, Mode, find_chapter};
use std::path::{Path, PathBuf};

pub(super) fn book() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("book")
        .join("src")
}

/// Draw at `width`×`height`, as the terminal loop does: the size first.
pub(super) fn draw(learn: &mut Learn, width: u16, height: u16) -> String {
    if learn.size() != (width, height) {
        learn.apply(Command::Resize(width, height));
    }
    let mut terminal = Terminal::new(TestBackend::new(width, height)).expect("a test terminal");
    terminal
        .draw(|f| spintop_app::learn::view::draw(f, learn))
        .expect("drawing never fails on a TestBackend");
    terminal.backend().to_string()
}

pub(super) fn key(code: KeyCode) -> KeyEvent {
    KeyEvent::new(code, KeyModifiers::NONE)
}

/// A key, as the terminal loop applies it.
pub(super) fn press(learn: &mut Learn, code: KeyCode) {
    if let Some(command) = learn.command_for(&Event::Key(key(code))) {
        learn.apply(command);
    }
}

/// The live-view settings of a chapter's scene, if it has them.
fn top_settings(spec: &Spec) -> Option<spintop_app::live::Settings> {
    match spec {
        Spec::Top { settings, .. } => Some(*settings),
        _ => None,
    }
}

/// Marks of text that was not rendered: raw TeX, mdBook directives, Markdown.
fn unrendered(text: &str) -> Option<&'static str> {
    let raw_tex = text.char_indices().any(|(i, c)| {
        c == '\\'
            && text[i + 1..]
                .chars()
                .next()
                .is_some_and(|n| n.is_ascii_alphabetic() || "[](){},".contains(n))
    });
    if raw_tex {
        return Some("raw TeX");
    }
    // A link target left in the text: `](http…`, `](#…` or `](….md…`.
    for (i, _) in text.match_indices("](") {
        let target = &text[i + 2..];
        let target = &target[..target.find(')').unwrap_or(target.len())];
        if target.starts_with("http") || target.starts_with('#') || target.contains(".md") {
            return Some("a Markdown link");
        }
    }
    for (needle, what) in [
        ("{{#", "an mdBook directive"),
        ("$$", "display-math delimiters"),
        ("**", "Markdown strong markup"),
        ("```", "a code fence"),
        ("<!--", "an HTML comment"),
    ] {
        if text.contains(needle) {
            return Some(what);
        }
    }
    None
}

#[test]
fn every_chapter_renders_with_no_raw_tex_or_markup_outside_code() {
    let learn = Learn::open(&book(), None).expect("the book opens");
    let chapters = learn.chapters().to_vec();
    assert!(
        chapters.len() >= 16,
        "SUMMARY.md lists {} chapters",
        chapters.len()
    );
    for chapter in &chapters {
        let source = std::fs::read_to_string(book().join(&chapter.file)).unwrap();
        let source = markdown::resolve_includes(&source, &book());
        for width in [60u16, 78, 100] {
            let rendered = markdown::render(&source, width);
            assert!(
                rendered.unknown_tex.is_empty(),
                "{}: TeX commands the terminal cannot show: {:?}",
                chapter.file,
                rendered.unknown_tex
            );
            assert!(
                rendered.lines.len() > 3,
                "{} rendered to almost nothing",
                chapter.file
            );
            for (n, line) in rendered.lines.iter().enumerate() {
                assert!(
                    line.width() <= usize::from(width),
                    "{} line {n} is wider than {width}",
                    chapter.file
                );
                let prose: String = line
                    .spans
                    .iter()
                    .filter(|s| s.style != code_style())
                    .map(|s| s.content.as_ref())
                    .collect();
                if let Some(what) = unrendered(&prose) {
                    panic!(
                        "{} at width {width}, line {n}: {what} on screen: {prose:?}",
                        chapter.file
                    );
                }
                let all: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
                assert!(
                    !all.contains("{{#include"),
                    "{}: an include was not resolved: {all:?}",
                    chapter.file
                );
            }
        }
    }
}

/// The named functions an equation writes upright, set off by spaces.
const NAMED_FUNCTIONS: [&str; 7] = ["sin", "cos", "tan", "cot", "ln", "exp", "log"];

/// Where an equation's text glues a named function to its neighbour:
/// `Rsin α`, `φ̇sin θ`, `sinα` (`sin²θ`, `sin(α)` and `ln(m)` are fine, and
/// so are words that only contain a name: `cosh`, `arcsin`, `using`).
fn glued_function(math: &str) -> Option<String> {
    let chars: Vec<char> = math.chars().collect();
    let operand = |c: char| {
        c.is_alphanumeric()
            || matches!(c as u32, 0x300..=0x36F | 0x20D0..=0x20FF)
            || "₀₁₂₃₄₅₆₇₈₉²³⁻¹ₑₘ)]}|".contains(c)
    };
    let mut i = 0;
    while i < chars.len() {
        if !chars[i].is_ascii_alphabetic() {
            i += 1;
            continue;
        }
        let start = i;
        while i < chars.len() && chars[i].is_ascii_alphabetic() {
            i += 1;
        }
        let word: String = chars[start..i].iter().collect();
        let context = || -> String {
            chars[start.saturating_sub(6)..(i + 6).min(chars.len())]
                .iter()
                .collect()
        };
        for f in NAMED_FUNCTIONS {
            if word == f {
                let before = start > 0 && operand(chars[start - 1]);
                let after = chars.get(i).is_some_and(|c| c.is_alphabetic());
                if before || after {
                    return Some(context());
                }
            } else if let Some(prefix) = word.strip_suffix(f)
                && (1..=2).contains(&prefix.len())
                && prefix != "arc"
            {
                // A one- or two-letter factor glued on: Rsin, kcos.
                return Some(context());
            }
        }
    }
    None
}

#[test]
fn the_named_function_check_finds_glued_names() {
    assert!(glued_function("Ω₂₀/Rsin α").is_some());
    assert!(glued_function("φ̇sin θ").is_some());
    assert!(glued_function("sinα").is_some());
    for fine in [
        "(Ω₂₀/R) sin α",
        "sin²θ",
        "ln(m/m₀)",
        "cosh x",
        "arcsin x",
        "arctan(1/3)",
    ] {
        assert_eq!(glued_function(fine), None, "{fine}");
    }
}

/// Every page of every chapter, drawn at 80×24 and 160×48: no raw TeX, no
/// mdBook directive and no Markdown markup outside code, and no equation
/// with a named function glued to its neighbour.
#[test]
fn every_page_of_every_chapter_draws_at_both_sizes() {
    let code = code_style().fg;
    let math = markdown::math_style().fg;
    for (w, h) in [(80u16, 24u16), (160, 48)] {
        let mut learn = Learn::open(&book(), None).expect("the book opens");
        let n = learn.chapters().len();
        for i in 0..n {
            let file = learn.chapters()[i].file.clone();
            let shown = draw(&mut learn, w, h);
            assert!(
                shown.contains(&learn.chapters()[i].title),
                "{file}: title not in the header"
            );
            // Scroll to the end page by page; every page must be clean.
            for _ in 0..400 {
                let before = learn.scroll();
                learn.apply(Command::Resize(w, h));
                let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
                terminal
                    .draw(|f| spintop_app::learn::view::draw(f, &learn))
                    .unwrap();
                let buffer = terminal.backend().buffer();
                for y in 0..h {
                    let cells: Vec<_> = (0..w).map(|x| &buffer[(x, y)]).collect();
                    let all: String = cells.iter().map(|c| c.symbol()).collect();
                    assert!(
                        !all.contains("{{#") && !all.contains("$$"),
                        "{file} at {w}×{h}: {all}"
                    );
                    let prose: String = cells
                        .iter()
                        .filter(|c| c.fg != code.unwrap_or_default())
                        .map(|c| c.symbol())
                        .collect();
                    if let Some(what) = unrendered(&prose) {
                        panic!("{file} at {w}×{h}: {what} on screen: {prose:?}");
                    }
                    let equations: String = cells
                        .iter()
                        .map(|c| {
                            if c.fg == math.unwrap_or_default() {
                                c.symbol()
                            } else {
                                "\u{1}"
                            }
                        })
                        .collect();
                    for equation in equations.split('\u{1}').filter(|e| !e.trim().is_empty()) {
                        if let Some(glued) = glued_function(equation) {
                            panic!("{file} at {w}×{h}: a named function glued in `{glued}`: {all}");
                        }
                    }
                }
                press(&mut learn, KeyCode::PageDown);
                if learn.scroll() == before {
                    break;
                }
            }
            press(&mut learn, KeyCode::Right);
        }
        assert_eq!(learn.current(), n - 1, "→ walks through every chapter");
    }
}

/// True when the break between a wrapped line `before` and its continuation
/// `rest` cut a token: both sides are parts of a name or a number, and the
/// source has them joined with no space between.
pub fn cuts_a_token(before: &str, rest: &str, source: &str) -> bool {
    let token = |c: char| c.is_alphanumeric() || c == '_' || c == '.';
    let before = before.trim_end();
    let rest = rest.trim_start();
    let (Some(a), Some(b)) = (before.chars().last(), rest.chars().next()) else {
        return false;
    };
    if !(token(a) && token(b)) {
        return false;
    }
    let tail: String = {
        let v: Vec<char> = before.chars().collect();
        v[v.len().saturating_sub(8)..].iter().collect()
    };
    let head: String = rest.chars().take(8).collect();
    source.contains(&format!("{tail}{head}"))
}

/// Code and program output are wrapped between tokens, with the rest of a
/// line marked ↪, never inside a name or a number, at the text widths of
/// 80×24 and 160×48, over every code block of the book, library source
/// unfolded.
#[test]
fn code_is_wrapped_between_tokens_in_every_chapter() {
    let learn = Learn::open(&book(), None).expect("the book opens");
    let mut wrapped = 0;
    for chapter in learn.chapters() {
        let source = std::fs::read_to_string(book().join(&chapter.file)).unwrap();
        let source = markdown::resolve_includes(&source, &book());
        for width in [76u16, 80] {
            let options = markdown::Options {
                unfold: true,
                ..Default::default()
            };
            let r = markdown::render_with(&source, width, &options);
            let text: Vec<String> = r
                .lines
                .iter()
                .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
                .collect();
            for (k, line) in text.iter().enumerate().skip(1) {
                let Some(rest) = line.trim_start().strip_prefix(markdown::CONTINUATION) else {
                    continue;
                };
                wrapped += 1;
                assert!(
                    !cuts_a_token(&text[k - 1], rest, &source),
                    "{} at {width}: a token is cut:\n{}\n{line}",
                    chapter.file,
                    text[k - 1]
                );
                assert!(line.chars().count() <= usize::from(width), "{line}");
            }
        }
    }
    assert!(
        wrapped > 10,
        "only {wrapped} wrapped lines: the test sees too little"
    );
}

/// The library's source excerpts are folded to one line by default, and
/// `o` shows them whole (and folds them again).
#[test]
fn library_source_is_folded_until_o() {
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    draw(&mut learn, 160, 48);
    let folded = learn.rendered().lines.len();
    let text = markdown::plain(&learn.rendered().lines);
    assert!(
        text.contains("▸ crates/spintop/src/physics/central.rs:abraham_lorentz"),
        "{text}"
    );
    assert!(!text.contains("pub fn abraham_lorentz_rhs"), "folded");
    press(&mut learn, KeyCode::Char('o'));
    let text = markdown::plain(&learn.rendered().lines);
    assert!(text.contains("pub fn abraham_lorentz_rhs"), "unfolded");
    assert!(learn.rendered().lines.len() > folded + 100);
    press(&mut learn, KeyCode::Char('o'));
    assert_eq!(learn.rendered().lines.len(), folded);
}

#[test]
fn every_experiment_in_the_book_applies_to_its_chapters_scene() {
    let learn = Learn::open(&book(), None).expect("the book opens");
    let mut total = 0;
    for chapter in learn.chapters() {
        let source = std::fs::read_to_string(book().join(&chapter.file)).unwrap();
        let rendered = markdown::render(&source, 100);
        let scene = chapter.scene();
        for (_, text) in &rendered.experiments {
            let e = Experiment::parse(text)
                .unwrap_or_else(|err| panic!("{}: `{text}`: {err}", chapter.file));
            let base = top_settings(&scene.spec).unwrap_or_else(|| {
                panic!("{}: an experiment, but no live-view scene", chapter.file)
            });
            e.apply(&base)
                .unwrap_or_else(|err| panic!("{}: `{text}`: {err}", chapter.file));
            total += 1;
        }
    }
    assert!(total >= 8, "only {total} experiments in the book");
}

#[test]
fn the_experiment_key_changes_the_scene_and_scrolls_to_the_experiment() {
    let mut learn = Learn::open(&book(), Some("4.2")).expect("chapter 4.2 opens");
    draw(&mut learn, 160, 48);
    let before = *learn.scene().unwrap().settings();
    press(&mut learn, KeyCode::Char('x'));
    let after = *learn.scene().unwrap().settings();
    assert_ne!(before, after, "x must change the scene's parameters");
    assert!(learn.scroll() > 0, "x scrolls the text to the experiment");
    let shown = draw(&mut learn, 160, 48);
    assert!(shown.contains("experiment 1 of"), "{shown}");
}

#[test]
fn chapters_are_found_by_section_or_file_name_and_contents_jump() {
    let learn = Learn::open(&book(), None).unwrap();
    let chapters = learn.chapters();
    for (wanted, file) in [
        ("§2", "section-2.md"),
        ("section 2", "section-2.md"),
        ("4.1", "section-4-1.md"),
        ("a", "appendix.md"),
        ("numerical-methods", "numerical-methods.md"),
    ] {
        let i = find_chapter(chapters, wanted).unwrap_or_else(|| panic!("--chapter {wanted}"));
        assert_eq!(chapters[i].file, file);
    }
    assert!(find_chapter(chapters, "9.9").is_none());
    assert!(
        Learn::open(&book(), Some("9.9"))
            .err()
            .is_some_and(|e| e.to_string().contains("4.2"))
    );

    // The contents list every chapter and its sections; Enter on a section
    // opens its chapter with the section's heading at the top of the page.
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 80, 24);
    press(&mut learn, KeyCode::Char('c'));
    assert_eq!(learn.mode(), &Mode::Contents(0));
    let wanted = learn
        .contents()
        .iter()
        .position(|e| {
            e.heading
                .as_ref()
                .is_some_and(|(_, h)| h.starts_with("The Coulomb collapse"))
        })
        .expect("Section 2's sections are in the contents");
    let chapter = learn.contents()[wanted].chapter;
    assert_eq!(learn.chapters()[chapter].file, "section-2.md");
    for _ in 0..wanted {
        press(&mut learn, KeyCode::Down);
    }
    press(&mut learn, KeyCode::Enter);
    assert_eq!(learn.current(), chapter);
    assert_eq!(learn.mode(), &Mode::Read);
    let shown = draw(&mut learn, 80, 24);
    let first_text_line = shown.lines().nth(2).unwrap_or_default();
    assert!(
        first_text_line.contains("The Coulomb collapse"),
        "the section's heading opens the page:\n{shown}"
    );
}

#[test]
fn section_4_2_at_80x24_and_160x48() {
    for (w, h) in [(80u16, 24u16), (160, 48)] {
        let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
        let shown = draw(&mut learn, w, h);
        assert!(shown.contains("Section 4.2: the reduced top"));
        // From 80 columns the scene stands beside the text.
        assert!(shown.contains("scene:"), "{shown}");
        {
            // The scene beside the text: the chart's Braille dots are drawn.
            assert!(
                shown
                    .chars()
                    .any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
                "{shown}"
            );
        }
        insta::assert_snapshot!(format!("learn_section_4_2_{w}x{h}"), shown);
    }
}

/// The course grader's reports reach the screen: the header counts the
/// passing assignments, and `a` lists every assignment with its state and the
/// next one's report. (The statuses here are made by hand; `spintop learn`
/// gets them from a background grader.)
#[test]
fn the_course_panel_shows_the_graders_verdicts() {
    use spintop_course::{Report, State, Status};
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    learn.course_report(Report::Grading);
    assert!(draw(&mut learn, 160, 48).contains("course: grading"));
    let status = Status::new(0, |a| match a.function {
        "larmor_rate" | "schott_angular_momentum" => State::Passing,
        "torque_rate" => {
            State::Failing("torque_rate, Eq. (2.2): wrong answer\n  hint: the sign".into())
        }
        _ => State::Unknown,
    });
    learn.course_report(Report::Graded(status));
    let shown = draw(&mut learn, 160, 48);
    assert!(shown.contains("course 2 of 22 ▰▱▱▱▱▱▱▱▱▱"), "{shown}");
    press(&mut learn, KeyCode::Char('a'));
    let shown = draw(&mut learn, 160, 48);
    for text in [
        "2 of 22 passing",
        "larmor_rate",
        "passing",
        "failing",
        "not graded",
        "next: (2.2) torque_rate",
        "hint: the sign",
    ] {
        assert!(shown.contains(text), "{text} in\n{shown}");
    }
}

/// `h` climbs the hint ladder of the chapter's first assignment that does not
/// pass yet, one rung per press, and shows the formula only on the third.
#[test]
fn h_climbs_the_hint_ladder_of_the_chapters_next_assignment() {
    use spintop_course::{Report, State, Status};
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    let status = Status::new(0, |a| {
        if a.function == "reduced_ale_rhs" {
            State::Passing
        } else {
            State::Unknown
        }
    });
    learn.course_report(Report::Graded(status));
    let target = learn.hint_target().unwrap();
    assert_eq!(
        target.function, "reduced_decay_time",
        "the first of Section 4.2 not passing"
    );
    let formula = target.hints[2];
    // h is the help in the text (as in `less`); the hints are the course
    // panel's h.
    press(&mut learn, KeyCode::Char('a'));
    for rung in 1..=3 {
        press(&mut learn, KeyCode::Char('h'));
        assert_eq!(learn.hint().unwrap().rung, rung);
        let shown = draw(&mut learn, 160, 48);
        assert!(shown.contains(&format!("hint {rung} of 3")), "{shown}");
        assert_eq!(shown.contains("sigma = I1^2"), rung == 3, "{shown}");
        assert!(formula.starts_with("sigma = I1^2"));
    }
    // Another press stays on the last rung; j scrolls the panel, any other
    // key closes it.
    press(&mut learn, KeyCode::Char('h'));
    assert_eq!(learn.hint().unwrap().rung, 3);
    press(&mut learn, KeyCode::Char('j'));
    assert!(matches!(learn.mode(), Mode::Course(_)));
    press(&mut learn, KeyCode::Char('x'));
    assert!(!draw(&mut learn, 160, 48).contains("hint 3 of 3"));
}

#[test]
fn the_progress_bar_fills_in_proportion() {
    use spintop_app::learn::progress_bar;
    assert_eq!(progress_bar(0, 22, 10), "▱▱▱▱▱▱▱▱▱▱");
    assert_eq!(progress_bar(11, 22, 10), "▰▰▰▰▰▱▱▱▱▱");
    assert_eq!(progress_bar(22, 22, 10), "▰▰▰▰▰▰▰▰▰▰");
    assert_eq!(progress_bar(1, 22, 22), format!("▰{}", "▱".repeat(21)));
}

/// The student's Ω(t) (sampled by the probe) is drawn under the scene
/// against the closed form, with the largest difference: a precession turning
/// the wrong way is seen, and the reference itself agrees.
#[test]
fn the_students_function_of_time_is_drawn_against_the_reference() {
    use spintop::math::Vec3;
    use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
    use spintop_course::{ProbeSpec, Probed};
    let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
    let spec = ProbeSpec::for_chapter("Section 4.2").unwrap();
    let top = SymmetricTop::new(spec.ratio, spec.tau).unwrap();
    let w0 = Vec3::from(spec.omega0);
    let sample = |flip: bool| {
        (0..=spec.samples)
            .map(|i| {
                let t = spec.t_end * i as f64 / spec.samples as f64;
                let w = if flip {
                    // The precession turning the wrong way: mirror Ω₂.
                    let m = sym::reduced_closed_form(&top, &Vec3::new(w0.x, -w0.y, w0.z), t);
                    [m.x, -m.y, m.z]
                } else {
                    let m = sym::reduced_closed_form(&top, &w0, t);
                    [m.x, m.y, m.z]
                };
                (t, w)
            })
            .collect::<Vec<_>>()
    };
    learn.probe_report((spec, Ok(Probed::Samples(sample(true)))));
    let shown = draw(&mut learn, 160, 48);
    assert!(shown.contains("yours: reduced_closed_form"), "{shown}");
    assert!(shown.contains("off by ") && shown.contains("✗"), "{shown}");
    learn.probe_report((spec, Ok(Probed::Samples(sample(false)))));
    let shown = draw(&mut learn, 160, 48);
    assert!(shown.contains("agrees ✓"), "{shown}");
    // A stub says so instead of a chart; another chapter shows nothing.
    learn.probe_report((spec, Ok(Probed::Panicked("not yet implemented".into()))));
    assert!(draw(&mut learn, 160, 48).contains("reduced_closed_form panics: not yet implemented"));
    press(&mut learn, KeyCode::Left);
    assert!(!draw(&mut learn, 160, 48).contains("yours:"));
}

/// A terminal resized between two frames is drawn at its new size before
/// the resize event reaches `apply` (the loop reads events only after the
/// frame): the frame must then be drawn in the frame's own area, never in
/// the size the state last heard of. Found by random keys and resizes under
/// tmux: shrinking the window while a chapter's scene was shown panicked
/// with "index outside of buffer" in the scene's columns.
#[test]
fn a_frame_of_a_new_size_draws_before_its_resize_event_arrives() {
    let sizes = [(200u16, 60u16), (80, 24), (192, 12), (106, 18), (160, 48)];
    for chapter in ["4.2", "2", "A", "asymmetric-top", "preface"] {
        for scene_full in [false, true] {
            // One opening per chapter and mode (opening reads the whole
            // book); each size pair then resizes the same state.
            let mut learn = Learn::open(&book(), Some(chapter)).unwrap();
            learn.apply(Command::Resize(sizes[0].0, sizes[0].1));
            if scene_full {
                press(&mut learn, KeyCode::Tab);
            }
            for &(w0, h0) in &sizes {
                for &(w, h) in &sizes {
                    learn.apply(Command::Resize(w0, h0));
                    // The terminal is now w×h; the state still thinks w0×h0.
                    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
                    let drawn = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        terminal
                            .draw(|f| spintop_app::learn::view::draw(f, &learn))
                            .unwrap();
                    }));
                    assert!(
                        drawn.is_ok(),
                        "{chapter} (scene full screen: {scene_full}): state at {w0}×{h0}, \
                         frame at {w}×{h}: the draw panicked"
                    );
                }
            }
        }
    }
}

/// `/` starts a new search, as in `less`: the word typed after it is the
/// whole query (the last one is not kept in front of it), and `/` then
/// Enter alone repeats the last search from the next match. Found under
/// tmux: a second search typed "k4z" after "hundredfold" and looked for
/// "hundredfoldk4z".
#[test]
fn a_new_search_starts_empty_and_an_empty_one_repeats_the_last() {
    let mut learn = Learn::open(&book(), Some("A")).unwrap();
    draw(&mut learn, 80, 24);
    let search = |learn: &mut Learn, word: &str| {
        press(learn, KeyCode::Char('/'));
        for c in word.chars() {
            press(learn, KeyCode::Char(c));
        }
        press(learn, KeyCode::Enter);
    };
    search(&mut learn, "hundredfold");
    assert_eq!(learn.search().unwrap().query, "hundredfold");
    search(&mut learn, "delay");
    let found = learn.search().unwrap();
    assert_eq!(found.query, "delay", "the second query stands alone");
    assert!(found.matches.len() > 2, "“delay” is all over the appendix");
    let at = found.at;
    search(&mut learn, "");
    let again = learn.search().expect("an empty search repeats the last");
    assert_eq!(again.query, "delay");
    assert_eq!(again.at.unwrap(), at.unwrap() + 1, "…from the next match");
}

/// A status message at 79 columns is shown whole, never cut: one that does
/// not fit its line takes the rows above it; an applied experiment says
/// first that s shows the scene. Found under tmux: "experiment 1 of 3
/// applied: method=rk4 omega=0,10,20 warp=1 (Tab shows the sce" at 80×24,
/// then "…press M to free the…".
#[test]
fn the_status_line_shows_a_long_message_whole_and_keeps_the_scene_hint() {
    let mut learn = Learn::open(&book(), Some("where-methods-fail")).unwrap();
    // The TestBackend writes each row in quotes; the status is row 22, and
    // a long message takes rows 20 and 21 too.
    let status_rows = |shown: &str| {
        shown
            .lines()
            .skip(20)
            .take(3)
            .map(|row| row.trim_matches('"').trim())
            .collect::<Vec<_>>()
            .join(" ")
    };
    // At 79 columns the scene is not beside the text: the message says how
    // to see it.
    for _ in 0..3 {
        draw(&mut learn, 79, 24);
        press(&mut learn, KeyCode::Char('x'));
        let (message, _) = learn.message().cloned().expect("x says what it did");
        let shown = status_rows(&draw(&mut learn, 79, 24));
        let words: Vec<&str> = message.split_whitespace().collect();
        assert!(
            shown.contains(&words.join(" ")) || shown.split_whitespace().eq(words.iter().copied()),
            "the whole message {message:?} in {shown:?}"
        );
        assert!(!shown.ends_with('…'), "{shown:?}");
        assert!(shown.contains("s shows the scene"), "{shown:?}");
    }
}

/// A scene's line names a key only where the key does something: "press x"
/// only in a chapter with experiments, "m" only where the scene takes a
/// method. Found under tmux: Numerical methods (no experiments) said "press
/// x to break it", and x answered "this chapter has no experiments".
#[test]
fn a_scene_names_x_only_in_a_chapter_with_experiments() {
    let mut learn = Learn::open(&book(), None).expect("the book opens");
    for i in 0..learn.chapters().len() {
        learn.apply(Command::Resize(80, 24));
        let file = learn.chapters()[i].file.clone();
        let about = learn.scene_info().describe();
        if about.contains("press x") || about.contains("x runs") {
            assert!(
                !learn.rendered().experiments.is_empty(),
                "{file}: the scene says “{about}” but the chapter has no experiment"
            );
        }
        press(&mut learn, KeyCode::Right);
    }
}

/// One subscript notation on the page: outside code (and tables, whose
/// code-name columns are plain text), no `m_em`-style name is left that
/// prose turns into `mₑₘ`, figure and diagram captions included.
/// Found under tmux: the appendix's prose said mₑₘ and its diagram's caption
/// m_em, a few lines apart.
#[test]
fn prose_and_captions_use_one_subscript_notation() {
    let code = code_style();
    let mut learn = Learn::open(&book(), None).expect("the book opens");
    for _ in 0..learn.chapters().len() {
        learn.apply(Command::Resize(80, 24));
        let file = learn.chapters()[learn.current()].file.clone();
        for line in &learn.rendered().lines {
            // A table's cells are plain text, its code-name column included.
            if line.spans.iter().any(|s| s.content == " │ ") {
                continue;
            }
            for span in &line.spans {
                if span.style.fg == code.fg {
                    continue;
                }
                let text = span.content.as_ref();
                assert_eq!(
                    markdown::prose_subscripts(text),
                    text,
                    "{file}: a subscript left in ASCII in {line:?}"
                );
            }
        }
        press(&mut learn, KeyCode::Right);
    }
}

/// A word that is only in folded library source is found: the search shows
/// the source whole (as `o` does) and goes to it, instead of saying the word
/// is not in the chapter. A word in neither leaves the folds as they were.
/// Found under tmux: "k4z" (a variable of the method of steps, shown in
/// Numerical methods) was "not in this chapter" until `o` was pressed.
#[test]
fn a_search_finds_words_in_folded_library_source() {
    let mut learn = Learn::open(&book(), Some("numerical-methods")).unwrap();
    draw(&mut learn, 80, 24);
    assert!(!learn.unfolded(), "library source starts folded");
    let search = |learn: &mut Learn, word: &str| {
        press(learn, KeyCode::Char('/'));
        for c in word.chars() {
            press(learn, KeyCode::Char(c));
        }
        press(learn, KeyCode::Enter);
    };
    search(&mut learn, "zqxj");
    assert!(learn.search().unwrap().matches.is_empty());
    assert!(!learn.unfolded(), "nothing found: the folds stay");
    search(&mut learn, "k4z");
    let found = learn.search().unwrap();
    assert!(!found.matches.is_empty(), "k4z is in the method of steps");
    assert!(learn.unfolded(), "the library source is shown whole");
    let shown = draw(&mut learn, 80, 24);
    assert!(shown.contains("k4z"), "the page shows the match:\n{shown}");
}
