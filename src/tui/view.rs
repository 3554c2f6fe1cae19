//! The layout of the screen. Drawing only reads the [`App`].
//!
//! ```text
//! ┌ header: t, running/paused, warp, Δt; I₃/I₁, Ω₀, method; message ┐
//! ├ truncated (4.2)–(4.4) ─────────┬ reduced (4.12)–(4.14) ──────────┤
//! │ Ω₁ Ω₂ Ω₃ Ω⊥ against t          │ Ω₁ Ω₂ Ω₃ Ω⊥ against t           │
//! │ hodograph │ top in space       │ hodograph │ top in space        │
//! │ live numbers                   │ live numbers                    │
//! └ footer: the keys ──────────────┴─────────────────────────────────┘
//! ```
//!
//! A general (asymmetric) top has three columns: the truncated ALE (3.3), the
//! reduced ALE and the physical solution of the full ALE (3.4); the header
//! shows I and d instead of I₃/I₁, time is in the κ = 1 unit "u" instead of
//! τ, and the I₃/I₁ keys leave the footer.

use super::app::{App, Mode, SUBSCRIPTS, TICK, Top};
use super::theme;
use super::widgets::{OmegaSeries, drift, hodograph, numbers, top_in_space};
use crate::numbers::fmt_param;
use crate::sim::Model;
use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Layout, Rect};
use ratatui::text::{Line, Span, Text};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};

/// The smallest terminal the layout fits, in columns.
pub const MIN_WIDTH: u16 = 80;
/// The smallest terminal the layout fits, in rows.
pub const MIN_HEIGHT: u16 = 24;

/// Above this width the numbers get their long labels.
const WIDE: u16 = 110;

/// From this width of a column's inside the numbers of a model with no
/// closed form get a third block (about 32 columns each).
const DRIFT_WIDTH: u16 = 96;

/// Draw the whole screen for the current state.
pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small(frame, area);
        return;
    }
    let [header, body, footer] = Layout::vertical([
        Constraint::Length(3),
        Constraint::Fill(1),
        Constraint::Length(1),
    ])
    .areas(area);
    draw_header(frame, header, app);
    let n = app.columns().len().max(1) as u32;
    let parts = Layout::horizontal((0..n).map(|_| Constraint::Ratio(1, n))).split(body);
    for (i, part) in parts.iter().enumerate() {
        draw_column(frame, *part, app, i);
    }
    draw_footer(frame, footer, app.settings().is_general());
    if *app.mode() == Mode::Help {
        draw_help(frame, area, app.settings().is_general());
    }
}

fn too_small(frame: &mut Frame, area: Rect) {
    let text = Text::from(vec![
        Line::from(Span::styled("Please enlarge the terminal", theme::error())),
        Line::from(format!(
            "spintop needs at least {MIN_WIDTH}×{MIN_HEIGHT}; this one is {}×{}.",
            area.width, area.height
        )),
        Line::from("q quits."),
    ]);
    // Three lines, or about eight once a narrow screen wraps them.
    let height = if area.width >= 60 { 3 } else { 8 }.min(area.height);
    let [_, middle, _] = Layout::vertical([
        Constraint::Fill(1),
        Constraint::Length(height),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(text)
            .alignment(Alignment::Center)
            .wrap(Wrap { trim: true }),
        middle,
    );
}

fn sep() -> Span<'static> {
    Span::styled("  │  ", theme::frame())
}

