//! A number typed into the Ω₀ field: every character is kept as typed
//! (never dropped: a paste of `0,1` must not become `01`), one that no
//! decimal number holds is said at once with its reason, and Enter reads
//! the text by the core's one rule for numbers
//! ([`spintop::numbers::parse_number`], which also refuses a number that
//! would underflow to 0), refusing `0,1`, `0x10` and `1_000` by name with the
//! field left open to correct.

use spintop::math::Real;

/// The most characters the Ω₀ edit field takes (a double needs at most 24).
pub const EDIT_LIMIT: usize = 32;

/// Why a character or a text is not taken as a number.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EntryError {
    /// A decimal comma.
    #[error("“,” is no part of a number here: use a point, 0.1 for a tenth")]
    Comma,
    /// A digit separator.
    #[error(
        "“_” is no part of a number here: type the digits together (1000) or in exponent form (1e3)"
    )]
    Underscore,
    /// A hexadecimal prefix.
    #[error("“0{0}” is no part of a number here: numbers are decimal (16, not 0x10)")]
    Radix(char),
    /// Any other character no number holds.
    #[error(
        "“{0}” cannot be part of a number: digits, . e + - only; Backspace corrects, Esc cancels the edit"
    )]
    NotInNumber(char),
    /// The field is full.
    #[error("the field holds {EDIT_LIMIT} characters; Backspace edits, Enter applies")]
    Full,
    /// Enter on an empty field.
    #[error("type a number first")]
    Empty,
    /// The text is not a finite number the core takes (`1e`, `1.2.3`, `1e-400`).
    #[error("{0}")]
    Number(String),
}

/// Why `c`, typed after `before`, is no part of a decimal number (`None`:
/// it may be), with what to type instead.
fn foreign(before: &str, c: char) -> Option<EntryError> {
    match c {
        '0'..='9' | '.' | 'e' | 'E' | '+' | '-' => None,
        ',' => Some(EntryError::Comma),
        '_' => Some(EntryError::Underscore),
        'x' | 'X' | 'b' | 'B' | 'o' | 'O' if before.trim_start_matches(['+', '-']) == "0" => {
            Some(EntryError::Radix(c))
        }
        other => Some(EntryError::NotInNumber(other)),
    }
}

/// Whether `c` typed into a field that holds `buffer` makes a number so
/// far: `Full` when there is no room (the one case it is not kept), else
/// the reason a character no decimal number holds is wrong.
pub fn check_char(buffer: &str, c: char) -> Result<(), EntryError> {
    if buffer.chars().count() >= EDIT_LIMIT {
        return Err(EntryError::Full);
    }
    foreign(buffer, c).map_or(Ok(()), Err)
}

/// The number in `text`, or why it is not one.
pub fn parse(text: &str) -> Result<Real, EntryError> {
    let text = text.trim();
    if text.is_empty() {
        return Err(EntryError::Empty);
    }
    if let Some(e) = first_foreign(text) {
        return Err(e);
    }
    spintop::numbers::parse_number(text).map_err(EntryError::Number)
}

/// The first character of `text` no decimal number holds, as the reason.
pub fn first_foreign(text: &str) -> Option<EntryError> {
    let text = text.trim();
    text.char_indices()
        .find_map(|(at, c)| foreign(&text[..at], c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_character_no_number_holds_is_refused_with_its_reason() {
        assert_eq!(check_char("0", ','), Err(EntryError::Comma));
        assert_eq!(check_char("0", 'x'), Err(EntryError::Radix('x')));
        assert_eq!(check_char("1", '_'), Err(EntryError::Underscore));
        assert_eq!(check_char("1", 'q'), Err(EntryError::NotInNumber('q')));
        for c in "0123456789.eE+-".chars() {
            assert_eq!(check_char("1", c), Ok(()), "{c}");
        }
        let full = "1".repeat(EDIT_LIMIT);
        assert_eq!(check_char(&full, '1'), Err(EntryError::Full));
    }

    #[test]
    fn a_text_is_read_by_the_cores_rule_underflow_refused() {
        assert_eq!(parse("0.25"), Ok(0.25));
        assert_eq!(parse("  "), Err(EntryError::Empty));
        assert!(matches!(parse("1e-400"), Err(EntryError::Number(m)) if m.contains("smallest")));
        assert!(matches!(parse("1.2.3"), Err(EntryError::Number(_))));
        // What a paste brings in is refused whole, by name.
        assert_eq!(parse("0,1"), Err(EntryError::Comma));
        assert_eq!(parse("0x10"), Err(EntryError::Radix('x')));
        assert_eq!(parse("1_000"), Err(EntryError::Underscore));
        assert_eq!(parse("0.1q"), Err(EntryError::NotInNumber('q')));
    }
}
