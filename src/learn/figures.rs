//! The paper's Figures 1 and 2 drawn in place in a chapter's text, from the
//! same points `spintop figure N` plots ([`spintop::figure::Figure`]): (a) the
//! hodograph of Ω with its pale shadow on the floor Ω₃ = 0, (b) the top in
//! space, the axis tip's path with L in red, (c) θ(t), (d) φ̇(t) and ψ̇(t).
//!
//! The panels are ratatui widgets drawn into a buffer the width of the text
//! and turned into styled lines, so the figure scrolls with the text.

use crate::live::widgets::{body_camera, lab_camera};
use crate::term::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Line as CanvasLine, Points};
use ratatui::widgets::{Axis, Block, Borders, Chart, Dataset, GraphType, Widget};
use spintop::figure::{Figure, FigureError, FigureNumber};
use std::sync::OnceLock;

/// The colour the book's prose gives L in the figures: red.
pub const L_COLOUR: Color = Color::Red;

/// Rows of one panel, title included.
const PANEL_ROWS: u16 = 11;

static ONE: OnceLock<Result<Figure, FigureError>> = OnceLock::new();
static TWO: OnceLock<Result<Figure, FigureError>> = OnceLock::new();

fn cell(number: FigureNumber) -> &'static OnceLock<Result<Figure, FigureError>> {
    match number {
        FigureNumber::One => &ONE,
        FigureNumber::Two => &TWO,
    }
}

/// The points of Figure `number`, computed once per process (here, now, if
/// they are not yet).
fn figure(number: FigureNumber) -> Result<&'static Figure, FigureError> {
    cell(number)
        .get_or_init(|| Figure::new(number))
        .as_ref()
        .map_err(Clone::clone)
}

/// Compute both figures on a thread of their own, once (the terminal's
/// way: Figure 2 integrates the reduced top's orientation to t = 8000).
pub fn compute_in_background() {
    static STARTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    if !STARTED.swap(true, std::sync::atomic::Ordering::Relaxed) {
        std::thread::spawn(|| {
            let _ = figure(FigureNumber::One);
            let _ = figure(FigureNumber::Two);
        });
    }
}

/// True once Figure `number` is computed.
pub fn ready(number: FigureNumber) -> bool {
    cell(number).get().is_some()
}

/// Which figure a book image shows, from its file name.
pub fn number_of(path: &str) -> Option<FigureNumber> {
    if path.ends_with("figure-1.svg") {
        Some(FigureNumber::One)
    } else if path.ends_with("figure-2.svg") {
        Some(FigureNumber::Two)
    } else {
        None
    }
}

/// Figure `number` as lines of at most `width` columns: four panels, two
/// side by side from 60 columns, else one under another. When `wait` is
/// false and the figure is still being computed, one line says so. When
/// `plain` (no colour, `NO_COLOR`), what colour told apart is drawn in
/// glyphs of its own, and the panels' titles name those.
pub fn lines(number: FigureNumber, width: u16, wait: bool, plain: bool) -> Vec<Line<'static>> {
    if !wait && !ready(number) {
        compute_in_background();
        return vec![Line::from(Span::styled(
            format!(
                "(Figure {} is being computed; it appears here in a moment)",
                number.number()
            ),
            theme::label(),
        ))];
    }
    let figure = match figure(number) {
        Ok(f) => f,
        Err(e) => {
            return vec![Line::from(Span::styled(
                format!("(Figure {} could not be computed: {e})", number.number()),
                theme::error(),
            ))];
        }
    };
    let width = width.max(20);
    let two = width >= 60;
    let rows = if two { 2 } else { 4 } * PANEL_ROWS;
    let area = Rect::new(0, 0, width, rows);
    let mut buf = Buffer::empty(area);
    let cells: Vec<Rect> = if two {
        let [top, bottom] = Layout::vertical([Constraint::Length(PANEL_ROWS); 2]).areas(area);
        let split = |r: Rect| -> [Rect; 2] {
            Layout::horizontal([Constraint::Ratio(1, 2); 2])
                .spacing(2)
                .areas(r)
        };
        let [a, b] = split(top);
        let [c, d] = split(bottom);
        vec![a, b, c, d]
    } else {
        Layout::vertical([Constraint::Length(PANEL_ROWS); 4])
            .split(area)
            .to_vec()
    };
    hodograph(figure, cells[0], &mut buf, plain);
    in_space(figure, cells[1], &mut buf, plain);
    tilt(figure, cells[2], &mut buf);
    rates(figure, cells[3], &mut buf, plain);
    to_lines(&buf)
}

fn panel(title: &str) -> Block<'_> {
    Block::new()
        .borders(Borders::TOP)
        .border_style(theme::frame())
        .title(Span::styled(title, theme::title()))
}

