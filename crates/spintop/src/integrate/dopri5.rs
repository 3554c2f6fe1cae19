//! The Dormand–Prince 5(4) pair with PI step-size control and dense output.
//!
//! Method: the 7-stage explicit pair of Dormand & Prince (1980), "first same as
//! last" (FSAL: the last stage `f(t + h, y_new)` is the first stage of the next
//! step, so an attempt costs 6 evaluations). The step is advanced with the
//! order-5 solution (local extrapolation); the order-4 embedded solution only
//! measures the error. Global order 5.
//! Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//! Equations I: Nonstiff Problems*, 2nd ed., Springer 1993, Sec. II.5 (Table 5.2),
//! II.4 (step-size control, starting step size), II.6 (dense output), and
//! Hairer's Fortran code `DOPRI5`.
//!
//! Continuous extension: Shampine's order-4 interpolant (Hairer's `d1…d7`,
//! SciPy's `RK45.P`), free of extra evaluations.
//!
//! Counting ([`Stats`]): `rhs_evals = 6·(steps + rejected) + 1 + g`, where the 1
//! is `f(t0, y0)` before the first step (again after every [`Stepper::reset`],
//! which drops the FSAL stage) and `g = 1` if the initial step size is guessed
//! (Hairer's `hinit`, `AdaptiveOptions::h_init == None`), else 0. The step budget
//! `max_steps` counts accepted plus rejected attempts.

use crate::integrate::control::{rms_scaled, stepper_getters};
use crate::integrate::explicit::{Core, EmbeddedPair, core_accessors};
use crate::integrate::{AdaptiveOptions, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State};

// Butcher tableau of Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, Table II.5.2).
const C2: Real = 1.0 / 5.0;
const C3: Real = 3.0 / 10.0;
const C4: Real = 4.0 / 5.0;
const C5: Real = 8.0 / 9.0;
const A21: Real = 1.0 / 5.0;
const A31: Real = 3.0 / 40.0;
const A32: Real = 9.0 / 40.0;
const A41: Real = 44.0 / 45.0;
const A42: Real = -56.0 / 15.0;
const A43: Real = 32.0 / 9.0;
const A51: Real = 19372.0 / 6561.0;
const A52: Real = -25360.0 / 2187.0;
const A53: Real = 64448.0 / 6561.0;
const A54: Real = -212.0 / 729.0;
const A61: Real = 9017.0 / 3168.0;
const A62: Real = -355.0 / 33.0;
const A63: Real = 46732.0 / 5247.0;
const A64: Real = 49.0 / 176.0;
const A65: Real = -5103.0 / 18656.0;
// The order-5 weights (= the last row of A, hence FSAL).
const B1: Real = 35.0 / 384.0;
const B3: Real = 500.0 / 1113.0;
const B4: Real = 125.0 / 192.0;
const B5: Real = -2187.0 / 6784.0;
const B6: Real = 11.0 / 84.0;
// E = b(order 5) − b̂(order 4): the error estimate is y5 − y4 = h Σ Eᵢ kᵢ.
const E1: Real = 71.0 / 57600.0;
const E3: Real = -71.0 / 16695.0;
const E4: Real = 71.0 / 1920.0;
const E5: Real = -17253.0 / 339200.0;
const E6: Real = 22.0 / 525.0;
const E7: Real = -1.0 / 40.0;
// Shampine's dense output (Hairer's DOPRI5 `d1…d7`).
const D1: Real = -12715105075.0 / 11282082432.0;
const D3: Real = 87487479700.0 / 32700410799.0;
const D4: Real = -10690763975.0 / 1880347072.0;
const D5: Real = 701980252875.0 / 199316789632.0;
const D6: Real = -1453857185.0 / 822651844.0;
const D7: Real = 69997945.0 / 29380423.0;

// Step-size control of Hairer's DOPRI5.
const SAFETY: Real = 0.9;
/// Smallest step ratio h_new/h.
const FAC_MIN: Real = 0.2;
/// Largest step ratio h_new/h.
const FAC_MAX: Real = 10.0;
const BETA: Real = 0.04;
const EXPO1: Real = 0.2 - 0.75 * BETA;
/// Dormand–Prince 5(4) with PI step-size control and order-4 dense output.
#[derive(Clone, Debug)]
pub struct Dopri5<const N: usize> {
    /// Position, memory and statistics (the shared step loop's).
    core: Core<N>,
    /// Stages k1…k7 of the last accepted step (k7 = f(t, y)).
    k: [State<N>; 7],
}

/// The pair as the shared step loop sees it.
struct Pair;

