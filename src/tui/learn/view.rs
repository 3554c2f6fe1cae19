//! The screen of `spintop learn`. Drawing only reads the [`Learn`] state.
//!
//! ```text
//! spintop learn │ Section 4.2: the reduced top │ 6 of 24 │ course …
//! ╭ section-4-2.md ──────────────╮ scene: what it is
//! │ the chapter, wrapped          │ its parameters, paused or running
//! │ …                             │ the live view's column(s), or the
//! ╰───────────────────────────────╯ chapter's own scene
//! status: the last thing done (an experiment, a search, a pause)
//! keys
//! ```

use super::super::theme;
use super::super::view::{
    Cell, Key, draw_columns, fit_cells, key, key_line, status as live_status,
};
use super::scene::{Stage, draw_orbit, draw_shell, playback_status};
use super::{Learn, Mode, Spec, progress_bar, text_inner};
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{
    Axis, Block, BorderType, Chart, Clear, Dataset, GraphType, List, ListItem, ListState,
    Paragraph, Wrap,
};

/// The keys of the footer.
const KEYS: [Key; 12] = [
    key("?", "help", "?", "help", 0),
    key("q", "quit", "q", "quit", 0),
    key("space b", "page", "spc b", "page", 3),
    key("/", "search", "/", "find", 5),
    key("← →", "chapter", "←→", "chapter", 6),
    key("c", "contents", "c", "contents", 7),
    key("x", "next experiment", "x", "try", 8),
    key("Tab", "scene full screen", "Tab", "scene", 9),
    key("p", "pause scene", "p", "pause", 4),
    key("o", "unfold code", "o", "code", 2),
    key("a", "assignments", "a", "course", 1),
    key("h", "hint", "h", "hint", 1),
];

/// Draw the screen for the current state.
pub fn draw(frame: &mut Frame, learn: &Learn) {
    let area = frame.area();
    if learn.too_small() || area.width < super::MIN_SIZE.0 || area.height < super::MIN_SIZE.1 {
        let p = Paragraph::new(vec![
            Line::from(Span::styled("Please enlarge the terminal", theme::error())),
            Line::from(format!(
                "spintop learn needs {}×{}; this one is {}×{}. q quits.",
                super::MIN_SIZE.0,
                super::MIN_SIZE.1,
                area.width,
                area.height
            )),
        ])
        .wrap(Wrap { trim: true });
        frame.render_widget(p, area);
        return;
    }
    let panes = learn.panes_in((area.width, area.height));
    draw_header(frame, panes.header, learn);
    if let Some(text) = panes.text {
        draw_text(frame, text, learn);
    }
    if let Some(scene) = panes.scene {
        draw_scene(frame, scene, learn);
    }
    draw_status(frame, panes.status, learn, panes.scene.is_some());
    draw_footer(frame, panes.footer, learn, panes.scene.is_some());
    match learn.mode() {
        Mode::Help => draw_help(frame, area),
        Mode::Course => draw_course(frame, area, learn),
        Mode::Contents(sel) => draw_contents(frame, area, learn, *sel),
        _ => {}
    }
}

fn draw_header(frame: &mut Frame, area: Rect, learn: &Learn) {
    let chapter = &learn.chapters()[learn.current()];
    let seen = learn.visited().iter().filter(|v| **v).count();
    let n = learn.chapters().len();
    let course = match (learn.course(), learn.grading(), learn.course_error()) {
        (_, _, Some(_)) => Some("course: cannot grade".to_string()),
        (Some(s), grading, _) => Some(format!(
            "course {} of {} {}{}",
            s.passing(),
            s.states.len(),
            progress_bar(s.passing(), s.states.len(), 10),
            if grading { " grading…" } else { "" }
        )),
        (None, true, _) => Some("course: grading…".to_string()),
        (None, false, None) => None,
    };
    let mut cells = vec![
        Cell::fixed(vec![Span::styled(" spintop learn ", theme::status(false))]),
        Cell::fixed(vec![Span::styled(chapter.title.clone(), theme::title())]),
        Cell::or(
            vec![Span::styled(
                format!("chapter {} of {n}, {seen} opened", learn.current() + 1),
                theme::label(),
            )],
            vec![Span::styled(
                format!("{}/{n}", learn.current() + 1),
                theme::label(),
            )],
        ),
    ];
    if let Some(c) = course {
        cells.push(Cell::or(vec![Span::styled(c, theme::key())], Vec::new()));
    }
    frame.render_widget(Paragraph::new(fit_cells(cells, area.width)), area);
}

