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

/// The rung a student has reached for `a` as `progress` records it (the
/// last one shown, wherever it was asked for), if any.
pub fn hint_reached(progress: &Progress, a: &'static Assignment) -> Option<Hint> {
    let used = usize::from(progress.hints.get(a.function).copied().unwrap_or(0));
    let rung = used.min(a.hints.len());
    (rung > 0).then(|| Hint {
        assignment: a,
        rung,
        text: a.hints[rung - 1],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::find;

    #[test]
    fn the_hint_ladder_climbs_one_rung_per_request_and_stays_on_the_formula() {
        let a = find("2.2").unwrap();
        assert_eq!(a.function, "torque_rate");
        assert_eq!(find("(2.2)"), Some(a));
        assert_eq!(find("eq_2_2_torque_rate"), Some(a));
        assert_eq!(find("nope"), None);
        let mut p = Progress::default();
        let rungs: Vec<usize> = (0..4).map(|_| next_hint(&mut p, a).rung).collect();
        assert_eq!(rungs, [1, 2, 3, 3]);
        let last = next_hint(&mut p, a);
        assert!(last.is_last() && last.text == a.hints[2]);
        assert_eq!(p.hints["torque_rate"], 3);
        // Another assignment starts at the bottom.
        let larmor = find("larmor_rate").unwrap();
        assert_eq!(hint_reached(&p, larmor), None);
        assert_eq!(next_hint(&mut p, larmor).rung, 1);
        assert_eq!(hint_reached(&p, larmor).map(|h| h.rung), Some(1));
        assert_eq!(hint_reached(&p, a), Some(last));
    }
}
