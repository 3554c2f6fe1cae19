//! The live view drawn headless into a ratatui `TestBackend`: the main screen
//! after a fixed number of model steps, the help overlay, the log-time view,
//! the smallest layout, the "please enlarge" message, and the one column of
//! a general (asymmetric) top, whose numbers must be those of an independent
//! run of its scene and must show a free top's E and |L| unchanged. Each screen is
//! pinned by an insta snapshot (tests/snapshots/, reviewed by hand) and by
//! assertions that say what must be on it, so that a changed snapshot is not
//! the only line of defence.

use ratatui::{Terminal, backend::TestBackend};
use spintop::math::Vec3;
use spintop::physics::general_top::GeneralTop;
use spintop::scene::{Body, Scene, catalogue};
use spintop::sim::{MethodChoice, Simulation};
use spintop_app::live::Command;
use spintop_app::live::app::{MIN_HEIGHT, MIN_WIDTH};
use spintop_app::live::widgets::fmt_num;
use spintop_app::live::{App, Settings};
use spintop_app::tui::view;

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
    // One name for each method across the screen: the header's.
    assert!(s.contains("method closed form"), "{s}");
    assert!(!s.contains("exact"), "{s}");
    insta::assert_snapshot!(terminal.backend());
}

#[test]
fn help_overlay() {
    let mut app = figure_app_at_60();
    app.apply(Command::ToggleHelp);
    let terminal = screen(&app, 120, 40);
    let s = text(&terminal);
    for key in ["space", ". or →", "[ / ]", "Enter", "q ^C"] {
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
    // The time axis spans Δt = 0.1 to t = 1000 in four decades, ticks at
    // both ends and in the middle: on a log axis the middle is 10 (on a
    // linear one it would be 500), halfway between the left label's start
    // and the right label's end.
    let ticks = s
        .lines()
        .find(|l| {
            l.trim_start_matches(['"', '│'])
                .trim_start()
                .starts_with("0.1")
                && l.contains("1000")
        })
        .expect("a tick line");
    let panel: Vec<char> = ticks.split("││").next().unwrap().chars().collect();
    let find = |label: &str, from: usize| {
        let l: Vec<char> = label.chars().collect();
        (from..=panel.len() - l.len())
            .find(|&i| {
                panel[i..i + l.len()] == l[..]
                    && !panel.get(i + l.len()).is_some_and(|c| c.is_ascii_digit())
            })
            .unwrap_or_else(|| panic!("{label} on {ticks}"))
    };
    let left = find("0.1", 0);
    let right_end = find("1000", left + 3) + 4;
    let middle = find("10", left + 3);
    let centre = middle as f64 + 1.0;
    let halfway = 0.5 * (left + right_end) as f64;
    assert!(
        (centre - halfway).abs() <= 1.5 && middle < right_end - 4,
        "10 at column {centre}, halfway {halfway}: {ticks}"
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
        app.apply(command.clone());
        app.advance_ticks(3);
        for (w, h) in [(80, 24), (97, 31), (120, 40), (250, 80)] {
            let s = text(&screen(&app, w, h));
            assert!(s.contains("reduced"), "{command:?} at {w}×{h}");
        }
    }
}

fn asymmetric_scene() -> Scene {
    catalogue::find("asymmetric-top")
        .expect("in the catalogue")
        .scene()
        .expect("the scene parses")
}

/// The catalogue's asymmetric top as `spintop tui asymmetric-top` opens it.
fn general_app() -> App {
    let (settings, note) = spintop_app::live::Settings::for_scene(&asymmetric_scene(), None)
        .expect("the live view opens it");
    App::new(settings)
        .expect("valid settings")
        .with_message(note)
}

/// The value printed after `label` on the screen (the first occurrence).
fn value_after<'a>(screen: &'a str, label: &str) -> &'a str {
    let at = screen
        .find(label)
        .unwrap_or_else(|| panic!("{label}:\n{screen}"))
        + label.len();
    screen[at..].split_whitespace().next().expect("a value")
}

