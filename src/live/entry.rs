//! A number typed into the Ω₀ field: every character is taken or refused
//! with its reason, never dropped, and the text is read by the core's one
//! rule for numbers ([`spintop::numbers::parse_number`], which also refuses a
//! number that would underflow to 0). `0,1` is not silently `01`, `0x10` not
//! `10`, `1_000` not `1000`.

use spintop::math::Real;

/// The most characters the Ω₀ edit field takes (a double needs at most 24).
pub const EDIT_LIMIT: usize = 32;

/// Why a character or a text is not taken as a number.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EntryError {
    /// A decimal comma.
    #[error("“,” is not taken: a number here uses a point, 0.1 for a tenth")]
    Comma,
    /// A digit separator.
    #[error("“_” is not taken: type the digits together (1000) or in exponent form (1e3)")]
    Underscore,
    /// A hexadecimal prefix.
    #[error("“{0}” is not taken: numbers are decimal here (16, not 0x10)")]
    Radix(char),
    /// Any other character no number holds.
    #[error("“{0}” cannot be part of a number: digits, . e + - only; Esc cancels the edit")]
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

/// Whether `c` may be typed into a field that holds `buffer`: a character
/// no decimal number holds is refused, with what to type instead.
pub fn check_char(buffer: &str, c: char) -> Result<(), EntryError> {
    if buffer.chars().count() >= EDIT_LIMIT {
        return Err(EntryError::Full);
    }
    match c {
        '0'..='9' | '.' | 'e' | 'E' | '+' | '-' => Ok(()),
        ',' => Err(EntryError::Comma),
        '_' => Err(EntryError::Underscore),
        'x' | 'X' | 'b' | 'B' | 'o' | 'O' if buffer.trim_start_matches(['+', '-']) == "0" => {
            Err(EntryError::Radix(c))
        }
        other => Err(EntryError::NotInNumber(other)),
    }
}

/// The number in `text`, or why it is not one.
pub fn parse(text: &str) -> Result<Real, EntryError> {
    if text.trim().is_empty() {
        return Err(EntryError::Empty);
    }
    spintop::numbers::parse_number(text).map_err(EntryError::Number)
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
    }
}
