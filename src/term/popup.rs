//! A box of text over the screen that scrolls when it is taller than the
//! terminal (the help of both views, the course panel, the contents): the
//! state that changes it keeps only the first row shown, clamped by
//! [`max_scroll`], and the drawing shows where the reader is and that more
//! follows.

use super::theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType, Clear, Paragraph, Wrap};
use unicode_width::{UnicodeWidthChar, UnicodeWidthStr};

/// Where a line's continuations start: under the words after its first
/// gap of two spaces (a key's row, `label:   value`), or under its own
/// indent; `None` for a line of prose, which wraps as it is.
fn hanging_indent(text: &str, inner: usize) -> Option<usize> {
    let chars: Vec<char> = text.chars().collect();
    let leading = chars.iter().take_while(|c| **c == ' ').count();
    let mut i = leading;
    while i + 1 < chars.len() {
        if chars[i] == ' ' && chars[i + 1] == ' ' {
            let end = i + chars[i..].iter().take_while(|c| **c == ' ').count();
            let width = chars[..end].iter().collect::<String>().width();
            if width * 2 <= inner {
                return Some(width);
            }
            break;
        }
        i += 1;
    }
    (leading > 0 && leading * 2 <= inner).then_some(leading)
}

/// Characters with their styles, as spans again (one per run of a style).
fn spans(cells: &[(char, Style)]) -> Vec<Span<'static>> {
    let mut out: Vec<Span<'static>> = Vec::new();
    for &(c, style) in cells {
        match out.last_mut() {
            Some(last) if last.style == style => last.content.to_mut().push(c),
            _ => out.push(Span::styled(c.to_string(), style)),
        }
    }
    out
}

/// Lines wrapped to `inner` columns with their continuations hung under
/// their words ([`hanging_indent`]): a key's row under what the key does,
/// a diagnosis's `expected:  (…)` under its value. Prose and lines that fit
/// are left to the paragraph.
fn hang(lines: Vec<Line<'static>>, inner: u16) -> Vec<Line<'static>> {
    let inner = usize::from(inner.max(1));
    let mut out = Vec::with_capacity(lines.len());
    for line in lines {
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        let indent = match hanging_indent(&text, inner) {
            Some(indent) if text.width() > inner => indent,
            _ => {
                out.push(line);
                continue;
            }
        };
        let cells: Vec<(char, Style)> = line
            .spans
            .iter()
            .flat_map(|s| {
                s.content
                    .chars()
                    .map(move |c| (c, line.style.patch(s.style)))
            })
            .collect();
        // The head up to the indent, then the words after it.
        let mut at = 0;
        let mut width = 0;
        while at < cells.len() && width < indent {
            width += cells[at].0.width().unwrap_or(0);
            at += 1;
        }
        let room = inner - indent;
        let mut rows: Vec<Vec<(char, Style)>> = vec![Vec::new()];
        for word in cells[at..]
            .split(|(c, _)| *c == ' ')
            .filter(|w| !w.is_empty())
        {
            let row = rows.last_mut().expect("one row at least");
            let used: usize = row.iter().map(|(c, _)| c.width().unwrap_or(0)).sum();
            let more: usize = word.iter().map(|(c, _)| c.width().unwrap_or(0)).sum();
            if !row.is_empty() && used + 1 + more > room {
                rows.push(word.to_vec());
            } else {
                if let Some(&(_, style)) = row.last() {
                    row.push((' ', style));
                }
                row.extend_from_slice(word);
            }
        }
        for (i, row) in rows.iter().enumerate() {
            let mut head = if i == 0 {
                spans(&cells[..at])
            } else {
                vec![Span::raw(" ".repeat(indent))]
            };
            head.extend(spans(row));
            out.push(Line::from(head));
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
/// The scroll that shows `lines[range]` in a box `width` wide on a screen
/// of `size`: 0 when they are on its first screen, else the row they start
/// at (as far as the box scrolls).
pub fn scroll_to(
    size: (u16, u16),
    width: u16,
    lines: &[Line<'static>],
    range: std::ops::Range<usize>,
) -> usize {
    let inner = width.min(size.0).saturating_sub(2);
    let all = hang(lines.to_vec(), inner);
    let at = placed(Rect::new(0, 0, size.0, size.1), width, &all);
    let inner = at.width.saturating_sub(2);
    let upto = |k: usize| rows(&hang(lines[..k.min(lines.len())].to_vec(), inner), inner);
    let (start, end) = (upto(range.start), upto(range.end));
    if end <= usize::from(at.height.saturating_sub(2)) {
        0
    } else {
        start.min(max_scroll(size, width, lines))
    }
}

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
    // A margin too narrow to read (a column or two beside the box) would
    // show stray letters of what lies under it: the rows of the box are
    // cleared across the whole width then.
    let band = if area.width.saturating_sub(at.width) < 8 {
        Rect {
            x: area.x,
            width: area.width,
            ..at
        }
    } else {
        at
    };
    frame.render_widget(Clear, band);
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
    /// prose, and a row that fits, are left as they are; a labelled value
    /// goes on under the value.
    #[test]
    fn a_long_keys_row_hangs_under_its_words() {
        let row = Line::from(vec![
            Span::raw("   Enter  "),
            Span::raw("edit it: type a number, Enter applies, Esc cancels"),
        ]);
        let prose = Line::from("a line of prose that is longer than the box is wide");
        let short = Line::from(vec![Span::raw("q  "), Span::raw("quit")]);
        let out = hang(vec![row, prose.clone(), short], 30);
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
        let value = Line::from("    got:       (4.04e-1, 8.33e-1, 4.76e-1)");
        let shown: Vec<String> = hang(vec![value], 34).iter().map(text).collect();
        assert_eq!(
            shown,
            [
                "    got:       (4.04e-1, 8.33e-1,",
                "               4.76e-1)"
            ]
        );
    }
}