/// `line` with the byte ranges `marks` of its text highlighted.
fn highlight(
    line: &Line<'static>,
    marks: &[std::ops::Range<usize>],
    current: Option<&std::ops::Range<usize>>,
) -> Line<'static> {
    if marks.is_empty() {
        return line.clone();
    }
    let mut spans = Vec::new();
    let mut offset = 0;
    for span in &line.spans {
        let text = span.content.as_ref();
        let end = offset + text.len();
        // Cut points inside this span.
        let mut cuts = vec![0, text.len()];
        for m in marks {
            for p in [m.start, m.end] {
                if p > offset && p < end && text.is_char_boundary(p - offset) {
                    cuts.push(p - offset);
                }
            }
        }
        cuts.sort_unstable();
        cuts.dedup();
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let piece = &text[a..b];
            let at = offset + a;
            let hit = marks.iter().find(|m| m.start <= at && at < m.end);
            let style = match hit {
                Some(m) if current == Some(m) => span.style.patch(
                    Style::new()
                        .fg(ratatui::style::Color::Black)
                        .bg(ratatui::style::Color::Yellow),
                ),
                Some(_) => span
                    .style
                    .patch(Style::new().add_modifier(Modifier::REVERSED)),
                None => span.style,
            };
            spans.push(Span::styled(piece.to_string(), style));
        }
        offset = end;
    }
    Line::from(spans)
}

fn draw_text(frame: &mut Frame, area: Rect, learn: &Learn) {
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Span::styled(
            format!(" {} ", learn.chapters()[learn.current()].file),
            theme::label(),
        ));
    frame.render_widget(block, area);
    let inner = text_inner(area);
    let lines = &learn.rendered().lines;
    let total = lines.len();
    let top = learn.scroll().min(total);
    let end = (top + usize::from(inner.height)).min(total);
    let search = learn.search();
    let shown: Vec<Line> = (top..end)
        .map(|i| {
            let marks: Vec<std::ops::Range<usize>> = search
                .map(|s| {
                    s.matches
                        .iter()
                        .filter(|(l, _)| *l == i)
                        .map(|(_, r)| r.clone())
                        .collect()
                })
                .unwrap_or_default();
            let current = search
                .and_then(|s| s.matches.get(s.at))
                .filter(|(l, _)| *l == i)
                .map(|(_, r)| r);
            highlight(&lines[i], &marks, current)
        })
        .collect();
    frame.render_widget(Paragraph::new(shown), inner);
    if total > usize::from(inner.height) && inner.height > 0 {
        // A one-column position mark on the right edge.
        let max = total.saturating_sub(usize::from(inner.height)).max(1);
        let pos = top * usize::from(inner.height - 1) / max;
        let mark = Rect {
            x: area.x + area.width - 1,
            y: inner.y + pos as u16,
            width: 1,
            height: 1,
        };
        frame.render_widget(Paragraph::new(Span::styled("┃", theme::key())), mark);
    }
}

