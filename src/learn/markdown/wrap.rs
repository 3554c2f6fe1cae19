//! Wrapping for the terminal: prose at spaces (an equation only between
//! its terms), code between tokens, table cells at words; and prose's
//! `m_em`-style names written as the equations write them.

use ratatui::style::Style;
use unicode_width::UnicodeWidthStr;

/// A word (or a space) waiting to be wrapped, and the link it is part of.
#[derive(Clone)]
pub(super) struct Piece {
    pub(super) text: String,
    pub(super) style: Style,
    pub(super) link: Option<usize>,
}

impl Piece {
    pub(super) fn new(text: impl Into<String>, style: Style) -> Self {
        Self {
            text: text.into(),
            style,
            link: None,
        }
    }
}

/// Greedy word wrap of plain text into lines of at most `width` columns.
pub(super) fn wrap_plain(text: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines = Vec::new();
    let mut current = String::new();
    for word in text.split_whitespace() {
        let mut word = word.to_string();
        while word.width() > width {
            // A word longer than the column is cut.
            let mut cut = 0;
            let mut w = 0;
            for (i, c) in word.char_indices() {
                w += c.to_string().width();
                if w > width {
                    break;
                }
                cut = i + c.len_utf8();
            }
            if !current.is_empty() {
                lines.push(std::mem::take(&mut current));
            }
            lines.push(word[..cut.max(1)].to_string());
            word = word[cut.max(1)..].to_string();
        }
        if !current.is_empty() && current.width() + 1 + word.width() > width {
            lines.push(std::mem::take(&mut current));
        }
        if !current.is_empty() {
            current.push(' ');
        }
        current.push_str(&word);
    }
    if !current.is_empty() || lines.is_empty() {
        lines.push(current);
    }
    lines
}

/// The mark that starts the continuation of a wrapped line of code.
pub const CONTINUATION: &str = "↪ ";

/// True for a character inside a token of code or output: a name, a number
/// (with its point and exponent) or a string of them.
fn token_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_' || c == '.' || c == '\''
}

/// A line of code or program output cut into pieces of at most `width`
/// columns (the first) and `width − 2` (the rest, after [`CONTINUATION`]),
/// between tokens: at a space when there is one, else after punctuation,
/// never inside a name or a number (`1.5e-3` is one token). Only a token
/// longer than a whole line is cut.
pub fn wrap_code(line: &str, width: usize) -> Vec<String> {
    let width = width.max(4);
    let chars: Vec<char> = line.chars().collect();
    // May the line break before chars[i]?
    let breakable = |i: usize| -> bool {
        if i == 0 || i >= chars.len() {
            return false;
        }
        let (a, b) = (chars[i - 1], chars[i]);
        // An exponent's sign belongs to its number: 1e-3, 2.5E+8.
        let exponent = |k: usize| {
            k >= 2
                && matches!(chars[k], '-' | '+')
                && matches!(chars[k - 1], 'e' | 'E')
                && chars[k - 2].is_ascii_digit()
                && chars.get(k + 1).is_some_and(char::is_ascii_digit)
        };
        if exponent(i) || exponent(i - 1) {
            return false;
        }
        !(token_char(a) && token_char(b))
    };
    let mut out = Vec::new();
    let mut start = 0;
    let mut first = true;
    while start < chars.len() {
        let room = if first { width } else { width - 2 };
        let mut used = 0;
        let mut end = start;
        while end < chars.len() {
            let w = UnicodeWidthStr::width(chars[end].encode_utf8(&mut [0; 4]) as &str);
            if used + w > room {
                break;
            }
            used += w;
            end += 1;
        }
        if end < chars.len() {
            // Prefer the last space, then the last token boundary.
            let space = (start + 1..=end)
                .rev()
                .find(|&i| chars[i - 1] == ' ' && chars.get(i).is_some_and(|c| *c != ' '));
            let boundary = (start + 1..=end).rev().find(|&i| breakable(i));
            end = space.or(boundary).unwrap_or(end.max(start + 1));
        }
        let piece: String = chars[start..end].iter().collect();
        out.push(if first {
            piece.trim_end().to_string()
        } else {
            piece.trim().to_string()
        });
        start = end;
        while start < chars.len() && chars[start] == ' ' && !first {
            start += 1;
        }
        first = false;
        while start < chars.len() && chars[start] == ' ' {
            start += 1;
        }
    }
    if out.is_empty() {
        out.push(String::new());
    }
    out
}

