//! `spintop plot` and the live view's command line as a user meets them: the
//! text charts for pipes (one per quantity and model, the curves where the
//! closed forms put them), bad input refused with one line and exit code 2,
//! and `spintop` / `spintop tui` refusing to start without a terminal.

use spintop::math::Vec3;
use spintop::physics::symmetric_top::{SymmetricTop, truncated_closed_form};
use std::process::{Command, Output, Stdio};

/// Run the binary with stdout and stderr piped (so neither is a terminal).
fn spintop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("the binary runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn no_terminal_no_live_view_one_line_and_exit_code_2() {
    for args in [&[][..], &["tui"][..], &["tui", "--ratio", "1.5"][..]] {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("spintop: error: "), "{err}");
        assert!(
            err.contains("needs a terminal, but stdout is not one"),
            "{err}"
        );
        assert!(
            err.contains("spintop simulate") && err.contains("spintop plot"),
            "{err}"
        );
        assert!(
            stdout(&out).is_empty(),
            "nothing on stdout: no escape codes in the pipe"
        );
    }
}

#[test]
fn bad_live_view_arguments_are_refused_before_the_terminal_check() {
    let cases: [(&[&str], &str); 4] = [
        (&["tui", "--ratio", "3"], "not a rigid body"),
        (&["tui", "--warp", "7"], "--warp must be one of"),
        (&["tui", "--omega", "0,nan,1"], "not a finite number"),
        (&["tui", "--bench", "0"], "--bench"),
    ];
    for (args, needle) in cases {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn plot_prints_four_charts_per_model() {
    let out = spintop(&["plot"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert_eq!(text.matches("# spintop plot: truncated model").count(), 1);
    assert_eq!(text.matches("# spintop plot: reduced model").count(), 1);
    for q in ["Ω₁(t)", "Ω₂(t)", "Ω₃(t)", "Ω⊥(t)"] {
        assert_eq!(text.matches(q).count(), 2, "{q} once per model");
    }
    let dots = text
        .chars()
        .filter(|c| ('\u{2801}'..='\u{28FF}').contains(c))
        .count();
    assert!(dots > 500, "Braille curves");
    assert!(stderr(&out).is_empty());
}

/// Where does a chart draw? The Ω₃ chart of the truncated model must end at
/// the height of the closed form (4.7), Ω₃(t_end) = Ω₃₀/R(t_end), read to the
/// chart's own resolution: each text line holds 4 Braille dot rows, so the
/// 20 lines are 80 rows of 0.5/80 = 0.00625 each. (With R's square root
/// dropped, Ω₃(1000) would be 0.0095 instead of 0.0436: 5.4 dot rows lower,
/// though only about one text line.)
#[test]
fn eq_4_7_plot_of_omega3_ends_at_the_closed_form() {
    let height = 20; // lines, 80 Braille rows, y from -0.25 to 0.25
    let out = spintop(&[
        "plot",
        "--model",
        "truncated",
        "--t-end",
        "1000",
        "--width",
        "40",
        "--height",
        "20",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let chart: Vec<&str> = text
        .split("Ω₃(t)")
        .nth(1)
        .expect("an Ω₃ chart")
        .lines()
        .skip(1)
        .take(height)
        .collect();
    // The last Braille character of each line: the first line from the top
    // with dots there holds the curve's end (the zero line lies below it).
    let braille = |c: char| ('\u{2800}'..='\u{28FF}').contains(&c);
    let (end_line, cell) = chart
        .iter()
        .enumerate()
        .find_map(|(i, line)| {
            line.chars()
                .rfind(|&c| braille(c))
                .filter(|&c| c != '\u{2800}')
                .map(|c| (i, c as u32 - 0x2800))
        })
        .expect("the curve reaches the right edge");
    // Dot rows 0-3 of the right column are bits 3, 4, 5, 7; of the left
    // column 0, 1, 2, 6. The curve's last dots: the right column if lit.
    let right = [0x08, 0x10, 0x20, 0x80];
    let left = [0x01, 0x02, 0x04, 0x40];
    let column = if right.iter().any(|b| cell & b != 0) {
        right
    } else {
        left
    };
    let rows: Vec<usize> = (0..4)
        .filter(|&r| cell & column[r] != 0)
        .map(|r| 4 * end_line + r)
        .collect();
    let (first, last) = (rows[0] as f64, rows[rows.len() - 1] as f64);
    // (4.7) in place: Ω₃ = Ω₃₀/R, R = √(1 + 2τΩ⊥₀²t) = √21 (τ = 1, Ω⊥₀ = 0.1).
    let omega3 = 0.2 / (1.0f64 + 2.0 * 0.01 * 1000.0).sqrt();
    let top = SymmetricTop::figure();
    let closed = truncated_closed_form(&top, &Vec3::new(0.0, 0.1, 0.2), 1000.0).z;
    assert!((closed - omega3).abs() < 1e-15, "{closed} vs {omega3}");
    // Dot row 0 is y = +0.25; each is 0.5/80 high.
    let expected = (0.25 - omega3) / (0.5 / (4 * height) as f64);
    assert!(
        expected >= first - 1.5 && expected <= last + 1.5,
        "Ω₃(1000) = {omega3}: dot rows {first}..={last}, expected {expected:.1}\n{}",
        chart.join("\n")
    );
}

#[test]
fn plot_log_time_spans_four_decades() {
    let out = spintop(&[
        "plot",
        "--model",
        "reduced",
        "--log-time",
        "--t-end",
        "1000",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("against log t"));
    // The x labels are t itself: 0.1 at the left, 1000 at the right.
    assert!(
        text.lines()
            .any(|l| l.trim_start().starts_with("0.1") && l.trim_end().ends_with("1000")),
        "{text}"
    );
}

#[test]
fn bad_plot_input_is_one_line_and_exit_code_2() {
    let cases: [(&[&str], &str); 6] = [
        (&["plot", "--ratio", "0"], "not a rigid body"),
        (&["plot", "--t-end", "0"], "--t-end 0 is out of range"),
        (&["plot", "--t-end", "inf"], "not a finite number"),
        (&["plot", "--width", "3"], "--width"),
        (&["plot", "--height", "1000"], "--height"),
        (
            &["plot", "--model", "general"],
            "--model general is not known",
        ),
    ];
    for (args, needle) in cases {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(stdout(&out).is_empty());
    }
}
