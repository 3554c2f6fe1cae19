//! Lines that fit the terminal: header cells that shorten or leave whole,
//! footer keys that shorten or leave in a set order, and a greedy word wrap.
//! Nothing is ever cut inside a cell (a number, a key and its word).

use super::theme;
use ratatui::text::{Line, Span};

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

pub fn width(spans: &[Span]) -> usize {
    spans.iter().map(Span::width).sum()
}

/// Cells joined by separators, made to fit `width`: narrower separators
/// first, then the last cells' shorter renderings, last cell first, then
/// (when even the shortest do not fit) whole cells left out from the end,
/// so that nothing is ever cut in the middle.
pub fn fit_cells(cells: Vec<Cell>, width_: u16) -> Line<'static> {
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

pub fn label(s: impl Into<String>) -> Span<'static> {
    Span::styled(s.into(), theme::label())
}

pub fn value(s: impl Into<String>) -> Span<'static> {
    Span::styled(s.into(), theme::value())
}

/// Greedy word wrap (a word longer than the width stays whole on its line).
pub fn wrap_words(text: &str, width: usize) -> Vec<String> {
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

/// One key of a footer: the key and what it does, long and short.
pub struct Key {
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
pub const fn key(
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

/// The keys as one line that fits `width`: long words with wide gaps, else
/// short ones, else without the keys that leave first (`?` shows them all).
pub fn key_line(keys: &[&Key], width_: u16) -> Line<'static> {
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
