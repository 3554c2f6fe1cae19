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
//! τ, and the I₃/I₁ keys leave the footer. Where the columns would be
//! narrower than [`crate::live::draw::COLUMN_WIDTH`] the screen shows one model at a time, and
//! Tab shows the next. Nothing is ever cut inside a number: a line that does
//! not fit loses a whole cell (a label, a block of numbers) first.

use crate::live::Top;
use crate::live::app::{App, MIN_HEIGHT, MIN_WIDTH, Mode, SUBSCRIPTS, TICK};
use crate::live::draw::{draw_columns, status};
use crate::term::cells::{Cell, Key, fit_cells, key, key_line, label, value, wrap_words};
use crate::term::{popup, theme};
use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Layout, Rect};
use ratatui::text::{Line, Span, Text};
use ratatui::widgets::{Paragraph, Wrap};
use spintop::numbers::fmt_param;

/// Draw the whole screen for the current state.
pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small(frame, area);
        return;
    }
    let message = message_lines(app, area.width);
    let [header, body, footer] = Layout::vertical([
        Constraint::Length(2 + message.len() as u16),
        Constraint::Fill(1),
        Constraint::Length(1),
    ])
    .areas(area);
    draw_header(frame, header, app, message);
    draw_columns(
        frame,
        body,
        app,
        &(0..app.columns().len()).collect::<Vec<_>>(),
        "Tab",
    );
    draw_footer(frame, footer, app);
    if let Mode::Help(scroll) = *app.mode() {
        draw_help(frame, area, app, scroll);
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

/// The message under the parameters, wrapped to the screen (a refusal says
/// why and what would work, which takes more than one line at 80 columns);
/// at most three lines.
fn message_lines(app: &App, width: u16) -> Vec<Line<'static>> {
    let (text, style) = match app.message() {
        Some(m) => (
            m.text.clone(),
            if m.is_error {
                theme::error()
            } else {
                theme::info()
            },
        ),
        None => {
            let (long, short) = match app.settings().top() {
                Top::General(_) => (
                    "Left: no Schott term, (3.3). Middle: Schott term kept, reduced. Right: (3.4)'s physical solution.",
                    "(3.3) │ reduced │ physical (3.4).",
                ),
                Top::Full(_) => (
                    "Left: the physical solution of (3.4). Right: (3.4) integrated forward, which runs away.",
                    "Left: (3.4)'s physical solution. Right: forward, it runs away.",
                ),
                Top::Symmetric(_) => (
                    "Left: no Schott term, loss law (2.1). Right: Schott term kept, torque (2.2).",
                    "Left: loss law (2.1). Right: torque (2.2).",
                ),
            };
            let i = SUBSCRIPTS[app.view().selected];
            let full = format!("{long} Ω{i}₀ selected (↑/↓, Enter edits). ? help");
            // One line when a shorter wording fits in one.
            let text = if Span::raw(full.as_str()).width() < usize::from(width) {
                full
            } else {
                format!("{short} Ω{i}₀: ↑/↓ Enter edits. ? help")
            };
            (text, theme::label())
        }
    };
    let room = usize::from(width.saturating_sub(1));
    let mut wrapped = wrap_words(&text, room);
    if wrapped.len() > 3 {
        // Never cut silently: the third line ends in … where more was said.
        wrapped.truncate(3);
        let last = &mut wrapped[2];
        while Span::raw(last.as_str()).width() + 2 > room {
            match last.rfind(' ') {
                Some(i) => last.truncate(i),
                None => break,
            }
        }
        last.push_str(" …");
    }
    wrapped
        .into_iter()
        .map(|l| Line::from(Span::styled(format!(" {l}"), style)))
        .collect()
}

