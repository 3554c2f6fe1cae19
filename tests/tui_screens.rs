//! The live view drawn headless into a ratatui `TestBackend`: the main screen
//! after a fixed number of model steps, the help overlay, the log-time view,
//! the smallest layout, and the "please enlarge" message. Each screen is
//! pinned by an insta snapshot (tests/snapshots/, reviewed by hand) and by
//! assertions that say what must be on it, so that a changed snapshot is not
//! the only line of defence.

use ratatui::{Terminal, backend::TestBackend};
use spintop::tui::Command;
use spintop::tui::app::{App, Settings};
use spintop::tui::view::{self, MIN_HEIGHT, MIN_WIDTH};

/// Draw `app` on a `width`×`height` test terminal and return the screen.
fn screen(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).expect("a test terminal");
    terminal
        .draw(|frame| view::draw(frame, app))
        .expect("drawing never fails on a TestBackend");
    terminal
}

fn text(terminal: &Terminal<TestBackend>) -> String {
    terminal.backend().to_string()
}

fn braille_count(s: &str) -> usize {
    // U+2800 is the blank pattern; every other one has at least one dot.
    s.chars()
        .filter(|c| ('\u{2801}'..='\u{28FF}').contains(c))
        .count()
}

/// The paper's figure parameters after 600 steps of Δt = 0.1τ (t = 60τ).
fn figure_app_at_60() -> App {
    let mut app = App::new(Settings::default()).expect("default settings");
    app.advance_ticks(600);
    app
}

#[test]
fn main_screen_after_600_steps() {
    let app = figure_app_at_60();
    let terminal = screen(&app, 120, 40);
    let s = text(&terminal);
    assert!(s.contains("t = 60.00τ"), "{s}");
    assert!(s.contains("truncated (4.2)–(4.4)") && s.contains("reduced (4.12)–(4.14)"));
    assert!(
        braille_count(&s) > 200,
        "charts and pictures are drawn in Braille"
    );
    // The truncated top keeps the corrected (4.11) tilt, 0.8961 rad; the
    // reduced one has already stood up part of the way.
    assert!(s.contains("0.8961 rad (51.34°)"), "{s}");
    assert!(s.contains("exact+dop853"));
    insta::assert_snapshot!(terminal.backend());
}

#[test]
fn help_overlay() {
    let mut app = figure_app_at_60();
    app.apply(Command::ToggleHelp);
    let terminal = screen(&app, 120, 40);
    let s = text(&terminal);
    for key in ["space", ". or →", "[ / ]", "Enter", "q Esc ^C"] {
        assert!(s.contains(key), "help lists {key}");
    }
    insta::assert_snapshot!(terminal.backend());
}

#[test]
fn log_time_view_after_a_long_run() {
    let mut app = App::new(Settings::default()).expect("default settings");
    app.apply(Command::ToggleLogTime);
    app.advance_ticks(10_000); // t = 1000τ: four decades from Δt
    let terminal = screen(&app, 120, 40);
    let s = text(&terminal);
    assert!(s.contains("log-time view") && s.contains("log t"));
    assert!(
        s.contains("0.1") && s.contains("1000"),
        "the axis spans Δt to t"
    );
    insta::assert_snapshot!(terminal.backend());
}

#[test]
fn smallest_layout_still_shows_everything() {
    let app = figure_app_at_60();
    let terminal = screen(&app, MIN_WIDTH, MIN_HEIGHT);
    let s = text(&terminal);
    assert!(!s.contains("Please enlarge"));
    assert!(s.contains("truncated") && s.contains("reduced"));
    for label in ["tilt", "method", "evals", "error", "? help"] {
        assert!(s.contains(label), "{label} is on the smallest screen");
    }
    insta::assert_snapshot!(terminal.backend());
}

#[test]
fn too_small_terminal_asks_to_enlarge() {
    let app = figure_app_at_60();
    let terminal = screen(&app, 60, 20);
    let s = text(&terminal);
    assert!(s.contains("Please enlarge the terminal"));
    assert!(s.contains("this one is 60×20"));
    insta::assert_snapshot!(terminal.backend());
    // Tiny and degenerate sizes must not panic either.
    for (w, h) in [
        (1, 1),
        (0, 0),
        (MIN_WIDTH - 1, MIN_HEIGHT),
        (MIN_WIDTH, MIN_HEIGHT - 1),
    ] {
        let terminal = screen(&app, w, h);
        // (TestBackend cannot print a 0-wide buffer; drawing it is the test.)
        if w > 30 {
            assert!(text(&terminal).contains("Please enlarge"), "{w}×{h}");
        }
    }
}

#[test]
fn every_state_draws_at_every_size_without_panicking() {
    let mut app = figure_app_at_60();
    let commands = [
        Command::ToggleLogTime,
        Command::StartEdit,
        Command::Input('7'),
        Command::Commit,
        Command::CycleMethod,
        Command::RatioUp,
        Command::ToggleHelp,
        Command::ToggleHelp,
        Command::TogglePause,
        Command::Step,
    ];
    for command in commands {
        app.apply(command);
        app.advance_ticks(3);
        for (w, h) in [(80, 24), (97, 31), (120, 40), (250, 80)] {
            let s = text(&screen(&app, w, h));
            assert!(s.contains("reduced"), "{command:?} at {w}×{h}");
        }
    }
}
