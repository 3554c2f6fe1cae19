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
//! narrower than [`COLUMN_WIDTH`] the screen shows one model at a time, and
//! Tab shows the next. Nothing is ever cut inside a number: a line that does
//! not fit loses a whole cell (a label, a block of numbers) first.

use super::app::{App, MIN_HEIGHT, MIN_WIDTH, Mode, SUBSCRIPTS, TICK, Top};
use super::theme;
use super::widgets::{OmegaSeries, drift, hodograph, numbers, top_in_space};
use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Layout, Rect};
use ratatui::text::{Line, Span, Text};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};
use spintop::numbers::fmt_param;

/// The narrowest a model's column is drawn; below it, one model at a time.
pub const COLUMN_WIDTH: u16 = 40;

/// Above this width of a column the numbers get their long labels.
const WIDE: u16 = 55;

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
    if *app.mode() == Mode::Help {
        draw_help(frame, area, app.settings().top());
    }
}

/// The columns `shown` of `app` in `area`: side by side when each gets
/// [`COLUMN_WIDTH`], else the one [`super::app::View::shown`] picks, its
/// title saying which of how many it is (also the scene of `spintop learn`).
/// `next` names the key that shows the next model there.
pub(crate) fn draw_columns(frame: &mut Frame, area: Rect, app: &App, shown: &[usize], next: &str) {
    let n = shown.len().max(1) as u16;
    if area.width / n >= COLUMN_WIDTH || n == 1 {
        let parts =
            Layout::horizontal((0..n).map(|_| Constraint::Ratio(1, u32::from(n)))).split(area);
        for (part, i) in parts.iter().zip(shown) {
            draw_column(frame, *part, app, *i, None, next);
        }
    } else {
        let at = app.view().shown % shown.len();
        draw_column(frame, area, app, shown[at], Some((at, shown.len())), next);
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

/// One cell of a header line: its renderings from the fullest to the
/// shortest (an empty one drops the cell).
pub struct Cell(pub Vec<Vec<Span<'static>>>);

impl Cell {
    /// A cell that is always shown whole.
    pub fn fixed(spans: Vec<Span<'static>>) -> Self {
        Cell(vec![spans])
    }

    /// A cell with a shorter rendering, or none (`short` empty: dropped).
    pub fn or(long: Vec<Span<'static>>, short: Vec<Span<'static>>) -> Self {
        Cell(vec![long, short])
    }
}

fn width(spans: &[Span]) -> usize {
    spans.iter().map(Span::width).sum()
}

/// Cells joined by separators, made to fit `width`: narrower separators
/// first, then the last cells' shorter renderings, last cell first, then
/// (when even the shortest do not fit) whole cells left out from the end,
/// so that nothing is ever cut in the middle.
pub(crate) fn fit_cells(cells: Vec<Cell>, width_: u16) -> Line<'static> {
    let limit = usize::from(width_);
    let mut pick = vec![0usize; cells.len()];
    // Cells left out whole when even their shortest rendering does not fit.
    let mut hidden = vec![false; cells.len()];
    let part = |i: usize, pick: &[usize]| &cells[i].0[pick[i].min(cells[i].0.len() - 1)];
    let build = |pick: &[usize], hidden: &[bool], wide: bool| -> Vec<Span<'static>> {
        let mut spans = Vec::new();
        for (i, &hide) in hidden.iter().enumerate() {
            let part = part(i, pick);
            if hide || part.is_empty() {
                continue;
            }
            if !spans.is_empty() {
                spans.push(Span::styled(
                    if wide { "  │  " } else { " │ " },
                    theme::frame(),
                ));
            }
            spans.extend(part.iter().cloned());
        }
        spans
    };
    if width(&build(&pick, &hidden, true)) <= limit {
        return Line::from(build(&pick, &hidden, true));
    }
    loop {
        let spans = build(&pick, &hidden, false);
        if width(&spans) <= limit {
            return Line::from(spans);
        }
        // Shorten the last cell that still can be; when none can, leave
        // out the last cell still shown but the first (whole: a cell is
        // never cut in the middle).
        let shorter = (0..cells.len())
            .rev()
            .find(|&i| pick[i] + 1 < cells[i].0.len());
        let last_shown = (1..cells.len())
            .rev()
            .find(|&i| !hidden[i] && !part(i, &pick).is_empty());
        match (shorter, last_shown) {
            (Some(i), _) => pick[i] += 1,
            (None, Some(i)) => hidden[i] = true,
            (None, None) => return Line::from(spans),
        }
    }
}

fn label(s: impl Into<String>) -> Span<'static> {
    Span::styled(s.into(), theme::label())
}

