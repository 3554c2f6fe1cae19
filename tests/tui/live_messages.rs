//! Every message of the live view at 80×24 says its remedy: the line under
//! the header (a refusal of `m`, `+`, an edit …) and a stopped model's
//! advice in its column, in the live view and beside a chapter of
//! `spintop learn`, where the column is narrowest.

use super::learn::{book, draw, press};
use crossterm::event::KeyCode;
use ratatui::{Terminal, backend::TestBackend};
use spintop::scene::catalogue;
use spintop::sim::MethodChoice;
use spintop_app::learn::Learn;
use spintop_app::live::{App, Command, Settings};
use spintop_app::tui::view;
use std::time::Duration;

fn screen(app: &App) -> String {
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    terminal.draw(|frame| view::draw(frame, app)).unwrap();
    terminal.backend().to_string()
}

fn words(s: &str) -> Vec<&str> {
    s.split_whitespace().collect()
}

/// The message's words that are not on the rows under the header, in order.
fn unsaid(app: &App) -> Vec<String> {
    let Some(m) = app.message() else {
        return Vec::new();
    };
    let s = screen(app);
    let rows: Vec<&str> = s.lines().skip(2).take(3).collect();
    let shown = rows.join(" ").replace('"', " ");
    let shown = words(&shown);
    words(&m.text)
        .into_iter()
        .filter(|w| !shown.contains(w))
        .map(str::to_string)
        .collect()
}

/// Type `text` into Ω₀'s `component` and Enter.
fn set_omega(app: &mut App, component: usize, text: &str) {
    while app.view().selected != component {
        app.apply(Command::SelectNext);
    }
    app.apply(Command::StartEdit);
    app.apply(Command::ClearField);
    for c in text.chars() {
        app.apply(Command::Input(c));
    }
    app.apply(Command::Commit);
    app.apply(Command::Cancel);
}

/// Every message the keys give at 80×24 (the method cycle, the warp, the
/// ratio, Tab, a step, a pause, an unknown key, an edit refused), from a
/// symmetric, a full and a general top at the fastest warp with a slow
/// and a fast spin, is on the screen whole: each word of it stands on the
/// rows under the header (a remedy comes last and would be cut first).
#[test]
fn every_message_of_the_live_view_is_whole_at_80x24() {
    let commands = [
        Command::CycleMethod,
        Command::Faster,
        Command::Slower,
        Command::RatioUp,
        Command::NextModel,
        Command::Step,
        Command::TogglePause,
        Command::Unknown("F5".into()),
    ];
    let mut said = 0;
    for name in ["figure-1", "full-ale-physical", "asymmetric-top"] {
        let scene = catalogue::find(name).unwrap().scene().unwrap();
        let (settings, _) = Settings::for_scene(&scene, Some(1000.0)).unwrap();
        for spin in ["0.2", "300"] {
            for c in &commands {
                let mut app = App::new(settings).unwrap();
                set_omega(&mut app, 1, spin);
                let missing = unsaid(&app);
                assert!(
                    missing.is_empty(),
                    "{name}, Ω₂₀ = {spin}: {missing:?}\n{}",
                    screen(&app)
                );
                for _ in 0..3 {
                    app.apply(c.clone());
                    said += usize::from(app.message().is_some());
                    let missing = unsaid(&app);
                    assert!(
                        missing.is_empty(),
                        "{name}, Ω₂₀ = {spin}, {c:?}: {missing:?}\n{}",
                        screen(&app)
                    );
                }
            }
        }
    }
    // The refusal of m where no method runs: its remedy last (Ω₃ never
    // spins down in the reduced model: its cost stays).
    let settings = Settings::new(0.4, [0.0, 0.2, 1000.0], MethodChoice::Rk4, 1000.0).unwrap();
    let mut app = App::new(settings).unwrap();
    app.apply(Command::CycleMethod);
    let text = app.message().unwrap().text.clone();
    assert!(text.ends_with("(- slows down)"), "{text}");
    assert!(unsaid(&app).is_empty(), "{}", screen(&app));
    assert!(said > 100, "only {said} messages seen");
}

/// The text of a stopped column from its "stopped:" down, its rows joined.
fn advice_on(screen: &str) -> String {
    let lines: Vec<&str> = screen.lines().collect();
    let Some((row, col)) = lines.iter().enumerate().find_map(|(i, l)| {
        let at = l.find("stopped:")?;
        Some((i, l[..at].chars().count()))
    }) else {
        return String::new();
    };
    let mut out = Vec::new();
    for l in &lines[row..] {
        // Inside the column's frame only.
        if l.chars().nth(col.saturating_sub(1)) != Some('│') {
            break;
        }
        let part: String = l.chars().skip(col).take_while(|c| *c != '│').collect();
        if part.trim().is_empty() {
            break;
        }
        out.push(part);
    }
    words(&out.join(" ")).join(" ")
}

/// A model stopped by RK4's instability (the experiment of "Where methods
/// fail" that makes it blow up) says its whole advice, the remedy at its
/// end, in the live view at 80×24 and in the scene beside the chapter at
/// 80×24 (a column 32 wide: the advice was cut after "a smaller Ω₀").
/// The advice names no warp: the warp does not change what a tick does.
#[test]
fn a_stopped_models_advice_is_whole_at_80x24() {
    let omega0 = [0.0, 100.0, 200.0];
    let settings = Settings::new(0.4, omega0, MethodChoice::Rk4, 1.0).unwrap();
    let mut app = App::new(settings).unwrap();
    app.advance_ticks(5);
    let why = app.columns()[0]
        .failure()
        .expect("RK4 blows up")
        .to_string();
    assert!(
        why.ends_with("a smaller Ω₀ helps") && !why.contains("warp"),
        "{why}"
    );
    let want = words(&format!("stopped: {why}")).join(" ");
    let s = screen(&app);
    assert_eq!(advice_on(&s), want, "{s}");

    let mut learn = Learn::open(&book(), Some("where-methods-fail")).unwrap();
    draw(&mut learn, 80, 24);
    for _ in 0..3 {
        if learn
            .scene()
            .is_some_and(|a| a.settings().omega0() == omega0)
        {
            break;
        }
        press(&mut learn, KeyCode::Char('x'));
    }
    assert_eq!(learn.scene().unwrap().settings().omega0(), omega0);
    for _ in 0..10 {
        learn.advance(Duration::from_millis(100));
    }
    let why = learn.scene().unwrap().columns()[0]
        .failure()
        .expect("stopped")
        .to_string();
    let s = draw(&mut learn, 80, 24);
    assert_eq!(
        advice_on(&s),
        words(&format!("stopped: {why}")).join(" "),
        "{s}"
    );
}
