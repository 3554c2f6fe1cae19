//! The panels of one column: the Ω(t) chart, the hodograph, the top in space
//! and the live numbers. Each is built from the state and only reads it.
//!
//! The two 3-D panels use a fixed oblique camera: a vector p is drawn at
//! (r·p, u·p), with r and u the camera's right and up directions. This is
//! drawing, not physics: the vectors themselves (Ω, O·e₃, L) come from the
//! [`spintop::sim::Sample`]s.

use super::columns::{Column, Point, WINDOW};
use super::stepper::TICK;
use crate::term::theme;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line as CanvasLine, Points};
use ratatui::widgets::{Axis, Block, Borders, Chart, Dataset, GraphType, Paragraph};
use spintop::math::Real;
pub use spintop::numbers::{fmt_axis, fmt_num, fmt_short, nice_ceiling};

/// The four curves of one Ω(t) chart and their axes.
#[derive(Clone, Debug, PartialEq)]
pub struct OmegaSeries {
    /// Ω₁, Ω₂, Ω₃, Ω⊥ against t (or log₁₀ t).
    pub curves: [Vec<(f64, f64)>; 4],
    /// The x range.
    pub x_bounds: [f64; 2],
    /// The y range, symmetric about zero.
    pub y_bounds: [f64; 2],
    /// The x axis is log₁₀ t.
    pub log_time: bool,
    /// The unit of time (τ, or u for a general top in κ = 1 units).
    pub unit: &'static str,
}

impl OmegaSeries {
    /// The curves of `column`: the last [`WINDOW`] (scrolling) or the whole run
    /// on a log₁₀ t axis.
    pub fn new(column: &Column, log_time: bool) -> Self {
        let now = Point::from(column.current());
        let (points, x_bounds): (Vec<Point>, [f64; 2]) = if log_time {
            let lo = TICK.log10();
            let hi = now.t.max(TICK).log10().max(lo + 2.0);
            let mut points: Vec<Point> = column.log_points().to_vec();
            if now.t > 0.0 && points.last().is_none_or(|p| p.t < now.t) {
                points.push(now);
            }
            (points, [lo, hi])
        } else {
            let hi = now.t.max(WINDOW);
            let lo = hi - WINDOW;
            let mut points: Vec<Point> = column
                .recent()
                .iter()
                .filter(|p| p.t >= lo)
                .copied()
                .collect();
            if points.last().is_none_or(|p| p.t < now.t) {
                points.push(now);
            }
            (points, [lo, hi])
        };
        let x = |p: &Point| if log_time { p.t.log10() } else { p.t };
        let curve = |f: &dyn Fn(&Point) -> f64| points.iter().map(|p| (x(p), f(p))).collect();
        // NOTE: the axis follows the curves shown, with 5% of room above
        // their largest value (a truncated top at Ω ≈ 0.02 is not drawn flat
        // on a ±0.2 axis); it is never larger than the column's scale, a
        // bound on every component at all times, so it only ever narrows as
        // the top slows down.
        let biggest = points
            .iter()
            .flat_map(|p| p.omega.iter().chain([&p.omega_perp]))
            .fold(0.0, |m: Real, w| m.max(w.abs()));
        let y = nice_ceiling(biggest.min(column.scale()) * 1.05);
        Self {
            curves: [
                curve(&|p| p.omega[0]),
                curve(&|p| p.omega[1]),
                curve(&|p| p.omega[2]),
                curve(&|p| p.omega_perp),
            ],
            x_bounds,
            y_bounds: [-y, y],
            log_time,
            unit: column.time_unit(),
        }
    }

