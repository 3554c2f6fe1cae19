//! Row 1 of the stability suite (placeholder until its experiment lands).

use super::{Row, RowError};

/// The measurement of row 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement;

/// Run the experiment of row 1.
pub fn measure() -> Result<Measurement, RowError> {
    Err(RowError::new(1, "not built yet"))
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        Row {
            number: 1,
            problem: String::new(),
            naive: Vec::new(),
            fix: Vec::new(),
            notes: Vec::new(),
        }
    }
}
