//! The hint ladder: one rung per request (where to look, the idea, the
//! formula), kept in the course's progress.

use super::{Assignment, Progress};

/// One rung of the hint ladder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Hint {
    /// The assignment.
    pub assignment: &'static Assignment,
    /// The rung, 1 to 3.
    pub rung: usize,
    /// Its text.
    pub text: &'static str,
}

impl Hint {
    /// What the rung gives: where to look, the idea, or the formula.
    pub fn label(&self) -> &'static str {
        ["where to look", "the idea", "the formula"][(self.rung.max(1) - 1).min(2)]
    }

    /// Whether this is the last rung (the formula).
    pub fn is_last(&self) -> bool {
        self.rung == self.assignment.hints.len()
    }
}

/// The hint a student has reached for `a`: `progress`'s rung count plus one
/// (one rung per request, staying on the last), recorded in `progress`.
pub fn next_hint(progress: &mut Progress, a: &'static Assignment) -> Hint {
    let used = progress.hints.entry(a.function.to_string()).or_insert(0);
    let rung = (*used as usize + 1).min(a.hints.len());
    *used = rung as u8;
    Hint {
        assignment: a,
        rung,
        text: a.hints[rung - 1],
    }
}