/// `sin`, `cos²`, `ln`, … written in prose: kept with the word after it.
pub(super) fn is_function_word(word: &str) -> bool {
    let w = word.trim_end_matches(|c: char| "²³⁻¹".contains(c));
    let last = w.rsplit(NBSP).next().unwrap_or(w);
    matches!(last, "sin" | "cos" | "tan" | "cot" | "ln" | "exp" | "log")
}

/// The no-break space that holds an equation's group together in prose.
pub(super) const NBSP: char = '\u{a0}';

/// `text` with the spaces inside parentheses, brackets and braces made
/// no-break, so that wrapping breaks an equation only between its terms.
pub(super) fn unbreakable_groups(text: &str) -> String {
    let mut depth = 0i32;
    text.chars()
        .map(|c| {
            match c {
                '(' | '[' | '{' | '⟨' => depth += 1,
                ')' | ']' | '}' | '⟩' => depth = (depth - 1).max(0),
                _ => {}
            }
            if c == ' ' && depth > 0 { NBSP } else { c }
        })
        .collect()
}

/// Pieces that are wider than `room` (an unbreakable group of an equation)
/// split again at their no-break spaces, so no line is wider than the text.
pub(super) fn split_too_long(pieces: Vec<Piece>, room: usize) -> Vec<Piece> {
    let mut out = Vec::with_capacity(pieces.len());
    for piece in pieces {
        if piece.text.width() > room && piece.text.contains(NBSP) {
            for (k, part) in piece.text.split(NBSP).enumerate() {
                if k > 0 {
                    out.push(Piece {
                        text: " ".into(),
                        style: piece.style,
                        link: piece.link,
                    });
                }
                out.push(Piece {
                    text: part.to_string(),
                    style: piece.style,
                    link: piece.link,
                });
            }
        } else {
            out.push(piece);
        }
    }
    out
}

/// Prose's `m_em`, `t_c`, `Z_AL`-style names written as the equations write
/// them (`mₑₘ`, `t_c` where a letter has no subscript form stays as it is),
/// so prose and equations use one notation.
pub fn prose_subscripts(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '_'
            && i >= 1
            && chars[i - 1].is_alphabetic()
            && (i < 2 || !chars[i - 2].is_alphanumeric())
        {
            let end = (i + 1..chars.len())
                .find(|&k| !chars[k].is_alphanumeric())
                .unwrap_or(chars.len());
            // One letter stays (R_x beside R_z, whose z has no subscript
            // form); digits and names of two or three letters (m_em) turn.
            let len = end - i - 1;
            let digits = chars[i + 1..end].iter().all(char::is_ascii_digit);
            let sub: Option<String> = ((2..=3).contains(&len) || (1..=3).contains(&len) && digits)
                .then(|| {
                    chars[i + 1..end]
                        .iter()
                        .map(|c| super::super::tex::subscript(*c))
                        .collect()
                })
                .flatten();
            if let Some(sub) = sub {
                out.push_str(&sub);
                i = end;
                continue;
            }
        }
        out.push(c);
        i += 1;
    }
    out
}

/// A caption without the colours the terminal does not show as the book
/// does: "(blue)", "(red)" and the like are left out.
pub fn without_colours(text: &str) -> String {
    const COLOURS: [&str; 8] = [
        "blue", "red", "green", "grey", "gray", "orange", "black", "pale",
    ];
    let mut out = text.to_string();
    for c in COLOURS {
        out = out.replace(&format!(" ({c})"), "");
    }
    out
}