fn value(s: impl Into<String>) -> Span<'static> {
    Span::styled(s.into(), theme::value())
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

/// Greedy word wrap (a word longer than the width stays whole on its line).
pub(crate) fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let w = Span::raw(word).width();
        if !line.is_empty() && Span::raw(line.as_str()).width() + 1 + w > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// The status of the clock: running, running behind the warp, or paused.
pub(crate) fn status(app: &App) -> Span<'static> {
    let u = app.settings().top().time_unit();
    if app.columns().iter().all(|c| c.failure().is_some()) {
        Span::styled(" stopped ", theme::status(true))
    } else if app.paused() {
        Span::styled(" paused ", theme::status(true))
    } else if let Some(rate) = app.behind() {
        Span::styled(
            format!(" running, {} {u}/s ", spintop::numbers::fmt_num(rate)),
            theme::status(true),
        )
    } else {
        Span::styled(" running ", theme::status(false))
    }
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
        _ => settings.method().title().to_string(),
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

/// One model's column: its chart, hodograph, top in space and numbers.
/// `which`: its place among models shown one at a time, if they are.
fn draw_column(
    frame: &mut Frame,
    area: Rect,
    app: &App,
    i: usize,
    which: Option<(usize, usize)>,
    next: &str,
) {
    let column = &app.columns()[i];
    let (name, equations, gist) = column.title();
    let mut marks = Vec::new();
    if column.failure().is_some() {
        marks.push(Span::styled(
            if column.is_forward() {
                "│ ran away "
            } else {
                "│ stopped "
            },
            theme::error(),
        ));
    }
    if column.stand_in().is_some() {
        marks.push(Span::styled("│ = reduced here ", theme::info()));
    }
    if let Some((at, n)) = which {
        marks.push(Span::styled(
            format!("│ model {} of {n} ({next}: next) ", at + 1),
            theme::key(),
        ));
    }
    let room = usize::from(area.width.saturating_sub(4))
        - width(&marks).min(usize::from(area.width.saturating_sub(4)));
    let long = format!(" {name} {equations}: {gist} ");
    let mut title = if Span::raw(long.as_str()).width() <= room {
        vec![
            Span::styled(format!(" {name} "), theme::title()),
            Span::styled(format!("{equations}: {gist} "), theme::label()),
        ]
    } else {
        vec![
            Span::styled(format!(" {name} "), theme::title()),
            Span::styled(format!("{equations} "), theme::label()),
        ]
    };
    title.extend(marks);
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Line::from(title));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    // NOTE: on a short terminal the last line of numbers (Ω itself, shown in
    // the chart anyway) gives its row to the pictures; a failure still shows.
    let roomy = inner.height >= 24 || column.failure().is_some();
    let numbers_height = if column.failure().is_some() {
        // A stopped model's advice gets up to four lines.
        9
    } else if roomy {
        6
    } else {
        5
    };
    // NOTE: the chart gets more of a short column than the pictures: below
    // eight rows its y axis has too few rows to read a curve.
    let [chart_area, pictures, numbers_area] = Layout::vertical([
        Constraint::Fill(3),
        Constraint::Fill(2),
        Constraint::Length(numbers_height),
    ])
    .areas(inner);
    let series = OmegaSeries::new(column, app.view().log_time);
    frame.render_widget(series.chart(chart_area.height), chart_area);
    let [hodo_area, space_area] =
        Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
            .areas(pictures);
    frame.render_widget(hodograph(column, hodo_area), hodo_area);
    frame.render_widget(top_in_space(column, space_area), space_area);
    let [rows, last] =
        Layout::vertical([Constraint::Length(5), Constraint::Fill(1)]).areas(numbers_area);
    let wide = area.width >= WIDE;
    let (l, r, bottom) = numbers(app, column, wide);
    // The blocks at their own widths, left to right, as many as fit whole:
    // a block is dropped before a number in it is cut.
    let mut blocks = vec![l, r];
    if column.closed_form_error().is_none() {
        blocks.push(drift(column));
    }
    let widths: Vec<u16> = blocks.iter().map(|b| b.width).collect();
    let mut keep = blocks.len();
    // Blocks one column apart at least.
    while keep > 1 && widths[..keep].iter().sum::<u16>() + keep as u16 - 1 > rows.width {
        keep -= 1;
    }
    let parts = Layout::horizontal(
        widths[..keep]
            .iter()
            .map(|w| Constraint::Min(*w))
            .collect::<Vec<_>>(),
    )
    .spacing(1)
    .split(rows);
    for (block, part) in blocks.into_iter().zip(parts.iter()) {
        frame.render_widget(block.paragraph, *part);
    }
    frame.render_widget(bottom, last);
}

