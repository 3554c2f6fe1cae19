//! The boxes over the text: the help, the course panel and the contents.
//! Each scrolls when it is taller than the terminal ([`popup`]).

use super::super::{Learn, progress_bar};
use crate::term::{popup, theme};
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, List, ListItem, ListState};
use spintop_course::State;

/// The help's width, at most.
pub const HELP_WIDTH: u16 = 78;

/// The course panel's width, at most.
pub const COURSE_WIDTH: u16 = 100;

/// The help's lines: every key, grouped.
const HELP: [(&str, &str); 26] = [
    (
        "space f b",
        "a page down, a page up (also PgDn PgUp z, ^F ^V ^B)",
    ),
    ("d u", "half a page down, up (also ^D ^U)"),
    (
        "j k ↓ ↑",
        "a line (also e y, ^E ^N ^Y ^P); the mouse wheel three, once M lets it",
    ),
    (
        "g G < >",
        "the top, the end of the chapter (the frame says where: %, END)",
    ),
    (
        "/ ? ^R",
        "search forward, backward (? and ^R): this chapter first, then the book",
    ),
    (
        "n N",
        "the next match that way, or back, from where you are",
    ),
    ("← → c", "the previous, the next chapter; the contents"),
    (
        "in c",
        "↑ ↓ PgUp PgDn g G move; a chapter's number jumps; Enter opens",
    ),
    ("Tab ⇧Tab", "the next, the previous link, scrolled to"),
    (
        "Enter",
        "follow the link in focus (another chapter, or its heading)",
    ),
    (
        "⌫ Alt-←",
        "back to where a link, the contents or a search took you from",
    ),
    ("o", "library source whole, or folded to one line"),
    (
        "s w",
        "the scene full screen; the scene beside the text hidden or shown",
    ),
    ("x", "the next experiment of the chapter (▶ try this)"),
    ("p .", "pause the scene; one step while it is paused"),
    ("r l + -", "restart, log time, warp of the scene"),
    ("m v", "the scene's method; its next model, one at a time"),
    ("a", "the assignments (h there: a hint for the next one)"),
    (
        "M",
        "the mouse wheel scrolls, or the mouse selects text (Shift-drag always selects)",
    ),
    (
        "Esc",
        "close a panel, clear a search or a link (never quits)",
    ),
    (
        "h F1",
        "this help (↑ ↓ PgUp PgDn scroll it, any other key, q too, closes)",
    ),
    ("^Z", "suspend to the shell; fg comes back"),
    ("^L", "draw the whole screen again"),
    (
        "q Q ^C",
        "quit from the text (q closes a panel): the chapter reopens where you left it",
    ),
    ("", ""),
    (
        "--chapter",
        "the header's number (9), a section (4.2, §5, A), a file, a title's words",
    ),
];

/// The help: what `spintop learn` is, then every key.
pub fn help_lines(_learn: &Learn) -> Vec<Line<'static>> {
    let mut lines = vec![
        Line::from(Span::styled("spintop learn", theme::title())),
        Line::from("The book's chapters, each beside the scene it is about."),
        Line::from("Places marked ▶ try this are experiments: x runs the next one."),
        Line::from("Your place is kept as you read, whatever ends the terminal."),
        Line::from(""),
    ];
    for (k, what) in HELP {
        lines.push(Line::from(vec![
            Span::styled(format!("{k:>9}  "), theme::key()),
            Span::raw(what),
        ]));
    }
    lines
}

pub(super) fn draw_help(frame: &mut Frame, area: Rect, learn: &Learn, scroll: usize) {
    popup::draw(frame, area, HELP_WIDTH, " help ", help_lines(learn), scroll);
}

fn mark(s: &State) -> (&'static str, Style) {
    match s {
        State::Passing => ("✓", theme::info()),
        State::Failing(_) | State::DoesNotCompile(_) | State::TimedOut(_) => ("✗", theme::error()),
        _ => ("·", theme::label()),
    }
}