    /// The chart, for an area `rows` high: Braille lines, labelled axes, the
    /// curve names in the title. A short chart labels only the ends of its y
    /// axis (three labels on two rows would print over each other). Without
    /// colours (`monochrome`) each curve has a mark of its own, shown beside
    /// its name in the title.
    pub fn chart(&self, rows: u16, monochrome: bool) -> Chart<'_> {
        let names = ["Ω₁", "Ω₂", "Ω₃", "Ω⊥"];
        let marks = if monochrome {
            MONOCHROME_MARKS
        } else {
            [(Marker::Braille, "━"); 4]
        };
        // Drawn widest mark first, so that the thin ones stay visible on it.
        let order: [usize; 4] = if monochrome {
            [3, 2, 1, 0]
        } else {
            [0, 1, 2, 3]
        };
        let datasets = order
            .iter()
            .map(|&i| {
                Dataset::default()
                    .name(names[i])
                    .marker(marks[i].0)
                    .graph_type(GraphType::Line)
                    .style(Style::new().fg(theme::OMEGA[i]))
                    .data(&self.curves[i])
            })
            .collect();
        let u = self.unit;
        let mut title = vec![Span::styled(format!("Ω(t) [1/{u}]: "), theme::title())];
        for ((name, color), (_, glyph)) in names.iter().zip(theme::OMEGA).zip(marks) {
            title.push(Span::styled(
                format!("{glyph}{name} "),
                Style::new().fg(color),
            ));
        }
        let [lo, hi] = self.x_bounds;
        let (x_title, x_labels) = if self.log_time {
            let mid = 0.5 * (lo + hi);
            (
                "log t",
                vec![
                    fmt_axis((10.0 as Real).powf(lo)),
                    fmt_axis((10.0 as Real).powf(mid)),
                    fmt_axis((10.0 as Real).powf(hi)),
                ],
            )
        } else {
            (
                if u == "τ" { "t/τ" } else { "t/u" },
                vec![
                    format!("{lo:.0}"),
                    format!("{:.0}", 0.5 * (lo + hi)),
                    format!("{hi:.0}"),
                ],
            )
        };
        let [ylo, yhi] = self.y_bounds;
        Chart::new(datasets)
            .block(Block::new().title(Line::from(title)))
            .legend_position(None)
            .x_axis(
                Axis::default()
                    .title(Span::styled(x_title, theme::label()))
                    .style(theme::frame())
                    .bounds(self.x_bounds)
                    .labels(
                        x_labels
                            .into_iter()
                            .map(|l| Span::styled(l, theme::label())),
                    ),
            )
            .y_axis(
                Axis::default()
                    .style(theme::frame())
                    .bounds(self.y_bounds)
                    .labels(
                        if rows >= 7 {
                            vec![fmt_axis(ylo), "0".into(), fmt_axis(yhi)]
                        } else {
                            vec![fmt_axis(ylo), fmt_axis(yhi)]
                        }
                        .into_iter()
                        .map(|l| Span::styled(l, theme::label())),
                    ),
            )
    }
}

/// The marks of Ω₁, Ω₂, Ω₃ and Ω⊥ without colours, and the glyph that
/// stands for each in the chart's title: four curves told apart by shape.
pub const MONOCHROME_MARKS: [(Marker, &str); 4] = [
    (Marker::Braille, "⠒"),
    (Marker::Dot, "•"),
    (Marker::Bar, "▄"),
    (Marker::Block, "█"),
];

/// Labels of a canvas placed where they do not overlap: each at its point
/// if its cells are free, else one row above or below, else one label's
/// width to the side, else left out (never printed over another).
pub struct Labels {
    x: [f64; 2],
    y: [f64; 2],
    size: (u16, u16),
    taken: Vec<(i32, i32, i32)>,
    placed: Vec<(f64, f64, Span<'static>)>,
}

impl Labels {
    /// Labels for a canvas of `size` cells over the bounds `x` and `y`.
    pub fn new(x: [f64; 2], y: [f64; 2], size: (u16, u16)) -> Self {
        Self {
            x,
            y,
            size,
            taken: Vec::new(),
            placed: Vec::new(),
        }
    }

    /// The cell a canvas puts a label at (x, y), as ratatui's canvas does:
    /// the fraction of the bounds times (cells − 1), truncated.
    fn cell(&self, x: f64, y: f64) -> Option<(i32, i32)> {
        let inside = (self.x[0]..=self.x[1]).contains(&x) && (self.y[0]..=self.y[1]).contains(&y);
        let w = f64::from(self.size.0.max(1) - 1);
        let h = f64::from(self.size.1.max(1) - 1);
        let col = (x - self.x[0]) * w / (self.x[1] - self.x[0]);
        let row = (self.y[1] - y) * h / (self.y[1] - self.y[0]);
        inside.then_some((col as i32, row as i32))
    }