fn draw_header(frame: &mut Frame, area: Rect, app: &App) {
    let settings = app.settings();
    let u = settings.top().time_unit();
    let status = if app.paused() {
        " paused "
    } else {
        " running "
    };
    let first = Line::from(vec![
        Span::styled(" spintop ", theme::title()),
        sep(),
        Span::styled("t = ", theme::label()),
        Span::styled(format!("{:.2}{u}", app.time()), theme::value()),
        Span::raw("  "),
        Span::styled(status, theme::status(app.paused())),
        sep(),
        Span::styled("warp ", theme::label()),
        Span::styled(format!("{} {u}/s", settings.warp()), theme::value()),
        sep(),
        Span::styled("step Δt ", theme::label()),
        Span::styled(format!("{TICK}{u}"), theme::value()),
        sep(),
        Span::styled(
            if settings.is_general() {
                "units: κ = 2/(3c³) = 1, time u"
            } else {
                "units: τ, 1/τ, I₁ = 1"
            },
            theme::label(),
        ),
    ]);
    let mut second = match settings.top() {
        Top::Symmetric(top) => vec![
            Span::styled(" I₃/I₁ = ", theme::label()),
            Span::styled(fmt_param(top.ratio()), theme::value()),
        ],
        Top::General(top) => vec![
            Span::styled(" I = ", theme::label()),
            Span::styled(fmt_triple(top.inertia().into()), theme::value()),
            sep(),
            Span::styled("d = ", theme::label()),
            Span::styled(fmt_triple(top.dipole().into()), theme::value()),
        ],
    };
    second.extend([sep(), Span::styled("Ω₀ = (", theme::label())]);
    let omega0 = settings.omega0();
    for (i, w) in omega0.iter().enumerate() {
        if i > 0 {
            second.push(Span::styled(", ", theme::label()));
        }
        let text = match app.mode() {
            Mode::Edit {
                component, buffer, ..
            } if *component == i => format!("{buffer}▏"),
            _ => fmt_param(*w),
        };
        let style = if i == app.view().selected {
            theme::selected()
        } else {
            theme::value()
        };
        second.push(Span::styled(text, style));
    }
    second.extend([
        Span::styled(format!(")/{u}"), theme::label()),
        sep(),
        Span::styled("method ", theme::label()),
        Span::styled(settings.method().title(), theme::value()),
        sep(),
        Span::styled(
            if app.view().log_time {
                "log-time view".to_string()
            } else {
                format!("last 200{u}")
            },
            theme::label(),
        ),
    ]);
    let third = match app.message() {
        Some(m) => Line::from(Span::styled(
            format!(" {}", m.text),
            if m.is_error {
                theme::error()
            } else {
                theme::info()
            },
        )),
        None => Line::from(Span::styled(
            format!(
                " {} Ω{}₀ selected (↑/↓, Enter edits). ? help",
                if settings.is_general() {
                    "Left: no Schott term, (3.3). Middle: Schott term kept, reduced. Right: (3.4)'s physical solution."
                } else {
                    "Left: no Schott term, loss law (2.1). Right: Schott term kept, torque (2.2)."
                },
                SUBSCRIPTS[app.view().selected]
            ),
            theme::label(),
        )),
    };
    frame.render_widget(
        Paragraph::new(vec![first, fit(second, area.width), third]),
        area,
    );
}

