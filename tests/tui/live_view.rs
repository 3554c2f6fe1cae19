//! The live view as a student drives it: the Ω₀ field refuses what it
//! cannot read, with the reason, and never drops a character or quits; a
//! number below the smallest double is refused, not read as 0; the help
//! scrolls at 80×24 and explains every panel and row; without colour the
//! four curves have four marks; the warp is judged on the models' state
//! now; Tab does nothing unseen; each method has one name on the screen;
//! labels never print over each other; the played-back scenes of `learn`
//! give their units.

use super::learn::{book, draw as draw_learn, press};
use crossterm::event::KeyCode;
use ratatui::{Terminal, backend::TestBackend};
use spintop::sim::MethodChoice;
use spintop_app::learn::Learn;
use spintop_app::live::{App, Command, Mode, Settings};

fn screen(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| spintop_app::tui::view::draw(f, app))
        .unwrap();
    terminal.backend().to_string()
}

fn sized(mut app: App, width: u16, height: u16) -> App {
    app.apply(Command::Resize(width, height));
    app
}

fn typed(app: &mut App, text: &str) {
    for c in text.chars() {
        app.apply(Command::Input(c));
    }
}

fn buffer(app: &App) -> String {
    match app.mode() {
        Mode::Edit { buffer, .. } => buffer.clone(),
        other => panic!("not editing: {other:?}"),
    }
}

fn refusal(app: &App) -> String {
    let m = app.message().expect("a message");
    assert!(m.is_error, "a refusal: {m:?}");
    m.text.clone()
}

/// `0,1` is not silently `01`, `0x10` not `10`, `1_000` not `1000`: each
/// character no number holds is refused with what to type instead, the
/// field unchanged; `q` is such a character and never quits.
#[test]
fn the_omega_field_refuses_what_it_cannot_read_and_never_quits() {
    let mut app = App::new(Settings::default()).unwrap();
    for (text, says) in [
        ("0,1", "point"),
        ("0x10", "decimal"),
        ("1_000", "digits together"),
        ("0.1q", "Esc cancels"),
        ("0 1", "cannot be part of a number"),
    ] {
        app.apply(Command::StartEdit);
        typed(&mut app, text);
        // Kept as typed (a paste of 0,1 must not become 01), and said at once.
        assert_eq!(buffer(&app), text, "nothing dropped");
        assert!(refusal(&app).contains(says), "{text}: {}", refusal(&app));
        assert!(!app.should_quit());
        // Enter refuses the whole text by name, and the field stays open.
        app.apply(Command::Commit);
        assert!(refusal(&app).contains(says), "{text}: {}", refusal(&app));
        assert!(matches!(app.mode(), Mode::Edit { .. }), "{text}");
        assert_eq!(app.settings().omega0(), [0.0, 0.1, 0.2], "{text}");
        app.apply(Command::Cancel);
    }
    app.apply(Command::StartEdit);
    typed(&mut app, "0,");
    app.apply(Command::Backspace);
    typed(&mut app, ".5");
    assert_eq!(buffer(&app), "0.5");
    app.apply(Command::Commit);
    assert_eq!(app.settings().omega0()[0], 0.5);
}

/// 1e-400 would be read as 0: it is refused with the reason, and the field
/// stays open to correct it.
#[test]
fn an_underflowing_omega_is_refused_not_read_as_zero() {
    let mut app = App::new(Settings::default()).unwrap();
    app.apply(Command::SelectNext);
    app.apply(Command::StartEdit);
    typed(&mut app, "1e-400");
    app.apply(Command::Commit);
    // The words a flag and a scene's key get (`--omega: 1e-400 underflows
    // to 0 in f64 …`), without a setting's name: the field is the setting.
    assert!(
        refusal(&app).contains("1e-400 underflows to 0 in f64")
            && refusal(&app).contains("write 0 if zero is meant"),
        "{}",
        refusal(&app)
    );
    assert!(matches!(app.mode(), Mode::Edit { .. }));
    assert_eq!(app.settings().omega0(), [0.0, 0.1, 0.2]);
}

