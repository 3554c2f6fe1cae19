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
use unicode_width::UnicodeWidthStr;

/// A key's row (two spans: the key padded with spaces, then what it does)
/// wrapped to `inner` columns with its continuations under the words, not
/// under the key; other lines as they are.
fn hang(lines: Vec<Line<'static>>, inner: u16) -> Vec<Line<'static>> {
    let inner = usize::from(inner.max(1));
    let mut out = Vec::with_capacity(lines.len());
    for line in lines {
        let [key, what] = line.spans.as_slice() else {
            out.push(line);
            continue;
        };
        let indent = key.content.width();
        if !key.content.ends_with(' ')
            || indent + what.content.width() <= inner
            || indent * 2 > inner
        {
            out.push(line);
            continue;
        }
        let room = inner - indent;
        let mut rows: Vec<String> = vec![String::new()];
        for word in what.content.split(' ') {
            let row = rows.last_mut().expect("one row at least");
            if !row.is_empty() && row.width() + 1 + word.width() > room {
                rows.push(word.to_string());
            } else {
                if !row.is_empty() {
                    row.push(' ');
                }
                row.push_str(word);
            }
        }
        for (i, row) in rows.into_iter().enumerate() {
            let head = if i == 0 {
                key.clone()
            } else {
                Span::raw(" ".repeat(indent))
            };
            out.push(Line::from(vec![head, Span::styled(row, what.style)]));
        }
    }
    out
}

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
pub fn max_scroll(size: (u16, u16), width: u16, lines: &[Line<'static>]) -> usize {
    let lines = &hang(lines.to_vec(), width.min(size.0).saturating_sub(2));
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
    let lines = hang(lines, width.min(area.width).saturating_sub(2));
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

#[cfg(test)]
mod tests {
    use super::*;

    fn text(line: &Line) -> String {
        line.spans.iter().map(|s| s.content.as_ref()).collect()
    }

    /// A key's row too long for the box goes on under its words; a line of
    /// prose, and a row that fits, are left as they are.
    #[test]
    fn a_long_keys_row_hangs_under_its_words() {
        let row = Line::from(vec![
            Span::raw("   Enter  "),
            Span::raw("edit it: type a number, Enter applies, Esc cancels"),
        ]);
        let prose = Line::from("a line of prose that is longer than the box is wide");
        let short = Line::from(vec![Span::raw("q  "), Span::raw("quit")]);
        let out = hang(vec![row, prose.clone(), short.clone()], 30);
        let shown: Vec<String> = out.iter().map(text).collect();
        assert_eq!(
            shown,
            [
                "   Enter  edit it: type a",
                "          number, Enter",
                "          applies, Esc cancels",
                &text(&prose),
                "q  quit",
            ]
        );
        assert!(shown[..3].iter().all(|r| r.width() <= 30), "{shown:?}");
    }
}
