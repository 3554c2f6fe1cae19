//! Output times: the one rule every entry point applies to the times a user
//! asks for (the command line's `--times`, `--t-end` and `--samples`, a
//! scene's `[solve]`), and the evenly spaced times `t_end` and `samples`
//! stand for.

use crate::math::Real;
use crate::numbers::fmt_value;
use thiserror::Error;

/// The most output times a request may ask for: a million samples is
/// already some hundred megabytes of table.
pub const MAX_SAMPLES: usize = 1_000_000;

/// Output times refused. Each message starts with the key's name (`times`),
/// so an entry point can put its own prefix before it (`--`, `[solve] `).
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum TimesError {
    /// No time at all.
    #[error("times needs at least one time")]
    Empty,
    /// NaN or an infinity.
    #[error("times holds {}, which is not a finite number", fmt_value(*.0))]
    NotFinite(Real),
    /// A time before 0.
    #[error("times must be >= 0, got {}", fmt_value(*.0))]
    Negative(Real),
    /// A time before the one listed ahead of it.
    #[error(
        "times must be non-decreasing ({} comes after {})",
        fmt_value(*.0),
        fmt_value(*.1)
    )]
    Decreasing(Real, Real),
}

/// Refuse output times that are empty or not finite, and, when `forward`
/// (every model that steps in time), below 0 or decreasing.
pub fn check_times(times: &[Real], forward: bool) -> Result<(), TimesError> {
    if times.is_empty() {
        return Err(TimesError::Empty);
    }
    if let Some(&t) = times.iter().find(|t| !t.is_finite()) {
        return Err(TimesError::NotFinite(t));
    }
    if !forward {
        return Ok(());
    }
    if let Some(&t) = times.iter().find(|t| **t < 0.0) {
        return Err(TimesError::Negative(t));
    }
    match times.windows(2).find(|w| w[1] < w[0]) {
        Some(w) => Err(TimesError::Decreasing(w[1], w[0])),
        None => Ok(()),
    }
}

/// `n` evenly spaced times from 0 to `t_end` (`t_end` alone for one):
/// t_end·i/(n − 1), also when t_end·i would overflow a double (a last time
/// near the largest double).
pub fn even_times(t_end: Real, n: usize) -> Vec<Real> {
    if n == 1 {
        return vec![t_end];
    }
    let last = (n - 1) as Real;
    (0..n)
        .map(|i| {
            let t = t_end * i as Real / last;
            if t.is_finite() {
                t
            } else {
                t_end * (i as Real / last)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn even_times_end_at_t_end_without_overflow() {
        assert_eq!(even_times(100.0, 11)[3], 30.0);
        assert_eq!(even_times(5.0, 1), vec![5.0]);
        let near_max = even_times(1e306, 200);
        assert!(near_max.iter().all(|t| t.is_finite()));
        assert_eq!(*near_max.last().unwrap(), 1e306);
        assert!(near_max.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn times_are_refused_with_the_value_written_short() {
        assert_eq!(check_times(&[], true), Err(TimesError::Empty));
        assert_eq!(
            check_times(&[1.0, -1e300], true).unwrap_err().to_string(),
            "times must be >= 0, got -1e300"
        );
        assert_eq!(
            check_times(&[5.0, 1e-300], true).unwrap_err().to_string(),
            "times must be non-decreasing (1e-300 comes after 5)"
        );
        assert!(check_times(&[5.0, -1.0], false).is_ok());
        assert!(check_times(&[Real::NAN], false).is_err());
    }
}