    /// A point of the canvas that falls in cell (col, row), a quarter of a
    /// cell in from its corner (so that rounding cannot move it out).
    fn point(&self, col: i32, row: i32) -> (f64, f64) {
        let w = f64::from(self.size.0.max(1) - 1).max(1.0);
        let h = f64::from(self.size.1.max(1) - 1).max(1.0);
        let x = self.x[0] + (f64::from(col) + 0.25) / w * (self.x[1] - self.x[0]);
        let y = self.y[1] - (f64::from(row) + 0.25) / h * (self.y[1] - self.y[0]);
        (x.min(self.x[1]), y.max(self.y[0]))
    }

    /// Adds `text` at (`x`, `y`), or as near as it fits without overlap.
    pub fn add(&mut self, x: f64, y: f64, text: Span<'static>) {
        let width = i32::try_from(text.width()).unwrap_or(1).max(1);
        let Some((col, row)) = self.cell(x, y) else {
            return;
        };
        let free = |c: i32, r: i32, taken: &[(i32, i32, i32)]| {
            c >= 0
                && r >= 0
                && c + width <= i32::from(self.size.0)
                && r < i32::from(self.size.1)
                && taken
                    .iter()
                    // A column of space between two labels.
                    .all(|&(tc, tr, tw)| tr != r || c + width < tc || tc + tw < c)
        };
        let tries = [
            (col, row),
            (col, row - 1),
            (col, row + 1),
            (col + width + 1, row),
            (col - width - 1, row),
        ];
        if let Some(&(c, r)) = tries.iter().find(|(c, r)| free(*c, *r, &self.taken)) {
            self.taken.push((c, r, width));
            let (px, py) = self.point(c, r);
            self.placed.push((px, py, text));
        }
    }

    /// Prints the labels placed.
    pub fn print(&self, ctx: &mut Context) {
        for (x, y, text) in &self.placed {
            ctx.print(*x, *y, text.clone());
        }
    }
}

/// A fixed oblique camera: azimuth and elevation of the viewer, in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    right: [f64; 3],
    up: [f64; 3],
}

impl Camera {
    /// Look at the origin from azimuth `az` (from +x toward +y) and elevation
    /// `el` above the xy plane; z points up on the screen.
    pub fn new(az: f64, el: f64) -> Self {
        let (sa, ca) = az.sin_cos();
        let (se, ce) = el.sin_cos();
        Self {
            right: [-sa, ca, 0.0],
            up: [-se * ca, -se * sa, ce],
        }
    }

    /// The screen position of `p`.
    pub fn project(&self, p: [f64; 3]) -> (f64, f64) {
        let dot = |a: [f64; 3]| a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
        (dot(self.right), dot(self.up))
    }
}

/// The camera of the hodograph (body frame: Ω₃ up).
pub fn body_camera() -> Camera {
    Camera::new(35f64.to_radians(), 30f64.to_radians())
}

/// The camera of the top in space (lab frame: z, the direction of L₀, up).
pub fn lab_camera() -> Camera {
    Camera::new(-60f64.to_radians(), 15f64.to_radians())
}

/// x bounds for a y range, so that the picture keeps its proportions in a
/// canvas of `area` (a Braille dot is about as wide as it is tall; a cell is
/// 2 dots wide and 4 tall, and about twice as tall as wide).
fn x_bounds_for(area: Rect, y: [f64; 2]) -> [f64; 2] {
    let cells_w = f64::from(area.width.max(1));
    let cells_h = f64::from(area.height.max(1));
    let half = 0.5 * (y[1] - y[0]) * cells_w / (2.0 * cells_h);
    [-half, half]
}

/// The long title when it fits in `area`'s width, else the short one.
fn fitting<'a>(area: Rect, long: &'a str, short: &'a str) -> &'a str {
    if usize::from(area.width) >= Span::raw(long).width() {
        long
    } else {
        short
    }
}

