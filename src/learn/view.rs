//! The screen of `spintop learn`. Drawing only reads the [`Learn`] state.
//!
//! ```text
//! spintop learn │ Section 4.2: the reduced top │ 6 of 25 │ course …
//! ╭ section-4-2.md ────────────╮ scene: what it is
//! │ the chapter, wrapped        ┃ its parameters, paused or running
//! │ …                           │ the live models' column(s), or the
//! ╰──────────── 25% lines 1–20 ─╯ chapter's own scene
//! status: the last thing done (an experiment, a search, a pause)
//! keys
//! ```

mod panels;
mod yours;

pub use panels::{COURSE_WIDTH, HELP_WIDTH, course_lines, help_lines};

use super::scene::Spec;
use super::scene::draw::{draw_orbit, draw_shell};
use super::scene::{Stage, playback_status};
use super::{Learn, Mode, text_inner};
use crate::live::draw::{draw_columns, status as live_status};
use crate::term::cells::{Cell, Key, fit_cells, key, key_line};
use crate::term::theme;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Paragraph, Wrap};

/// The keys of the footer.
const KEYS: [Key; 11] = [
    key("h", "help", "h", "help", 0),
    key("q", "quit", "q", "quit", 0),
    key("space b", "page", "spc b", "page", 3),
    key("/ ?", "search", "/?", "find", 5),
    key("← →", "chapter", "←→", "chapter", 6),
    key("c", "contents", "c", "contents", 7),
    key("x", "next experiment", "x", "try", 8),
    key("s", "scene full screen", "s", "scene", 9),
    key("p", "pause scene", "p", "pause", 4),
    key("o", "unfold code", "o", "code", 2),
    // The course stays at every width: a student's way to the grades.
    key("a", "assignments", "a", "course", 0),
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
    if let Some(mut text) = panes.text {
        // A message of more rows than one takes them from the text's
        // bottom, above its frame line: the position stays in sight.
        let more = message_rows(learn, panes.status.width).saturating_sub(1);
        text.height = text.height.saturating_sub(more).max(3.min(text.height));
        draw_text(frame, text, learn);
    }
    if let Some(scene) = panes.scene {
        draw_scene(frame, scene, learn);
    }
    draw_status(frame, panes.status, learn, panes.scene.is_some());
    draw_footer(frame, panes.footer, learn, panes.scene.is_some());
    match learn.mode() {
        Mode::Help(scroll) => panels::draw_help(frame, area, learn, *scroll),
        Mode::Course(scroll) => panels::draw_course(frame, area, learn, *scroll),
        Mode::Contents(sel) => panels::draw_contents(frame, area, learn, *sel),
        _ => {}
    }
}

/// The course's cell in the header: "course 3 of 22 ▰▱…", or how far its
/// grading has got; short forms keep it on a narrow screen.
fn course_cell(learn: &Learn) -> Option<Cell> {
    let panel = learn.course_panel();
    let styled = |s: String| vec![Span::styled(s, theme::key())];
    let clock = |g: &spintop_course::building::Snapshot| {
        let s = g.elapsed.as_secs();
        format!("{}:{:02}", s / 60, s % 60)
    };
    let (long, short) = match (panel.status(), panel.grading(), panel.error()) {
        (_, _, Some(_)) => ("course: cannot grade".to_string(), "course ✗".to_string()),
        (Some(s), grading, _) => {
            let (k, n) = (s.passing(), s.states.len());
            let busy = grading
                .as_ref()
                .map_or(String::new(), |g| format!(" grading {}", clock(g)));
            (
                format!("course {k} of {n} {}{busy}", super::progress_bar(k, n, 10)),
                format!("course {k}/{n}{busy}"),
            )
        }
        (None, Some(g), _) => {
            let what = match g.units {
                Some((done, total)) => format!("compiling {done} of {total}, "),
                None => String::new(),
            };
            (
                format!("course: grading, {what}{}", clock(&g)),
                format!("grading {}", clock(&g)),
            )
        }
        (None, None, None) => return None,
    };
    Some(Cell::or(styled(long), styled(short)))
}

fn draw_header(frame: &mut Frame, area: Rect, learn: &Learn) {
    let chapter = &learn.chapters()[learn.current()];
    let seen = learn.visited().iter().filter(|v| **v).count();
    let n = learn.chapters().len();
    let mut cells = vec![
        Cell::fixed(vec![Span::styled(" spintop learn ", theme::status(false))]),
        // The title shortens before the course would be left out: at 80
        // columns beside the scene the header keeps the course's count.
        Cell(
            [
                chapter.title.clone(),
                shortened(&chapter.title, 30),
                chapter
                    .section()
                    .map_or_else(|| format!("{}", learn.current() + 1), |s| format!("§{s}")),
            ]
            .into_iter()
            .map(|t| vec![Span::styled(t, theme::title())])
            .collect(),
        ),
    ];
    // The course before the chapter's count: the count shortens first.
    cells.extend(course_cell(learn));
    cells.push(Cell::or(
        vec![Span::styled(
            format!("chapter {} of {n}, {seen} opened", learn.current() + 1),
            theme::label(),
        )],
        vec![Span::styled(
            format!("{}/{n}", learn.current() + 1),
            theme::label(),
        )],
    ));
    frame.render_widget(Paragraph::new(fit_cells(cells, area.width)), area);
}

