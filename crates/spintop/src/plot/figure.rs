//! Figures 1 and 2 drawn: as text charts and as SVG (plotters, SVG backend).
//!
//! Output formatting only: the points come from [`crate::figure`], and
//! nothing here computes physics. Both renderers are deterministic, so the
//! book can keep copies of their output and a test can tell when they go stale.
//!
//! The SVG has four panels, as the paper's captions describe them:
//!
//! | panel | what it shows |
//! |---|---|
//! | (a) | the hodograph of Ω in the body frame, and its projections on the three coordinate planes |
//! | (b) | the top in space: the path of the symmetry axis tip on the unit sphere, L(t) and L∞ |
//! | (c) | the tilt θ(t) of the axis from L∞ |
//! | (d) | the precession rate φ̇(t) and the proper rotation rate ψ̇(t) |

use super::{Series, chart};
use crate::figure::{Figure, FigureNumber};
use crate::math::{Real, Vec3};
use crate::physics::symmetric_top::reduced_decay_time;
use plotters::coord::Shift;
use plotters::coord::ranged3d::Cartesian3d;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::fmt::Write as _;

/// The colour of the hodograph and of the axis-tip path (the data curves).
pub const CURVE_COLOR: RGBColor = RGBColor(0x1f, 0x4e, 0xa8);
/// The colour of the three projections of the hodograph.
pub const PROJECTION_COLOR: RGBColor = RGBColor(0x8a, 0x9b, 0xbd);
/// The colour of L∞ and of the path of L(t).
pub const L_COLOR: RGBColor = RGBColor(0xc0, 0x39, 0x2b);
/// The colour of the symmetry axis drawn at the start and at the end.
pub const AXIS_COLOR: RGBColor = RGBColor(0x33, 0x33, 0x33);
/// The colour of φ̇(t) in panel (d).
pub const PHI_DOT_COLOR: RGBColor = RGBColor(0x1e, 0x84, 0x49);
/// The colour of ψ̇(t) in panel (d).
pub const PSI_DOT_COLOR: RGBColor = RGBColor(0xb9, 0x77, 0x0e);

/// Width and height of the SVG, in pixels.
pub const SVG_SIZE: (u32, u32) = (1000, 900);

/// Half-width of the Ω₁ and Ω₂ axes of panel (a), and the top of the Ω₃ axis, in 1/τ.
const OMEGA_PERP_AXIS: Real = 0.1;
const OMEGA3_AXIS: Real = 0.25;

/// A short label for the model.
fn model_label(figure: &Figure) -> &'static str {
    match figure.number {
        FigureNumber::One => "truncated ALE (4.2)-(4.4), no Schott term",
        FigureNumber::Two => "reduced ALE (4.12)-(4.14), Schott term kept",
    }
}

/// The figure as text: a summary of the start and the end, then one chart per
/// projection of the hodograph, the axis tip seen from above, θ(t), φ̇ and ψ̇.
pub fn ascii(figure: &Figure) -> String {
    [
        summary(figure),
        hodograph_charts(figure),
        axis_tip_chart(figure),
        theta_chart(figure),
        rates_chart(figure),
    ]
    .concat()
}