/// x bounds keeping a picture's proportions in `area` (a cell is about
/// twice as tall as wide).
fn x_bounds(area: Rect, y: [f64; 2]) -> [f64; 2] {
    let half = 0.5 * (y[1] - y[0]) * f64::from(area.width.max(1))
        / (2.0 * f64::from(area.height.saturating_sub(1).max(1)));
    [-half, half]
}

/// The marker of what colour alone told apart (the shadows, L): braille
/// with colour, dots without.
fn second_marker(plain: bool) -> Marker {
    if plain { Marker::Dot } else { Marker::Braille }
}

/// Draws `points` over a panel already drawn, with `marker`: a second
/// canvas on the panel's inside, which leaves the cells it does not mark.
fn overlay(
    points: &[(f64, f64)],
    color: Color,
    marker: Marker,
    area: Rect,
    bounds: [[f64; 2]; 2],
    buf: &mut Buffer,
) {
    Canvas::default()
        .marker(marker)
        .x_bounds(bounds[0])
        .y_bounds(bounds[1])
        .paint(|ctx| ctx.draw(&Points::new(points, color)))
        .render(area, buf);
}

fn hodograph(figure: &Figure, area: Rect, buf: &mut Buffer, plain: bool) {
    let cam = body_camera();
    let scale = figure.omega0.norm();
    let project = |w: [f64; 3]| cam.project([w[0] / scale, w[1] / scale, w[2] / scale]);
    let curve: Vec<(f64, f64)> = figure.samples.iter().map(|s| project(s.omega)).collect();
    // Its shadows on the three coordinate planes, as in the paper's panel.
    let shadow: Vec<(f64, f64)> = figure
        .samples
        .iter()
        .flat_map(|s| {
            let [w1, w2, w3] = s.omega;
            [
                project([w1, w2, 0.0]),
                project([0.0, w2, w3]),
                project([w1, 0.0, w3]),
            ]
        })
        .collect();
    let y = [-0.6, 1.1];
    let inner = panel("").inner(area);
    let title = if plain {
        "(a) Ω, body frame; •: its shadows"
    } else {
        "(a) Ω, body frame; pale: its shadows"
    };
    Canvas::default()
        .block(panel(title))
        .marker(Marker::Braille)
        .x_bounds(x_bounds(inner, y))
        .y_bounds(y)
        .paint(|ctx| {
            for (axis, name) in [
                ([1.0, 0.0, 0.0], "Ω₁"),
                ([0.0, 1.0, 0.0], "Ω₂"),
                ([0.0, 0.0, 1.0], "Ω₃"),
            ] {
                let (x1, y1) = cam.project([0.0; 3]);
                let (x2, y2) = cam.project(axis);
                ctx.draw(&CanvasLine::new(x1, y1, x2, y2, theme::GUIDE));
                ctx.print(x2, y2, Span::styled(name, theme::label()));
            }
            if !plain {
                ctx.draw(&Points::new(&shadow, theme::GUIDE));
                ctx.layer();
            }
            ctx.draw(&Points::new(&curve, theme::OMEGA[2]));
        })
        .render(area, buf);
    if plain {
        let bounds = [x_bounds(inner, y), y];
        overlay(
            &shadow,
            theme::GUIDE,
            second_marker(plain),
            inner,
            bounds,
            buf,
        );
        // The curve over its shadows, as with colour.
        overlay(&curve, theme::OMEGA[2], Marker::Braille, inner, bounds, buf);
    }
}

fn in_space(figure: &Figure, area: Rect, buf: &mut Buffer, plain: bool) {
    let cam = lab_camera();
    let tip: Vec<(f64, f64)> = figure
        .samples
        .iter()
        .map(|s| {
            let a = Figure::axis(s);
            cam.project([a.x, a.y, a.z])
        })
        .collect();
    let l_path: Vec<(f64, f64)> = figure
        .samples
        .iter()
        .map(|s| {
            let l = spintop::math::Vec3::from(s.l_lab);
            let d = l / l.norm().max(f64::MIN_POSITIVE);
            cam.project([1.1 * d.x, 1.1 * d.y, 1.1 * d.z])
        })
        .collect();
    let last = figure.samples.last().map(Figure::axis);
    let y = [-0.4, 1.3];
    let inner = panel("").inner(area);
    let title = if plain {
        "(b) the top in space; L: •"
    } else {
        "(b) the top in space; L in red"
    };
    Canvas::default()
        .block(panel(title))
        .marker(Marker::Braille)
        .x_bounds(x_bounds(inner, y))
        .y_bounds(y)
        .paint(|ctx| {
            let (x1, y1) = cam.project([0.0; 3]);
            let (x2, y2) = cam.project([0.0, 0.0, 1.2]);
            ctx.draw(&CanvasLine::new(x1, y1, x2, y2, theme::GUIDE));
            ctx.print(x2, y2, Span::styled("z", theme::label()));
            ctx.draw(&Points::new(&tip, theme::AXIS));
            if let Some(a) = last {
                let (x, y) = cam.project([a.x, a.y, a.z]);
                ctx.draw(&CanvasLine::new(x1, y1, x, y, theme::AXIS));
                ctx.print(x, y, Span::styled("e₃", Style::new().fg(theme::AXIS)));
            }
            ctx.layer();
            if !plain {
                ctx.draw(&Points::new(&l_path, L_COLOUR));
            }
            // L's label left of its end, clear of the axis's e₃.
            if let Some(&(x, y)) = l_path.last() {
                ctx.print(x - 0.25, y, Span::styled("L", Style::new().fg(L_COLOUR)));
            }
        })
        .render(area, buf);
    if plain {
        let bounds = [x_bounds(inner, y), y];
        overlay(&l_path, L_COLOUR, second_marker(plain), inner, bounds, buf);
    }
}

