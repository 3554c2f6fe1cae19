//! The live view's front door as a reviewer found it: `m` never sticks on a
//! refusal and its help lists the methods it cycles; keys it does not know
//! are answered; without colour the selected Ω₀ stays reversed.

use spintop::sim::MethodChoice;
use spintop_app::live::{App, Command, Settings};

/// The methods `m` visits from `app`, pressing it `n` times, and whether
/// each press was refused.
fn presses(app: &mut App, n: usize) -> Vec<(MethodChoice, bool)> {
    (0..n)
        .map(|_| {
            app.apply(Command::CycleMethod);
            let refused = app.message().is_some_and(|m| m.is_error);
            (app.settings().method(), refused)
        })
        .collect()
}

/// At a fast warp a fast top cannot run every method live: `m` from RK4
/// lands on the first method after it in the cycle that runs (each judged
/// independently, by the settings' own constructor), whichever ones before
/// it are refused; auto included (the reviewer's `m` stuck on DP5's
/// refusal at warp 1000).
#[test]
fn m_lands_on_the_next_method_that_runs() {
    let cycle = [
        MethodChoice::Dopri5,
        MethodChoice::Dop853,
        MethodChoice::Radau5,
        MethodChoice::Taylor,
        MethodChoice::Auto,
    ];
    let mut reached_auto = false;
    for warp in [50.0, 200.0, 1000.0] {
        for w in [0.1, 30.0, 100.0, 300.0, 600.0] {
            // Ω₃ never spins down in the reduced model: its cost stays.
            let omega0 = [0.0, 0.2, w];
            let Ok(settings) = Settings::new(0.4, omega0, MethodChoice::Rk4, warp) else {
                continue;
            };
            let runs = |m| Settings::new(0.4, omega0, m, warp).is_ok();
            let Some(want) = cycle.iter().copied().find(|m| runs(*m)) else {
                continue;
            };
            let mut app = App::new(settings).unwrap();
            app.advance_ticks(20);
            let seen = presses(&mut app, 1);
            assert_eq!(seen, vec![(want, false)], "Ω₀ = {omega0:?} at {warp}");
            reached_auto |= want == MethodChoice::Auto;
        }
    }
    assert!(reached_auto, "no case where only auto runs was tried");
}

/// Where no other method runs at this warp, `m` says so and names the
/// method that runs at the fastest slower warp (checked by the settings'
/// constructor), not the first refusal's advice.
#[test]
fn where_no_method_runs_m_names_the_fastest_warp_that_does() {
    let omega0 = [0.0, 0.2, 1000.0];
    let settings = Settings::new(0.4, omega0, MethodChoice::Rk4, 1000.0).unwrap();
    let mut app = App::new(settings).unwrap();
    let seen = presses(&mut app, 1);
    assert_eq!(seen, vec![(MethodChoice::Rk4, true)]);
    let text = app.message().unwrap().text.clone();
    assert!(
        text.contains("no other method runs this top live at 1000"),
        "{text}"
    );
    let top = *app.settings().top();
    // Every other method of the cycle, at the fastest warp below 1000 at
    // which it runs; any of those that tie may be named.
    let runs_at = |m| {
        spintop_app::live::settings::WARPS
            .into_iter()
            .filter(|w| *w < 1000.0 && Settings::new(0.4, omega0, m, *w).is_ok())
            .fold(None, |a: Option<f64>, w| Some(a.map_or(w, |a| a.max(w))))
    };
    let others: Vec<(MethodChoice, f64)> = spintop_app::live::layout::method_cycle(&top)
        .into_iter()
        .filter(|m| *m != MethodChoice::Rk4)
        .filter_map(|m| Some((m, runs_at(m)?)))
        .collect();
    let fastest = others.iter().map(|(_, w)| *w).fold(0.0, f64::max);
    assert!(fastest > 0.0, "some other method runs slower");
    let named = others.iter().filter(|(_, w)| *w == fastest).any(|(m, w)| {
        text.contains(&format!(
            "{} runs at {w} τ/s",
            spintop_app::live::app::method_title(*m, &top)
        ))
    });
    assert!(named, "{text}: want one of {others:?} at {fastest}");
}

