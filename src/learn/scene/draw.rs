//! The played-back scenes drawn: Section 2's charge on its orbit and the
//! appendix's shell. Drawing only reads the [`Playback`].

use super::{OrbitRuns, OrbitSample, PLAYBACK_UNIT, Playback, SHELL_T_END, ShellRun, ShellSample};
use crate::term::theme;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Points};
use ratatui::widgets::{Axis, Block, BorderType, Chart, Dataset, GraphType, Paragraph, Wrap};
use spintop::math::Real;
use spintop::physics::central::coulomb_circular_radius;

/// Draw the orbit scene in `area`: the Landau–Lifshitz orbit (its plane,
/// r(t) against (2.9), its numbers) and the forward Abraham–Lorentz run.
pub fn draw_orbit(frame: &mut Frame, area: Rect, p: &Playback<OrbitRuns>) {
    let runs = match p.data() {
        None => return computing(frame, area, "the orbits"),
        Some(Err(e)) => return failed(frame, area, &e.to_string()),
        Some(Ok(runs)) => runs,
    };
    let t = p.t();
    let shown: Vec<&OrbitSample> = runs.ll.iter().take_while(|s| s.t <= t).collect();
    let [left, right] = if area.width >= 100 {
        Layout::horizontal([Constraint::Percentage(60), Constraint::Percentage(40)]).areas(area)
    } else {
        Layout::vertical([Constraint::Fill(3), Constraint::Length(7)]).areas(area)
    };
    let block = panel(" Landau–Lifshitz: the orbit decays, r³ = r₀³ − 6τ₀t (2.9) ");
    let inner = block.inner(left);
    frame.render_widget(block, left);
    let [pictures, numbers] =
        Layout::vertical([Constraint::Fill(1), Constraint::Length(3)]).areas(inner);
    let [plane, radius] =
        Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)])
            .areas(pictures);
    orbit_plane(frame, plane, &shown, runs);
    radius_chart(frame, radius, &shown, runs, p.t_end);
    orbit_numbers(
        frame,
        numbers,
        shown.last().copied().or(runs.ll.first()),
        runs,
    );
    forward_run(frame, right, runs);
}

/// The orbit in its plane: the trail and the charge now, round.
fn orbit_plane(frame: &mut Frame, area: Rect, shown: &[&OrbitSample], runs: &OrbitRuns) {
    let now = shown.last().copied().or(runs.ll.first());
    let trail: Vec<(f64, f64)> = shown
        .iter()
        .map(|s| (s.position[0], s.position[1]))
        .collect();
    let here = now
        .map(|s| vec![(s.position[0], s.position[1])])
        .unwrap_or_default();
    // The whole orbit (radius 1) in view, round: a cell is two Braille dots
    // wide and four tall, so x spans w/(2h) of y's span per cell ratio.
    let aspect = f64::from(area.width.max(1)) / (2.0 * f64::from(area.height.max(1)));
    let (half_w, half_h) = if aspect >= 1.0 {
        (1.1 * aspect, 1.1)
    } else {
        (1.1, 1.1 / aspect)
    };
    frame.render_widget(
        Canvas::default()
            .marker(Marker::Braille)
            .x_bounds([-half_w, half_w])
            .y_bounds([-half_h, half_h])
            .paint(move |ctx| {
                ctx.draw(&Points::new(&trail, theme::TRAIL));
                ctx.draw(&Points::new(&here, theme::MOMENTUM));
                ctx.print(0.0, 0.0, Span::styled("+", theme::key()));
            }),
        area,
    );
}

/// r(t) against the averaged closed form (2.9).
fn radius_chart(
    frame: &mut Frame,
    area: Rect,
    shown: &[&OrbitSample],
    runs: &OrbitRuns,
    t_end: Real,
) {
    let r_data: Vec<(f64, f64)> = shown.iter().map(|s| (s.t, s.r)).collect();
    let closed: Vec<(f64, f64)> = (0..=100)
        .map(|i| {
            let t = t_end * f64::from(i) / 100.0;
            (t, coulomb_circular_radius(runs.tau0, 1.0, t))
        })
        .collect();
    let chart = Chart::new(vec![
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(theme::frame())
            .data(&closed),
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(theme::OMEGA[2]))
            .data(&r_data),
    ])
    .block(Block::new().title(Line::from(vec![
        Span::styled("r(t): ", theme::title()),
        Span::styled("━run ", Style::new().fg(theme::OMEGA[2])),
        Span::styled("━(2.9) averaged", theme::frame()),
    ])))
    .x_axis(time_axis(t_end))
    .y_axis(value_axis([0.0, 1.05], ["0".into(), "1".into()]));
    frame.render_widget(chart, area);
}

