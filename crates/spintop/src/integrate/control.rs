//! The step control every method shares, in one place: the checks before a
//! run and before each attempt (a finite start and stop, the step budget, a
//! step the time axis can resolve), the first stage and Hairer's starting
//! step, landing on `t_stop`, the scaled RMS error norm and the cut after a
//! non-finite attempt. The explicit pairs' loop (`explicit.rs`), Radau IIA 5,
//! RK4 and the splittings call these; no method file calls another.
//!
//! Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary
//! Differential Equations I*, 2nd ed., Springer 1993, Sec. II.4 (step-size
//! control, starting step size) and Hairer's codes DOPRI5, DOP853 and RADAU5.

use crate::integrate::{AdaptiveOptions, IntegrateError, Rhs, Stats};
use crate::math::{Real, State};

/// Step ratio after an attempt whose error estimate was not finite.
pub(crate) const NONFINITE_CUT: Real = 0.2;

/// Check options the caller may have built by hand.
pub(crate) fn validate_options(opts: &AdaptiveOptions) -> Result<(), IntegrateError> {
    let bad = |msg: String| Err(IntegrateError::InvalidOption(msg));
    if !(opts.rtol.is_finite() && opts.rtol > 0.0 && opts.rtol < 1.0) {
        return bad(format!("rtol must lie in (0, 1), got {}", opts.rtol));
    }
    if !(opts.atol.is_finite() && opts.atol >= 0.0) {
        return bad(format!("atol must be finite and ≥ 0, got {}", opts.atol));
    }
    if let Some(h) = opts.h_init
        && !(h.is_finite() && h > 0.0)
    {
        return bad(format!("h_init must be finite and > 0, got {h}"));
    }
    if opts.h_max.is_nan() || opts.h_max <= 0.0 {
        return bad(format!("h_max must be > 0, got {}", opts.h_max));
    }
    Ok(())
}

/// `x / s` that reads 0/0 as 0 (a component that is exactly zero with `atol = 0`
/// has zero error, not NaN error).
#[inline]
fn ratio(x: Real, s: Real) -> Real {
    if x == 0.0 { 0.0 } else { x / s }
}

/// Root mean square of `v_i / scale_i`.
pub(crate) fn rms_scaled<const N: usize>(v: &State<N>, scale: &State<N>) -> Real {
    if N == 0 {
        return 0.0;
    }
    let sum: Real = v
        .iter()
        .zip(scale.iter())
        .map(|(&x, &s)| ratio(x, s).powi(2))
        .sum();
    (sum / N as Real).sqrt()
}

/// The error scale `atol + rtol·max(|y_i|, |y_new_i|)`.
pub(crate) fn error_scale<const N: usize>(
    opts: &AdaptiveOptions,
    y: &State<N>,
    y_new: &State<N>,
) -> State<N> {
    y.zip_map(y_new, |a, b| opts.atol + opts.rtol * a.abs().max(b.abs()))
}

/// Hairer's starting step size (`hinit` in DOPRI5/DOP853; HNW I, Sec. II.4): a
/// step magnitude from one explicit Euler step and a second-derivative estimate.
/// Costs exactly one evaluation of `rhs`, which the caller counts.
// NOTE: the norms are RMS norms (as in SciPy's `select_initial_step`) rather than
// Hairer's plain sums, so that the guess is consistent with the RMS error norm;
// the two differ only by √N in the second-derivative estimate.
#[allow(clippy::too_many_arguments)]
pub(crate) fn hinit<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    f0: &State<N>,
    direction: Real,
    order: i32,
    opts: &AdaptiveOptions,
) -> Real {
    let scale = y.map(|v| opts.atol + opts.rtol * v.abs());
    let d0 = rms_scaled(y, &scale);
    let d1 = rms_scaled(f0, &scale);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 || !d0.is_finite() || !d1.is_finite() {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let h0 = h0.min(opts.h_max);
    let y1 = y + f0 * (direction * h0);
    let f1 = rhs.eval(t + direction * h0, &y1);
    let d2 = rms_scaled(&(f1 - f0), &scale) / h0;
    let h1 = if !d2.is_finite() {
        h0 * 1e-3
    } else if d1 <= 1e-15 && d2 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / order as Real)
    };
    let h = (100.0 * h0).min(h1).min(opts.h_max);
    if h > 0.0 && h.is_finite() { h } else { h0 }
}

/// The step size (magnitude) below which the time axis cannot resolve a step.
pub(crate) fn underflow_limit(t: Real) -> Real {
    16.0 * Real::EPSILON * t.abs().max(Real::MIN_POSITIVE)
}