fn draw_scene(frame: &mut Frame, area: Rect, learn: &Learn) {
    let [about, params, rest] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(1),
        Constraint::Fill(1),
    ])
    .areas(area);
    frame.render_widget(
        Paragraph::new(Line::from(Span::styled(
            shortened(
                &format!(" scene: {}", learn.scene_info().about),
                about.width,
            ),
            theme::label(),
        ))),
        about,
    );
    let stage = learn.stage();
    frame.render_widget(
        Paragraph::new(fit_cells(stage.parameters(), params.width)),
        params,
    );
    match stage {
        Stage::Top(app) => {
            let columns: Vec<usize> = match &learn.scene_info().spec {
                Spec::Top { columns, .. } => columns
                    .iter()
                    .copied()
                    .filter(|c| *c < app.columns().len())
                    .collect(),
                _ => Vec::new(),
            };
            // The student's function of time, when there is one, below the scene.
            let rest = if learn.yours().is_some() && rest.height >= 20 {
                let [scene, yours] =
                    Layout::vertical([Constraint::Fill(2), Constraint::Fill(1)]).areas(rest);
                draw_yours(frame, yours, learn);
                scene
            } else {
                rest
            };
            draw_columns(frame, rest, app, &columns, "v");
        }
        Stage::Orbit(p) => draw_orbit(frame, rest, p),
        Stage::Shell(p) => draw_shell(frame, rest, p),
        Stage::None => {}
    }
}

/// `text` cut at a word to fit `width` columns, "…" where it was cut.
fn shortened(text: &str, width: u16) -> String {
    let limit = usize::from(width);
    if Span::raw(text).width() <= limit {
        return text.to_string();
    }
    let lead = text.len() - text.trim_start().len();
    let mut out = text[..lead].to_string();
    for word in text.trim_start().split(' ') {
        let next = if out.trim().is_empty() {
            format!("{out}{word}")
        } else {
            format!("{out} {word}")
        };
        if Span::raw(next.as_str()).width() + 1 > limit {
            break;
        }
        out = next;
    }
    format!("{}…", out.trim_end_matches([',', ':', ';']))
}

fn draw_status(frame: &mut Frame, area: Rect, learn: &Learn, scene_shown: bool) {
    let line = match (learn.mode(), learn.message()) {
        (Mode::Search(q), _) => Line::from(vec![
            Span::styled(" /", theme::key()),
            Span::styled(format!("{q}▏"), theme::selected()),
            Span::styled(
                match learn.search() {
                    Some(last) if q.is_empty() => {
                        format!("  Enter finds (alone: “{}” again), Esc cancels", last.query)
                    }
                    _ => "  Enter finds, Esc cancels".to_string(),
                },
                theme::label(),
            ),
        ]),
        // A message too long for the line is cut at a word, with "…".
        (_, Some((m, true))) => Line::from(Span::styled(
            shortened(&format!(" {m}"), area.width),
            theme::error(),
        )),
        (_, Some((m, false))) => Line::from(Span::styled(
            shortened(&format!(" {m}"), area.width),
            theme::info(),
        )),
        _ => {
            let stage = learn.stage();
            let mut spans = vec![Span::styled(" scene ", theme::label())];
            match stage.clock() {
                Some(clock) => {
                    spans.push(Span::styled(clock, theme::value()));
                    spans.push(Span::raw(" "));
                    spans.push(match stage {
                        Stage::Top(app) => live_status(app),
                        _ => playback_status(stage.paused()),
                    });
                    if !scene_shown {
                        spans.push(Span::styled("  (Tab shows it)", theme::label()));
                    }
                }
                None => spans.push(Span::styled(learn.scene_info().describe(), theme::label())),
            }
            Line::from(spans)
        }
    };
    frame.render_widget(Paragraph::new(line), area);
}

fn draw_footer(frame: &mut Frame, area: Rect, learn: &Learn, scene_shown: bool) {
    let has_scene = !matches!(learn.stage(), Stage::None);
    let keys: Vec<&Key> = KEYS
        .iter()
        .filter(|k| {
            let scene_key = matches!(k.key, "Tab" | "p" | "x");
            (has_scene || !scene_key)
                && !(k.key == "Tab" && scene_shown && *learn.mode() != Mode::Scene)
        })
        .collect();
    frame.render_widget(Paragraph::new(key_line(&keys, area.width)), area);
}

