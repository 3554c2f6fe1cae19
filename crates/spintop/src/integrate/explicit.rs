//! The adaptive step loop that every explicit embedded Runge–Kutta pair
//! shares: the first stage (FSAL), Hairer's starting step, the step budget,
//! step-size underflow, landing on `t_stop`, the error test, the (P)I
//! controller, rejection and the statistics. A pair ([`EmbeddedPair`])
//! supplies only its stages, its error norm and its controller constants;
//! its file keeps its dense output.
//!
//! Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary
//! Differential Equations I*, 2nd ed., Springer 1993, Sec. II.4 (step-size
//! control, starting step) and Hairer's codes DOPRI5 and DOP853, whose loop
//! this is.

use crate::integrate::control::{
    NONFINITE_CUT, attempt_allowed, check_start, check_t_stop, clip_step, error_scale, start_step,
    validate_options,
};
use crate::integrate::{AdaptiveOptions, IntegrateError, Rhs, Stats};
use crate::math::{Real, State, all_finite};

/// What an explicit embedded pair gives the shared loop.
pub(crate) trait EmbeddedPair<const N: usize> {
    /// The stages of one attempt, kept for the dense output of an accepted step.
    type Stages: Copy;
    /// The order Hairer's starting-step guess assumes.
    const HINIT_ORDER: i32;
    /// Evaluations of one attempt (the first stage comes from the last step).
    const EVALS: u64;
    /// Controller: safety factor, the smallest and largest step ratios, the
    /// exponent of the error, and the PI term's exponent (0: plain I control).
    const SAFETY: Real;
    /// Smallest ratio h_new/h.
    const FAC_MIN: Real;
    /// Largest ratio h_new/h.
    const FAC_MAX: Real;
    /// The error's exponent in the controller.
    const EXPO: Real;
    /// The exponent of the previous error (Gustafsson's PI term).
    const BETA: Real;

    /// `err^EXPO`, the controller's power of the error norm. Pairs whose
    /// exponent allows a cheaper exact form override it (a libm `pow` is about
    /// a tenth of a DOP853 step on a cheap right-hand side).
    #[inline(always)]
    fn err_power(err: Real) -> Real {
        err.powf(Self::EXPO)
    }

    /// One attempt of signed size `h` from `(t, y)` with first stage `f0`,
    /// ending at `t_new`: the new state and the stages (the last of which is
    /// `f(t_new, y_new)`).
    fn attempt<R: Rhs<N>>(
        rhs: &R,
        t: Real,
        y: &State<N>,
        f0: &State<N>,
        h: Real,
        t_new: Real,
    ) -> (State<N>, Self::Stages);

    /// The attempt's error norm, the components scaled by `scale`.
    fn error_norm(stages: &Self::Stages, h: Real, scale: &State<N>) -> Real;

    /// `f(t_new, y_new)`, the first stage of the next step.
    fn fsal(stages: &Self::Stages) -> State<N>;
}

/// Where an adaptive explicit stepper stands and what it remembers.
#[derive(Clone, Debug)]
pub(crate) struct Core<const N: usize> {
    /// The current time and state.
    pub t: Real,
    pub y: State<N>,
    /// The start of the last accepted step.
    pub t_prev: Real,
    pub y_prev: State<N>,
    /// Signed size of the last accepted step (0 before the first / after reset).
    pub h_last: Real,
    /// `f(t, y)` when known (FSAL).
    pub f: Option<State<N>>,
    /// Magnitude of the next step to try (None: guess it with `hinit`).
    pub h_next: Option<Real>,
    /// Error norm of the previous accepted step (the PI controller's memory).
    pub facold: Real,
    pub opts: AdaptiveOptions,
    pub stats: Stats,
}

impl<const N: usize> Core<N> {
    /// At `(t0, y0)`; options re-checked (their fields are public).
    pub fn new(t0: Real, y0: State<N>, opts: AdaptiveOptions) -> Result<Self, IntegrateError> {
        validate_options(&opts)?;
        check_start(t0, all_finite(&y0))?;
        Ok(Self {
            t: t0,
            y: y0,
            t_prev: t0,
            y_prev: y0,
            h_last: 0.0,
            f: None,
            h_next: opts.h_init,
            facold: 1e-4,
            opts,
            stats: Stats::default(),
        })
    }

    /// A new state at the current time; the FSAL stage and the last step
    /// are forgotten.
    pub fn reset(&mut self, y: State<N>) {
        self.y = y;
        self.f = None;
        self.t_prev = self.t;
        self.y_prev = y;
        self.h_last = 0.0;
    }