fn panel<'a>(title: impl Into<std::borrow::Cow<'a, str>>) -> Block<'a> {
    Block::new()
        .borders(Borders::TOP)
        .border_style(theme::frame())
        .title(Span::styled(title, theme::title()))
}

fn segment(ctx: &mut Context, cam: &Camera, a: [f64; 3], b: [f64; 3], color: Color) {
    let (x1, y1) = cam.project(a);
    let (x2, y2) = cam.project(b);
    ctx.draw(&CanvasLine::new(x1, y1, x2, y2, color));
}

/// The hodograph of Ω in the body frame (a projection of the left panels of
/// the paper's Figures 1 and 2), with its shadow on the Ω₁Ω₂ plane. Ω is
/// drawn in units of |Ω₀|.
pub fn hodograph(column: &Column, area: Rect) -> Canvas<'static, impl Fn(&mut Context<'_>)> {
    let cam = body_camera();
    let scale = column.scale();
    let down = column.initial().omega.z < 0.0;
    let y = if down { [-1.25, 0.6] } else { [-0.6, 1.25] };
    let scaled = |p: &[f64; 3]| [p[0] / scale, p[1] / scale, p[2] / scale];
    let trail: Vec<(f64, f64)> = column
        .omega_trail()
        .iter()
        .map(|p| cam.project(scaled(p)))
        .collect();
    let shadow: Vec<(f64, f64)> = column
        .omega_trail()
        .iter()
        .map(|p| cam.project([p[0] / scale, p[1] / scale, 0.0]))
        .collect();
    let now = scaled(&column.current().omega);
    let inner = panel("").inner(area);
    let z = if down { -1.0 } else { 1.0 };
    let title = fitting(area, "hodograph of Ω (body frame)", "hodograph of Ω");
    let x = x_bounds_for(inner, y);
    let axes = [
        ([1.0, 0.0, 0.0], "Ω₁"),
        ([0.0, 1.0, 0.0], "Ω₂"),
        ([0.0, 0.0, z], "Ω₃"),
    ];
    let mut labels = Labels::new(x, y, (inner.width, inner.height));
    for (axis, name) in axes {
        let (px, py) = cam.project([axis[0] * 1.1, axis[1] * 1.1, axis[2] * 1.1]);
        labels.add(px, py, Span::styled(name, theme::label()));
    }
    Canvas::default()
        .block(panel(title))
        .marker(Marker::Braille)
        .x_bounds(x)
        .y_bounds(y)
        .paint(move |ctx| {
            let o = [0.0; 3];
            for (axis, _) in axes {
                segment(ctx, &cam, o, axis, theme::GUIDE);
            }
            labels.print(ctx);
            ctx.draw(&Points::new(&shadow, theme::GUIDE));
            ctx.draw(&Points::new(&trail, theme::TRAIL));
            segment(ctx, &cam, o, now, Color::White);
        })
}