/// `line` with the byte ranges `marks` of its text styled: `(range, style)`.
fn highlight(line: &Line<'static>, marks: &[(std::ops::Range<usize>, Style)]) -> Line<'static> {
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
        for (m, _) in marks {
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
            let at = offset + a;
            let style = marks
                .iter()
                .find(|(m, _)| m.start <= at && at < m.end)
                .map_or(span.style, |(_, s)| span.style.patch(*s));
            spans.push(Span::styled(text[a..b].to_string(), style));
        }
        offset = end;
    }
    Line::from(spans)
}

/// The marks on line `i`: the search's matches (the current one brighter)
/// and the link in focus.
fn marks_on(learn: &Learn, i: usize) -> Vec<(std::ops::Range<usize>, Style)> {
    let mut marks = Vec::new();
    if let Some(s) = learn.search() {
        for (k, m) in s.matches.iter().enumerate() {
            let style = if s.at == Some(k) {
                // Bold and underlined besides the colour: without colour
                // (NO_COLOR) the match is still told from the others.
                Style::new()
                    .fg(ratatui::style::Color::Black)
                    .bg(ratatui::style::Color::Yellow)
                    .add_modifier(Modifier::BOLD | Modifier::UNDERLINED)
            } else {
                Style::new().add_modifier(Modifier::REVERSED)
            };
            for (_, r) in m.0.iter().filter(|(l, _)| *l == i) {
                marks.push((r.clone(), style));
            }
        }
    }
    if let Some(link) = learn
        .focused_link()
        .and_then(|k| learn.rendered().links.get(k))
    {
        for (_, r) in link.parts.iter().filter(|(l, _)| *l == i) {
            marks.push((
                r.clone(),
                Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD),
            ));
        }
    }
    marks
}

/// Where the reader is, as `less` says it: the share of the chapter read
/// and the lines shown, or END.
pub fn position(top: usize, shown: usize, total: usize) -> String {
    if total == 0 {
        return " empty ".into();
    }
    let last = (top + shown).min(total);
    if last >= total {
        return format!(" lines {}–{last} of {total} END ", top + 1);
    }
    format!(
        " {}% lines {}–{last} of {total} ",
        100 * last / total,
        top + 1
    )
}

fn draw_text(frame: &mut Frame, area: Rect, learn: &Learn) {
    let inner = text_inner(area);
    let lines = &learn.rendered().lines;
    let total = lines.len();
    let top = learn.scroll().min(total);
    let end = (top + usize::from(inner.height)).min(total);
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Span::styled(
            format!(" {} ", learn.chapters()[learn.current()].file),
            theme::label(),
        ))
        .title_bottom(
            Line::from(Span::styled(
                position(top, usize::from(inner.height), total),
                theme::label(),
            ))
            .right_aligned(),
        );
    frame.render_widget(block, area);
    let shown: Vec<Line> = (top..end)
        .map(|i| highlight(&lines[i], &marks_on(learn, i)))
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
                let [scene, mine] =
                    Layout::vertical([Constraint::Fill(2), Constraint::Fill(1)]).areas(rest);
                yours::draw_yours(frame, mine, learn);
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
pub fn shortened(text: &str, width: u16) -> String {
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
        _ if learn.searching().is_some() => Line::from(Span::styled(
            shortened(
                &format!(" {}", learn.searching().unwrap_or_default()),
                area.width,
            ),
            theme::info(),
        )),
        (Mode::Search(q, forward), _) => search_line(learn, q, *forward, area.width),
        // A message too long for the line is shown whole, over the rows
        // above it (up to three), never cut.
        (_, Some((m, refused))) => {
            let style = if *refused {
                theme::error()
            } else {
                theme::info()
            };
            return draw_message(frame, area, m, style);
        }
        _ => scene_status(learn, scene_shown, area.width),
    };
    frame.render_widget(Paragraph::new(line), area);
}

