//! A box of text over the screen that scrolls when it is taller than the
//! terminal (the help of both views, the course panel, the contents): the
//! state that changes it keeps only the first row shown, clamped by
//! [`max_scroll`], and the drawing shows where the reader is and that more
//! follows.

use super::theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};

/// The rows `lines` take once wrapped to `inner` columns, as the drawing
/// wraps them (at words: ratatui's own count).
pub fn rows(lines: &[Line], inner: u16) -> usize {
    Paragraph::new(lines.to_vec())
        .wrap(Wrap { trim: false })
        .line_count(inner.max(1))
}

/// Where a box at most `width` wide holding `lines` stands in `area`:
/// centred, as tall as its lines once wrapped, at most the area's height.
pub fn placed(area: Rect, width: u16, lines: &[Line]) -> Rect {
    let w = width.min(area.width);
    let total = rows(lines, w.saturating_sub(2)) as u16;
    let h = total.saturating_add(2).min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

/// The last first row of `lines` worth scrolling to in a terminal of
/// `size`: the one that shows the end at the bottom of the box.
pub fn max_scroll(size: (u16, u16), width: u16, lines: &[Line]) -> usize {
    let at = placed(Rect::new(0, 0, size.0, size.1), width, lines);
    let total = rows(lines, at.width.saturating_sub(2));
    total.saturating_sub(usize::from(at.height.saturating_sub(2)))
}

/// Draws the box with `lines` from row `scroll` (clamped), its title, and in
/// its bottom border where the reader is when not everything fits.
pub fn draw(
    frame: &mut Frame,
    area: Rect,
    width: u16,
    title: &str,
    lines: Vec<Line<'static>>,
    scroll: usize,
) {
    let at = placed(area, width, &lines);
    let max = max_scroll((area.width, area.height), width, &lines);
    let scroll = scroll.min(max);
    let mut block = Block::bordered()
        .border_type(BorderType::Rounded)
        .title(Span::styled(title.to_string(), theme::title()));
    if max > 0 {
        let total = rows(&lines, at.width.saturating_sub(2));
        let shown = usize::from(at.height.saturating_sub(2));
        let end = (scroll + shown).min(total);
        let more = if scroll < max {
            "↓ j/PgDn more"
        } else {
            "end; ↑ k/PgUp back"
        };
        block = block.title_bottom(Line::from(Span::styled(
            format!(" rows {}–{end} of {total}: {more} ", scroll + 1),
            theme::key(),
        )));
    }
    frame.render_widget(Clear, at);
    frame.render_widget(
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .scroll((u16::try_from(scroll).unwrap_or(u16::MAX), 0))
            .block(block),
        at,
    );
}
