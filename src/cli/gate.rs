//! The gate: the one way a command's output reaches stdout.
//!
//! [`super::run()`] hands each command a [`Gate`] and nothing else to write its
//! output with (stderr stays for warnings), so no command can skip it:
//!
//! - a result ([`Gate::emit`]) is checked first, every number in its
//!   JSON form finite ([`first_non_finite`]); a number that is not, or a value
//!   the check cannot walk, stops the command with exit 3 and nothing written;
//!   then it is written in its format ([`spintop::output::write`]), and a run
//!   that stopped early says so in every format (`# stopped: …` after a table
//!   or a CSV file, `"stopped"` in JSON) and exits 3;
//! - prose (listings, progress, charts: `write!` on the gate) is refused the
//!   moment it holds a number printed as `NaN` or `inf`, again with exit 3.
//!
//! `tests/cli/gate.rs` lists every command and fails on one that writes around
//! the gate.

use super::CliError;
use serde::Serialize;
use spintop::numbers::non_finite_word;
use spintop::output::check::first_non_finite;
use spintop::output::{Format, Output};
use std::io::{self, Write};

/// Where a command's output goes, checked.
pub struct Gate<'a> {
    out: &'a mut dyn Write,
}

impl<'a> Gate<'a> {
    /// A gate in front of `out` (stdout).
    pub(crate) fn new(out: &'a mut dyn Write) -> Self {
        Self { out }
    }

    /// Check `value`, write it in `format`, and exit 3 if its run stopped
    /// before giving all that was asked (after writing what it did give).
    pub fn emit<T: Output + ?Sized>(&mut self, value: &T, format: Format) -> Result<(), CliError> {
        // The command line's gate: advice names flags (a scene's answer
        // names its keys whatever it is told).
        self.check(value, &value.advice(spintop::output::Entry::CommandLine))?;
        spintop::output::write(self.out, value, format)?;
        match value.stopped() {
            Some(stop) => Err(CliError::Stopped(stop.message)),
            None => Ok(()),
        }
    }

    /// Check the numbers behind prose the command writes next (the rows
    /// behind a chart and a table): every one finite, or exit 3 naming where,
    /// with `advice`.
    pub fn check<T: Serialize + ?Sized>(
        &mut self,
        value: &T,
        advice: &str,
    ) -> Result<(), CliError> {
        match first_non_finite(value) {
            Ok(None) => Ok(()),
            Ok(Some(path)) => Err(CliError::Stopped(format!(
                "the result is not a finite number at {path}: the inputs are beyond what a double can carry through this computation; {advice}"
            ))),
            Err(e) => Err(CliError::Stopped(format!("{e}; nothing was written"))),
        }
    }
}

/// Prose that printed a number as NaN or an infinity.
#[derive(Debug)]
pub(crate) struct NonFiniteText(String);

impl std::fmt::Display for NonFiniteText {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the output would print a number as `{}`: a result is not finite, so nothing more is written",
            self.0
        )
    }
}

impl std::error::Error for NonFiniteText {}

impl Write for Gate<'_> {
    /// Prose: written as it comes, unless it holds a non-finite number.
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if let Some(word) = non_finite_word(&String::from_utf8_lossy(buf)) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                NonFiniteText(word.to_string()),
            ));
        }
        self.out.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prose_with_a_non_finite_number_is_refused() {
        for (text, word) in [
            ("error NaN at t = 3", Some("NaN")),
            ("rate inf", Some("inf")),
            ("(-inf, 2)", Some("-inf")),
            ("x=NaN\n", Some("NaN")),
            ("an infinite loop; infinity and info", None),
            ("1.5e300, 0, -0.25", None),
        ] {
            assert_eq!(non_finite_word(text), word, "{text}");
        }
        let mut sink = Vec::new();
        let mut gate = Gate::new(&mut sink);
        assert!(writeln!(gate, "fine {}", 1.5).is_ok());
        let e = writeln!(gate, "bad {}", f64::NAN).unwrap_err();
        assert!(matches!(CliError::from(e), CliError::Stopped(_)));
        assert_eq!(sink, b"fine 1.5\nbad ");
    }
}
