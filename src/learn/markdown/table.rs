//! Tables: columns as wide as their words allow, cells wrapped at words;
//! a table too narrow for that drawn row by row, as records.

use super::wrap::wrap_plain;
use super::{Renderer, Table, style};
use pulldown_cmark::Alignment;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use unicode_width::UnicodeWidthStr;

impl Renderer {
    pub(super) fn draw_table(&mut self, t: Table) {
        let columns = t.rows.iter().map(Vec::len).max().unwrap_or(0);
        if columns == 0 {
            return;
        }
        let indent = self.prefix.concat();
        // Cells may hold math or code spans; they are plain text here.
        let mut widths = vec![0usize; columns];
        for row in &t.rows {
            for (i, cell) in row.iter().enumerate() {
                widths[i] = widths[i].max(cell.width());
            }
        }
        // Shrink the widest columns until the table fits, each no narrower
        // than its longest word while any other can give (cells wrap at
        // words: "equatio/n" only when no column has room to spare).
        let floors: Vec<usize> = (0..columns)
            .map(|i| {
                t.rows
                    .iter()
                    .filter_map(|r| r.get(i))
                    .flat_map(|c| c.split_whitespace())
                    .map(UnicodeWidthStr::width)
                    .max()
                    .unwrap_or(1)
            })
            .collect();
        let budget = self
            .width
            .saturating_sub(indent.width() + 3 * columns)
            .max(columns * 4);
        if floors.iter().sum::<usize>() > budget && t.rows.len() > 1 {
            // Too narrow for its columns with words whole: row by row.
            self.draw_records(&t, &indent);
            return;
        }
        while widths.iter().sum::<usize>() > budget {
            let widest = |above_floor: bool| {
                widths
                    .iter()
                    .enumerate()
                    .filter(|(i, w)| !above_floor || **w > floors[*i])
                    .max_by_key(|(_, w)| **w)
                    .map(|(i, _)| i)
            };
            let Some(i) = widest(true).or_else(|| widest(false)) else {
                break;
            };
            if widths[i] <= 1 {
                break;
            }
            widths[i] -= 1;
        }
        for (r, row) in t.rows.iter().enumerate() {
            let cells: Vec<Vec<String>> = (0..columns)
                .map(|i| wrap_plain(row.get(i).map(String::as_str).unwrap_or(""), widths[i]))
                .collect();
            let height = cells.iter().map(Vec::len).max().unwrap_or(1);
            for k in 0..height {
                let mut spans = vec![Span::raw(indent.clone())];
                for i in 0..columns {
                    let text = cells[i].get(k).cloned().unwrap_or_default();
                    let pad = widths[i].saturating_sub(text.width());
                    let cell = match t.align.get(i) {
                        Some(Alignment::Right) => format!("{}{text}", " ".repeat(pad)),
                        Some(Alignment::Center) => {
                            format!("{}{text}{}", " ".repeat(pad / 2), " ".repeat(pad - pad / 2))
                        }
                        _ => format!("{text}{}", " ".repeat(pad)),
                    };
                    let s = if r == 0 {
                        Style::new().add_modifier(Modifier::BOLD)
                    } else {
                        Style::new()
                    };
                    spans.push(Span::styled(cell, s));
                    if i + 1 < columns {
                        spans.push(Span::styled(" │ ", style::rule()));
                    }
                }
                self.out.lines.push(Line::from(spans));
            }
            if r == 0 {
                let rule: Vec<String> = widths.iter().map(|w| "─".repeat(*w)).collect();
                self.out.lines.push(Line::from(Span::styled(
                    format!("{indent}{}", rule.join("─┼─")),
                    style::rule(),
                )));
            }
        }
        self.blank();
    }

    /// A table too wide for its columns, by rule: each row a record, its
    /// first cell in bold and the others under it as "heading: cell",
    /// wrapped at words.
    fn draw_records(&mut self, t: &Table, indent: &str) {
        let head = &t.rows[0];
        let width = self.width.saturating_sub(indent.width() + 2).max(10);
        for row in &t.rows[1..] {
            let first = row.first().map(String::as_str).unwrap_or("");
            for (k, l) in wrap_plain(first, width + 2).into_iter().enumerate() {
                let lead = if k == 0 { "" } else { "  " };
                self.out.lines.push(Line::from(vec![
                    Span::raw(format!("{indent}{lead}")),
                    Span::styled(l, Style::new().add_modifier(Modifier::BOLD)),
                ]));
            }
            for (i, cell) in row.iter().enumerate().skip(1) {
                let name = head.get(i).map(String::as_str).unwrap_or("");
                let text = if name.is_empty() {
                    cell.clone()
                } else {
                    format!("{name}: {cell}")
                };
                for (k, l) in wrap_plain(&text, width.saturating_sub(2).max(8))
                    .into_iter()
                    .enumerate()
                {
                    let lead = if k == 0 { "  " } else { "    " };
                    self.out
                        .lines
                        .push(Line::from(format!("{indent}{lead}{l}")));
                }
            }
        }
        self.blank();
    }
}
