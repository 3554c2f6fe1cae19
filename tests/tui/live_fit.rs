//! The numbers under each live column keep every row at 80×24 and 100×30:
//! a long value shortens the numbers, it never drops the column beside it
//! or cuts a number at the edge.

use ratatui::{Terminal, backend::TestBackend};
use spintop::sim::MethodChoice;
use spintop_app::live::{App, Command, Settings};

fn screen(app: &mut App, width: u16, height: u16) -> String {
    app.apply(Command::Resize(width, height));
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| spintop_app::tui::view::draw(f, app))
        .unwrap();
    terminal.backend().to_string()
}

/// How many times `label` names a number in the rows of numbers (the rows
/// that start with t, E, |L|, tilt and φ̇ at a column's border).
fn rows_named(screen: &str, label: &str) -> usize {
    screen
        .lines()
        .filter(|l| {
            ["│t ", "│E ", "│|L| ", "│tilt ", "│φ̇ "]
                .iter()
                .any(|s| l.contains(s))
        })
        .map(|l| l.matches(&format!("{label} ")).count())
        .sum()
}

/// Ω₀ = (0, 1e-12, 2e-12): φ̇ is `1.281e-12/τ`, too wide for the full
/// numbers beside the right-hand block in 38 columns; both columns keep
/// ψ̇, method, step, evals and error.
#[test]
fn every_number_row_stays_at_80x24_with_long_values() {
    let settings = Settings::new(0.4, [0.0, 1e-12, 2e-12], MethodChoice::Auto, 1.0).unwrap();
    let mut app = App::new(settings).unwrap();
    app.advance_ticks(3);
    let s = screen(&mut app, 80, 24);
    for label in ["ψ̇", "method", "step", "evals", "error", "φ̇", "tilt"] {
        assert_eq!(rows_named(&s, label), 2, "{label} in both columns:\n{s}");
    }
}

/// At 100×30 the last row gives Ω⊥ with its value, never the name alone.
#[test]
fn the_last_row_is_never_cut_after_its_name() {
    for omega in [[0.3, -0.2, 0.1], [1.234e-7, -2.5e-9, 3.3e-11]] {
        let settings = Settings::new(0.4, omega, MethodChoice::Auto, 1.0).unwrap();
        let mut app = App::new(settings).unwrap();
        app.advance_ticks(3);
        for (w, h) in [(100, 30), (80, 24), (100, 40), (120, 40)] {
            let s = screen(&mut app, w, h);
            let rows: Vec<&str> = s
                .lines()
                .filter(|l| l.contains("│Ω ") && l.contains(")/τ"))
                .collect();
            for row in &rows {
                let after = row.split("Ω⊥ ").nth(1).unwrap_or("");
                assert!(
                    after.starts_with(|c: char| c.is_ascii_digit() || c == '-'),
                    "Ω⊥ without its value at {w}×{h}: {row}\n{s}"
                );
            }
        }
    }
}

/// A start that spins down within a few τ is judged on what its run costs:
/// `--omega 0,10000,0.2` (closed forms) and `--omega 1000,0.1,0.2` by DP5
/// run at 1000 τ/s, and the first 100τ (a tenth of a wall-clock second
/// there) take each column fewer steps than a tenth of the view's budget.
#[test]
fn eq_4_16_a_start_that_spins_down_is_judged_on_what_it_costs() {
    use spintop_app::live::settings::LIVE_STEPS_PER_SECOND;
    for (omega, method) in [
        ([0.0, 1e4, 0.2], MethodChoice::Exact),
        ([1000.0, 0.1, 0.2], MethodChoice::Dopri5),
    ] {
        let settings = Settings::new(0.4, omega, method, 1000.0)
            .unwrap_or_else(|e| panic!("{omega:?} by {method:?} refused: {e}"));
        let mut app = App::new(settings).unwrap();
        app.advance_ticks(1000);
        for c in app.columns() {
            assert!(c.failure().is_none(), "{omega:?}: {:?}", c.failure());
            let s = c.stats();
            let work = (s.steps + s.rejected) as f64;
            assert!(
                work <= 0.1 * LIVE_STEPS_PER_SECOND,
                "{omega:?} {}: {work} steps in 100τ",
                c.name()
            );
        }
    }
}

/// On the command line a refusal names the flag, not the key: a slower
/// warp as `--warp W`, and that warp is taken.
#[test]
fn the_command_line_refusal_names_a_flag_that_works() {
    // Ω₃ does not spin down in the reduced model: its orientation turns
    // 1e4 rad per τ at any warp.
    let omega = [0.0, 0.0, 1e4];
    let refusal = Settings::new(0.4, omega, MethodChoice::Exact, 1000.0).unwrap_err();
    let line = refusal.on_command_line();
    assert!(!line.contains("(- slows down)"), "{line}");
    let warp: f64 = line
        .split("(--warp ")
        .nth(1)
        .and_then(|r| r.split(')').next())
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("no --warp in: {line}"));
    assert!(
        Settings::new(0.4, omega, MethodChoice::Exact, warp).is_ok(),
        "{line}"
    );
    // In the live view the key is named.
    assert!(refusal.to_string().contains("(- slows down)"), "{refusal}");
}

/// From Ω₁₀ = 1000 (h·3τ|Ω|² = 3e4 for RK4's step) `m` never lands on RK4,
/// which would blow up on its first step, and says why it skipped it; a
/// top at rest takes RK4 (the rule can let it through).
#[test]
fn m_skips_a_fixed_step_method_unstable_for_the_state() {
    let omega = [1000.0, 0.1, 0.2];
    let mut app =
        App::new(Settings::new(0.4, omega, MethodChoice::Dopri5, 1000.0).unwrap()).unwrap();
    let mut said = false;
    for _ in 0..8 {
        app.apply(Command::CycleMethod);
        assert_ne!(
            app.settings().method(),
            MethodChoice::Rk4,
            "{:?}",
            app.message()
        );
        said |= app
            .message()
            .is_some_and(|m| m.text.contains("RK4 skipped"));
    }
    assert!(said, "m never said why RK4 is skipped");
    let mut calm =
        App::new(Settings::new(0.4, [0.0, 0.1, 0.2], MethodChoice::Auto, 1.0).unwrap()).unwrap();
    let mut seen = false;
    for _ in 0..8 {
        calm.apply(Command::CycleMethod);
        seen |= calm.settings().method() == MethodChoice::Rk4;
    }
    assert!(seen, "RK4 is in the cycle of a slow top");
}

/// RK4 stopped by its instability advises an adaptive method, not a slower
/// warp (the same fixed step), and its panel shows no error for the state
/// where it failed.
#[test]
fn a_fixed_step_blow_up_advises_an_adaptive_method() {
    let settings = Settings::new(0.4, [1000.0, 0.1, 0.2], MethodChoice::Rk4, 1.0).unwrap();
    let mut app = App::new(settings).unwrap();
    app.advance_ticks(5);
    let stopped: Vec<&str> = app.columns().iter().filter_map(|c| c.failure()).collect();
    assert!(!stopped.is_empty(), "RK4 ran from Ω₁₀ = 1000");
    for why in &stopped {
        assert!(why.contains("adaptive method"), "{why}");
        assert!(!why.contains("slows the warp"), "{why}");
    }
    let s = screen(&mut app, 120, 40);
    assert!(!s.contains("error   0/τ"), "{s}");
    assert!(s.contains("— (stopped)"), "{s}");
}
