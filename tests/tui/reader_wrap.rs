//! The reader's search finds a phrase as written, not as wrapped (as `less`
//! searches a file's lines, not the screen's rows): the count is the same
//! at every width, and a match the wrap splits is marked on both lines.

use super::learn::{book, draw, press};
use crossterm::event::KeyCode;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::Color;
use spintop_app::learn::{Command, Learn};

/// `/` `phrase` Enter.
fn search(learn: &mut Learn, phrase: &str) {
    learn.apply(Command::SearchStart);
    for c in phrase.chars() {
        learn.apply(Command::SearchInput(c));
    }
    learn.apply(Command::SearchCommit);
}

/// How many times the chapter's words hold `phrase`, counted on the text
/// rendered so wide that no prose line wraps (an independent count).
fn count_unwrapped(learn: &Learn, phrase: &str) -> usize {
    let path = book().join(&learn.chapters()[learn.current()].file);
    let source = spintop_app::learn::search::chapter_source(&path, &book());
    let lines = spintop_app::learn::markdown::render(&source, 2000).lines;
    spintop_app::learn::markdown::plain(&lines)
        .to_lowercase()
        .matches(phrase)
        .count()
}

/// §4.1 at 80×24 with the scene beside the text, then without it (`w`),
/// then 200 wide: "closed form" is found as often each time, as often as
/// the unwrapped text holds it, and more than once split by the wrap.
#[test]
fn search_finds_a_phrase_the_wrap_splits_at_every_width() {
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    let phrase = "closed form";
    let expected = count_unwrapped(&learn, phrase);
    assert!(expected >= 3, "§4.1 says “{phrase}” {expected} times");
    draw(&mut learn, 80, 24);
    assert!(
        learn.panes().scene.is_some(),
        "the scene beside the text at 80×24"
    );
    search(&mut learn, phrase);
    let narrow = learn.search().unwrap().matches.clone();
    let said = learn.message().map(|m| m.0.clone()).unwrap_or_default();
    assert!(said.contains(&format!("match 1 of {expected}")), "{said}");
    press(&mut learn, KeyCode::Char('w'));
    draw(&mut learn, 80, 24);
    let wide = learn.search().unwrap().matches.len();
    draw(&mut learn, 200, 50);
    let widest = learn.search().unwrap().matches.len();
    assert_eq!((narrow.len(), wide, widest), (expected, expected, expected));
    let split = narrow.iter().filter(|m| m.0.len() == 2).count();
    assert!(
        split >= 1,
        "the scene's narrow column splits one: {narrow:?}"
    );
}

/// A match split by the wrap is marked on both lines: the current one's
/// colour on "closed" at one line's end and "form" at the next's start.
#[test]
fn a_match_the_wrap_splits_is_marked_on_both_lines() {
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    draw(&mut learn, 80, 24);
    search(&mut learn, "closed form");
    // n until the match shown is a split one.
    let n = learn.search().unwrap().matches.len();
    for _ in 0..n {
        let s = learn.search().unwrap();
        if s.matches[s.at.unwrap()].0.len() == 2 {
            break;
        }
        press(&mut learn, KeyCode::Char('n'));
    }
    let s = learn.search().unwrap().clone();
    let m = &s.matches[s.at.unwrap()];
    assert_eq!(m.0.len(), 2, "a split match: {:?}", s.matches);
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| spintop_app::learn::view::draw(f, &learn))
        .unwrap();
    let buffer = terminal.backend().buffer().clone();
    let mut marked = Vec::new();
    for y in 0..24 {
        let row: String = (0..80)
            .filter(|&x| buffer[(x, y)].bg == Color::Yellow)
            .map(|x| buffer[(x, y)].symbol().to_string())
            .collect();
        if !row.is_empty() {
            marked.push(row);
        }
    }
    let joined = marked.join(" ").to_lowercase();
    assert_eq!(marked.len(), 2, "{marked:?}");
    assert_eq!(joined, "closed form", "{marked:?}");
}

/// The scene's header gives Ω₀ in the unit of time the live view names
/// for the same top (`/τ` for the symmetric top of §4.1).
#[test]
fn the_scene_header_gives_omega0_its_unit() {
    let mut learn = Learn::open(&book(), Some("4.1")).unwrap();
    let shown = draw(&mut learn, 120, 40);
    let Some(settings) = (match learn.stage() {
        spintop_app::learn::scene::Stage::Top(app) => Some(*app.settings()),
        _ => None,
    }) else {
        panic!("§4.1 runs a top: {shown}")
    };
    let unit = settings.top().time_unit();
    // Wide, and at 80×24 beside the text.
    for shown in [shown, draw(&mut learn, 80, 24)] {
        let row = shown
            .lines()
            .find(|l| l.contains("Ω₀ = ("))
            .unwrap_or_default();
        let after = &row[row.find("Ω₀ = (").unwrap_or(0)..];
        let close = after.find(')').map_or("", |i| &after[i..]);
        assert!(close.starts_with(&format!(")/{unit}")), "{shown}");
        assert!(row.contains("I₃/I₁"), "{row}");
    }
}