/// A chart's curve: its points, its style and its marker.
type Curve = (Vec<(f64, f64)>, Style, Marker);

fn chart_of(
    title: &'static str,
    curves: Vec<Curve>,
    t_end: f64,
    y: [f64; 2],
    area: Rect,
    buf: &mut Buffer,
) {
    let datasets = curves
        .iter()
        .map(|(data, style, marker)| {
            Dataset::default()
                .marker(*marker)
                .graph_type(GraphType::Line)
                .style(*style)
                .data(data)
        })
        .collect();
    Chart::new(datasets)
        .block(panel(title))
        .x_axis(
            Axis::default()
                .style(theme::frame())
                .bounds([0.0, t_end])
                .labels(["0".to_string(), format!("{t_end:.0} t/τ")]),
        )
        .y_axis(Axis::default().style(theme::frame()).bounds(y).labels([
            spintop::numbers::fmt_axis(y[0]),
            spintop::numbers::fmt_axis(y[1]),
        ]))
        .render(area, buf);
}

fn tilt(figure: &Figure, area: Rect, buf: &mut Buffer) {
    let t_end = figure.number.t_end();
    let data: Vec<(f64, f64)> = figure.samples.iter().map(|s| (s.t, s.euler[1])).collect();
    chart_of(
        "(c) the tilt θ(t), rad",
        vec![(data, Style::new().fg(theme::AXIS), Marker::Braille)],
        t_end,
        [0.0, 1.0],
        area,
        buf,
    );
}

fn rates(figure: &Figure, area: Rect, buf: &mut Buffer, plain: bool) {
    let t_end = figure.number.t_end();
    let pick = |i: usize| -> Vec<(f64, f64)> {
        figure
            .samples
            .iter()
            .filter_map(|s| s.euler_rates.map(|r| (s.t, r[i])))
            .collect()
    };
    let (phi, psi) = (pick(0), pick(2));
    let top = phi
        .iter()
        .chain(&psi)
        .map(|p| p.1.abs())
        .fold(0.0, f64::max);
    let y = spintop::numbers::nice_ceiling(top * 1.05);
    let title = if plain {
        "(d) φ̇ •, ψ̇ braille ⠒, 1/τ"
    } else {
        "(d) φ̇ yellow, ψ̇ green, 1/τ"
    };
    chart_of(
        title,
        vec![
            (phi, Style::new().fg(theme::OMEGA[3]), second_marker(plain)),
            (psi, Style::new().fg(theme::OMEGA[1]), Marker::Braille),
        ],
        t_end,
        [0.0, y],
        area,
        buf,
    );
}

/// The buffer's rows as styled lines, trailing blanks dropped.
pub(super) fn to_lines(buf: &Buffer) -> Vec<Line<'static>> {
    let area = buf.area;
    (area.y..area.y + area.height)
        .map(|y| {
            let mut spans: Vec<Span<'static>> = Vec::new();
            let mut text = String::new();
            let mut style = Style::new();
            for x in area.x..area.x + area.width {
                let cell = &buf[(x, y)];
                let s = cell.style();
                if s != style && !text.is_empty() {
                    spans.push(Span::styled(std::mem::take(&mut text), style));
                }
                style = s;
                text.push_str(cell.symbol());
            }
            let trimmed = text.trim_end_matches([' ', '\u{2800}']).to_string();
            if !trimmed.is_empty() {
                spans.push(Span::styled(trimmed, style));
            }
            // Drop empty trailing spans.
            while spans.last().is_some_and(|s| s.content.trim().is_empty()) {
                spans.pop();
            }
            Line::from(spans)
        })
        .collect()
}
