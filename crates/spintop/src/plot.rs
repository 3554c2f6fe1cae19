//! ASCII line charts (textplots) for the lessons, the book and the command line.
//!
//! Output formatting only: nothing here is physics. Charts are deterministic
//! text, so the book can show a lesson's real output and a test can tell when
//! it goes stale.

use std::fmt::Write as _;

pub mod diagram;
pub mod figure;
pub mod panels;
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

/// One curve of a log-log chart: its points (x, y > 0, in linear units) and
/// the character that marks each of them.
#[derive(Clone, Debug, PartialEq)]
pub struct Marked {
    /// What the curve is, printed in the legend.
    pub label: String,
    /// The character drawn at every point.
    pub marker: char,
    /// The points, in the order they are joined.
    pub points: Vec<(f64, f64)>,
}

/// A log-log chart `width × height` Braille dots: each curve is drawn as
/// lines between its points (log₁₀ of both coordinates), and every point is
/// overwritten by its curve's marker, so curves stay apart in plain text.
/// The ranges are padded out to whole decades. Points with a coordinate ≤ 0
/// or non-finite are left out. The first line names the chart, the axes and
/// the markers; the corner labels are powers of ten.
pub fn loglog_chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[Marked],
    width: u32,
    height: u32,
) -> String {
    let logs: Vec<Vec<(f32, f32)>> = curves
        .iter()
        .map(|c| {
            c.points
                .iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
                .map(|&(x, y)| (x.log10() as f32, y.log10() as f32))
                .collect()
        })
        .collect();
    let all = || logs.iter().flatten();
    let lo = |f: fn(&(f32, f32)) -> f32| all().map(f).fold(f32::INFINITY, f32::min).floor();
    let hi = |f: fn(&(f32, f32)) -> f32| all().map(f).fold(f32::NEG_INFINITY, f32::max).ceil();
    let (mut x0, mut x1) = (lo(|p| p.0), hi(|p| p.0));
    let (mut y0, mut y1) = (lo(|p| p.1), hi(|p| p.1));
    if !(x0.is_finite() && x1.is_finite()) {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let shapes: Vec<Shape> = logs.iter().map(|p| Shape::Lines(p)).collect();
    let mut c = Chart::new_with_y_range(width, height, x0, x1, y0, y1);
    let mut chart = c
        .x_label_format(LabelFormat::Custom(Box::new(|v| {
            format!("1e{}", v.round())
        })))
        .y_label_format(LabelFormat::Custom(Box::new(|v| {
            format!("1e{}", v.round())
        })));
    for shape in &shapes {
        chart = chart.lineplot(shape);
    }
    chart.figures();
    let text = format!("{chart}");
    // NOTE: the markers go where textplots puts each point: dot column
    // round((x − x0)/(x1 − x0)·width), dot row height − round((y − y0)/(y1 − y0)·height),
    // two dot columns and four dot rows per character cell.
    let mut grid: Vec<Vec<char>> = text.lines().map(|l| l.chars().collect()).collect();
    let rows = (height / 4 + 1) as usize;
    for (curve, pts) in curves.iter().zip(&logs) {
        for &(x, y) in pts {
            let i = ((x - x0) / (x1 - x0) * width as f32).round() as usize;
            let j = height as usize - ((y - y0) / (y1 - y0) * height as f32).round() as usize;
            let (col, row) = (i / 2, j / 4);
            if row < rows.min(grid.len())
                && let Some(cell) = grid[row].get_mut(col)
            {
                *cell = curve.marker;
            }
        }
    }
    let legend: Vec<String> = curves
        .iter()
        .map(|c| format!("{} {}", c.marker, c.label))
        .collect();
    let mut out = format!("{title} ({y_label} against {x_label}, log-log)\n");
    let _ = writeln!(out, "  {}", legend.join(", "));
    for line in grid {
        let line: String = line.into_iter().collect();
        out.push_str(line.trim_end_matches(['\u{2800}', ' ']));
        out.push('\n');
    }
    out
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

    #[test]
    fn loglog_chart_marks_every_point_where_it_lies() {
        // Two decades each way: (1, 1) bottom left, (100, 100) top right.
        let curve = Marked {
            label: "diagonal".into(),
            marker: 'X',
            points: vec![(1.0, 1.0), (10.0, 10.0), (100.0, 100.0)],
        };
        let text = loglog_chart("t", "x", "y", &[curve], 40, 20);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[1], "  X diagonal");
        let grid = &lines[2..2 + 6];
        let at = |row: usize, col: usize| grid[row].chars().nth(col);
        // 40 dots = 20 columns, 20 dots = 5 rows (+1 for the edge).
        assert_eq!(at(5, 0), Some('X'), "{text}");
        assert_eq!(at(0, 20), Some('X'), "{text}");
        assert_eq!(at(3, 10).or(at(2, 10)), Some('X'), "{text}");
        assert!(text.contains("1e0") && text.contains("1e2"), "{text}");
    }
}