/// The panel's first lines: which course, and where its grading stands.
fn course_head(learn: &Learn, lines: &mut Vec<Line<'static>>) {
    let panel = learn.course_panel();
    if let Some(c) = panel.course() {
        lines.push(Line::from(vec![
            Span::styled("grading ", theme::label()),
            Span::styled(c.describe(), theme::title()),
        ]));
    }
    if let Some(g) = panel.grading() {
        lines.push(Line::from(Span::styled(
            format!("grading now: {}", g.describe()),
            theme::key(),
        )));
    }
    match (panel.status(), panel.error(), panel.off()) {
        (status, Some(e), _) => {
            lines.push(Line::from(Span::styled(
                match panel.graded_ago() {
                    Some(s) => format!("{e} (graded {s} s ago)"),
                    None => e.to_string(),
                },
                theme::error(),
            )));
            // A grading that could not run changes no grade: say whose these are.
            if let Some(status) = status {
                lines.push(Line::from(Span::styled(
                    format!(
                        "the grades below ({} of {} passing) are the last grading's that ran; saving a file grades again",
                        status.passing(),
                        status.states.len()
                    ),
                    theme::label(),
                )));
            }
        }
        (None, None, Some(why)) => {
            lines.push(Line::from(Span::styled(
                "The assignments are not graded in this session.",
                theme::title(),
            )));
            lines.push(Line::from(why.to_string()));
        }
        (None, None, None) if panel.grading().is_none() => {
            lines.push(Line::from(
                "not graded yet: the grader starts with the session",
            ));
        }
        (Some(status), None, _) => lines.push(Line::from(Span::styled(
            format!(
                "{} {} of {} passing{}",
                progress_bar(status.passing(), status.states.len(), 22),
                status.passing(),
                status.states.len(),
                panel
                    .graded_ago()
                    .map_or(String::new(), |s| format!(", graded {s} s ago"))
            ),
            theme::title(),
        ))),
        _ => {}
    }
}

/// The next assignment's diagnosis: what is wrong and how to grade it
/// alone, named as the course names its files.
fn course_next(learn: &Learn, lines: &mut Vec<Line<'static>>) {
    let panel = learn.course_panel();
    let Some(status) = panel.status() else { return };
    let course = panel.course();
    if let Some(place) = status.next_place() {
        let what = status.whole_copy_reason().unwrap_or_default();
        lines.push(Line::from(""));
        lines.push(Line::from(Span::styled(
            format!("next: fix {place} ({what})"),
            theme::title(),
        )));
        if let Some(l) = status.compile_error.as_ref().or(status.shortcut.as_ref()) {
            lines.push(Line::from(format!("  {}", l.message)));
        }
        return;
    }
    let target = learn.hint_target();
    let Some((a, s)) =
        target.and_then(|t| status.states.iter().find(|(a, _)| a.function == t.function))
    else {
        lines.push(Line::from(Span::styled(
            "every assignment passes: the course is done",
            theme::info(),
        )));
        return;
    };
    let file = course.map_or(a.file.to_string(), |c| c.file(a));
    lines.push(Line::from(""));
    lines.push(Line::from(Span::styled(
        format!(
            "next: {} {} in {file} ({})",
            a.equation, a.function, a.chapter
        ),
        theme::title(),
    )));
    // What is wrong first, then the command, then how to get the inputs
    // again: at 80×24 the command is on the panel's first screen. The
    // report's "stuck?" names the command line's hint; here it is a key.
    let (what, again): (Vec<&str>, Vec<&str>) = match s {
        State::Failing(report) => report
            .lines()
            .take(10)
            .filter(|l| !l.trim_start().starts_with("stuck?"))
            .partition(|l| !l.trim_start().starts_with("seed:")),
        _ => (Vec::new(), Vec::new()),
    };
    match s {
        State::Failing(_) => {
            for l in &what {
                lines.push(Line::from(format!("  {l}")));
            }
        }
        State::DoesNotCompile(e) | State::TimedOut(e) => lines.push(Line::from(format!("  {e}"))),
        State::Passing => {}
        _ => lines.push(Line::from(format!(
            "  edit {file}: its todo!() is still there; saving re-grades"
        ))),
    }
    if let Some(c) = course {
        // The command on a line of its own, so that it is broken at a
        // narrow width only when it is wider than the whole box.
        lines.push(Line::from(Span::styled(
            "  grade it alone:",
            theme::label(),
        )));
        lines.push(Line::from(Span::styled(
            format!("    {}", c.test_command(a)),
            theme::key(),
        )));
    }
    for l in &again {
        lines.push(Line::from(format!("  {l}")));
    }
    if matches!(s, State::Failing(_)) {
        lines.push(Line::from(Span::styled(
            "  stuck? h shows a hint (one rung at a time)",
            theme::label(),
        )));
    }
}