#[test]
fn general_top_screen_after_600_steps() {
    let mut app = general_app();
    app.advance_ticks(600);
    // Three columns, each wide enough for its drift block.
    let terminal = screen(&app, 300, 40);
    let s = text(&terminal);
    assert!(s.contains("t = 60.00u"), "{s}");
    assert!(s.contains("scene asymmetric-top: a general top under (3.3), the reduced ALE and the physical solution of (3.4) side by side"));
    assert!(s.contains("truncated (3.3)") && !s.contains("truncated (4.2)"));
    assert!(s.contains("reduced (3.4): Schott term kept") && s.contains("physical (3.4)"));
    assert!(
        !s.contains('τ'),
        "time is in u, the kappa = 1 unit, not tau:\n{s}"
    );
    assert!(s.contains("I = (1, 1.5, 0.8)") && s.contains("d = (0.2, 0, 1)"));
    for panel in [
        "Ω(t) [1/u]",
        "hodograph of Ω",
        "the top in space",
        "since t = 0",
    ] {
        assert!(s.contains(panel), "{panel}");
    }
    assert!(s.contains("— (no closed form)"));
    assert!(!s.contains("[ ]"), "no I₃/I₁ keys in the footer");
    assert!(braille_count(&s) > 200);
    insta::assert_snapshot!(terminal.backend());
}

/// The Ω, E and |L| on the screen at t = 50 are those of the scene run on its
/// own by `Simulation` (its own Euler angles, which the view starts from
/// too, and its own method).
#[test]
fn sec3_general_top_shows_the_omega_of_an_independent_run_of_its_scene() {
    let scene = asymmetric_scene();
    let Body::Top(top) = &scene.body else {
        panic!("a top scene")
    };
    let mut sim = Simulation::new(top.model, top.method, top.options, top.initial, Some(50.0))
        .expect("the scene runs");
    let other = *sim.advance_to(50.0).expect("to t = 50");
    let mut app = general_app();
    app.apply(Command::TogglePause);
    app.advance_ticks(500);
    let s = app.columns()[0].current();
    assert_eq!(s.t, 50.0);
    assert!(
        (s.omega_vec() - other.omega_vec()).norm() < 1e-9,
        "{:?} vs {:?}",
        s.omega,
        other.omega
    );
    assert!((s.energy - other.energy).abs() < 1e-10);
    let screen = text(&screen(&app, 300, 40));
    let [o1, o2, o3] = other.omega.map(fmt_num);
    assert!(
        screen.contains(&format!("({o1}, {o2}, {o3})/u")),
        "Ω = ({o1}, {o2}, {o3}) on\n{screen}"
    );
    assert_eq!(value_after(&screen, "│E "), fmt_num(other.energy));
    let l = Vec3::from(other.l_lab).norm();
    assert_eq!(value_after(&screen, "│|L| "), fmt_num(l));
    // Both runs start from the scene's Euler angles (the view honours
    // them), so they agree on the orientation as well.
    assert_eq!(
        top.method,
        MethodChoice::Auto,
        "the scene leaves the method to auto"
    );
    assert!((s.rotation_matrix() - other.rotation_matrix()).norm() < 1e-8);
}

/// A free top (dipole a million times smaller): the E and |L| shown do not
/// change over 500 time units, and the drift block reads 1 for both.
#[test]
fn sec3_general_top_with_a_tiny_dipole_shows_constant_energy_and_momentum() {
    let top = GeneralTop::new(Vec3::new(1.0, 1.5, 0.8), Vec3::new(0.2e-6, 0.0, 1e-6)).unwrap();
    // NOTE: not the scene's Ω₀, whose E₀ = 0.022875 sits on a rounding
    // boundary of the four digits shown, where a drift of 1e-15 flips a digit.
    let settings = Settings::general(top, [0.1, 0.06, 0.2], MethodChoice::Dop853, 10.0).unwrap();
    let mut app = App::new(settings).unwrap();
    // τ_f|Ω₀| is about 3e-13: the physical column's backward shoot would buy
    // nothing the screen can show, so the reduced model stands in, and says so.
    assert!(app.columns()[2].stand_in().is_some());
    assert!(matches!(
        app.columns()[2].model(),
        spintop::sim::Model::GeneralReduced(_)
    ));
    let at_start = text(&screen(&app, 300, 40));
    let (e0, l0) = (
        value_after(&at_start, "│E ").to_owned(),
        value_after(&at_start, "│|L| ").to_owned(),
    );
    assert_eq!(e0, "0.02370", "E₀ = ½ Ω₀·IΩ₀ = 0.0237");
    assert_eq!(l0, "0.2090", "|L₀| = |IΩ₀| = √0.0437");
    for _ in 0..10 {
        app.advance_ticks(500);
        let later = text(&screen(&app, 300, 40));
        assert_eq!(value_after(&later, "│E "), e0);
        assert_eq!(value_after(&later, "│|L| "), l0);
        // "1.000", or "1.0000" for a ratio a hair below 1: one, to the digits shown.
        for label in ["E/E₀", "|L|/|L₀|"] {
            let shown = value_after(&later, label);
            assert_eq!(shown.parse::<f64>(), Ok(1.0), "{label} = {shown}");
        }
    }
    // With the scene's dipole the same top radiates: E falls by half by t = 60.
    let mut app = general_app();
    app.advance_ticks(600);
    let later = text(&screen(&app, 300, 40));
    let ratio: f64 = value_after(&later, "E/E₀").parse().unwrap();
    assert!(ratio < 0.6, "{ratio}");
}