/// The parameter line, shortened to `width` if it must be: narrower
/// separators first, then without the last cell (the chart's time window,
/// which its axis shows anyway). The general top's I and d need this at 80
/// columns; the method stays in view.
fn fit(mut spans: Vec<Span<'static>>, width: u16) -> Line<'static> {
    let too_wide = |spans: &[Span]| Line::from(spans.to_vec()).width() > usize::from(width);
    if too_wide(&spans) {
        for span in &mut spans {
            if span.content == sep().content {
                *span = Span::styled(" │ ", theme::frame());
            }
        }
    }
    if too_wide(&spans) {
        spans.truncate(spans.len().saturating_sub(2));
    }
    Line::from(spans)
}

/// `(1, 1.5, 0.8)`: a vector as the user would type it.
fn fmt_triple(v: [crate::math::Real; 3]) -> String {
    format!(
        "({}, {}, {})",
        fmt_param(v[0]),
        fmt_param(v[1]),
        fmt_param(v[2])
    )
}

/// One model's column: its chart, hodograph, top in space and numbers
/// (also the scene panel of `spintop learn`).
pub(crate) fn draw_column(frame: &mut Frame, area: Rect, app: &App, i: usize) {
    let column = &app.columns()[i];
    let (name, equations, gist) = match column.sim().model() {
        Model::Truncated(_) => ("truncated", "(4.2)–(4.4)", "no Schott term"),
        Model::Reduced(_) => ("reduced", "(4.12)–(4.14)", "Schott term kept"),
        Model::GeneralReduced(_) => (
            "reduced",
            "(3.4) reduced",
            "Schott term kept, runaways removed",
        ),
        Model::GeneralFull(_) => ("physical", "(3.4)", "its non-runaway solution, Ω̈ kept"),
        // The view builds no other model than these and the general top.
        Model::General(_) | Model::Full(_) => ("truncated", "(3.3)", "no Schott term"),
    };
    let mut title = vec![
        Span::styled(format!(" {name} "), theme::title()),
        Span::styled(format!("{equations}: {gist} "), theme::label()),
    ];
    if column.failure().is_some() {
        title.push(Span::styled("stopped ", theme::error()));
    }
    if column.stand_in().is_some() {
        title.push(Span::styled("= reduced here ", theme::info()));
    }
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Line::from(title));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    // NOTE: on a short terminal the last line of numbers (Ω itself, shown in
    // the chart anyway) gives its row to the pictures; a failure still shows.
    let roomy = inner.height >= 24 || column.failure().is_some();
    let [chart_area, pictures, numbers_area] = Layout::vertical([
        Constraint::Fill(1),
        Constraint::Fill(1),
        // A stopped model's advice gets up to four lines.
        Constraint::Length(if column.failure().is_some() {
            9
        } else if roomy {
            6
        } else {
            5
        }),
    ])
    .areas(inner);
    let series = OmegaSeries::new(column, app.view().log_time);
    frame.render_widget(series.chart(), chart_area);
    let [hodo_area, space_area] =
        Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
            .areas(pictures);
    frame.render_widget(hodograph(column, hodo_area), hodo_area);
    frame.render_widget(top_in_space(column, space_area), space_area);
    let [rows, last] =
        Layout::vertical([Constraint::Length(5), Constraint::Fill(1)]).areas(numbers_area);
    // A model with no closed form has room (one column) for a third block:
    // how far E, |L| and the direction of L have moved since t = 0.
    let third = column.closed_form_error().is_none() && rows.width >= DRIFT_WIDTH;
    let blocks = Layout::horizontal(if third {
        [Constraint::Ratio(1, 3); 3].to_vec()
    } else {
        [Constraint::Ratio(1, 2); 2].to_vec()
    })
    .split(rows);
    let (l, r, bottom) = numbers(app, column, area.width >= WIDE / 2);
    frame.render_widget(l, blocks[0]);
    frame.render_widget(r, blocks[1]);
    if third {
        frame.render_widget(drift(column), blocks[2]);
    }
    frame.render_widget(bottom, last);
}

/// The keys of the footer, in order (`[ ]` only for a symmetric top).
const KEYS: [(&str, &str); 10] = [
    ("?", "help"),
    ("q", "quit"),
    ("space", "pause"),
    (".", "step"),
    ("+/-", "warp"),
    ("r", "reset"),
    ("[ ]", "I₃/I₁"),
    ("↑↓ Enter", "edit Ω₀"),
    ("m", "method"),
    ("l", "log t"),
];

