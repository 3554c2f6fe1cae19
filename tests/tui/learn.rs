//! `spintop learn`: every chapter of the book rendered for the terminal.
//!
//! The chapters come from `book/src` itself, so these tests read the real
//! book: every chapter (and every page of it, scrolled through) is drawn on a
//! `TestBackend` at 80×24 and 160×48, and the screen must hold no raw TeX, no
//! mdBook directive and no Markdown markup outside code. Every experiment
//! comment in the book must parse and apply to its chapter's scene. Two
//! screens of Section 4.2 are pinned by insta snapshots (reviewed by hand).

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::{Terminal, backend::TestBackend};
use spintop::tui::learn::markdown::{self, code_style};
use spintop::tui::learn::{Experiment, Learn, Mode, find_chapter};
use std::path::{Path, PathBuf};

fn book() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("book")
        .join("src")
}

fn draw(learn: &mut Learn, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).expect("a test terminal");
    terminal
        .draw(|f| learn.draw(f))
        .expect("drawing never fails on a TestBackend");
    terminal.backend().to_string()
}

fn key(code: KeyCode) -> KeyEvent {
    KeyEvent::new(code, KeyModifiers::NONE)
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

#[test]
fn every_page_of_every_chapter_draws_at_both_sizes() {
    for (w, h) in [(80u16, 24u16), (160, 48)] {
        let mut learn = Learn::open(&book(), None).expect("the book opens");
        let n = learn.chapters().len();
        for i in 0..n {
            let shown = draw(&mut learn, w, h);
            assert!(
                shown.contains(&learn.chapters()[i].title),
                "{}: title not in the header",
                learn.chapters()[i].file
            );
            // Scroll to the end page by page; the screen must stay clean.
            for _ in 0..400 {
                let before = learn.scroll();
                learn.key(key(KeyCode::PageDown));
                let page = draw(&mut learn, w, h);
                for line in page.lines() {
                    assert!(
                        !line.contains("{{#") && !line.contains("$$"),
                        "{}: {line}",
                        learn.chapters()[i].file
                    );
                }
                if learn.scroll() == before {
                    break;
                }
            }
            learn.key(key(KeyCode::Right));
        }
        assert_eq!(learn.current(), n - 1, "→ walks through every chapter");
    }
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
            e.apply(&scene.settings)
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
    let before = *learn.scene().settings();
    learn.key(key(KeyCode::Char('x')));
    let after = *learn.scene().settings();
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
        ("2", "section-2.md"),
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
            .is_some_and(|e| e.contains("4.2"))
    );

    let mut learn = Learn::open(&book(), None).unwrap();
    learn.key(key(KeyCode::Char('c')));
    assert_eq!(learn.mode(), Mode::Contents(0));
    for _ in 0..3 {
        learn.key(key(KeyCode::Down));
    }
    learn.key(key(KeyCode::Enter));
    assert_eq!(learn.current(), 3);
    assert_eq!(learn.mode(), Mode::Read);
}

#[test]
fn section_4_2_at_80x24_and_160x48() {
    for (w, h) in [(80u16, 24u16), (160, 48)] {
        let mut learn = Learn::open(&book(), Some("4.2")).unwrap();
        let shown = draw(&mut learn, w, h);
        assert!(shown.contains("Section 4.2: the reduced top"));
        if w >= 120 {
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
    use spintop::course::{Report, State, Status};
    let mut learn = Learn::open(&book(), Some("2")).unwrap();
    learn.course_report(Report::Grading);
    assert!(draw(&mut learn, 160, 48).contains("course: grading…"));
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
    learn.key(key(KeyCode::Char('a')));
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
    use spintop::course::{Report, State, Status};
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
    for rung in 1..=3 {
        learn.key(key(KeyCode::Char('h')));
        assert_eq!(learn.hint().unwrap().rung, rung);
        let shown = draw(&mut learn, 160, 48);
        assert!(shown.contains(&format!("hint {rung} of 3")), "{shown}");
        assert_eq!(shown.contains("sigma = I1^2"), rung == 3, "{shown}");
        assert!(formula.starts_with("sigma = I1^2"));
    }
    // Another press stays on the last rung; any other key closes the panel.
    learn.key(key(KeyCode::Char('h')));
    assert_eq!(learn.hint().unwrap().rung, 3);
    learn.key(key(KeyCode::Char('j')));
    assert!(!draw(&mut learn, 160, 48).contains("hint 3 of 3"));
}

#[test]
fn the_progress_bar_fills_in_proportion() {
    use spintop::tui::learn::progress_bar;
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
    use spintop::course::{ProbeSpec, Probed};
    use spintop::math::Vec3;
    use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
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
    learn.key(key(KeyCode::Left));
    assert!(!draw(&mut learn, 160, 48).contains("yours:"));
}