/// At 80×24 the help scrolls, and between its first row and its last it
/// explains every key, every panel and every row of numbers.
#[test]
fn the_help_scrolls_at_80x24_and_explains_every_panel_and_row() {
    let mut app = sized(App::new(Settings::default()).unwrap(), 80, 24);
    app.apply(Command::ToggleHelp);
    let mut seen = String::new();
    let mut last = None;
    for _ in 0..100 {
        let shown = screen(&app, 80, 24);
        seen.push_str(&shown);
        if last == Some(app.mode().clone()) {
            break;
        }
        last = Some(app.mode().clone());
        app.apply(Command::ScrollHelp(5));
    }
    assert!(seen.contains("rows 1–"), "the help says where it is");
    for needed in [
        "space",
        "Enter",
        "Tab",
        "q ^C",
        "Ω(t)",
        "hodograph",
        "top in space",
        "ran away",
        "stopped",
        "= reduced here",
        "tilt",
        "φ̇ ψ̇",
        "method",
        "step",
        "evals",
        "error",
        "since t = 0",
        "header",
        "end;",
    ] {
        assert!(seen.contains(needed), "the help explains {needed}");
    }
}

/// Without colour (NO_COLOR) each curve of the Ω(t) chart has a mark of
/// its own, named in the chart's title; with colour the marks are Braille.
#[test]
fn without_colour_the_four_curves_have_four_marks() {
    let mut app = App::new(Settings::default()).unwrap().monochrome(true);
    app.advance_ticks(300);
    let shown = screen(&app, 120, 40);
    for legend in ["⠒Ω₁", "•Ω₂", "▄Ω₃", "█Ω⊥"] {
        assert!(shown.contains(legend), "{legend} in the title:\n{shown}");
    }
    for mark in ['•', '▄', '█'] {
        assert!(shown.matches(mark).count() > 3, "{mark} drawn:\n{shown}");
    }
    let coloured = screen(
        &{
            let mut a = App::new(Settings::default()).unwrap();
            a.advance_ticks(300);
            a
        },
        120,
        40,
    );
    assert!(coloured.contains("━Ω₂") && !coloured.contains('•'));
}