/// `lines` in a bordered box `width` wide (at most), as tall as they are
/// once wrapped, in the middle of `area`.
fn popup(frame: &mut Frame, area: Rect, width: u16, title: &str, lines: Vec<Line<'static>>) {
    let width = width.min(area.width);
    // Rows once wrapped to the popup's inner width.
    let inner = usize::from(width.saturating_sub(2)).max(1);
    let rows: usize = lines.iter().map(|l| l.width().max(1).div_ceil(inner)).sum();
    let at = centered(area, width, rows as u16 + 2);
    frame.render_widget(Clear, at);
    frame.render_widget(
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(
            Block::bordered()
                .border_type(BorderType::Rounded)
                .title(title.to_string()),
        ),
        at,
    );
}

fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let w = width.min(area.width);
    let h = height.min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

/// The help's lines: every key, grouped.
const HELP: [(&str, &str); 14] = [
    ("space b", "a page down, a page up (also PgDn, PgUp, f)"),
    ("j k ↓ ↑", "a line; the mouse wheel: three"),
    ("g G", "the top, the end of the chapter"),
    ("/ n N", "search; the next, the previous match"),
    ("← → c", "the previous, the next chapter; the contents"),
    ("o", "library source whole, or folded to one line"),
    (
        "Tab x",
        "the scene full screen; the next experiment (▶ try this)",
    ),
    ("p .", "pause the scene; one step while it is paused"),
    ("r l + -", "restart, log time, warp of the scene"),
    ("m v", "the scene's method; its next model, one at a time"),
    ("a h", "the assignments; a hint for the next one"),
    ("Esc", "close a panel, clear a search (never quits)"),
    ("?", "this help (any key closes it)"),
    ("q ^C", "quit: the chapter reopens where you left it"),
];

fn draw_help(frame: &mut Frame, area: Rect) {
    let mut lines = vec![
        Line::from(Span::styled("spintop learn", theme::title())),
        Line::from("The book's chapters, each beside the scene it is about."),
        Line::from("Places marked ▶ try this are experiments: x runs the next one."),
        Line::from(""),
    ];
    // A short terminal gets the keys alone.
    if area.height < HELP.len() as u16 + lines.len() as u16 + 2 {
        lines.clear();
    }
    for (k, what) in HELP {
        lines.push(Line::from(vec![
            Span::styled(format!("{k:>8}  "), theme::key()),
            Span::raw(what),
        ]));
    }
    popup(frame, area, 72, " help ", lines);
}

