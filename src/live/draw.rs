//! One model's column as both shells draw it: its chart of Ω(t), its
//! hodograph, the top in space and its live numbers (the live view shows
//! every column, `spintop learn` the ones its chapter is about), and the
//! clock's status.

use super::app::App;
use super::columns::Column;
pub use super::layout::COLUMN_WIDTH;
use super::widgets::{NumberBlock, OmegaSeries, drift, hodograph, numbers, top_in_space};
use crate::term::cells::width;
use crate::term::theme;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Paragraph, Wrap};

/// Above this width of a column the numbers get their long labels.
const WIDE: u16 = 55;

/// The columns `shown` of `app` in `area`: side by side when each gets
/// [`COLUMN_WIDTH`], else the one [`super::app::View::shown`] picks, its
/// title saying which of how many it is (also the scene of `spintop learn`).
/// `next` names the key that shows the next model there.
pub fn draw_columns(frame: &mut Frame, area: Rect, app: &App, shown: &[usize], next: &str) {
    let n = shown.len().max(1) as u16;
    if !super::layout::takes_turns(area.width, shown.len()) {
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

/// The status of the clock: running, running behind the warp, or paused.
pub fn status(app: &App) -> Span<'static> {
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

/// A column's title: the model's name and equations (with its gist where
/// it fits), then its marks (stopped, a stand-in, its place among models
/// shown one at a time).
fn column_title(
    column: &Column,
    width_of_area: u16,
    which: Option<(usize, usize)>,
    next: &str,
) -> Vec<Span<'static>> {
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
    let short_title = Span::raw(format!(" {name} {equations} ")).width();
    if let Some((at, n)) = which {
        // The long form where it fits beside the short title, else "1/2 v▸".
        let long = format!("│ model {} of {n} ({next}: next) ", at + 1);
        let fits = short_title + width(&marks) + Span::raw(long.as_str()).width()
            <= usize::from(width_of_area.saturating_sub(4));
        marks.push(Span::styled(
            if fits {
                long
            } else {
                format!("│ {}/{n} {next}▸ ", at + 1)
            },
            theme::key(),
        ));
    }
    let room = usize::from(width_of_area.saturating_sub(4))
        - width(&marks).min(usize::from(width_of_area.saturating_sub(4)));
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
    title
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
    let title = column_title(column, area.width, which, next);
    let block = Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Line::from(title));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    // NOTE: on a short terminal the last line of numbers (Ω itself, shown in
    // the chart anyway) gives its row to the pictures; a failure still shows.
    let roomy = inner.height >= 24;
    let wide = area.width >= WIDE;
    // Both blocks of numbers whole (shortened where they must be), the
    // drift block where it fits; see `number_blocks`.
    let (blocks, bottom) = number_blocks(column, wide, inner.width);
    let numbers_height = if column.failure().is_some() {
        // A stopped model's advice gets every row it wraps to (its remedy
        // is at its end), the chart keeping four.
        let advice = u16::try_from(bottom.line_count(inner.width)).unwrap_or(u16::MAX);
        (5 + advice).min(inner.height.saturating_sub(4)).max(6)
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
    frame.render_widget(
        series.chart(chart_area.height, app.view().monochrome),
        chart_area,
    );
    let [hodo_area, space_area] =
        Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
            .areas(pictures);
    frame.render_widget(hodograph(column, hodo_area), hodo_area);
    frame.render_widget(
        top_in_space(column, space_area, app.settings().euler0().is_none()),
        space_area,
    );
    let [rows, last] =
        Layout::vertical([Constraint::Length(5), Constraint::Fill(1)]).areas(numbers_area);
    let widths: Vec<u16> = blocks.iter().map(|b| b.width).collect();
    let mut keep = blocks.len();
    // Blocks one column apart at least.
    while keep > 2.min(blocks.len())
        && widths[..keep].iter().sum::<u16>() + keep as u16 - 1 > rows.width
    {
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

/// The blocks of numbers of `column` for a row `room` columns wide, and its
/// last line: the two first blocks always, their numbers shortened to three
/// digits when the full ones would not fit side by side (a row is never
/// lost); the drift block after them where it fits whole. The last line is
/// the widest of its forms that fits (a failure's advice is wrapped whole).
fn number_blocks(column: &Column, wide: bool, room: u16) -> (Vec<NumberBlock>, Paragraph<'static>) {
    let fits = |l: &NumberBlock, r: &NumberBlock| l.width + 1 + r.width <= room;
    let (mut l, mut r, mut last) = numbers(column, wide, false);
    if !fits(&l, &r) {
        (l, r, last) = numbers(column, wide, true);
    }
    if !fits(&l, &r) && wide {
        (l, r, last) = numbers(column, false, true);
    }
    if !fits(&l, &r) {
        // Too narrow for two blocks even shortened (a scene beside the
        // text of `learn`): the left one whole, never a number cut.
        let (l, _, last) = numbers(column, wide, false);
        return (vec![l], bottom_line(column, last, room));
    }
    let mut blocks = vec![l, r];
    if column.closed_form_error().is_none() {
        blocks.push(drift(column));
    }
    let bottom = bottom_line(column, last, room);
    (blocks, bottom)
}

/// The last line of numbers: a failure's advice wrapped whole, else the
/// widest of its forms that fits in `room`.
fn bottom_line(column: &Column, last: Vec<Line<'static>>, room: u16) -> Paragraph<'static> {
    if column.failure().is_some() {
        return Paragraph::new(last).wrap(Wrap { trim: true });
    }
    let n = last.len();
    let line = last
        .into_iter()
        .enumerate()
        .find(|(i, line)| line.width() <= usize::from(room) || *i + 1 == n)
        .map(|(_, line)| line)
        .unwrap_or_default();
    Paragraph::new(line)
}