/// One key of a footer: the key and what it does, long and short.
pub(crate) struct Key {
    /// The key, in full.
    pub key: &'static str,
    /// What it does.
    pub word: &'static str,
    /// The key, short.
    pub short_key: &'static str,
    /// What it does, short.
    pub short_word: &'static str,
    /// The order in which keys leave a narrow footer (0 never; 1 first).
    pub drop: u8,
}

/// A footer key: the key and its word, long and short, and when it leaves.
pub(crate) const fn key(
    key: &'static str,
    word: &'static str,
    short_key: &'static str,
    short_word: &'static str,
    drop: u8,
) -> Key {
    Key {
        key,
        word,
        short_key,
        short_word,
        drop,
    }
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
    let turns = (area.width / app.columns().len().max(1) as u16) < COLUMN_WIDTH;
    let keys: Vec<&Key> = KEYS
        .iter()
        .filter(|k| {
            (ratio || k.key != "[ ]") && (turns || k.key != "Tab") && (method || k.key != "m")
        })
        .collect();
    frame.render_widget(Paragraph::new(key_line(&keys, area.width)), area);
}

/// The keys as one line that fits `width`: long words with wide gaps, else
/// short ones, else without the keys that leave first (`?` shows them all).
pub(crate) fn key_line(keys: &[&Key], width_: u16) -> Line<'static> {
    let line = |short: bool, gap: &str, keys: &[&Key]| -> Vec<Span<'static>> {
        let mut spans = vec![Span::raw(" ")];
        for (i, k) in keys.iter().enumerate() {
            if i > 0 {
                spans.push(Span::raw(gap.to_string()));
            }
            let (key, word) = if short {
                (k.short_key, k.short_word)
            } else {
                (k.key, k.word)
            };
            spans.push(Span::styled(key.to_string(), theme::key()));
            spans.push(label(format!(" {word}")));
        }
        spans
    };
    let limit = usize::from(width_);
    for (short, gap) in [(false, "  "), (true, "  "), (true, " ")] {
        let spans = line(short, gap, keys);
        if width(&spans) <= limit {
            return Line::from(spans);
        }
    }
    let mut kept: Vec<&Key> = keys.to_vec();
    let mut order: Vec<u8> = kept.iter().map(|k| k.drop).filter(|d| *d > 0).collect();
    order.sort_unstable();
    for d in order {
        if width(&line(true, " ", &kept)) <= limit {
            break;
        }
        kept.retain(|k| k.drop != d);
    }
    Line::from(line(true, " ", &kept))
}