/// The smallest and largest first coordinate of `pts`.
fn x_span(pts: &[(f64, f64)]) -> (f64, f64) {
    let lo = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let hi = pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

/// The model, the start, the caption, and a table of three samples.
fn summary(figure: &Figure) -> String {
    let mut out = String::new();
    let first = figure.samples.first().expect("a figure has points");
    let last = figure.samples.last().expect("a figure has points");
    let n = figure.number.number();
    let _ = writeln!(out, "Figure {n}: {}", model_label(figure));
    let _ = writeln!(
        out,
        "I3/I1 = {}, Omega0 = ({}, {}, {}) in 1/tau; {} points, 0 <= t <= {}",
        figure.top().ratio(),
        figure.omega0.x,
        figure.omega0.y,
        figure.omega0.z,
        figure.samples.len(),
        last.t
    );
    let _ = writeln!(out, "{}", figure.caption());
    let _ = writeln!(
        out,
        "Lab frame: z along the final direction of L, so theta is the tilt of the axis from it.\n"
    );
    let _ = writeln!(
        out,
        "{:>8} {:>28} {:>10} {:>10} {:>10} {:>10}",
        "t", "Omega (body frame)", "Om3/Om_p", "theta", "phi_dot", "psi_dot"
    );
    for s in [first, &figure.samples[figure.samples.len() / 10], last] {
        let w = s.omega;
        let rates = s
            .euler_rates
            .map_or(("-".to_string(), "-".to_string()), |r| {
                (format!("{:.4e}", r[0]), format!("{:.4e}", r[2]))
            });
        let _ = writeln!(
            out,
            "{:>8.1} ({:>8.5}, {:>8.5}, {:>8.5}) {:>10.5} {:>10.4e} {:>10} {:>10}",
            s.t,
            w[0],
            w[1],
            w[2],
            w[2] / s.omega_perp,
            s.euler[1],
            rates.0,
            rates.1
        );
    }
    let _ = writeln!(out);
    out
}

/// The hodograph of Ω projected on the three coordinate planes of the body.
fn hodograph_charts(figure: &Figure) -> String {
    let mut out = String::new();
    let project = |i: usize, j: usize| -> Vec<(f64, f64)> {
        figure
            .samples
            .iter()
            .map(|s| (s.omega[i], s.omega[j]))
            .collect()
    };
    let names = ["Omega_1", "Omega_2", "Omega_3"];
    for (i, j, plane) in [
        (0, 1, "Omega_3 = 0"),
        (1, 2, "Omega_1 = 0"),
        (0, 2, "Omega_2 = 0"),
    ] {
        let pts = project(i, j);
        let x_range = x_span(&pts);
        let mut series = vec![Series::line("Omega(t)", pts)];
        if j == 2 {
            // The side views start at Omega_3 = 0, so the cone reaches down to
            // its apex and the flat reduced hodograph is not squashed to a line.
            series.push(Series::line(
                "Omega_3 = 0",
                vec![(x_range.0, 0.0), (x_range.1, 0.0)],
            ));
        }
        let _ = writeln!(
            out,
            "{}",
            chart(
                &format!(
                    "Hodograph projected on the plane {plane}: {} (up) against {} (across)",
                    names[j], names[i]
                ),
                &series,
                x_range,
                100,
                48,
            )
        );
    }
    out
}

/// The path of the axis tip seen from above, along L∞.
fn axis_tip_chart(figure: &Figure) -> String {
    let tip: Vec<(f64, f64)> = figure
        .samples
        .iter()
        .map(|s| {
            let e3 = Figure::axis(s);
            (e3.x, e3.y)
        })
        .collect();
    let centre = vec![(0.0, 0.0)];
    let mut x_range = x_span(&tip);
    x_range = (x_range.0.min(0.0), x_range.1.max(0.0));
    format!(
        "{}\n",
        chart(
            "The top in space, seen from above along L_inf = lab z: the axis tip, y (up) against x (across)",
            &[
                Series::line("axis tip path", tip),
                Series::dots("L_inf", centre)
            ],
            x_range,
            100,
            48,
        )
    )
}

/// θ(t), the tilt of the axis from L∞.
fn theta_chart(figure: &Figure) -> String {
    let last = figure.samples.last().expect("a figure has points");
    let theta: Vec<(f64, f64)> = figure.samples.iter().map(|s| (s.t, s.euler[1])).collect();
    format!(
        "{}\n",
        chart(
            "theta(t), the tilt of the axis from L_inf, rad",
            &[
                Series::line("theta", theta),
                Series::line("upright, theta = 0", vec![(0.0, 0.0), (last.t, 0.0)]),
            ],
            (0.0, last.t),
            120,
            32,
        )
    )
}

/// The precession rate φ̇(t) and the proper rotation rate ψ̇(t).
fn rates_chart(figure: &Figure) -> String {
    let last = figure.samples.last().expect("a figure has points");
    let rate = |k: usize| -> Vec<(f64, f64)> {
        figure
            .samples
            .iter()
            .filter_map(|s| s.euler_rates.map(|r| (s.t, r[k])))
            .collect()
    };
    chart(
        "precession rate phi_dot(t) and proper rotation rate psi_dot(t), 1/tau",
        &[
            Series::line("phi_dot", rate(0)),
            Series::line("psi_dot", rate(2)),
            Series::line("0", vec![(0.0, 0.0), (last.t, 0.0)]),
        ],
        (0.0, last.t),
        120,
        32,
    )
}

/// The figure as an SVG document, `SVG_SIZE` pixels.
pub fn svg(figure: &Figure) -> String {
    let mut buffer = String::new();
    {
        let root = SVGBackend::with_string(&mut buffer, SVG_SIZE).into_drawing_area();
        // NOTE: drawing into a String cannot fail for I/O reasons; an error here
        // would be a plotting bug (a range that plotters refuses), so it panics.
        draw(figure, &root).expect("plotters draws into a string");
        root.present().expect("plotters draws into a string");
    }
    buffer
}

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
type DrawResult = Result<(), Box<dyn std::error::Error>>;
type Chart3d<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian3d<RangedCoordf64, RangedCoordf64, RangedCoordf64>>;

/// A lab (or body) vector in plotters' 3D coordinates.
///
/// plotters' (X, Y, Z) is right-handed with Y up the page, X to the front
/// right and Z to the front left in the panels' view; the cyclic map
/// (x, y, z) ↦ (y, z, x) is a rotation, so the lab frame stays right-handed
/// on the page: z up, x to the front left, y to the front right, and a turn
/// about z in the positive sense runs counterclockwise seen from above.
fn lab_to_plot(v: Vec3) -> (Real, Real, Real) {
    (v.y, v.z, v.x)
}

/// A 3D panel in the figures' view: `lab` gives the ranges of lab x, y, z.
fn panel_3d<'a, 'b>(
    area: &'a Area<'b>,
    caption: &str,
    lab: [std::ops::Range<Real>; 3],
) -> Result<Chart3d<'a, 'b>, Box<dyn std::error::Error>> {
    let [x, y, z] = lab;
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(10)
        // plotters' (X, Y, Z) = lab (y, z, x), see [`lab_to_plot`].
        .build_cartesian_3d(y, z, x)?;
    chart.with_projection(|mut pb| {
        pb.yaw = 0.6;
        pb.pitch = 0.35;
        pb.scale = 0.85;
        pb.into_matrix()
    });
    Ok(chart)
}

fn draw(figure: &Figure, root: &Area) -> DrawResult {
    root.fill(&WHITE)?;
    let n = figure.number.number();
    let title = format!(
        "Figure {n}: {}. I\u{2083}/I\u{2081} = 2/5, \u{3a9}\u{2080} = (0, 0.1, 0.2)/\u{3c4}",
        model_label(figure)
    );
    let (head, body) = root.split_vertically(40);
    head.draw(&Text::new(
        title,
        (20, 12),
        ("sans-serif", 20).into_font().color(&BLACK),
    ))?;
    let (top, bottom) = body.split_vertically(500);
    let (a, b) = top.split_horizontally(500);
    let (c, d) = bottom.split_horizontally(500);
    hodograph_panel(figure, &a)?;
    space_panel(figure, &b)?;
    theta_panel(figure, &c)?;
    rates_panel(figure, &d)?;
    Ok(())
}

/// Panel (a): Ω(t) in the body frame, Ω₃ up, and its three projections.
fn hodograph_panel(figure: &Figure, area: &Area) -> DrawResult {
    let p = OMEGA_PERP_AXIS;
    let mut chart = panel_3d(
        area,
        "(a) \u{3a9}(t) in the body frame and its projections",
        [-p..p, -p..p, 0.0..OMEGA3_AXIS],
    )?;
    chart
        .configure_axes()
        .light_grid_style(BLACK.mix(0.06))
        .max_light_lines(1)
        .x_labels(3)
        .y_labels(3)
        .z_labels(3)
        .label_style(("sans-serif", 11))
        .draw()?;
    let omega: Vec<(Real, Real, Real)> = figure
        .samples
        .iter()
        .map(|s| lab_to_plot(Vec3::from(s.omega)))
        .collect();
    // The projections lie on the floor Ω₃ = 0 and the two back walls,
    // Ω₂ = −p (left) and Ω₁ = −p (right).
    for project in [
        |(x, _, z): (Real, Real, Real)| (x, 0.0, z),
        |(_, y, z): (Real, Real, Real)| (-OMEGA_PERP_AXIS, y, z),
        |(x, y, _): (Real, Real, Real)| (x, y, -OMEGA_PERP_AXIS),
    ] {
        chart.draw_series(LineSeries::new(
            omega.iter().map(|&q| project(q)),
            PROJECTION_COLOR.stroke_width(1),
        ))?;
    }
    chart.draw_series(LineSeries::new(
        omega.iter().copied(),
        CURVE_COLOR.stroke_width(2),
    ))?;
    let start = omega[0];
    chart.draw_series(std::iter::once(Circle::new(start, 4, CURVE_COLOR.filled())))?;
    let label = ("sans-serif", 15).into_font().color(&BLACK);
    // The axis names sit beyond the tick labels of the two front edges: Ω₂'s
    // ticks are on the front-left edge, Ω₁'s on the front-right one.
    for (text, at) in [
        ("\u{3a9}\u{2081}", lab_to_plot(Vec3::new(0.0, p * 1.5, 0.0))),
        (
            "\u{3a9}\u{2082}",
            lab_to_plot(Vec3::new(p * 1.55, 0.0, 0.0)),
        ),
        (
            "\u{3a9}\u{2083}",
            lab_to_plot(Vec3::new(-p, -p * 0.9, OMEGA3_AXIS * 0.97)),
        ),
        (
            "\u{3a9}\u{2080}",
            (start.0 + 0.012, start.1 + 0.01, start.2),
        ),
    ] {
        chart.draw_series(std::iter::once(Text::new(text, at, label.clone())))?;
    }
    Ok(())
}

/// Panel (b): the top in space, lab z (L∞) up.
fn space_panel(figure: &Figure, area: &Area) -> DrawResult {
    let mut chart = panel_3d(
        area,
        "(b) the top in space: axis tip path, L(t) and L\u{221e}",
        [-1.0..1.0, -1.0..1.0, 0.0..1.2],
    )?;
    chart
        .configure_axes()
        .light_grid_style(BLACK.mix(0.06))
        .max_light_lines(1)
        .x_labels(3)
        .y_labels(3)
        .z_labels(3)
        .label_style(("sans-serif", 11))
        .draw()?;
    let up = lab_to_plot;
    let tip: Vec<(Real, Real, Real)> = figure.samples.iter().map(|s| up(Figure::axis(s))).collect();
    let l_dir: Vec<(Real, Real, Real)> = figure
        .samples
        .iter()
        .map(|s| up(Vec3::from(s.l_lab).normalize()))
        .collect();
    // The axis tip's shadow on the floor shows the circle or the spiral plainly.
    chart.draw_series(LineSeries::new(
        tip.iter().map(|&(x, _, z)| (x, 0.0, z)),
        PROJECTION_COLOR.stroke_width(1),
    ))?;
    chart.draw_series(LineSeries::new(
        tip.iter().copied(),
        CURVE_COLOR.stroke_width(2),
    ))?;
    chart.draw_series(LineSeries::new(
        l_dir.iter().copied(),
        L_COLOR.stroke_width(2),
    ))?;
    let origin = (0.0, 0.0, 0.0);
    let l_inf = up(figure.l_limit);
    chart.draw_series(LineSeries::new([origin, l_inf], L_COLOR.stroke_width(3)))?;
    for (end, width) in [(tip[0], 1), (*tip.last().expect("points"), 3)] {
        chart.draw_series(LineSeries::new(
            [origin, end],
            AXIS_COLOR.stroke_width(width),
        ))?;
    }
    let label = ("sans-serif", 14).into_font().color(&BLACK);
    let red = ("sans-serif", 14).into_font().color(&L_COLOR);
    let t_end = figure.samples.last().expect("points").t;
    chart.draw_series([
        Text::new(
            "L\u{221e}".to_string(),
            (l_inf.0 - 0.2, l_inf.1 + 0.06, l_inf.2),
            red.clone(),
        ),
        Text::new(
            "axis, t = 0".to_string(),
            (tip[0].0 + 0.04, tip[0].1, tip[0].2),
            label.clone(),
        ),
        Text::new(
            format!("axis, t = {t_end}"),
            {
                // Halfway up the final axis, beside it.
                let end = tip.last().expect("points");
                (0.5 * end.0 + 0.06, 0.5 * end.1, 0.5 * end.2)
            },
            label.clone(),
        ),
        // Beside the tick labels of their edges: y front left, x front right.
        Text::new("x".to_string(), up(Vec3::new(0.0, 1.5, 0.0)), label.clone()),
        Text::new(
            "y".to_string(),
            up(Vec3::new(1.55, 0.0, 0.0)),
            label.clone(),
        ),
        Text::new("z".to_string(), up(Vec3::new(-1.0, -0.9, 1.16)), label),
    ])?;
    Ok(())
}

/// Panel (c): θ(t).
fn theta_panel(figure: &Figure, area: &Area) -> DrawResult {
    let t_end = figure.samples.last().expect("points").t;
    let theta_max = figure
        .samples
        .iter()
        .map(|s| s.euler[1])
        .fold(0.0, Real::max);
    let mut chart = ChartBuilder::on(area)
        .caption(
            "(c) tilt \u{3b8}(t) of the axis from L\u{221e}, rad",
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(48)
        .build_cartesian_2d(0.0..t_end, 0.0..(1.15 * theta_max))?;
    chart
        .configure_mesh()
        .light_line_style(BLACK.mix(0.05))
        .x_desc("t / \u{3c4}")
        .label_style(("sans-serif", 12))
        .draw()?;
    chart.draw_series(LineSeries::new(
        figure.samples.iter().map(|s| (s.t, s.euler[1])),
        CURVE_COLOR.stroke_width(2),
    ))?;
    let note = match figure.number {
        FigureNumber::One => format!(
            "\u{3b8} = {:.4} rad for ever: arctan(I\u{2081}\u{3a9}\u{22a5}\u{2080}/(I\u{2083}\u{3a9}\u{2083}\u{2080})), (4.11) corrected",
            figure.samples[0].euler[1]
        ),
        FigureNumber::Two => format!(
            "\u{3b8} \u{2192} 0 like e^(\u{2212}t/\u{3c3}), \u{3c3} = I\u{2081}\u{b2}/(I\u{2083}\u{b2}\u{3a9}\u{2083}\u{b2}\u{3c4}) = {:.2} \u{3c4}, (4.18)",
            reduced_decay_time(&figure.top(), figure.omega0.z)
        ),
    };
    chart.draw_series(std::iter::once(Text::new(
        note,
        (0.3 * t_end, 0.75 * theta_max),
        ("sans-serif", 13).into_font().color(&BLACK),
    )))?;
    Ok(())
}

/// Panel (d): φ̇(t) and ψ̇(t).
fn rates_panel(figure: &Figure, area: &Area) -> DrawResult {
    let t_end = figure.samples.last().expect("points").t;
    let rates: Vec<(Real, [Real; 3])> = figure
        .samples
        .iter()
        .filter_map(|s| s.euler_rates.map(|r| (s.t, r)))
        .collect();
    let top = rates
        .iter()
        .flat_map(|(_, r)| [r[0], r[2]])
        .fold(0.0, Real::max);
    let mut chart = ChartBuilder::on(area)
        .caption(
            "(d) precession \u{3c6}\u{307} and proper rotation \u{3c8}\u{307}, 1/\u{3c4}",
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(48)
        .build_cartesian_2d(0.0..t_end, 0.0..(1.15 * top))?;
    chart
        .configure_mesh()
        .light_line_style(BLACK.mix(0.05))
        .x_desc("t / \u{3c4}")
        .label_style(("sans-serif", 12))
        .draw()?;
    for (k, color, name) in [
        (0, PHI_DOT_COLOR, "\u{3c6}\u{307}"),
        (2, PSI_DOT_COLOR, "\u{3c8}\u{307}"),
    ] {
        chart.draw_series(LineSeries::new(
            rates.iter().map(|(t, r)| (*t, r[k])),
            color.stroke_width(2),
        ))?;
        // Name each curve halfway along instead of in a legend box: the
        // upper curve above itself, the lower one below.
        let (t, r) = rates[rates.len() / 2];
        let other = if k == 0 { r[2] } else { r[0] };
        let dy = if r[k] >= other { 0.1 } else { -0.03 };
        chart.draw_series(std::iter::once(Text::new(
            name,
            (t, r[k] + dy * top),
            ("sans-serif", 16).into_font().color(&color),
        )))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Mat3;

    /// The panels' lab frame is right-handed on the page: rebuilt from the
    /// page coordinates plotters gives the lab axes and their depth (away
    /// from the viewer), x̂, ŷ, ẑ have a positive determinant; z goes up the
    /// page and leans toward the viewer (seen from above); and x̂ to ŷ turns
    /// counterclockwise on the page.
    #[test]
    fn the_figures_3d_panels_draw_the_lab_frame_right_handed() {
        let mut buffer = String::new();
        let root = SVGBackend::with_string(&mut buffer, (500, 500)).into_drawing_area();
        let chart = panel_3d(&root, "", [-1.0..1.0, -1.0..1.0, -1.0..1.0]).unwrap();
        let spec = chart.as_coord_spec();
        let page = |v: Vec3| {
            let (x, y, z) = lab_to_plot(v);
            let (px, py) = spec.translate(&(x, y, z));
            // Page right, page up, toward the viewer.
            Vec3::new(
                px as Real,
                -(py as Real),
                -(spec.projected_depth(&x, &y, &z) as Real),
            )
        };
        let o = page(Vec3::zeros());
        let [ex, ey, ez] = [Vec3::x(), Vec3::y(), Vec3::z()].map(|v| (page(v) - o).normalize());
        assert!(ex.cross(&ey).dot(&ez) > 0.95, "left-handed on the page");
        assert!(
            ez.y > 0.9 && ez.z > 0.0,
            "z is not up, or the view is from below"
        );
        assert!(ex.x * ey.y - ex.y * ey.x > 0.0, "x to y turns clockwise");
        // And the map itself is a rotation.
        let m = Mat3::from_columns(&[Vec3::x(), Vec3::y(), Vec3::z()].map(|v| {
            let (a, b, c) = lab_to_plot(v);
            Vec3::new(a, b, c)
        }));
        assert!((m.determinant() - 1.0).abs() < 1e-15);
    }
}