    /// Change the largest step magnitude from the next step on (ignored
    /// unless positive).
    pub fn set_h_max(&mut self, h_max: Real) {
        if h_max > 0.0 {
            self.opts.h_max = h_max;
        }
    }

    /// One accepted step of pair `P` toward `t_stop`: the stages of the
    /// accepted attempt, or `None` when already at `t_stop`.
    #[inline(always)]
    pub fn step<P: EmbeddedPair<N>, R: Rhs<N>>(
        &mut self,
        rhs: &R,
        t_stop: Real,
    ) -> Result<Option<P::Stages>, IntegrateError> {
        check_t_stop(t_stop)?;
        if t_stop == self.t {
            return Ok(None);
        }
        let dir = (t_stop - self.t).signum();
        let (f0, h) = start_step(
            rhs,
            self.t,
            &self.y,
            &mut self.f,
            &mut self.stats,
            self.h_next,
            dir,
            P::HINIT_ORDER,
            &self.opts,
        )?;
        let mut h = h.min(self.opts.h_max);
        let mut rejected_here = false;
        loop {
            if let Err(e) = attempt_allowed(&self.stats, self.opts.max_steps, self.t, h, dir) {
                self.h_next = Some(h);
                return Err(e);
            }
            let (hs, t_new, clipped) = clip_step(self.t, t_stop, h);
            let (y_new, stages) = P::attempt(rhs, self.t, &self.y, &f0, hs, t_new);
            self.stats.rhs_evals += P::EVALS;
            let scale = error_scale(&self.opts, &self.y, &y_new);
            let err = P::error_norm(&stages, hs, &scale);
            let fsal = P::fsal(&stages);
            if !(err.is_finite() && all_finite(&y_new) && all_finite(&fsal)) {
                // NOTE: an overflowing attempt says nothing about the error's
                // size, only that the step was far too long: cut hard and retry.
                self.stats.rejected += 1;
                rejected_here = true;
                h = hs.abs() * NONFINITE_CUT;
                continue;
            }
            // ANCHOR: pi_controller
            let fac11 = P::err_power(err);
            if err <= 1.0 {
                // NOTE: PI control (Gustafsson; HNW I, Sec. IV.2 and DOPRI5):
                // dividing by facold^β damps the oscillation of the step size
                // that the plain I controller shows near the stability
                // boundary. With β = 0 (DOP853) facold^β is exactly 1, and
                // not computed.
                let fac = if P::BETA == 0.0 {
                    fac11
                } else {
                    fac11 / self.facold.powf(P::BETA)
                };
                let fac = (fac / P::SAFETY).clamp(1.0 / P::FAC_MAX, 1.0 / P::FAC_MIN);
                let mut h_new = hs.abs() / fac;
                // ANCHOR_END: pi_controller
                if rejected_here {
                    h_new = h_new.min(hs.abs());
                }
                if clipped && !rejected_here {
                    // NOTE: a step shortened only to land on t_stop says nothing
                    // against the step the controller proposed before it.
                    h_new = h_new.max(h);
                }
                self.facold = err.max(1e-4);
                self.h_next = Some(h_new.min(self.opts.h_max));
                self.t_prev = self.t;
                self.y_prev = self.y;
                self.h_last = hs;
                self.t = t_new;
                self.y = y_new;
                self.f = Some(fsal);
                self.stats.steps += 1;
                return Ok(Some(stages));
            }
            self.stats.rejected += 1;
            rejected_here = true;
            h = hs.abs() / (1.0 / P::FAC_MIN).min(fac11 / P::SAFETY);
        }
    }
}

/// The inherent accessors of a stepper built on [`Core`]: its options, the
/// next step to try, and a new cap on the step.
macro_rules! core_accessors {
    () => {
        /// The options the stepper runs with.
        pub fn options(&self) -> &AdaptiveOptions {
            &self.core.opts
        }

        /// Magnitude of the next step to try (`None` until it has been chosen).
        pub fn next_step_size(&self) -> Option<Real> {
            self.core.h_next
        }

        /// Change the largest step magnitude from the next step on, for a driver
        /// that knows how a scale of its problem changes along the solution (the
        /// SO(3) driver caps the rotation per step this way). A NaN or non-positive
        /// value is ignored.
        pub fn set_h_max(&mut self, h_max: Real) {
            self.core.set_h_max(h_max);
        }
    };
}
pub(crate) use core_accessors;