fn draw_course(frame: &mut Frame, area: Rect, learn: &Learn) {
    use spintop_course::State;
    let mut lines = Vec::new();
    let grading_on = learn.grading_off_reason().is_none();
    match (
        learn.course(),
        learn.course_error(),
        learn.grading_off_reason(),
    ) {
        (_, Some(e), _) => lines.push(Line::from(Span::styled(e.to_string(), theme::error()))),
        (None, None, Some(why)) => {
            lines.push(Line::from(Span::styled(
                "The assignments are not graded in this session.",
                theme::title(),
            )));
            lines.push(Line::from(why.to_string()));
        }
        (None, None, None) => lines.push(Line::from(if learn.grading() {
            "grading (cargo test -p spintop-lessons)…"
        } else {
            "not graded yet: the grader starts with the session"
        })),
        (Some(status), None, _) => {
            lines.push(Line::from(Span::styled(
                format!(
                    "{} {} of {} passing{}",
                    progress_bar(status.passing(), status.states.len(), 22),
                    status.passing(),
                    status.states.len(),
                    if learn.grading() {
                        "  (grading…)"
                    } else {
                        ""
                    }
                ),
                theme::title(),
            )));
            // This chapter's assignments; the whole course where it has none.
            let title = &learn.chapters()[learn.current()].title;
            let mine: Vec<_> = status
                .states
                .iter()
                .filter(|(a, _)| title.starts_with(a.chapter))
                .collect();
            let shown = if mine.is_empty() {
                status.states.iter().collect()
            } else {
                lines.push(Line::from(Span::styled(
                    format!("this chapter ({}):", mine.len()),
                    theme::label(),
                )));
                mine
            };
            for (a, s) in shown {
                let (mark, style) = match s {
                    State::Passing => ("✓", theme::info()),
                    State::Failing(_) | State::DoesNotCompile(_) | State::TimedOut(_) => {
                        ("✗", theme::error())
                    }
                    _ => ("·", theme::label()),
                };
                lines.push(Line::from(vec![
                    Span::styled(format!(" {mark} "), style),
                    Span::raw(format!(
                        "{:<14} {:<24} {:<24} ",
                        a.equation, a.function, a.file
                    )),
                    Span::styled(s.word(), style),
                ]));
            }
            let target = learn.hint_target();
            if let Some((a, s)) =
                target.and_then(|t| status.states.iter().find(|(a, _)| a.function == t.function))
            {
                lines.push(Line::from(""));
                lines.push(Line::from(Span::styled(
                    format!("next: {} {} ({})", a.equation, a.function, a.chapter),
                    theme::title(),
                )));
                match s {
                    State::Failing(report) => {
                        for l in report.lines().take(8) {
                            lines.push(Line::from(format!("  {l}")));
                        }
                    }
                    State::DoesNotCompile(e) | State::TimedOut(e) => {
                        lines.push(Line::from(format!("  {e}")))
                    }
                    _ => lines.push(Line::from(format!(
                        "  edit {}: its todo!() is still there; saving re-grades",
                        a.file
                    ))),
                }
            }
        }
    }
    if let Some(h) = learn.hint()
        && learn
            .hint_target()
            .is_some_and(|t| t.function == h.assignment.function)
    {
        let label = h.label();
        lines.push(Line::from(Span::styled(
            format!(
                "hint {} of {} ({label}) for {}:",
                h.rung,
                h.assignment.hints.len(),
                h.assignment.function
            ),
            theme::title(),
        )));
        lines.push(Line::from(format!("  {}", h.text)));
    }
    lines.push(Line::from(""));
    lines.push(Line::from(Span::styled(
        if grading_on {
            "saving a file under lessons/src re-grades it; h: a hint (one rung per press); any other key closes"
        } else {
            "h: a hint (one rung per press); any other key closes"
        },
        theme::label(),
    )));
    popup(frame, area, 100, " course ", lines);
}

fn draw_contents(frame: &mut Frame, area: Rect, learn: &Learn, selected: usize) {
    let mut items = Vec::new();
    let mut part = None;
    let mut row_of = Vec::new();
    let chapters = learn.chapters();
    for entry in learn.contents() {
        let c = &chapters[entry.chapter];
        if entry.heading.is_none() && c.part != part {
            part = c.part.clone();
            if let Some(p) = &part {
                items.push(ListItem::new(Line::from(Span::styled(
                    p.clone(),
                    theme::label(),
                ))));
            }
        }
        row_of.push(items.len());
        match &entry.heading {
            None => {
                let mark = if learn.visited()[entry.chapter] {
                    "✓"
                } else {
                    " "
                };
                let section = c
                    .section()
                    .map(|s| format!("§{s:<4}"))
                    .unwrap_or_else(|| "     ".into());
                items.push(ListItem::new(Line::from(Span::styled(
                    format!(" {mark} {section} {}", c.title),
                    theme::title(),
                ))));
            }
            Some((level, text)) => {
                let indent = if *level <= 2 { 11 } else { 14 };
                items.push(ListItem::new(Line::from(Span::styled(
                    format!("{}· {text}", " ".repeat(indent)),
                    theme::label(),
                ))));
            }
        }
    }
    let height = (items.len() as u16 + 2).min(area.height);
    let popup = centered(area, 76, height);
    let mut state = ListState::default().with_selected(row_of.get(selected).copied());
    frame.render_widget(Clear, popup);
    frame.render_stateful_widget(
        List::new(items)
            .highlight_style(Style::new().add_modifier(Modifier::REVERSED))
            .block(
                Block::bordered()
                    .border_type(BorderType::Rounded)
                    .title(" contents: ↑↓ Enter opens a chapter or a section, Esc closes "),
            ),
        popup,
        &mut state,
    );
}