/// The search prompt: `/` or `?`, the field scrolled so that its end
/// (what was typed last, and the cursor) is always in sight, then what the
/// keys do where it fits. A full field says its limit before the text: no
/// character is dropped unannounced.
fn search_line(learn: &Learn, q: &str, forward: bool, width: u16) -> Line<'static> {
    let width = usize::from(width);
    let mut spans = vec![Span::styled(
        if forward { " /" } else { " ?" },
        theme::key(),
    )];
    let mut room = width.saturating_sub(2);
    if q.chars().count() >= crate::learn::search::LONGEST {
        let long = format!(
            "(full: {} characters; Ctrl-U clears) ",
            crate::learn::search::LONGEST
        );
        // The note leaves the field a third of the line at least.
        let note = if Span::raw(long.as_str()).width() + room / 3 <= room {
            long
        } else {
            "(full; ^U clears) ".to_string()
        };
        room = room.saturating_sub(Span::raw(note.as_str()).width());
        spans.push(Span::styled(note, theme::error()));
    }
    let field = field_end(q, room);
    room = room.saturating_sub(Span::raw(field.as_str()).width());
    spans.push(Span::styled(field, theme::selected()));
    let hint = match learn.search() {
        Some(last) if q.is_empty() => format!(
            "  Enter finds (alone: “{}” again), Esc cancels{}",
            last.query,
            if forward { "" } else { "; backward" }
        ),
        _ if !forward => "  Enter finds backward, Ctrl-U clears, Esc cancels".to_string(),
        _ => "  Enter finds, Ctrl-U clears, Esc cancels".to_string(),
    };
    if q.chars().count() < crate::learn::search::LONGEST && room > 8 {
        let hint = shortened(&hint, u16::try_from(room).unwrap_or(u16::MAX));
        spans.push(Span::styled(hint, theme::label()));
    }
    Line::from(spans)
}

/// The end of a typed field that fits `room` columns with its cursor `▏`:
/// the whole text when it fits, else "…" and as much of its end as fits
/// (what is typed last stays in sight, as a shell's line scrolls).
pub fn field_end(text: &str, room: usize) -> String {
    if Span::raw(text).width() < room {
        return format!("{text}▏");
    }
    let mut tail = Vec::new();
    let mut used = 2;
    for c in text.chars().rev() {
        let w = unicode_width::UnicodeWidthChar::width(c).unwrap_or(0);
        if used + w > room {
            break;
        }
        used += w;
        tail.push(c);
    }
    let tail: String = tail.into_iter().rev().collect();
    format!("…{tail}▏")
}

/// The rows the status message takes (1 to 3), as [`draw_message`] wraps it.
fn message_rows(learn: &Learn, width: u16) -> u16 {
    match (learn.mode(), learn.message()) {
        _ if learn.searching().is_some() => 1,
        (Mode::Search(..), _) | (_, None) => 1,
        (_, Some((m, _))) => {
            let p = Paragraph::new(Line::from(m.as_str())).wrap(Wrap { trim: false });
            u16::try_from(p.line_count(width.saturating_sub(1)))
                .unwrap_or(u16::MAX)
                .clamp(1, 3)
        }
    }
}

/// A status message, wrapped upward over the text when one row is too
/// narrow for it (the last rows of the text come back with the next key),
/// every row one column in from the edge.
fn draw_message(frame: &mut Frame, area: Rect, text: &str, style: Style) {
    let width = area.width.saturating_sub(1);
    let paragraph = Paragraph::new(Line::from(Span::styled(text.to_string(), style)))
        .wrap(Wrap { trim: false });
    let rows = u16::try_from(paragraph.line_count(width))
        .unwrap_or(u16::MAX)
        .clamp(1, 3)
        .min(area.y + 1);
    let at = Rect {
        y: area.y + 1 - rows,
        height: rows,
        ..area
    };
    if rows > 1 {
        frame.render_widget(ratatui::widgets::Clear, at);
    }
    let paragraph = if usize::from(rows) < paragraph.line_count(width) {
        Paragraph::new(Line::from(Span::styled(
            shortened(text, width.saturating_mul(rows)),
            style,
        )))
        .wrap(Wrap { trim: false })
    } else {
        paragraph
    };
    let inset = Rect {
        x: at.x + 1,
        width,
        ..at
    };
    frame.render_widget(paragraph, inset);
}

/// The scene's clock and state, when nothing else is said.
fn scene_status(learn: &Learn, scene_shown: bool, width: u16) -> Line<'static> {
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
                spans.push(Span::styled(
                    "  (s shows it, w beside the text)",
                    theme::label(),
                ));
            }
        }
        None => {
            // A chapter without a scene: its note whole when it fits, else
            // its last clause (the command it names) rather than a cut one.
            let about = learn.scene_info().describe();
            let last = about.rsplit("; ").next().unwrap_or(&about).to_string();
            let choices = [
                format!(" scene {about}"),
                format!(" {about}"),
                format!(" no scene: {last}"),
                format!(" {last}"),
            ];
            let fits = choices
                .iter()
                .find(|c| Span::raw(c.as_str()).width() <= usize::from(width));
            let text = fits.map_or_else(|| shortened(&choices[3], width), Clone::clone);
            return Line::from(Span::styled(text, theme::label()));
        }
    }
    Line::from(spans)
}

fn draw_footer(frame: &mut Frame, area: Rect, learn: &Learn, scene_shown: bool) {
    let has_scene = !matches!(learn.stage(), Stage::None);
    let keys: Vec<&Key> = KEYS
        .iter()
        .filter(|k| {
            let scene_key = matches!(k.key, "s" | "p" | "x");
            (has_scene || !scene_key)
                && !(k.key == "s" && scene_shown && *learn.mode() != Mode::Scene)
        })
        .collect();
    frame.render_widget(Paragraph::new(key_line(&keys, area.width)), area);
}
