//! `spintop figure` as a user runs it: the paper's Figures 1 and 2 as text
//! charts and SVG, equal to what the core draws (the figures' physics is
//! tested in the core's tests).

use spintop::figure::{Figure, FigureNumber};
use spintop::plot::figure::{ascii, svg};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn figure(number: FigureNumber) -> &'static Figure {
    static ONE: OnceLock<Figure> = OnceLock::new();
    static TWO: OnceLock<Figure> = OnceLock::new();
    let cell = match number {
        FigureNumber::One => &ONE,
        FigureNumber::Two => &TWO,
    };
    cell.get_or_init(|| Figure::new(number).expect("the paper's parameters run"))
}

fn spintop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .output()
        .expect("the binary runs")
}

#[test]
fn cli_figure_prints_the_charts_and_writes_the_svg() {
    let dir = std::env::temp_dir().join(format!("spintop-figure-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (arg, number) in [("1", FigureNumber::One), ("2", FigureNumber::Two)] {
        let path = dir.join(format!("figure-{arg}.svg"));
        let out = spintop(&["figure", arg, "--svg", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(0));
        assert!(out.stderr.is_empty());
        let stdout = String::from_utf8(out.stdout).unwrap();
        assert!(stdout.starts_with(&ascii(figure(number))));
        assert!(stdout.ends_with(&format!("SVG written to {}\n", path.display())));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), svg(figure(number)));
        // Without --svg: the charts alone.
        let out = spintop(&["figure", arg]);
        assert_eq!(out.status.code(), Some(0));
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            ascii(figure(number))
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_figure_refuses_bad_input_with_one_line_and_exit_code_2() {
    let unwritable = "/nonexistent-spintop-dir/figure.svg";
    let cases: [(&[&str], &str); 5] = [
        (&["figure", "3"], "Figures 1 and 2 only, not 3"),
        (&["figure", "one"], "not one"),
        (&["figure"], "required"),
        (
            &["figure", "1", "--svg", unwritable],
            "cannot write the SVG",
        ),
        (&["figure", "1", "--svg"], "--svg"),
    ];
    for (args, needle) in cases {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}: nothing on stdout");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("spintop: error: "), "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