/// The help overlay's keys and explanations.
const HELP_KEYS: [(&str, &str); 12] = [
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
    ("m", "method: closed form, RK4, DP5, DOP853, Radau5, Taylor"),
    ("l", "log-time charts (the whole run) or the last 200τ"),
    ("Tab", "the next model, where one is shown at a time"),
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
        "method of (3.3) and the reduced model: RK4, DP5, DOP853, Radau5, Taylor (no closed forms; the physical column always shoots backward)",
    ),
];

/// What the help says instead for the full ALE.
const FULL_HELP_KEYS: [(&str, &str); 2] = [
    ("r", "restart both runs at t = 0"),
    (
        "m",
        "off: each column has its own method (backward shooting, forward DOP853)",
    ),
];

fn draw_help(frame: &mut Frame, area: Rect, top: &Top) {
    let mut lines = match top {
        Top::General(_) => vec![
            Line::from(Span::styled(
                "Duviryak's polarized top, any shape: the general top",
                theme::title(),
            )),
            Line::from("The truncated ALE (3.3): loss law (2.1) for three different moments"),
            Line::from("and a dipole anywhere in the body. Nothing is closed: Ω and the"),
            Line::from("orientation are integrated together. The lab z axis is along L₀."),
            Line::from(""),
        ],
        Top::Full(_) => vec![
            Line::from(Span::styled(
                "The full ALE (3.4): the physical solution and the runaway",
                theme::title(),
            )),
            Line::from("Left: (3.4) solved backward from its slow manifold, where the runaway"),
            Line::from("decays; it stays close to the reduced model. Right: the same equation"),
            Line::from("integrated forward from the same start: it leaves at a rate ≈ 1/τ."),
            Line::from(""),
        ],
        Top::Symmetric(_) => vec![
            Line::from(Span::styled(
                "Duviryak's polarized spinning top, two ways",
                theme::title(),
            )),
            Line::from("Left: truncated (4.2)–(4.4), loss law (2.1) without the Schott term."),
            Line::from("Right: reduced (4.12)–(4.14), Abraham–Lorentz torque (2.2) with it."),
            Line::from("Both start from the same I₃/I₁ and Ω₀; the lab z axis is along L₀."),
            Line::from(""),
        ],
    };
    let instead: &[(&str, &str)] = match top {
        Top::General(_) => &GENERAL_HELP_KEYS,
        Top::Full(_) => &FULL_HELP_KEYS,
        Top::Symmetric(_) => &[],
    };
    for (key, what) in HELP_KEYS {
        let what = instead
            .iter()
            .find(|(k, _)| *k == key)
            .map_or(what, |(_, w)| w);
        lines.push(Line::from(vec![
            Span::styled(format!("{key:<10}"), theme::key()),
            Span::raw(what),
        ]));
    }
    lines.push(Line::from(""));
    lines.extend(if matches!(top, Top::General(_)) {
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
    let width = 78.min(area.width);
    let inner = usize::from(width.saturating_sub(2)).max(1);
    let rows_of =
        |lines: &[Line]| -> usize { lines.iter().map(|l| l.width().max(1).div_ceil(inner)).sum() };
    // A short terminal gets the keys alone: the title, then the keys.
    if rows_of(&lines) + 4 > usize::from(area.height) {
        let keys = 5..5 + HELP_KEYS.len();
        let mut short = vec![lines[0].clone()];
        short.extend(lines[keys].iter().cloned());
        lines = short;
    }
    let rows = rows_of(&lines);
    let height = (rows as u16 + 2).min(area.height);
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
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .title(Span::styled(" help ", theme::title())),
        ),
        popup,
    );
}