/// The top in space (the right panels of the paper's figures): the symmetry
/// axis O·e₃, the direction of L, and the trail of the axis tip, which traces
/// the precession cone. The lab z axis is the direction of L₀ in the
/// paper's frame (`paper_frame`); a scene with Euler angles of its own
/// starts in its lab frame, and the title gives e₃∠z, the angle of the axis
/// from lab z (not the tilt of the numbers, the angle from L).
pub fn top_in_space(
    column: &Column,
    area: Rect,
    paper_frame: bool,
) -> Canvas<'static, impl Fn(&mut Context<'_>)> {
    let cam = lab_camera();
    let y = [-1.15, 1.35];
    let s = column.current();
    let r = &s.rotation;
    let axis = [r[0][2], r[1][2], r[2][2]];
    let l = s.l_lab;
    let l_norm = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let l_dir = (l_norm > 0.0).then(|| [l[0] / l_norm, l[1] / l_norm, l[2] / l_norm]);
    let trail: Vec<(f64, f64)> = column
        .axis_trail()
        .iter()
        .map(|p| cam.project(*p))
        .collect();
    let disc: Vec<(f64, f64)> = disc_around(axis, 0.7, 0.3)
        .into_iter()
        .map(|p| cam.project(p))
        .collect();
    let inner = panel("").inner(area);
    let (long, short) = if paper_frame {
        (
            "the top in space (lab z ∥ L₀)".to_string(),
            "top in space".to_string(),
        )
    } else {
        let theta = fmt_num(axis[2].clamp(-1.0, 1.0).acos());
        (
            format!("the top in space (e₃∠z = {theta})"),
            format!("e₃∠z {theta}"),
        )
    };
    let title = fitting(area, &long, &short).to_string();
    let x = x_bounds_for(inner, y);
    // The labels of what moves first (e₃, then L), then the fixed z: one that
    // would print over another moves aside or is left out.
    let mut labels = Labels::new(x, y, (inner.width, inner.height));
    let (ex, ey) = cam.project(axis);
    labels.add(ex, ey, Span::styled("e₃", Style::new().fg(theme::AXIS)));
    if let Some(d) = l_dir {
        let (lx, ly) = cam.project([1.3 * d[0], 1.3 * d[1], 1.3 * d[2]]);
        labels.add(lx, ly, Span::styled("L", Style::new().fg(theme::MOMENTUM)));
    }
    // Left of the z axis, so L drawn along it stays visible.
    let (zx, zy) = cam.project([0.0, 0.0, 1.25]);
    labels.add(zx - 0.2, zy, Span::styled("z", theme::label()));
    Canvas::default()
        .block(panel(title))
        .marker(Marker::Braille)
        .x_bounds(x)
        .y_bounds(y)
        .paint(move |ctx| {
            let o = [0.0; 3];
            segment(ctx, &cam, [0.0, 0.0, -0.3], [0.0, 0.0, 1.25], theme::GUIDE);
            segment(ctx, &cam, [-0.4, 0.0, 0.0], [0.4, 0.0, 0.0], theme::GUIDE);
            segment(ctx, &cam, [0.0, -0.4, 0.0], [0.0, 0.4, 0.0], theme::GUIDE);
            ctx.draw(&Points::new(&trail, theme::TRAIL));
            if let Some(d) = l_dir {
                let tip = [1.2 * d[0], 1.2 * d[1], 1.2 * d[2]];
                segment(ctx, &cam, o, tip, theme::MOMENTUM);
            }
            segment(ctx, &cam, o, axis, theme::AXIS);
            ctx.draw(&Points::new(&disc, theme::AXIS));
            labels.print(ctx);
        })
}

/// Points on the circle of radius `radius` about the unit vector `axis`, at
/// `along` on it: the body of the top, seen as a disc perpendicular to its axis.
fn disc_around(axis: [f64; 3], along: f64, radius: f64) -> Vec<[f64; 3]> {
    let [a0, a1, a2] = axis;
    // Any vector not parallel to the axis gives a basis (u, v) of the disc.
    let h = if a2.abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let u = cross(axis, h);
    let n = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let u = [u[0] / n, u[1] / n, u[2] / n];
    let v = cross(axis, u);
    (0..64)
        .map(|i| {
            let (s, c) = (f64::from(i) * std::f64::consts::TAU / 64.0).sin_cos();
            [
                along * a0 + radius * (c * u[0] + s * v[0]),
                along * a1 + radius * (c * u[1] + s * v[1]),
                along * a2 + radius * (c * u[2] + s * v[2]),
            ]
        })
        .collect()
}

/// `label` padded with spaces to `width` terminal columns (φ̇ and ψ̇ carry a
/// combining dot that takes no column of its own).
fn padded(label: &str, width: usize) -> String {
    let used = Span::raw(label).width();
    format!("{label}{}", " ".repeat(width.saturating_sub(used)))
}

/// A block of numbers and the width it needs: the layout drops a whole
/// block before it cuts a number in one.
pub struct NumberBlock {
    /// The lines.
    pub paragraph: Paragraph<'static>,
    /// The widest line, in columns.
    pub width: u16,
}

impl NumberBlock {
    fn new(lines: Vec<Line<'static>>) -> Self {
        let width = lines.iter().map(Line::width).max().unwrap_or(0);
        Self {
            paragraph: Paragraph::new(lines),
            width: u16::try_from(width).unwrap_or(u16::MAX),
        }
    }
}