/// The help of a scene lists the methods in the order `m` walks them, auto
/// included, on a general top (asymmetric-top) as on a symmetric one.
#[test]
fn the_help_lists_the_methods_m_walks_auto_included() {
    use spintop::scene::catalogue;
    let scene = catalogue::find("asymmetric-top").unwrap().scene().unwrap();
    let (general, _) = Settings::for_scene(&scene, None).unwrap();
    let symmetric = Settings::new(0.4, [0.0, 0.1, 0.2], MethodChoice::Rk4, 10.0).unwrap();
    for settings in [general, symmetric] {
        let mut app = App::new(settings).unwrap();
        let start = app.settings().method();
        let mut walked = vec![start];
        for (m, refused) in presses(&mut app, 12) {
            assert!(!refused, "{:?}", app.message());
            if m == start {
                break;
            }
            walked.push(m);
        }
        assert!(walked.contains(&MethodChoice::Auto), "{walked:?}");
        let top = *app.settings().top();
        let names: Vec<String> = walked
            .iter()
            .map(|m| spintop_app::live::app::method_title(*m, &top))
            .collect();
        let help: String = spintop_app::live::help::lines(&top)
            .iter()
            .map(|l| l.to_string())
            .collect::<Vec<_>>()
            .join("\n");
        // The help's list, from auto, is the walk rotated to start at auto.
        let at = walked
            .iter()
            .position(|m| *m == MethodChoice::Auto)
            .unwrap();
        let mut from_auto = names[at..].to_vec();
        from_auto.extend_from_slice(&names[..at]);
        let want = from_auto.join(", ");
        assert!(
            help.replace('\n', " ").contains(&want),
            "help lacks `{want}`:\n{help}"
        );
    }
}

/// A key the view does not take is answered at once, naming the key, and
/// the answer replaces whatever was said before.
#[test]
fn unknown_keys_are_answered() {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    let mut app = App::new(Settings::default()).unwrap();
    for (code, name) in [
        (KeyCode::Char('x'), "x"),
        (KeyCode::F(1), "F1"),
        (KeyCode::Left, "←"),
    ] {
        app.apply(Command::Reset);
        let before = app.message().unwrap().text.clone();
        let key = KeyEvent::new(code, KeyModifiers::NONE);
        let command = spintop_app::tui::event::command_for(key, app.mode(), 10)
            .unwrap_or_else(|| panic!("{name} gets no command"));
        app.apply(command);
        let m = app.message().expect("an answer");
        assert_ne!(m.text, before);
        assert!(
            m.text.starts_with(&format!("{name}: no such key")),
            "{}",
            m.text
        );
    }
}

/// The command §2's scene suggests runs as printed (it lacked the flags
/// `spintop orbit` requires: --potential, --tau0).
#[test]
fn the_orbit_command_section_2_suggests_runs_as_printed() {
    let line = spintop_app::learn::scene::draw::physical_run_command(1e-3);
    let mut words = line.split_whitespace();
    assert_eq!(words.next(), Some("spintop"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(words)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "`{line}` failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// With `NO_COLOR`, crossterm wrote each colour as an empty SGR (`ESC[m`),
/// which a terminal reads as "reset everything": the selected Ω₀ lost its
/// reversal. Drawn through the loop's own frame function into a real
/// crossterm back end (crossterm's colours switched off, as `NO_COLOR` does),
/// the bytes keep the reversal and carry no colour and no bare reset.
#[test]
fn without_colour_the_selected_component_stays_reversed() {
    use ratatui::backend::CrosstermBackend;
    use ratatui::layout::Rect;
    use ratatui::{Terminal, TerminalOptions, Viewport};
    use std::sync::{Arc, Mutex};
    /// The bytes the back end writes, kept.
    #[derive(Clone, Default)]
    struct Kept(Arc<Mutex<Vec<u8>>>);
    impl std::io::Write for Kept {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    crossterm::style::force_color_output(false);
    let kept = Kept::default();
    let backend = CrosstermBackend::new(kept.clone());
    let options = TerminalOptions {
        viewport: Viewport::Fixed(Rect::new(0, 0, 120, 40)),
    };
    let mut terminal = Terminal::with_options(backend, options).unwrap();
    let mut app = App::new(Settings::default()).unwrap().monochrome(true);
    app.apply(Command::Resize(120, 40));
    spintop_app::term::session::draw_frame(
        &mut terminal,
        |f| spintop_app::tui::view::draw(f, &app),
        true,
    )
    .unwrap();
    let bytes = String::from_utf8_lossy(&kept.0.lock().unwrap()).to_string();
    assert!(bytes.contains("\u{1b}[7m"), "no reversal written");
    for bare in ["\u{1b}[m", "\u{1b}[;m"] {
        assert!(
            !bytes.contains(bare),
            "a bare SGR {bare:?} resets the emphasis"
        );
    }
    for colour in ["38;5;", "48;5;", "[91m", "[92m", "[33m"] {
        assert!(!bytes.contains(colour), "colour {colour:?} written");
    }
}