#[test]
fn general_top_draws_every_state_at_every_size() {
    let mut app = general_app();
    app.advance_ticks(100);
    let small = text(&screen(&app, MIN_WIDTH, MIN_HEIGHT));
    for label in [
        "truncated (3.3)",
        "method Taylor",
        "error",
        "tilt",
        "? help",
    ] {
        assert!(small.contains(label), "{label} at 80×24:\n{small}");
    }
    let commands = [
        Command::ToggleLogTime,
        Command::RatioUp,
        Command::StartEdit,
        Command::Input('7'),
        Command::Commit,
        Command::CycleMethod,
        Command::ToggleHelp,
        Command::ToggleHelp,
        Command::TogglePause,
        Command::Step,
    ];
    for command in commands {
        app.apply(command.clone());
        app.advance_ticks(3);
        for (w, h) in [(80, 24), (97, 31), (120, 40), (250, 80)] {
            let s = text(&screen(&app, w, h));
            assert!(s.contains("(3.3)"), "{command:?} at {w}×{h}");
        }
    }
    app.apply(Command::ToggleHelp);
    let help = text(&screen(&app, 120, 40));
    assert!(help.contains("the general top") && help.contains("no closed form"));
}

/// Type `text` into Ω₀'s component `i` (↑/↓ to it, Enter, the characters),
/// leaving the field open when `commit` is false.
fn type_omega(app: &mut App, i: usize, text: &str, commit: bool) {
    while app.view().selected != i {
        app.apply(Command::SelectNext);
    }
    app.apply(Command::StartEdit);
    for c in text.chars() {
        app.apply(Command::Input(c));
    }
    if commit {
        app.apply(Command::Commit);
    }
}

/// The header never cuts a number at 80 columns: with every Ω₀ component
/// written in exponent form (ten characters each), and while a long entry
/// is being typed, the Ω₀ cell is shown whole (the cells of I, d or I₃/I₁
/// give way first) and the line fits the screen. Found under tmux: the
/// asymmetric top's header ran to "Ω₀ = (-1.235e-14, -1.235e-14, -1.23456789"
/// and off the screen.
#[test]
fn the_header_shows_omega0_whole_at_80_columns() {
    let long = "-1.23456789e-14";
    let shown = "-1.235e-14";
    for general in [true, false] {
        let mut app = if general {
            general_app()
        } else {
            App::new(Settings::default()).unwrap()
        };
        let u = if general { "u" } else { "τ" };
        for i in 0..3 {
            type_omega(&mut app, i, long, true);
        }
        let s = text(&screen(&app, MIN_WIDTH, MIN_HEIGHT));
        let cell = format!("Ω₀ = ({shown}, {shown}, {shown})/{u}");
        let line = s.lines().nth(1).unwrap();
        assert!(line.contains(&cell), "general: {general}; {line:?}\n{s}");
        // Now type the longest entry the field takes into the last one.
        let typed = "-1.234567890123456789012345678e-1";
        type_omega(&mut app, 2, &typed[..32], false);
        let s = text(&screen(&app, MIN_WIDTH, MIN_HEIGHT));
        let cell = format!("Ω₀ = ({shown}, {shown}, {}▏)/{u}", &typed[..32]);
        let line = s.lines().nth(1).unwrap();
        assert!(line.contains(&cell), "general: {general}; {line:?}\n{s}");
    }
}