/// A warp is judged on the models' state now: from a large Ω₀ the next
/// warp is refused at the start, and once Ω has decayed it is taken. (A symmetric top's
/// truncated and reduced models spin Ω⊥ down so fast that their start is
/// judged cheap already; the full ALE's physical solution is tabulated
/// until it settles, and that table is what a large Ω₀ costs.)
#[test]
fn a_faster_warp_is_judged_on_the_state_now() {
    // The largest Ω₂₀ at which the slowest warp runs live; the next warp
    // is refused from it.
    let fits = |w: f64, warp: f64| Settings::full(0.4, [0.0, w, 0.0], warp).is_ok();
    let (mut lo, mut hi) = (1e-3f64, 1e12f64);
    for _ in 0..80 {
        let mid = (lo * hi).sqrt();
        if fits(mid, 0.5) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    assert!(!fits(lo, 1.0), "at Ω₂₀ = {lo} the next warp is refused");
    let settings = Settings::full(0.4, [0.0, lo, 0.0], 0.5).unwrap();
    let mut app = App::new(settings).unwrap();
    // Running, the forward run's table is paid and the physical one is
    // judged from the state: once it has spun down the next warp is taken.
    let mut ticks = 0;
    while app.columns()[..1].iter().any(|c| {
        let w = c.current().omega;
        (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt() > lo / 3.0
    }) {
        app.advance_ticks(50);
        ticks += 50;
        assert!(ticks < 5000, "Ω did not decay");
    }
    app.apply(Command::Faster);
    assert_eq!(app.settings().warp(), 1.0, "{:?}", app.message());
}

/// Tab shows the next model only where they take turns; where both are on
/// the screen it says so and changes nothing.
#[test]
fn tab_does_nothing_unseen_where_every_model_is_shown() {
    let mut app = sized(App::new(Settings::default()).unwrap(), 120, 40);
    app.apply(Command::NextModel);
    assert!(refusal(&app).contains("both models are on the screen"));
    assert_eq!(app.view().shown, 0);
    let top = spintop::physics::general_top::GeneralTop::new(
        spintop::math::Vec3::new(1.0, 1.5, 0.8),
        spintop::math::Vec3::new(0.2, 0.0, 1.0),
    )
    .unwrap();
    let general = Settings::general(top, [0.1, 0.05, 0.2], MethodChoice::Dop853, 10.0).unwrap();
    let mut app = sized(App::new(general).unwrap(), 80, 24);
    app.apply(Command::NextModel);
    assert_eq!(app.view().shown, 1);
    assert!(screen(&app, 80, 24).contains("model 2 of 3"));
}

/// One name for each method across the screen: the header's, the columns'
/// and the messages' are the same (DP5, not dopri5; closed form, not exact).
#[test]
fn each_method_has_one_name_on_the_screen() {
    for (method, name, not) in [
        (MethodChoice::Dopri5, "DP5", "dopri5"),
        (MethodChoice::Exact, "closed form", "exact"),
        (MethodChoice::Taylor, "Taylor", "taylor"),
    ] {
        let settings = Settings::new(0.4, [0.0, 0.1, 0.2], method, 10.0).unwrap();
        let mut app = App::new(settings).unwrap();
        app.advance_ticks(50);
        let shown = screen(&app, 120, 40);
        assert!(shown.contains(&format!("method {name}")), "{shown}");
        assert!(
            shown.matches(name).count() >= 3,
            "header and both columns:\n{shown}"
        );
        assert!(!shown.contains(not), "{not} on the screen:\n{shown}");
    }
}

/// Labels of a panel never print over each other: at every size the
/// hodograph's and the top's names stand apart.
#[test]
fn labels_never_print_over_each_other() {
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::text::Span;
    use ratatui::widgets::Widget;
    use ratatui::widgets::canvas::Canvas;
    use spintop_app::live::widgets::Labels;
    // Three names at one point: each is placed whole, apart, or left out.
    let mut labels = Labels::new([0.0, 1.0], [0.0, 1.0], (12, 4));
    for name in ["Ω₁", "Ω₂", "Ω₃"] {
        labels.add(0.5, 0.5, Span::raw(name));
    }
    let mut buf = Buffer::empty(Rect::new(0, 0, 12, 4));
    Canvas::default()
        .x_bounds([0.0, 1.0])
        .y_bounds([0.0, 1.0])
        .paint(|ctx| labels.print(ctx))
        .render(Rect::new(0, 0, 12, 4), &mut buf);
    let text: String = (0..4)
        .map(|y| {
            (0..12)
                .map(|x| buf[(x, y)].symbol().to_string())
                .collect::<String>()
                + "\n"
        })
        .collect();
    for name in ["Ω₁", "Ω₂", "Ω₃"] {
        assert_eq!(text.matches(name).count(), 1, "{name} whole, once:\n{text}");
    }
    // On the live screens, at small and large sizes.
    let mut app = App::new(Settings::default()).unwrap();
    app.advance_ticks(600);
    for (w, h) in [(80, 24), (100, 30), (160, 48)] {
        let shown = screen(&app, w, h);
        for glued in ["Ω₁Ω", "Ω₂Ω", "Ω₃Ω", "zL", "Le₃", "e₃L"] {
            assert!(!shown.contains(glued), "{glued} at {w}×{h}:\n{shown}");
        }
    }
}

/// The played-back scenes of `spintop learn` (Section 2's charge) give
/// their unit of time in the clock, the warp and the pause.
#[test]
fn the_played_back_scenes_give_their_units() {
    let mut learn = Learn::open(&book(), Some("§2")).unwrap();
    let shown = draw_learn(&mut learn, 120, 40);
    assert!(shown.contains("1/ω₀"), "{shown}");
    press(&mut learn, KeyCode::Char('+'));
    let said = learn.message().unwrap().0.clone();
    assert!(said.contains("(1/ω₀)/s"), "{said}");
    press(&mut learn, KeyCode::Char('p'));
    let said = learn.message().unwrap().0.clone();
    assert!(said.contains("1/ω₀"), "{said}");
}

/// At 80×24 the help box leaves a column each side: nothing of the screen
/// under it shows there (no stray letter of the footer beside the box).
#[test]
fn nothing_shows_beside_the_help_box_at_80x24() {
    let mut app = sized(App::new(Settings::default()).unwrap(), 80, 24);
    let plain = screen(&app, 80, 24);
    app.apply(Command::ToggleHelp);
    let shown = screen(&app, 80, 24);
    let rows: Vec<&str> = shown.lines().collect();
    let boxed: Vec<&&str> = rows.iter().filter(|r| r.contains('│')).collect();
    assert!(boxed.len() > 10, "{shown}");
    for row in rows
        .iter()
        .filter(|r| r.contains('╭') || r.contains('│') || r.contains('╰'))
    {
        let cells: Vec<char> = row.trim_start_matches('"').chars().collect();
        let (first, last) = (cells[0], cells[79]);
        assert!(
            first == ' ' && last == ' ',
            "a stray cell beside the box: {row}\nunder it:\n{plain}"
        );
    }
}