/// Ω(t) of the probe's model by spintop's own closed form, the reference
/// the student's function is drawn against.
fn reference_omega(spec: &spintop_course::ProbeSpec, t: f64) -> [f64; 3] {
    use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
    let Ok(top) = SymmetricTop::new(spec.ratio, spec.tau) else {
        return [f64::NAN; 3];
    };
    let w0 = spintop::math::Vec3::from(spec.omega0);
    let w = if spec.function == "truncated_closed_form" {
        sym::truncated_closed_form(&top, &w0, t)
    } else {
        sym::reduced_closed_form(&top, &w0, t)
    };
    [w.x, w.y, w.z]
}

fn draw_yours(frame: &mut Frame, area: Rect, learn: &Learn) {
    use spintop_course::Probed;
    let Some((spec, probed)) = learn.yours() else {
        return;
    };
    let samples = match probed {
        Ok(Probed::Samples(s)) => s,
        Ok(Probed::Panicked(m)) => {
            let line = format!(" yours: {} panics: {m}", spec.function);
            frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
            return;
        }
        Err(e) => {
            let line = format!(" yours: {} could not be sampled: {e}", spec.function);
            frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
            return;
        }
    };
    let reference: Vec<(f64, [f64; 3])> = samples
        .iter()
        .map(|(t, _)| (*t, reference_omega(spec, *t)))
        .collect();
    let worst = samples
        .iter()
        .zip(&reference)
        .map(|((_, a), (_, b))| (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max))
        .fold(
            0.0,
            |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        );
    let scale = spec.omega0.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let agrees = worst <= 1e-9 * scale.max(1e-300);
    let curve = |data: &[(f64, [f64; 3])], i: usize| -> Vec<(f64, f64)> {
        data.iter().map(|(t, w)| (*t, w[i])).collect()
    };
    let series = [
        (curve(&reference, 0), theme::frame()),
        (curve(&reference, 1), theme::frame()),
        (curve(samples, 0), Style::new().fg(theme::OMEGA[0])),
        (curve(samples, 1), Style::new().fg(theme::OMEGA[1])),
    ];
    let datasets = series
        .iter()
        .map(|(data, style)| {
            Dataset::default()
                .marker(ratatui::symbols::Marker::Braille)
                .graph_type(GraphType::Line)
                .style(*style)
                .data(data)
        })
        .collect();
    let equation = if spec.function == "truncated_closed_form" {
        "(4.7)"
    } else {
        "(4.15)-(4.16)"
    };
    let verdict = if agrees {
        Span::styled(format!("agrees ✓ ({worst:.0e})"), theme::info())
    } else {
        Span::styled(format!("off by {worst:.1e} ✗"), theme::error())
    };
    let title = Line::from(vec![
        Span::styled(format!(" yours: {} ", spec.function), theme::title()),
        Span::styled("━Ω₁ ", Style::new().fg(theme::OMEGA[0])),
        Span::styled("━Ω₂ ", Style::new().fg(theme::OMEGA[1])),
        Span::styled(format!("vs {equation} grey │ "), theme::label()),
        verdict,
    ]);
    // Ω₁ and Ω₂ are drawn: they stay within Ω⊥₀.
    let perp = spec.omega0[0].hypot(spec.omega0[1]);
    let y = spintop::numbers::nice_ceiling(if perp > 0.0 { perp } else { scale } * 1.05);
    let chart = Chart::new(datasets)
        .block(Block::new().title(title))
        .legend_position(None)
        .x_axis(
            Axis::default()
                .style(theme::frame())
                .bounds([0.0, spec.t_end])
                .labels(["0".to_string(), format!("{:.0} t/τ", spec.t_end)]),
        )
        .y_axis(
            Axis::default()
                .style(theme::frame())
                .bounds([-y, y])
                .labels([format!("{}", -y), "0".into(), format!("{y}")]),
        );
    frame.render_widget(chart, area);
}