fn draw_footer(frame: &mut Frame, area: Rect, general: bool) {
    let mut spans = vec![Span::raw(" ")];
    for (key, what) in KEYS {
        if general && key == "[ ]" {
            continue;
        }
        spans.push(Span::styled(key, theme::key()));
        spans.push(Span::styled(format!(" {what}  "), theme::label()));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

/// The help overlay's keys and explanations.
const HELP_KEYS: [(&str, &str); 11] = [
    ("space", "pause / resume"),
    (". or →", "one step of Δt while paused"),
    ("+ / -", "time warp (τ per wall-clock second)"),
    ("r", "restart both models at t = 0"),
    (
        "[ / ]",
        "I₃/I₁ down / up by 0.1 (a rigid body has 0 < I₃/I₁ ≤ 2)",
    ),
    ("↑ / ↓", "select a component of Ω₀"),
    (
        "Enter",
        "edit it: type, ↑/↓ ±0.01, Enter applies, Esc cancels",
    ),
    ("m", "method: closed form, RK4, DP5, DOP853, Radau5"),
    ("l", "log-time charts (the whole run) or the last 200τ"),
    ("?", "this help; any key closes it"),
    ("q Esc ^C", "quit"),
];

/// What the help says instead for a general top.
const GENERAL_HELP_KEYS: [(&str, &str); 5] = [
    (
        "+ / -",
        "time warp (u per wall-clock second; u: the time unit where κ = 1)",
    ),
    ("l", "log-time charts (the whole run) or the last 200u"),
    ("r", "restart all three models at t = 0"),
    (
        "[ / ]",
        "off: I₃/I₁ is for symmetric tops; I is set in the scene",
    ),
    (
        "m",
        "method of (3.3) and the reduced model: RK4, DP5, DOP853, Radau5 (no closed forms; the physical column always shoots backward)",
    ),
];

fn draw_help(frame: &mut Frame, area: Rect, general: bool) {
    let mut lines = if general {
        vec![
            Line::from(Span::styled(
                "Duviryak's polarized top, any shape: the general top",
                theme::title(),
            )),
            Line::from("The truncated ALE (3.3): loss law (2.1) for three different moments"),
            Line::from("and a dipole anywhere in the body. Nothing is closed: Ω and the"),
            Line::from("orientation are integrated together. The lab z axis is along L₀."),
            Line::from(""),
        ]
    } else {
        vec![
            Line::from(Span::styled(
                "Duviryak's polarized spinning top, two ways",
                theme::title(),
            )),
            Line::from("Left: truncated (4.2)–(4.4), loss law (2.1) without the Schott term."),
            Line::from("Right: reduced (4.12)–(4.14), Abraham–Lorentz torque (2.2) with it."),
            Line::from("Both start from the same I₃/I₁ and Ω₀; the lab z axis is along L₀."),
            Line::from(""),
        ]
    };
    for (key, what) in HELP_KEYS {
        let what = match GENERAL_HELP_KEYS.iter().find(|(k, _)| general && *k == key) {
            Some((_, instead)) => instead,
            None => what,
        };
        lines.push(Line::from(vec![
            Span::styled(format!("{key:<10}"), theme::key()),
            Span::raw(what),
        ]));
    }
    lines.push(Line::from(""));
    lines.extend(if general {
        [
            Line::from("Panels: Ω(t) in the body frame; the hodograph of Ω (body frame, with"),
            Line::from("its shadow on the Ω₁Ω₂ plane); the top in space: body axis e₃, L, and"),
            Line::from("the trail of the axis tip. There is no closed form to compare with:"),
            Line::from("E and |L| drain away as the top radiates. Times are in κ = 1 units."),
        ]
    } else {
        [
            Line::from("Panels: Ω(t) in the body frame; the hodograph of Ω (body frame, with"),
            Line::from("its shadow on the Ω₁Ω₂ plane); the top in space: axis e₃, L, and the"),
            Line::from("trail of the axis tip, which traces the precession cone. error is"),
            Line::from("|Ω − Ω_closed form| at the same t, from (4.7) and (4.15)–(4.16)."),
        ]
    });
    let width = 76.min(area.width);
    let height = (lines.len() as u16 + 2).min(area.height);
    let [_, h, _] = Layout::horizontal([
        Constraint::Fill(1),
        Constraint::Length(width),
        Constraint::Fill(1),
    ])
    .areas(area);
    let [_, popup, _] = Layout::vertical([
        Constraint::Fill(1),
        Constraint::Length(height),
        Constraint::Fill(1),
    ])
    .areas(h);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .title(Span::styled(" help ", theme::title())),
        ),
        popup,
    );
}