/// The orbit's numbers now (wrapped over all rows but the last), and the
/// averaged collapse time on the last, shortened to fit with its value kept.
fn orbit_numbers(frame: &mut Frame, area: Rect, now: Option<&OrbitSample>, runs: &OrbitRuns) {
    let n = now.map_or(String::new(), |s| {
        format!(
            "t = {:.2} {PLAYBACK_UNIT}   r = {}   (2.9): {}   L = {}   E = {}",
            s.t,
            spintop::numbers::fmt_num(s.r),
            spintop::numbers::fmt_num(coulomb_circular_radius(runs.tau0, 1.0, s.t)),
            spintop::numbers::fmt_num(s.l),
            spintop::numbers::fmt_num(s.energy)
        )
    });
    let rows = area.height.max(1);
    let [now_area, collapse_area] =
        Layout::vertical([Constraint::Length(rows - 1), Constraint::Length(1)]).areas(area);
    frame.render_widget(
        Paragraph::new(Line::from(Span::styled(n, theme::value()))).wrap(Wrap { trim: true }),
        now_area,
    );
    let t_c = format!(
        "{} {PLAYBACK_UNIT}",
        spintop::numbers::fmt_num(runs.collapse)
    );
    let collapse = fitting(
        area.width,
        &[
            format!("collapse by the averaged law at t_c = r₀³/(6τ₀) = {t_c}"),
            format!("averaged collapse: t_c = r₀³/(6τ₀) = {t_c}"),
            format!("averaged collapse t_c = {t_c}"),
            format!("t_c = {t_c}"),
        ],
    );
    frame.render_widget(
        Paragraph::new(Line::from(Span::styled(collapse, theme::label()))),
        collapse_area,
    );
}

/// The forward Abraham–Lorentz run: its runaway, in numbers.
fn forward_run(frame: &mut Frame, area: Rect, runs: &OrbitRuns) {
    let block = panel(" Abraham–Lorentz (2.5), forward: runs away ");
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let mut lines = vec![Line::from(Span::styled(
        "From the Newtonian start v̇ = F/m the third-order equation has a mode that grows as e^(t/τ₀).",
        theme::label(),
    ))];
    match &runs.forward.runaway {
        Some(r) => {
            lines.push(Line::from(Span::styled(
                format!(
                    "runaway at t = {} {PLAYBACK_UNIT} ({} τ₀): |v̇ − F| passed {} |F(r₀)|",
                    spintop::numbers::fmt_num(r.t),
                    spintop::numbers::fmt_num(r.t / runs.tau0),
                    spintop::numbers::fmt_num(r.threshold)
                ),
                theme::error(),
            )));
            lines.push(Line::from(Span::styled(
                format!(
                    "growth rate {} against 1/τ₀ = {}",
                    r.growth_rate.map_or("—".into(), spintop::numbers::fmt_num),
                    spintop::numbers::fmt_num(r.predicted_rate)
                ),
                theme::value(),
            )));
        }
        None => lines.push(Line::from("no runaway within the run")),
    }
    lines.push(Line::from(Span::styled(
        format!(
            "Its physical solution is found backward in time: {}",
            physical_run_command(runs.tau0)
        ),
        theme::label(),
    )));
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), inner);
}

/// The command that runs §2's charge by the Abraham–Lorentz law's physical
/// solution, as the scene prints it: every flag `spintop orbit` requires.
pub fn physical_run_command(tau0: spintop::math::Real) -> String {
    format!(
        "spintop orbit --potential coulomb --tau0 {} --force al --times 0,50,100,150",
        spintop::numbers::fmt_param(tau0)
    )
}

/// The first of `choices` (longest first) that fits `width` columns; the
/// last when none does.
fn fitting(width: u16, choices: &[String]) -> String {
    use unicode_width::UnicodeWidthStr;
    choices
        .iter()
        .find(|c| c.width() <= usize::from(width))
        .or(choices.last())
        .cloned()
        .unwrap_or_default()
}

/// Draw the shell scene in `area`.
pub fn draw_shell(frame: &mut Frame, area: Rect, p: &Playback<Vec<ShellRun>>) {
    let runs = match p.data() {
        None => return computing(frame, area, "the delay equation"),
        Some(Err(e)) => return failed(frame, area, &e.to_string()),
        Some(Ok(runs)) => runs,
    };
    let parts = if area.width >= 100 {
        Layout::horizontal([Constraint::Ratio(1, 2); 2]).split(area)
    } else {
        Layout::vertical([Constraint::Ratio(1, 2); 2]).split(area)
    };
    for (run, part) in runs.iter().zip(parts.iter()) {
        draw_shell_run(frame, *part, run, p.t());
    }
}