/// The signed step to attempt from `t` toward `t_stop` with magnitude `h`, and
/// the time it ends at; clipped (or stretched by at most 1 %) to land exactly on
/// `t_stop`. The bool says whether it was clipped.
pub(crate) fn clip_step(t: Real, t_stop: Real, h: Real) -> (Real, Real, bool) {
    let dir = (t_stop - t).signum();
    // NOTE: Hairer's 1.01: a step that would leave less than 1 % of itself before
    // t_stop is stretched to t_stop instead of leaving a sliver step behind.
    // NOTE: the step taken is the difference of the rounded ends, so that the
    // clock and the state advance by the same amount: with t + h rounded and
    // the stages spanning h, every step of a long run (t ~ 1e5, h ~ 60)
    // moved the state 1e-13 of a step ahead of its clock, and a spin's
    // phase drifted by 5e-11 rad over 4e4 rad.
    if dir * (t + dir * 1.01 * h - t_stop) >= 0.0 {
        (t_stop - t, t_stop, true)
    } else {
        let t_new = t + dir * h;
        (t_new - t, t_new, false)
    }
}

/// Refuse a non-finite `t_stop` (shared by the steppers).
pub(crate) fn check_t_stop(t_stop: Real) -> Result<(), IntegrateError> {
    if t_stop.is_finite() {
        Ok(())
    } else {
        Err(IntegrateError::InvalidOption(format!(
            "t_stop must be finite, got {t_stop}"
        )))
    }
}

/// A stepper starts only from a finite time and state.
pub(crate) fn check_start(t0: Real, finite_state: bool) -> Result<(), IntegrateError> {
    if t0.is_finite() && finite_state {
        Ok(())
    } else {
        Err(IntegrateError::InvalidOption(
            "the initial time and state must be finite".into(),
        ))
    }
}

/// The checks before every attempt of an adaptive method: the step budget
/// (accepted plus rejected attempts) and a step magnitude `h` the time axis
/// can still resolve at `t` (`dir` is the direction of integration).
pub(crate) fn attempt_allowed(
    stats: &Stats,
    max_steps: u64,
    t: Real,
    h: Real,
    dir: Real,
) -> Result<(), IntegrateError> {
    if stats.steps + stats.rejected >= max_steps {
        return Err(IntegrateError::TooManySteps { t, max_steps });
    }
    if h.is_nan() || h < underflow_limit(t) {
        return Err(IntegrateError::StepSizeUnderflow { t, h: dir * h });
    }
    Ok(())
}

/// The step budget of a fixed-step method: `steps` taken of `max_steps`.
pub(crate) fn fixed_step_allowed(
    steps: u64,
    max_steps: u64,
    t: Real,
) -> Result<(), IntegrateError> {
    if steps >= max_steps {
        Err(IntegrateError::TooManySteps { t, max_steps })
    } else {
        Ok(())
    }
}

/// The start of an adaptive step: `f(t, y)` (from the last step when known,
/// else evaluated and counted) and the step magnitude to try first, from the
/// last step's controller or, the first time, Hairer's guess for a method of
/// order `order` (one more evaluation, counted).
#[allow(clippy::too_many_arguments)]
pub(crate) fn start_step<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    f: &mut Option<State<N>>,
    stats: &mut Stats,
    h_next: Option<Real>,
    dir: Real,
    order: i32,
    opts: &AdaptiveOptions,
) -> Result<(State<N>, Real), IntegrateError> {
    let f0 = first_stage(rhs, t, y, f, stats)?;
    let h = match h_next {
        Some(h) => h,
        None => {
            stats.rhs_evals += 1;
            hinit(rhs, t, y, &f0, dir, order, opts)
        }
    };
    Ok((f0, h))
}

/// The first stage `f(t, y)`: the cached one (FSAL, or the end slope of the
/// last step) when there is one, else evaluated, counted and cached. A
/// non-finite slope is reported at `t`.
pub(crate) fn first_stage<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    cache: &mut Option<State<N>>,
    stats: &mut Stats,
) -> Result<State<N>, IntegrateError> {
    if let Some(f) = *cache {
        return Ok(f);
    }
    let f = rhs.eval(t, y);
    stats.rhs_evals += 1;
    if !crate::math::all_finite(&f) {
        return Err(IntegrateError::NonFinite { t });
    }
    *cache = Some(f);
    Ok(f)
}

/// The five [`Stepper`] getters of a stepper whose position lives in the
/// fields `t`, `y`, `t_prev`, `h_last` and `stats`, of itself
/// (`stepper_getters!()`) or of one of its fields (`stepper_getters!(core)`).
macro_rules! stepper_getters {
    ($($at:ident)?) => {
        fn t(&self) -> Real {
            self$(.$at)?.t
        }

        fn y(&self) -> &State<N> {
            &self$(.$at)?.y
        }

        fn t_prev(&self) -> Real {
            self$(.$at)?.t_prev
        }

        fn last_step(&self) -> Real {
            self$(.$at)?.h_last
        }

        fn stats(&self) -> Stats {
            self$(.$at)?.stats
        }
    };
}
pub(crate) use stepper_getters;
