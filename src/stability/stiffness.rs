//! Row 3 of the stability suite (placeholder until its experiment lands).

use super::{Row, RowError};

/// The measurement of row 3.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement;

/// Run the experiment of row 3.
pub fn measure() -> Result<Measurement, RowError> {
    Err(RowError::new(3, "not built yet"))
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        Row {
            number: 3,
            problem: String::new(),
            naive: Vec::new(),
            fix: Vec::new(),
            notes: Vec::new(),
        }
    }
}