fn draw_shell_run(frame: &mut Frame, area: Rect, run: &ShellRun, t: Real) {
    let m = run.model;
    let stable = m.m0() > m.m_em();
    let (delta, tau0) = (
        spintop::numbers::fmt_param(m.delta()),
        spintop::numbers::fmt_param(m.tau0()),
    );
    let (masses, verdict) = if stable {
        ("m₀ > mₑₘ", "stable")
    } else {
        ("mₑₘ > m₀", "unstable")
    };
    // The verdict is what the panel is for: shorter titles keep it.
    let room = area.width.saturating_sub(4);
    let title = fitting(
        room,
        &[
            format!(" shell δ = {delta}, τ₀ = {tau0}: {masses}, {verdict} "),
            format!(" δ = {delta}, τ₀ = {tau0}: {masses}, {verdict} "),
            format!(" δ = {delta}, τ₀ = {tau0}: {verdict} "),
            format!(" {verdict} "),
        ],
    );
    let block = panel(&title);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let [chart_area, numbers] =
        Layout::vertical([Constraint::Fill(1), Constraint::Length(2)]).areas(inner);
    let shown: Vec<&ShellSample> = run.samples.iter().take_while(|s| s.t <= t).collect();
    let dev = |s: &ShellSample| s.z_minus_z_al[0].hypot(s.z_minus_z_al[1]);
    let data: Vec<(f64, f64)> = shown
        .iter()
        .filter(|s| dev(s) > 0.0)
        .map(|s| (s.t, dev(s).log10()))
        .collect();
    let all: Vec<f64> = run
        .samples
        .iter()
        .map(dev)
        .filter(|d| *d > 0.0)
        .map(f64::log10)
        .collect();
    let lo = all.iter().copied().fold(f64::INFINITY, f64::min).floor();
    let hi = all.iter().copied().fold(f64::NEG_INFINITY, f64::max).ceil();
    let (lo, hi) = if lo.is_finite() && hi > lo {
        (lo, hi)
    } else {
        (-16.0, 0.0)
    };
    let t_end = run.samples.last().map_or(SHELL_T_END, |s| s.t.max(1.0));
    let chart = Chart::new(vec![
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(if stable {
                theme::OMEGA[1]
            } else {
                theme::OMEGA[0]
            }))
            .data(&data),
    ])
    .block(Block::new().title(Span::styled(
        fitting(
            chart_area.width,
            &[
                "log₁₀|Z − Z_AL|: the shell against the point charge".into(),
                "log₁₀|Z − Z_AL|: shell against point charge".into(),
                "log₁₀|Z − Z_AL|".into(),
            ],
        ),
        theme::title(),
    )))
    .x_axis(time_axis(t_end))
    .y_axis(value_axis(
        [lo, hi],
        [format!("{lo:.0}"), format!("{hi:.0}")],
    ));
    frame.render_widget(chart, chart_area);
    let growth = match m.growth_rate() {
        Some(g) => format!(
            "grows at {} (ln(mₑₘ/m₀)/δ = {})",
            spintop::numbers::fmt_num(g),
            spintop::numbers::fmt_num((m.m_em() / m.m0()).abs().ln() / m.delta())
        ),
        None => "every mode decays: it stays near the point charge".into(),
    };
    let mut text = format!(
        "mₑₘ = {}, m₀ = {}; {growth}",
        spintop::numbers::fmt_num(m.m_em()),
        spintop::numbers::fmt_num(m.m0())
    );
    if let Some(e) = &run.ended
        && shown.len() == run.samples.len()
    {
        text.push_str(&format!("; stopped: {e}"));
    }
    frame.render_widget(
        Paragraph::new(Span::styled(text, theme::value())).wrap(Wrap { trim: true }),
        numbers,
    );
}

/// A time axis from 0 to `t_end`, labelled at its ends.
fn time_axis(t_end: Real) -> Axis<'static> {
    Axis::default()
        .style(theme::frame())
        .bounds([0.0, t_end])
        .labels(["0".to_string(), format!("{t_end:.0}")])
}

/// A value axis over `bounds`, labelled at its ends.
fn value_axis(bounds: [Real; 2], labels: [String; 2]) -> Axis<'static> {
    Axis::default()
        .style(theme::frame())
        .bounds(bounds)
        .labels(labels)
}

fn panel(title: &str) -> Block<'static> {
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Span::styled(title.to_string(), theme::title()))
}

fn computing(frame: &mut Frame, area: Rect, what: &str) {
    frame.render_widget(
        Paragraph::new(Span::styled(format!(" computing {what}…"), theme::label())),
        area,
    );
}

fn failed(frame: &mut Frame, area: Rect, why: &str) {
    frame.render_widget(
        Paragraph::new(Span::styled(
            format!(" the scene failed: {why}"),
            theme::error(),
        ))
        .wrap(Wrap { trim: true }),
        area,
    );
}