/// The time t as a column shows it: two decimals, fewer (`compact`) once
/// they would push the numbers beside it out of the column.
fn fmt_time(t: Real, compact: bool) -> String {
    if !compact || t < 1e4 {
        format!("{t:.2}")
    } else if t < 1e7 {
        format!("{t:.0}")
    } else {
        format!("{t:.2e}")
    }
}

/// The live numbers of a column, as two side-by-side blocks of five lines and
/// a last full-width line (Ω now, or why the model stopped). `wide` selects
/// the long labels; `compact` shortens every number to three significant
/// digits (for a column where the full ones would not fit side by side).
pub fn numbers(
    column: &Column,
    wide: bool,
    compact: bool,
) -> (NumberBlock, NumberBlock, Vec<Line<'static>>) {
    let s = column.current();
    let u = column.time_unit();
    let num = |x: Real| if compact { fmt_short(x) } else { fmt_num(x) };
    let (left_width, width) = if wide { (6, 8) } else { (5, 7) };
    let pair_in = |label: &str, value: String, width: usize| {
        Line::from(vec![
            Span::styled(padded(label, width), theme::label()),
            Span::styled(value, theme::value()),
        ])
    };
    let pair = |label: &str, value: String| pair_in(label, value, width);
    let left_pair = |label: &str, value: String| pair_in(label, value, left_width);
    let l = s.l_lab;
    let l_abs = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let (phi_dot, psi_dot) = match s.euler_rates {
        Some([phi_dot, _, psi_dot]) => (
            format!("{}/{u}", num(phi_dot)),
            format!("{}/{u}", num(psi_dot)),
        ),
        // (4.8) divides by sin θ: on the pole only φ̇ + ψ̇ is defined.
        None => ("— (pole)".into(), "— (pole)".into()),
    };
    let tilt = if wide && !compact {
        format!("{} rad ({:.2}°)", num(s.tilt), s.tilt.to_degrees())
    } else {
        format!("{} rad", num(s.tilt))
    };
    let left = vec![
        left_pair("t", format!("{} {u}", fmt_time(s.t, compact))),
        left_pair("E", num(s.energy)),
        left_pair("|L|", num(l_abs)),
        left_pair("tilt", tilt),
        left_pair("φ̇", phi_dot),
    ];
    let step = column.last_step();
    let stopped = column.failure().is_some();
    // NOTE: |Ω − Ω_closed form| at the same t, from the core's (4.7) and
    // (4.15)–(4.16); zero by construction when Ω is the closed form.
    // The general top (3.3) has nothing to compare with: "—". A stopped
    // model's last state is where it failed, not a solution: no error.
    let error = match column.closed_form_error() {
        _ if stopped => "— (stopped)".to_string(),
        None => if wide && !compact {
            "— (no closed form)"
        } else {
            "— (none)"
        }
        .to_string(),
        Some(_)
            if matches!(
                column.method(),
                spintop::sim::Method::ClosedForm | spintop::sim::Method::ClosedFormDop853
            ) =>
        {
            if compact {
                "0 (exact)"
            } else {
                "0 (closed form)"
            }
            .to_string()
        }
        Some(e) if wide && !compact => format!("|ΔΩ| = {}/{u}", num(e)),
        Some(e) => format!("{}/{u}", num(e)),
    };
    let step = match (step > 0.0, stopped) {
        (true, false) => format!("{} {u}", num(step)),
        (true, true) => format!("{} {u} (last)", num(step)),
        (false, true) => "none accepted".into(),
        (false, false) => "none".into(),
    };
    let evals = column.stats().rhs_evals;
    let right = vec![
        pair("ψ̇", psi_dot),
        pair("method", column.method_name().to_string()),
        pair("step", step),
        pair(
            "evals",
            if compact && evals >= 100_000 {
                fmt_short(evals as Real)
            } else {
                evals.to_string()
            },
        ),
        pair("error", error),
    ];
    let last = last_lines(column, left_width, compact);
    (NumberBlock::new(left), NumberBlock::new(right), last)
}

