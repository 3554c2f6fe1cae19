//! What a value must be, and the three ways it is written: in a message's
//! "expected" (`a time >= 0`), at the end of a flag's help line (`in (0,
//! 2]`) and in a command's summary of ranges (`0 < --ratio <= 2`).

use crate::math::Real;
use crate::numbers::fmt_value;

/// One end of a range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// No end.
    None,
    /// The end, excluded.
    Open(Real),
    /// The end, included.
    Closed(Real),
}

/// What a value must be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// Any finite number (or numbers).
    Finite,
    /// A number between two ends.
    Between(Bound, Bound),
    /// A number (or vector) that is not zero.
    NonZero,
    /// Numbers, each at most this in size.
    EachAtMost(Real),
    /// Numbers, each positive.
    EachPositive,
    /// The principal moments of a rigid body.
    RigidBody,
    /// A whole number from the first to the second.
    Count(usize, usize),
    /// Output times: finite, and when `forward` also >= 0 and non-decreasing.
    Times {
        /// Whether the times step forward from 0.
        forward: bool,
    },
    /// One of these names.
    Names(&'static [&'static str]),
}

/// A number in a range, as written (`pi` for π).
fn bound_text(x: Real) -> String {
    if x == std::f64::consts::PI {
        "pi".to_string()
    } else {
        fmt_value(x)
    }
}

impl Range {
    /// True when the number `x` lies in the range (names and lists: always).
    pub fn contains(&self, x: Real) -> bool {
        match *self {
            Range::Finite => x.is_finite(),
            Range::Between(lo, hi) => {
                let above = match lo {
                    Bound::None => true,
                    Bound::Open(a) => x > a,
                    Bound::Closed(a) => x >= a,
                };
                let below = match hi {
                    Bound::None => true,
                    Bound::Open(b) => x < b,
                    Bound::Closed(b) => x <= b,
                };
                x.is_finite() && above && below
            }
            Range::NonZero => x.is_finite() && x != 0.0,
            Range::EachAtMost(m) => x.abs() <= m,
            Range::EachPositive => x > 0.0 && x.is_finite(),
            Range::Count(lo, hi) => x >= lo as Real && x <= hi as Real && x.fract() == 0.0,
            Range::RigidBody | Range::Times { .. } | Range::Names(_) => true,
        }
    }

    /// The interval, in the notation `(0, 2]`, `>= 0`, `> 0`.
    fn interval(lo: Bound, hi: Bound) -> String {
        match (lo, hi) {
            (Bound::None, Bound::None) => String::new(),
            (lo, Bound::None) => match lo {
                Bound::Open(a) => format!("> {}", bound_text(a)),
                Bound::Closed(a) => format!(">= {}", bound_text(a)),
                Bound::None => unreachable!("matched above"),
            },
            (Bound::None, Bound::Open(b)) => format!("< {}", bound_text(b)),
            (Bound::None, Bound::Closed(b)) => format!("<= {}", bound_text(b)),
            (lo, hi) => {
                let end = |b: Bound, open: char, closed: char| match b {
                    Bound::Open(x) => (open, x),
                    Bound::Closed(x) => (closed, x),
                    Bound::None => (open, Real::INFINITY),
                };
                let (open, a) = end(lo, '(', '[');
                let (close, b) = end(hi, ')', ']');
                format!("in {open}{}, {}{close}", bound_text(a), bound_text(b))
            }
        }
    }

    /// What a message expects, for a value described by `noun` ("a time"):
    /// `a time >= 0`, `a positive step in units of tau`, `one of a, b`.
    pub fn expected(&self, noun: &str) -> String {
        match self {
            Range::Finite => noun.to_string(),
            Range::Between(Bound::Open(a), Bound::None) if *a == 0.0 => {
                let bare = noun
                    .strip_prefix("an ")
                    .or_else(|| noun.strip_prefix("a "))
                    .unwrap_or(noun);
                format!("a positive {bare}")
            }
            Range::Between(lo, hi) => format!("{noun} {}", Self::interval(*lo, *hi)),
            Range::NonZero => format!("{noun}, not zero"),
            Range::EachAtMost(m) => format!("{noun}, each at most {} in size", bound_text(*m)),
            Range::EachPositive => format!("{noun}, each positive"),
            Range::RigidBody => {
                format!("{noun}: positive, each at most the sum of the other two")
            }
            Range::Count(lo, hi) => format!("a whole number from {lo} to {hi}"),
            Range::Times { forward: true } => "finite times >= 0, in increasing order".into(),
            Range::Times { forward: false } => "finite numbers".into(),
            Range::Names(names) => format!("one of {}", names.join(", ")),
        }
    }

    /// The range as a flag's help line ends: `in (0, 2]`, `>= 0`; empty for
    /// what says itself (any number, a name clap lists).
    pub fn short(&self) -> String {
        match self {
            Range::Finite | Range::Names(_) => String::new(),
            Range::Between(lo, hi) => Self::interval(*lo, *hi),
            Range::NonZero => "not zero".into(),
            Range::EachAtMost(m) => format!("each at most {} in size", bound_text(*m)),
            Range::EachPositive => "each positive".into(),
            Range::RigidBody => "positive, each at most the sum of the other two".into(),
            Range::Count(lo, hi) => format!("{lo} to {hi}"),
            Range::Times { forward: true } => ">= 0 and non-decreasing".into(),
            Range::Times { forward: false } => String::new(),
        }
    }

    /// The range with the flag in it, for a command's summary of ranges:
    /// `0 < --ratio <= 2`, `each --omega component at most 1e100`; `None`
    /// for what has no range to state.
    pub fn with_flag(&self, flag: &str) -> Option<String> {
        let side = |b: Bound, before: bool| match (b, before) {
            (Bound::Open(x), true) => Some(format!("{} < ", bound_text(x))),
            (Bound::Closed(x), true) => Some(format!("{} <= ", bound_text(x))),
            (Bound::Open(x), false) => Some(format!(" < {}", bound_text(x))),
            (Bound::Closed(x), false) => Some(format!(" <= {}", bound_text(x))),
            (Bound::None, _) => None,
        };
        match self {
            Range::Finite | Range::Names(_) | Range::Times { forward: false } => None,
            Range::Between(lo, Bound::None) => {
                Some(format!("{flag} {}", Self::interval(*lo, Bound::None)))
            }
            Range::Between(lo, hi) => Some(format!(
                "{}{flag}{}",
                side(*lo, true).unwrap_or_default(),
                side(*hi, false).unwrap_or_default()
            )),
            Range::NonZero => Some(format!("{flag} not zero")),
            Range::EachAtMost(m) => {
                Some(format!("each {flag} component at most {}", bound_text(*m)))
            }
            Range::EachPositive => Some(format!("each of {flag} positive")),
            Range::RigidBody => Some(format!(
                "{flag} positive and a rigid body (each at most the sum of the other two)"
            )),
            Range::Count(lo, hi) => Some(format!("{flag} from {lo} to {hi}")),
            Range::Times { forward: true } => Some(format!("{flag} >= 0 and non-decreasing")),
        }
    }
}
