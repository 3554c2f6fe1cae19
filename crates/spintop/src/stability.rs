//! The stability suite: every place in the project where a natural numerical
//! method breaks, measured beside the method spintop uses instead.
//!
//! Each row is a small experiment in its own module. It returns a typed
//! measurement (what the tests in `tests/numerics/stability.rs` assert on) that turns
//! into a printable [`Row`] (what `spintop stability` prints). Pure: no I/O, no
//! clock; every number is a count, a time, a rate or an error.
//!
//! | row | module | the naive method | spintop's method |
//! |---|---|---|---|
//! | 1 | [`runaway`] | (3.4) integrated forward | backward shooting / the reduced model |
//! | 2 | [`pole`] | Euler angles (4.8) near θ = 0 | the orientation on SO(3) |
//! | 3 | [`stiffness`] | explicit RK4 / DP5 at τΩ² ≫ 1 | an L-stable implicit method; exact splitting |
//! | 4 | [`long_run`] | RK4 / DP5 at τ = 0 over long times | Strang and Yoshida-4 splittings |
//! | 5 | [`closed_forms`] | the printed closed forms | the careful closed forms |
//! | 6 | [`delay`] | (A.1) with m₀ < m_em | the stability check before the run |

use serde::Serialize;

pub mod closed_forms;
pub mod delay;
pub mod long_run;
pub mod pole;
pub mod runaway;
pub mod stiffness;

/// What one method did in one row.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// The method, as a reader would name it ("RK4, h = 0.05").
    pub method: String,
    /// Whether it gave a usable answer.
    pub ok: bool,
    /// What happened, with the measured numbers, in one line.
    pub result: String,
}

/// One row of the suite: the naive method, spintop's method, and the
/// numbers behind the verdict.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// Row number, 1–6.
    pub number: u8,
    /// The problem, with its equation ("Full ALE (3.4), forward").
    pub problem: String,
    /// The naive method(s), each expected to fail.
    pub naive: Vec<Outcome>,
    /// spintop's method(s), each expected to succeed.
    pub fix: Vec<Outcome>,
    /// Further measured numbers, one line each.
    pub notes: Vec<String>,
}

impl Row {
    /// True when every naive method failed and every fix succeeded: the row
    /// shows what it claims.
    pub fn holds(&self) -> bool {
        !self.naive.is_empty()
            && !self.fix.is_empty()
            && self.naive.iter().all(|o| !o.ok)
            && self.fix.iter().all(|o| o.ok)
    }
}

impl std::fmt::Display for Row {
    /// One block: the problem and verdict, each method with its result, the notes.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let verdict = if self.holds() {
            "holds"
        } else {
            "DOES NOT HOLD"
        };
        writeln!(f, "Row {}: {}  [{verdict}]", self.number, self.problem)?;
        for (label, outcomes) in [("naive", &self.naive), ("spintop", &self.fix)] {
            for o in outcomes {
                let mark = if o.ok { "ok  " } else { "FAIL" };
                writeln!(f, "  {label:<7} {mark} {}", o.method)?;
                writeln!(f, "               {}", o.result)?;
            }
        }
        for note in &self.notes {
            writeln!(f, "  note: {note}")?;
        }
        Ok(())
    }
}

/// A failure of a row's experiment itself (not of the method it shows failing).
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
#[error("stability row {row}: {message}")]
pub struct RowError {
    /// The row.
    pub row: u8,
    /// What went wrong.
    pub message: String,
}

impl RowError {
    /// A row error from anything printable.
    pub fn new(row: u8, message: impl std::fmt::Display) -> Self {
        Self {
            row,
            message: message.to_string(),
        }
    }
}

/// Row `n` (1–6), measured.
pub fn row(n: u8) -> Result<Row, RowError> {
    match n {
        1 => runaway::measure().map(|m| m.row()),
        2 => pole::measure().map(|m| m.row()),
        3 => stiffness::measure().map(|m| m.row()),
        4 => long_run::measure().map(|m| m.row()),
        5 => closed_forms::measure().map(|m| m.row()),
        6 => delay::measure().map(|m| m.row()),
        _ => Err(RowError::new(n, "there are six rows, 1 to 6")),
    }
}

/// Every row, in order.
pub fn all_rows() -> Vec<Result<Row, RowError>> {
    (1..=6).map(row).collect()
}