/// The last line of a column's numbers: why it stopped, or Ω and Ω⊥ in
/// forms from the widest to the shortest (the caller takes the first that
/// fits; a number is never cut at the edge).
fn last_lines(column: &Column, left_width: usize, compact: bool) -> Vec<Line<'static>> {
    let s = column.current();
    let u = column.time_unit();
    let num = |x: Real| if compact { fmt_short(x) } else { fmt_num(x) };
    match column.failure() {
        Some(why) if column.is_forward() => {
            vec![Line::from(Span::styled(why.to_string(), theme::error()))]
        }
        Some(why) => vec![Line::from(Span::styled(
            format!("stopped: {why}"),
            theme::error(),
        ))],
        None => {
            // The widest form first, then shorter ones: a number is never
            // cut at the edge (the caller takes the first that fits).
            let [o1, o2, o3] = s.omega;
            let line = |f: &dyn Fn(Real) -> String, gap: &str| {
                Line::from(vec![
                    Span::styled(padded("Ω", left_width), theme::label()),
                    Span::styled(
                        format!(
                            "({}, {}, {})/{u}{gap}Ω⊥ {}/{u}",
                            f(o1),
                            f(o2),
                            f(o3),
                            f(s.omega_perp)
                        ),
                        theme::value(),
                    ),
                ])
            };
            vec![
                line(&|x| num(x), "   "),
                line(&fmt_short, "  "),
                Line::from(vec![
                    Span::styled("Ω ", theme::label()),
                    Span::styled(
                        format!(
                            "({},{},{})/{u} Ω⊥ {}/{u}",
                            fmt_short(o1),
                            fmt_short(o2),
                            fmt_short(o3),
                            fmt_short(s.omega_perp)
                        ),
                        theme::value(),
                    ),
                ]),
                Line::from(vec![
                    Span::styled("Ω⊥ ", theme::label()),
                    Span::styled(format!("{}/{u}", fmt_short(s.omega_perp)), theme::value()),
                ]),
            ]
        }
    }
}

/// How far the general top has drifted from t = 0, for the numbers of a
/// model with no closed form: E/E₀, |L|/|L₀| and the angle L has turned
/// through (the radiation torque of (3.3) need not be along L). With a tiny
/// dipole the top is free, and the first two stay 1.
pub fn drift(column: &Column) -> NumberBlock {
    let (s, s0) = (column.current(), column.start());
    let norm = |v: [Real; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let ratio = |a: Real, b: Real| if b > 0.0 { a / b } else { Real::NAN };
    let (l, l0) = (s.l_lab, s0.l_lab);
    let cross = [
        l[1] * l0[2] - l[2] * l0[1],
        l[2] * l0[0] - l[0] * l0[2],
        l[0] * l0[1] - l[1] * l0[0],
    ];
    let dot = l[0] * l0[0] + l[1] * l0[1] + l[2] * l0[2];
    let turned = if norm(l) > 0.0 && norm(l0) > 0.0 {
        norm(cross).atan2(dot)
    } else {
        Real::NAN
    };
    let pair = |label: &str, value: String| {
        Line::from(vec![
            Span::styled(padded(label, 10), theme::label()),
            Span::styled(value, theme::value()),
        ])
    };
    NumberBlock::new(vec![
        Line::from(Span::styled("since t = 0", theme::label())),
        pair("E/E₀", fmt_num(ratio(s.energy, s0.energy))),
        pair("|L|/|L₀|", fmt_num(ratio(norm(l), norm(l0)))),
        pair(
            "L from L₀",
            if turned.is_finite() {
                format!("{} rad ({:.2}°)", fmt_num(turned), turned.to_degrees())
            } else {
                "—".into()
            },
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_keeps_z_up_and_lengths_in_the_screen_plane() {
        let cam = Camera::new(0.7, 0.0);
        let (x, y) = cam.project([0.0, 0.0, 1.0]);
        assert!((x - 0.0).abs() < 1e-15 && (y - 1.0).abs() < 1e-15);
        // The viewing direction itself projects to the centre.
        let (x, y) = cam.project([0.7f64.cos(), 0.7f64.sin(), 0.0]);
        assert!(x.abs() < 1e-15 && y.abs() < 1e-15);
    }
}
