//! ASCII line charts (textplots) for the lessons, the book and the command line.
//!
//! Output formatting only: nothing here is physics. Charts are deterministic
//! text, so the book can show a lesson's real output and a test can tell when
//! it goes stale.

use std::fmt::Write as _;

pub mod figure;
use textplots::{Chart, LabelBuilder, LabelFormat, Plot, Shape};

/// One curve: a label and its points (x, y).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// What the curve is, printed in the legend line above the chart.
    pub label: String,
    /// The points; drawn as connected lines, or as dots when `dots` is set.
    pub points: Vec<(f64, f64)>,
    /// Draw the points as dots (for sampled data over a smooth curve).
    pub dots: bool,
}

impl Series {
    /// A curve drawn with connected lines.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            dots: false,
        }
    }

    /// Points drawn as dots.
    pub fn dots(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            dots: true,
        }
    }
}

/// A chart `width × height` Braille dots (two columns and four rows of dots
/// per character), x from `x_range.0` to `x_range.1`, y scaled to the data.
/// The first line names the chart and its curves.
pub fn chart(
    title: &str,
    series: &[Series],
    x_range: (f64, f64),
    width: u32,
    height: u32,
) -> String {
    let pts: Vec<Vec<(f32, f32)>> = series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|&(x, y)| (x as f32, y as f32))
                .collect()
        })
        .collect();
    let shapes: Vec<Shape> = series
        .iter()
        .zip(&pts)
        .map(|(s, p)| {
            if s.dots {
                Shape::Points(p)
            } else {
                Shape::Lines(p)
            }
        })
        .collect();
    let mut c = Chart::new(width, height, x_range.0 as f32, x_range.1 as f32);
    let mut chart = c.y_label_format(LabelFormat::Custom(Box::new(|v| format!("{v:.3e}"))));
    for shape in &shapes {
        chart = chart.lineplot(shape);
    }
    chart.axis();
    chart.figures();
    let mut out = String::new();
    let legend: Vec<String> = series
        .iter()
        .map(|s| format!("{} ({})", s.label, if s.dots { "dots" } else { "line" }))
        .collect();
    let _ = writeln!(out, "{title}: {}", legend.join(", "));
    let _ = write!(out, "{chart}");
    // NOTE: textplots pads with U+2800 (the blank Braille cell); trailing blanks
    // are trimmed so the text compares and diffs cleanly.
    out.lines()
        .map(|l| l.trim_end_matches(['\u{2800}', ' ']))
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chart_draws_braille_and_names_its_curves() {
        let pts: Vec<(f64, f64)> = (0..50)
            .map(|i| (i as f64, (i as f64 / 8.0).sin()))
            .collect();
        let text = chart(
            "sine",
            &[Series::line("sin(t/8)", pts)],
            (0.0, 49.0),
            80,
            20,
        );
        assert!(text.starts_with("sine: sin(t/8) (line)"));
        assert!(text.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)));
        // Title, at least height/4 rows of dots, then the x range.
        assert!(text.lines().count() > 1 + 20 / 4);
        let last = text.lines().last().unwrap();
        assert!(
            last.starts_with("0.0") && last.trim_end().ends_with("49.0"),
            "{last}"
        );
    }
}
