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
