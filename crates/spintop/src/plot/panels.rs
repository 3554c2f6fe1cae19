//! Line charts side by side as one SVG document (plotters, SVG backend): the
//! figures of the book that are not the paper's.
//!
//! Output formatting only. The drawing is deterministic, so the book can
//! embed what the code draws and a test can tell when it goes stale.

use plotters::prelude::*;

/// One panel: a caption, axis descriptions and its curves (label, points).
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Shown above the panel.
    pub caption: String,
    /// The x axis.
    pub x_label: String,
    /// The y axis.
    pub y_label: String,
    /// The curves, each a label and its points (x, y).
    pub curves: Vec<(String, Vec<(f64, f64)>)>,
}

/// Pixels per panel.
const PANEL: (u32, u32) = (560, 420);

/// The curve colours, in order (six, so that a panel of six curves has no
/// two alike).
const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(120, 120, 120),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

/// The panels side by side under `title`, as an SVG document, each legend
/// at the middle of the right edge.
pub fn panels_svg(title: &str, panels: &[Panel]) -> String {
    panels_svg_legend(title, panels, SeriesLabelPosition::MiddleRight)
}

/// [`panels_svg`] with each panel's legend at `legend` (where its curves
/// leave room).
pub fn panels_svg_legend(title: &str, panels: &[Panel], legend: SeriesLabelPosition) -> String {
    let n = panels.len().max(1) as u32;
    let size = (PANEL.0 * n, PANEL.1 + 40);
    let mut buffer = String::new();
    {
        let root = SVGBackend::with_string(&mut buffer, size).into_drawing_area();
        // NOTE: drawing into a String cannot fail for I/O reasons; an error
        // here would be a plotting bug, so it panics (as figure::svg does).
        draw(title, panels, legend, &root).expect("plotters draws into a string");
        root.present().expect("plotters draws into a string");
    }
    buffer
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;
type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// The range of the finite values, widened by 5% (and to a unit when flat).
fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0..1.0;
    }
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 };
    (lo - pad)..(hi + pad)
}

fn draw(title: &str, panels: &[Panel], legend: SeriesLabelPosition, root: &Area) -> DrawResult {
    root.fill(&WHITE)?;
    let (head, body) = root.split_vertically(40);
    head.draw(&Text::new(
        title.to_string(),
        (20, 12),
        ("sans-serif", 18).into_font().color(&BLACK),
    ))?;
    let areas = body.split_evenly((1, panels.len().max(1)));
    for (panel, area) in panels.iter().zip(&areas) {
        let points = || panel.curves.iter().flat_map(|(_, p)| p.iter());
        let xs = range(points().map(|p| p.0));
        let ys = range(points().map(|p| p.1));
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.caption, ("sans-serif", 15))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(xs, ys)?;
        chart
            .configure_mesh()
            .light_line_style(BLACK.mix(0.06))
            .x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .label_style(("sans-serif", 12))
            // A tick at zero lands a rounding error away from it.
            .y_label_formatter(&|v| {
                if v.abs() < 1e-15 {
                    "0".into()
                } else {
                    format!("{v:.2e}")
                }
            })
            .draw()?;
        for ((label, pts), color) in panel.curves.iter().zip(COLORS.iter().cycle()) {
            chart
                .draw_series(LineSeries::new(
                    pts.iter()
                        .copied()
                        .filter(|p| p.0.is_finite() && p.1.is_finite()),
                    color.stroke_width(2),
                ))?
                .label(label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(legend.clone())
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 12))
            .draw()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_draw_every_curve_and_label() {
        let panel = |name: &str| Panel {
            caption: format!("panel {name}"),
            x_label: "t".into(),
            y_label: "y".into(),
            curves: vec![
                ("rising".into(), vec![(0.0, 0.0), (1.0, 1.0)]),
                ("flat".into(), vec![(0.0, 0.5), (1.0, 0.5)]),
            ],
        };
        let svg = panels_svg("two panels", &[panel("a"), panel("b")]);
        assert!(svg.starts_with("<svg"));
        for text in ["two panels", "panel a", "panel b", "rising", "flat"] {
            assert!(svg.contains(text), "{text}");
        }
        // A non-finite point is skipped, not drawn as NaN.
        let odd = Panel {
            curves: vec![("odd".into(), vec![(0.0, f64::NAN), (1.0, 2.0), (2.0, 3.0)])],
            ..panel("c")
        };
        assert!(!panels_svg("x", &[odd]).contains("NaN"));
    }
}
