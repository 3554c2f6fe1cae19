//! The classical fourth-order Runge–Kutta method with a fixed step.
//!
//! Method: the "classical" RK4 (Kutta 1901), tableau `c = (0, ½, ½, 1)`,
//! `b = (⅙, ⅓, ⅓, ⅙)`; global order 4 (local error O(h⁵)).
//! Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//! Equations I: Nonstiff Problems*, 2nd ed., Springer 1993, Sec. II.1, Table 1.2.
//!
//! Continuous extension: the cubic Hermite polynomial through `(t_prev, y_prev,
//! f_prev)` and `(t, y, f)`, whose local error is O(h⁴) (the interpolation error
//! dominates the O(h⁵) error of the end points).
//!
//! Counting: every call of the right-hand side adds one to
//! [`Stats::rhs_evals`]. A step costs 4 evaluations, except that `f(t, y)` at the
//! end of a step is cached and reused as the next step's first stage, so a run of
//! `n` steps costs `4n` evaluations, and calling [`Stepper::dense`] inside a step
//! costs nothing extra (it evaluates the end slope once, which the next step then
//! reuses), except inside the very last step: `4n + 1`. [`Stepper::reset`] drops
//! the cached slope. [`Stats::rejected`] is always 0. The step budget
//! (`with_max_steps`) counts accepted steps.
//!
//! Failure: a non-finite stage or state ends the step with
//! [`IntegrateError::NonFinite`] at the time of the last finite state, which is
//! kept; the stepper never holds a non-finite state.

use crate::integrate::control::{check_start, check_t_stop, fixed_step_allowed, stepper_getters};
use crate::integrate::{DEFAULT_MAX_STEPS, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State, all_finite};

/// Classical RK4 with a fixed step size, stepping forward or backward.
#[derive(Clone, Debug)]
pub struct Rk4<const N: usize> {
    t: Real,
    y: State<N>,
    /// Start of the last accepted step.
    t_prev: Real,
    /// State at `t_prev`.
    y_prev: State<N>,
    /// `f(t_prev, y_prev)`, the first stage of the last step.
    f_prev: State<N>,
    /// Signed size of the last accepted step (0 before the first step).
    h_last: Real,
    /// `f(t, y)` once it has been evaluated (FSAL-like cache).
    f: Option<State<N>>,
    /// Step size magnitude.
    h: Real,
    max_steps: u64,
    stats: Stats,
}

// ANCHOR: rk4_step
/// One RK4 step from `(t, y)` with the first stage `k1 = f(t, y)` given.
fn rk4_with_k1<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    k1: &State<N>,
    h: Real,
) -> State<N> {
    let half = 0.5 * h;
    let k2 = rhs.eval(t + half, &(y + k1 * half));
    let k3 = rhs.eval(t + half, &(y + k2 * half));
    let k4 = rhs.eval(t + h, &(y + k3 * h));
    y + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0)
}
// ANCHOR_END: rk4_step

/// One classical RK4 step of size `h` from `(t, y)` (4 evaluations).
pub fn rk4_step<const N: usize, R: Rhs<N>>(rhs: &R, t: Real, y: &State<N>, h: Real) -> State<N> {
    let k1 = rhs.eval(t, y);
    rk4_with_k1(rhs, t, y, &k1, h)
}

impl<const N: usize> Rk4<N> {
    /// A stepper at `(t0, y0)` with step size `h` (finite and > 0; the direction
    /// of each step comes from its `t_stop`).
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0` or `y0`, or
    /// an `h` that is not finite and positive.
    pub fn new(t0: Real, y0: State<N>, h: Real) -> Result<Self, IntegrateError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(IntegrateError::InvalidOption(format!(
                "the RK4 step size must be finite and > 0, got {h}"
            )));
        }
        check_start(t0, all_finite(&y0))?;
        Ok(Self {
            t: t0,
            y: y0,
            t_prev: t0,
            y_prev: y0,
            f_prev: State::zeros(),
            h_last: 0.0,
            f: None,
            h,
            max_steps: DEFAULT_MAX_STEPS,
            stats: Stats::default(),
        })
    }

    /// Replace the step budget (accepted steps over the life of the stepper;
    /// default [`DEFAULT_MAX_STEPS`]).
    pub fn with_max_steps(mut self, n: u64) -> Self {
        self.max_steps = n;
        self
    }

    /// The step size magnitude.
    pub fn h(&self) -> Real {
        self.h
    }

    /// One raw RK4 step of signed size `h` from `(t, y)`: 4 evaluations, no
    /// checks, no counting.
    pub fn step_once<R: Rhs<N>>(rhs: &R, t: Real, y: &State<N>, h: Real) -> State<N> {
        let k1 = rhs.eval(t, y);
        rk4_with_k1(rhs, t, y, &k1, h)
    }

    /// `f(t, y)`, evaluated (and counted) only if it is not cached yet.
    fn slope<R: Rhs<N>>(&mut self, rhs: &R) -> State<N> {
        match self.f {
            Some(f) => f,
            None => {
                let f = rhs.eval(self.t, &self.y);
                self.stats.rhs_evals += 1;
                self.f = Some(f);
                f
            }
        }
    }
}

impl<const N: usize> Stepper<N> for Rk4<N> {
    stepper_getters!();

    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        check_t_stop(t_stop)?;
        if t_stop == self.t {
            return Ok(());
        }
        fixed_step_allowed(self.stats.steps, self.max_steps, self.t)?;
        let remaining = t_stop - self.t;
        // NOTE: the last step is stretched by up to a relative 1e-9 (plus a few
        // ulps of t) rather than leaving a rounding-sized sliver of a step for
        // later: a step count that "should" land on t_stop then does.
        let slack = 1e-9 * self.h + 64.0 * Real::EPSILON * self.t.abs().max(t_stop.abs());
        let (h, t_new) = if remaining.abs() <= self.h + slack {
            (remaining, t_stop)
        } else {
            let h = self.h.copysign(remaining);
            (h, self.t + h)
        };
        let k1 = self.slope(rhs);
        if !all_finite(&k1) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        let y_new = rk4_with_k1(rhs, self.t, &self.y, &k1, h);
        self.stats.rhs_evals += 3;
        if !all_finite(&y_new) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.f_prev = k1;
        self.h_last = h;
        self.t = t_new;
        self.y = y_new;
        self.f = None;
        self.stats.steps += 1;
        Ok(())
    }

    fn dense<R: Rhs<N>>(&mut self, rhs: &R, t: Real) -> State<N> {
        if self.h_last == 0.0 || t == self.t {
            return self.y;
        }
        let h = self.h_last;
        let f1 = self.slope(rhs);
        let s = (t - self.t_prev) / h;
        if !all_finite(&f1) {
            // NOTE: the end slope overflowed (the next step will report it);
            // fall back to the chord so a sample is never NaN.
            return self.y_prev + (self.y - self.y_prev) * s;
        }
        let s2 = s * s;
        let s3 = s2 * s;
        // Cubic Hermite basis on [0, 1].
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        self.y_prev * h00 + self.f_prev * (h10 * h) + self.y * h01 + f1 * (h11 * h)
    }

    fn reset(&mut self, y: State<N>) {
        self.y = y;
        self.f = None;
        // The last step's interpolant ended at the old state: forget it.
        self.t_prev = self.t;
        self.y_prev = y;
        self.h_last = 0.0;
    }
}