fn draw_header(frame: &mut Frame, area: Rect, app: &App, message: Vec<Line<'static>>) {
    let settings = app.settings();
    let u = settings.top().time_unit();
    let first = vec![
        Cell::fixed(vec![Span::styled(" spintop ", theme::title())]),
        Cell::fixed(vec![
            label("t = "),
            value(format!("{:.2}{u}", app.time())),
            Span::raw(" "),
            status(app),
        ]),
        Cell::or(
            vec![label("warp "), value(format!("{} {u}/s", settings.warp()))],
            vec![value(format!("{} {u}/s", settings.warp()))],
        ),
        Cell::or(
            vec![label("step Δt "), value(format!("{TICK}{u}"))],
            vec![label("Δt "), value(format!("{TICK}{u}"))],
        ),
        Cell::or(
            vec![label(if settings.is_general() {
                "units: κ = 2/(3c³) = 1, time u"
            } else {
                "units: τ, 1/τ, I₁ = 1"
            })],
            vec![label(if settings.is_general() {
                "κ = 1 units"
            } else {
                "τ units"
            })],
        ),
    ];
    // The body's constants give way before Ω₀ (the values the keys change,
    // and the one being typed): dropped whole, never cut.
    let mut params = match settings.top() {
        Top::Symmetric(top) | Top::Full(top) => vec![Cell::or(
            vec![label("I₃/I₁ = "), value(fmt_param(top.ratio()))],
            Vec::new(),
        )],
        Top::General(top) => vec![
            Cell::or(
                vec![label("I = "), value(fmt_triple(top.inertia().into()))],
                Vec::new(),
            ),
            Cell::or(
                vec![label("d = "), value(fmt_triple(top.dipole().into()))],
                Vec::new(),
            ),
        ],
    };
    let mut omega = vec![label("Ω₀ = (")];
    for (i, w) in settings.omega0().iter().enumerate() {
        if i > 0 {
            omega.push(label(", "));
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
        omega.push(Span::styled(text, style));
    }
    omega.push(label(format!(")/{u}")));
    params.push(Cell::fixed(omega));
    let method = match settings.top() {
        Top::Full(_) => "physical, forward".to_string(),
        top => crate::live::app::method_title(settings.method(), top),
    };
    params.push(Cell::or(
        vec![label("method "), value(method.clone())],
        vec![value(method)],
    ));
    params.push(Cell::or(
        vec![label(if app.view().log_time {
            "log-time view".to_string()
        } else {
            format!("last 200{u}")
        })],
        Vec::new(),
    ));
    // One column of margin, whichever cell comes first.
    let mut params = fit_cells(params, area.width.saturating_sub(1));
    params.spans.insert(0, Span::raw(" "));
    let mut lines = vec![fit_cells(first, area.width), params];
    lines.extend(message);
    frame.render_widget(Paragraph::new(lines), area);
}

/// `(1, 1.5, 0.8)`: a vector as the user would type it.
fn fmt_triple(v: [spintop::math::Real; 3]) -> String {
    format!(
        "({}, {}, {})",
        fmt_param(v[0]),
        fmt_param(v[1]),
        fmt_param(v[2])
    )
}

/// The keys of the footer, in order. `[ ]` only where I₃/I₁ can change,
/// `Tab` only where models take turns.
const KEYS: [Key; 11] = [
    key("?", "help", "?", "help", 0),
    key("q", "quit", "q", "quit", 0),
    key("space", "pause", "space", "pause", 0),
    key(".", "step", ".", "step", 1),
    key("+/-", "warp", "+-", "warp", 4),
    key("r", "reset", "r", "reset", 3),
    key("[ ]", "I₃/I₁", "[]", "I₃/I₁", 5),
    key("↑↓ Enter", "edit Ω₀", "↑↓⏎", "Ω₀", 6),
    key("m", "method", "m", "method", 7),
    key("l", "log t", "l", "log", 2),
    key("Tab", "next model", "Tab", "model", 8),
];

fn draw_footer(frame: &mut Frame, area: Rect, app: &App) {
    let ratio = app.settings().ratio().is_some();
    let method = app.settings().top().takes_a_method();
    let turns = crate::live::layout::takes_turns(area.width, app.columns().len());
    let keys: Vec<&Key> = KEYS
        .iter()
        .filter(|k| {
            (ratio || k.key != "[ ]") && (turns || k.key != "Tab") && (method || k.key != "m")
        })
        .collect();
    frame.render_widget(Paragraph::new(key_line(&keys, area.width)), area);
}

fn draw_help(frame: &mut Frame, area: Rect, app: &App, scroll: usize) {
    let lines = crate::live::help::lines(app.settings().top());
    popup::draw(
        frame,
        area,
        crate::live::help::HELP_WIDTH,
        " help ",
        lines,
        scroll,
    );
}