impl<const N: usize> EmbeddedPair<N> for Pair {
    type Stages = Attempt<N>;
    const HINIT_ORDER: i32 = 5;
    const EVALS: u64 = 6;
    const SAFETY: Real = SAFETY;
    const FAC_MIN: Real = FAC_MIN;
    const FAC_MAX: Real = FAC_MAX;
    const EXPO: Real = EXPO1;
    const BETA: Real = BETA;

    #[inline(always)]
    fn attempt<R: Rhs<N>>(
        rhs: &R,
        t: Real,
        y: &State<N>,
        f0: &State<N>,
        h: Real,
        t_new: Real,
    ) -> (State<N>, Attempt<N>) {
        let a = attempt(rhs, t, y, f0, h, t_new);
        (a.y_new, a)
    }

    #[inline(always)]
    fn error_norm(stages: &Attempt<N>, _h: Real, scale: &State<N>) -> Real {
        rms_scaled(&stages.err, scale)
    }

    #[inline(always)]
    fn fsal(stages: &Attempt<N>) -> State<N> {
        stages.k[6]
    }
}

/// The stages of one attempt.
#[derive(Clone, Copy)]
struct Attempt<const N: usize> {
    k: [State<N>; 7],
    y_new: State<N>,
    err: State<N>,
}

fn attempt<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    k1: &State<N>,
    h: Real,
    t_new: Real,
) -> Attempt<N> {
    let k1 = *k1;
    let k2 = rhs.eval(t + C2 * h, &(y + k1 * (A21 * h)));
    let k3 = rhs.eval(t + C3 * h, &(y + (k1 * A31 + k2 * A32) * h));
    let k4 = rhs.eval(t + C4 * h, &(y + (k1 * A41 + k2 * A42 + k3 * A43) * h));
    let k5 = rhs.eval(
        t + C5 * h,
        &(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h),
    );
    let k6 = rhs.eval(
        t + h,
        &(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h),
    );
    let y_new = y + (k1 * B1 + k3 * B3 + k4 * B4 + k5 * B5 + k6 * B6) * h;
    let k7 = rhs.eval(t_new, &y_new);
    let err = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    Attempt {
        k: [k1, k2, k3, k4, k5, k6, k7],
        y_new,
        err,
    }
}

/// One Dormand–Prince 5(4) step of size `h` from `(t, y)`: the fifth-order
/// solution and the difference to the embedded fourth-order one (the local
/// error estimate), without step control. Costs 7 evaluations (6 without
/// FSAL reuse, plus `f` at the new point for the estimate).
pub fn dopri5_step<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    h: Real,
) -> (State<N>, State<N>) {
    let k1 = rhs.eval(t, y);
    let a = attempt(rhs, t, y, &k1, h, t + h);
    (a.y_new, a.err)
}

impl<const N: usize> Dopri5<N> {
    /// A stepper at `(t0, y0)` with the given tolerances and options.
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0`/`y0` or an
    /// invalid option (options are re-checked here because the struct's fields
    /// are public).
    pub fn new(t0: Real, y0: State<N>, opts: AdaptiveOptions) -> Result<Self, IntegrateError> {
        Ok(Self {
            core: Core::new(t0, y0, opts)?,
            k: [State::zeros(); 7],
        })
    }

    core_accessors!();

    /// One raw Dormand–Prince step of signed size `h` from `(t, y)`: returns the
    /// order-5 solution and the error-estimate vector `y5 − y4`. Seven
    /// evaluations, no checks, no counting.
    pub fn step_once<R: Rhs<N>>(rhs: &R, t: Real, y: &State<N>, h: Real) -> (State<N>, State<N>) {
        let k1 = rhs.eval(t, y);
        let a = attempt(rhs, t, y, &k1, h, t + h);
        (a.y_new, a.err)
    }
}

impl<const N: usize> Stepper<N> for Dopri5<N> {
    stepper_getters!(core);

    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        if let Some(a) = self.core.step::<Pair, R>(rhs, t_stop)? {
            self.k = a.k;
        }
        Ok(())
    }

    fn dense<R: Rhs<N>>(&mut self, _rhs: &R, t: Real) -> State<N> {
        let c = &self.core;
        if c.h_last == 0.0 || t == c.t {
            return c.y;
        }
        let h = c.h_last;
        let k = &self.k;
        let theta = (t - c.t_prev) / h;
        let theta1 = 1.0 - theta;
        let ydiff = c.y - c.y_prev;
        let bspl = k[0] * h - ydiff;
        let r4 = ydiff - k[6] * h - bspl;
        let r5 = (k[0] * D1 + k[2] * D3 + k[3] * D4 + k[4] * D5 + k[5] * D6 + k[6] * D7) * h;
        c.y_prev + (ydiff + (bspl + (r4 + r5 * theta1) * theta) * theta1) * theta
    }

    fn reset(&mut self, y: State<N>) {
        self.core.reset(y);
    }
}