/// The course panel's lines at a terminal `width` wide: which course, the
/// next assignment's diagnosis first, a hint, then the list.
pub fn course_lines(learn: &Learn, width: u16) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    course_head(learn, &mut lines);
    course_next(learn, &mut lines);
    let panel = learn.course_panel();
    if let Some(h) = panel.hint()
        && learn
            .hint_target()
            .is_some_and(|t| t.function == h.assignment.function)
    {
        lines.push(Line::from(""));
        lines.push(Line::from(Span::styled(
            format!(
                "hint {} of {} ({}) for {}:",
                h.rung,
                h.assignment.hints.len(),
                h.label(),
                h.assignment.function
            ),
            theme::title(),
        )));
        lines.push(Line::from(format!("  {}", h.text)));
    }
    if let Some(status) = panel.status() {
        // This chapter's assignments first, then the whole course.
        let title = &learn.chapters()[learn.current()].title;
        let mine = status
            .states
            .iter()
            .filter(|(a, _)| title.starts_with(a.chapter))
            .count();
        lines.push(Line::from(""));
        lines.push(Line::from(Span::styled(
            format!(
                "all {} assignments ({mine} in this chapter, marked ▸):",
                status.states.len()
            ),
            theme::label(),
        )));
        let wide = width >= 100;
        for (a, s) in &status.states {
            let (m, style) = mark(s);
            let here = if title.starts_with(a.chapter) {
                "▸"
            } else {
                " "
            };
            let file = panel.course().map_or(a.file.to_string(), |c| c.file(a));
            let row = if wide {
                format!("{:<14} {:<25} {:<26} ", a.equation, a.function, file)
            } else {
                format!("{:<13} {:<25} ", a.equation, a.function)
            };
            lines.push(Line::from(vec![
                Span::styled(format!("{here}{m} "), style),
                Span::raw(row),
                Span::styled(status.word_of(s), style),
            ]));
        }
    }
    lines.push(Line::from(""));
    let sources = panel.course().map_or("src".to_string(), |c| c.path("src"));
    lines.push(Line::from(Span::styled(
        if panel.off().is_none() {
            format!(
                "saving a file under {sources}/ re-grades it; h: a hint (one rung per press); ↑ ↓ PgUp PgDn scroll; any other key closes"
            )
        } else {
            "h: a hint (one rung per press); ↑ ↓ scroll; any other key closes".to_string()
        },
        theme::label(),
    )));
    lines
}

pub(super) fn draw_course(frame: &mut Frame, area: Rect, learn: &Learn, scroll: usize) {
    let lines = course_lines(learn, area.width);
    popup::draw(frame, area, COURSE_WIDTH, " course ", lines, scroll);
}

/// The contents: every chapter with its number, its headings under it; the
/// list pages with the highlight.
pub(super) fn draw_contents(frame: &mut Frame, area: Rect, learn: &Learn, selected: usize) {
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
                    format!("{:>3} {mark} {section} {}", entry.chapter + 1, c.title),
                    theme::title(),
                ))));
            }
            Some((level, text)) => {
                let indent = if *level <= 2 { 15 } else { 18 };
                items.push(ListItem::new(Line::from(Span::styled(
                    format!("{}· {text}", " ".repeat(indent)),
                    theme::label(),
                ))));
            }
        }
    }
    let height = (items.len() as u16 + 2).min(area.height);
    let width = 80.min(area.width);
    let popup = Rect {
        x: area.x + (area.width - width) / 2,
        y: area.y + (area.height - height) / 2,
        width,
        height,
    };
    let mut state = ListState::default().with_selected(row_of.get(selected).copied());
    let typed = if learn.typed().is_empty() {
        String::new()
    } else {
        format!(" chapter {}… ", learn.typed())
    };
    frame.render_widget(Clear, popup);
    frame.render_stateful_widget(
        List::new(items)
            .highlight_style(Style::new().add_modifier(Modifier::REVERSED))
            .block(
                Block::bordered()
                    .border_type(BorderType::Rounded)
                    .title(" contents: ↑↓ PgUp PgDn, a number jumps, Enter opens, Esc closes ")
                    .title_bottom(Span::styled(typed, theme::key())),
            ),
        popup,
        &mut state,
    );
}
