//! A reviewer's leftovers of the reader: Backspace (or Alt-←) goes back to
//! where a link, the contents or a search into another chapter took the
//! reader from, as a browser's back;
//! the search field scrolls so that what is typed last stays in sight.

use super::learn::{book, draw, press};
use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use spintop_app::learn::{Command, Learn, Mode};

fn message(learn: &Learn) -> String {
    learn.message().map(|m| m.0.clone()).unwrap_or_default()
}

fn alt_left(learn: &mut Learn) {
    let event = Event::Key(KeyEvent::new(KeyCode::Left, KeyModifiers::ALT));
    if let Some(command) = learn.command_for(&event) {
        learn.apply(command);
    }
}

/// Focus the link to `target` on the asymmetric top's chapter, from a page
/// scrolled to it; the place (chapter, first line) before following it.
fn focus(learn: &mut Learn, target: &str) -> (usize, usize, usize) {
    let link = learn
        .rendered()
        .links
        .iter()
        .position(|l| l.target == target)
        .expect("the chapter has the link");
    let line = learn.rendered().links[link].parts[0].0;
    learn.apply(Command::Scroll(line.saturating_sub(5) as i64));
    while learn.focused_link() != Some(link) {
        press(learn, KeyCode::Tab);
    }
    (learn.current(), learn.scroll(), link)
}

/// Enter on a link to another chapter, then Backspace: the chapter, the
/// line and the link in focus are those before; Alt-← does the same; two
/// links deep, two Backspaces come back in order; with nothing to go back
/// to, Backspace says so and moves nothing (← stays the previous chapter).
#[test]
fn backspace_returns_to_where_a_link_was_followed() {
    let mut learn = Learn::open(&book(), Some("asymmetric-top")).unwrap();
    draw(&mut learn, 100, 30);
    let before = focus(&mut learn, "scene-reference.md#what-auto-chooses");
    press(&mut learn, KeyCode::Enter);
    assert_ne!(learn.current(), before.0, "{}", message(&learn));
    assert!(message(&learn).contains("Backspace"), "{}", message(&learn));
    let away = (learn.current(), learn.scroll());
    press(&mut learn, KeyCode::Backspace);
    assert_eq!(
        (learn.current(), learn.scroll(), learn.focused_link()),
        (before.0, before.1, Some(before.2)),
        "{}",
        message(&learn)
    );
    // Again, back by Alt-←.
    press(&mut learn, KeyCode::Enter);
    assert_eq!((learn.current(), learn.scroll()), away);
    alt_left(&mut learn);
    assert_eq!((learn.current(), learn.scroll()), (before.0, before.1));
    // Two deep: a link, then the contents to another chapter.
    press(&mut learn, KeyCode::Enter);
    press(&mut learn, KeyCode::Char('c'));
    press(&mut learn, KeyCode::Char('2'));
    press(&mut learn, KeyCode::Enter);
    assert_eq!(learn.current(), 1, "{}", message(&learn));
    press(&mut learn, KeyCode::Backspace);
    assert_eq!(
        (learn.current(), learn.scroll()),
        away,
        "{}",
        message(&learn)
    );
    press(&mut learn, KeyCode::Backspace);
    assert_eq!((learn.current(), learn.scroll()), (before.0, before.1));
    press(&mut learn, KeyCode::Backspace);
    assert_eq!((learn.current(), learn.scroll()), (before.0, before.1));
    assert!(message(&learn).contains("nothing to go back to"));
    // ← is still the previous chapter.
    press(&mut learn, KeyCode::Left);
    assert_eq!(learn.current(), before.0 - 1);
}

/// A search that goes on into another chapter is left by Backspace for
/// the page it started from, as `less`'s '' returns from a search's jump;
/// a match in the same chapter keeps no place.
#[test]
fn backspace_returns_from_a_search_in_another_chapter() {
    let mut learn = Learn::open(&book(), None).unwrap();
    draw(&mut learn, 80, 24);
    learn.apply(Command::Scroll(3));
    let from = (learn.current(), learn.scroll());
    learn.apply(Command::SearchStart);
    for c in "Coulomb".chars() {
        learn.apply(Command::SearchInput(c));
    }
    learn.apply(Command::SearchCommit);
    assert_ne!(learn.current(), from.0, "{}", message(&learn));
    press(&mut learn, KeyCode::Backspace);
    assert_eq!(
        (learn.current(), learn.scroll()),
        from,
        "{}",
        message(&learn)
    );
    // Again, with a second match of the same chapter between: still one
    // Backspace back.
    press(&mut learn, KeyCode::Char('n'));
    let found = learn.current();
    assert!(
        learn.search().unwrap().matches.len() >= 2,
        "two matches there"
    );
    press(&mut learn, KeyCode::Char('n'));
    assert_eq!(learn.current(), found, "{}", message(&learn));
    press(&mut learn, KeyCode::Backspace);
    assert_eq!(
        (learn.current(), learn.scroll()),
        from,
        "{}",
        message(&learn)
    );
}

/// The help names the key that goes back.
#[test]
fn the_help_names_the_back_key() {
    let mut learn = Learn::open(&book(), None).unwrap();
    press(&mut learn, KeyCode::Char('h'));
    let help: String = spintop_app::learn::view::help_lines(&learn)
        .iter()
        .map(|l| l.to_string() + "\n")
        .collect();
    let row = help
        .lines()
        .find(|l| l.contains("back to where a link"))
        .unwrap_or_else(|| panic!("{help}"));
    assert!(row.contains('⌫') && row.contains("Alt-←"), "{row}");
}

/// The status line of a search being typed, at `width` columns.
fn prompt(learn: &mut Learn, width: u16) -> String {
    let shown = draw(learn, width, 24);
    shown.lines().nth(22).unwrap_or_default().to_string()
}

/// A search field longer than the line shows its end: what was typed last
/// and the cursor, at 80 columns and at the smallest screen, full (the
/// limit said) or not.
#[test]
fn a_long_search_field_keeps_its_end_in_sight() {
    let longest = spintop_app::learn::search::LONGEST;
    for width in [80, 40] {
        let mut learn = Learn::open(&book(), None).unwrap();
        draw(&mut learn, width, 24);
        learn.apply(Command::SearchStart);
        // The alphabet over and over: the last six letters typed are
        // recognisable wherever the field is cut.
        let typed: Vec<char> = (0..longest)
            .map(|i| char::from(b'a' + (i % 26) as u8))
            .collect();
        for (i, c) in typed.iter().enumerate() {
            learn.apply(Command::SearchInput(*c));
            let line = prompt(&mut learn, width);
            let end: String = typed[(i + 1).saturating_sub(6)..=i].iter().collect();
            assert!(
                line.contains(&format!("{end}▏")),
                "at {width} columns, {} typed: {line:?}",
                i + 1
            );
        }
        let line = prompt(&mut learn, width);
        assert!(line.contains("full"), "{line:?}");
        assert!(matches!(learn.mode(), Mode::Search(..)));
        // One more is refused, and the end stays.
        learn.apply(Command::SearchInput('Z'));
        assert!(!prompt(&mut learn, width).contains('Z'));
    }
}
