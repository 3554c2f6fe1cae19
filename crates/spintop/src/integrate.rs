//! Numerical methods for `y' = f(t, y)` on fixed-size states.
//!
//! Every Runge–Kutta method is generic over one small trait, [`Rhs`], steps a
//! fixed-size [`State`] (no allocation per step) and implements [`Stepper`]; the
//! splitting methods compose exact sub-flows instead (see below). Every method
//! counts its work in [`Stats`], and reports a numerical failure
//! (a non-finite state, a step-size underflow, an exhausted step budget) as an
//! [`IntegrateError`] that carries the time `t` where it happened. A method never
//! hands back a NaN sample.
//!
//! | method | order | step control | continuous extension |
//! |---|---|---|---|
//! | [`Rk4`] | 4 | fixed step | cubic Hermite |
//! | [`Dopri5`] | 5(4) | PI controller | Shampine's order-4 interpolant |
//! | [`Dop853`] | 8(5,3) | Hairer's controller | order-7 interpolant (3 extra stages) |
//! | [`Radau5`] | 5 (implicit, L-stable) | Hairer's RADAU5 (predictive), or fixed step | the collocation polynomial (order 3) |
//! | [`Splitting`] ([`Composition::LieTrotter`]) | 1 (exact for commuting parts) | fixed step | none |
//! | [`Splitting`] ([`Composition::Strang`]) | 2, symmetric | fixed step | none |
//! | [`Splitting`] ([`Composition::Yoshida4`]) | 4, symmetric | fixed step | none |
//! | [`Taylor`] | variable, ⌈−½ ln rtol + 1⌉ (11 at 1e-8, 18 at 1e-14) | Jorba & Zou, from the last two coefficients; no rejections | the step's own Taylor polynomial |
//!
//! The two explicit pairs share one adaptive step loop (`explicit.rs`: the
//! error test, the controller, rejection and the statistics); each keeps only
//! its stages, error norm, controller constants and dense output. The step
//! control they, Radau IIA 5, RK4 and the splittings share (the checks before
//! a run and before each attempt, the first stage and Hairer's starting step,
//! landing on `t_stop`, the error norm) lives once, in `control.rs`, and no
//! method file imports another.
//!
//! All of them step forward or backward: the direction is the sign of
//! `t_stop − t`. The explicit methods use only [`Rhs::eval`]; [`Radau5`] also
//! calls [`Rhs::jacobian`] (analytic when the right-hand side provides it, else
//! forward differences).
//!
//! The Taylor method needs more than `f`: the Taylor coefficients of `f(y(t))`
//! order by order, which a [`TaylorRhs`] gives by recurrence for a right-hand
//! side made of sums and products (each top model has one, in
//! `taylor/tops.rs`). The stepper owns that system and implements [`Stepper`]
//! without calling the `rhs` it is handed; it shares the checks of
//! `control.rs` with the others.
//!
//! The splittings do not take a right-hand side: they compose the exact flows
//! of the parts of any [`SplitFlow`] (the free rigid body cut into three axis
//! rotations, the reduced model (4.12)–(4.14) cut into a rotation and a
//! damping: see [`crate::sim::split`]), on a state that may hold an
//! orientation, so they have their own small API instead of [`Stepper`]. They
//! count sub-flow evaluations in [`Stats::rhs_evals`].

use crate::math::{Real, State};
use nalgebra::SMatrix;
use serde::Serialize;
use thiserror::Error;

pub(crate) mod control;
pub mod dop853;
pub mod dopri5;
pub(crate) mod explicit;
pub mod radau5;
pub mod rk4;
pub mod splitting;
pub mod taylor;

pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use radau5::Radau5;
pub use rk4::Rk4;
pub use splitting::{Composition, SplitFlow, Splitting};
pub use taylor::{Taylor, TaylorRhs};

// ANCHOR: rhs_trait
/// A right-hand side `y' = f(t, y)` on ℝᴺ.
pub trait Rhs<const N: usize> {
    /// Evaluate `f(t, y)`.
    fn eval(&self, t: Real, y: &State<N>) -> State<N>;

    /// The Jacobian `∂f/∂y` at `(t, y)`: entry `(i, j)` is `∂f_i/∂y_j`.
    ///
    /// Only the implicit method ([`Radau5`]) calls it. The default is
    /// [`forward_difference_jacobian`], which costs `N + 1` evaluations of
    /// [`Rhs::eval`] and has an error of about √ε relative to the entries; a
    /// right-hand side that knows its derivative should override it (an
    /// analytic Jacobian is exact, cheaper, and keeps the simplified Newton
    /// iteration converging on very stiff problems).
    fn jacobian(&self, t: Real, y: &State<N>) -> SMatrix<Real, N, N> {
        forward_difference_jacobian(self, t, y)
    }
}
// ANCHOR_END: rhs_trait

/// The Jacobian `∂f/∂y` of `rhs` at `(t, y)` by forward differences, one
/// column per component: `(f(t, y + δⱼeⱼ) − f(t, y)) / δⱼ`.
///
/// The increment is Hairer's `δⱼ = √(ε · max(10⁻⁵, |yⱼ|))` (RADAU5's
/// numerical Jacobian; E. Hairer, G. Wanner, *Solving Ordinary Differential
/// Equations II*, 2nd ed., Springer 1996, Sec. IV.8), rounded so that
/// `yⱼ + δⱼ` is exactly representable. Costs `N + 1` evaluations.
pub fn forward_difference_jacobian<const N: usize, R: Rhs<N> + ?Sized>(
    rhs: &R,
    t: Real,
    y: &State<N>,
) -> SMatrix<Real, N, N> {
    let f0 = rhs.eval(t, y);
    let mut jac = SMatrix::<Real, N, N>::zeros();
    for j in 0..N {
        let mut yj = *y;
        let delta = (Real::EPSILON * y[j].abs().max(1e-5)).sqrt();
        yj[j] += delta;
        // NOTE: divide by the increment actually applied, not the one asked for.
        let delta = yj[j] - y[j];
        let column = (rhs.eval(t, &yj) - f0) / delta;
        jac.set_column(j, &column);
    }
    jac
}

impl<const N: usize, F> Rhs<N> for F
where
    F: Fn(Real, &State<N>) -> State<N>,
{
    fn eval(&self, t: Real, y: &State<N>) -> State<N> {
        self(t, y)
    }
}

/// The work a method has done so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Evaluations of the right-hand side, including those for the initial
    /// step-size guess and for continuous output.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts (always 0 for fixed-step methods).
    pub rejected: u64,
}

impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, other: Stats) {
        self.rhs_evals += other.rhs_evals;
        self.steps += other.steps;
        self.rejected += other.rejected;
    }
}

/// A numerical failure, always with the time at which it was detected.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum IntegrateError {
    /// The state or the error estimate stopped being finite.
    #[error("the solution became non-finite at t = {}", crate::numbers::fmt_time(*t))]
    NonFinite {
        /// Time of the last finite state.
        t: Real,
    },
    /// The adaptive step size fell below what the floating-point time axis can resolve.
    #[error("the step size fell to {h:.3e} at t = {}, below what the time axis can resolve", crate::numbers::fmt_time(*t))]
    StepSizeUnderflow {
        /// Time where the method gave up.
        t: Real,
        /// The last step size tried.
        h: Real,
    },
    /// More accepted steps than the budget allows (a guard against hangs).
    #[error("the step budget of {max_steps} steps ran out at t = {}", crate::numbers::fmt_time(*t))]
    TooManySteps {
        /// Time reached when the budget ran out.
        t: Real,
        /// The budget.
        max_steps: u64,
    },
    /// The implicit method's Newton iteration did not converge and the step
    /// could not be shortened (the fixed-step mode of [`Radau5`]).
    #[error(
        "the Newton iteration of the implicit method did not converge at t = {} with step {h:.3e}", crate::numbers::fmt_time(*t)
    )]
    NoConvergence {
        /// Time of the step's start (the state there is kept).
        t: Real,
        /// The signed step size tried.
        h: Real,
    },
    /// An option was rejected when the method was built.
    #[error("invalid integrator option: {0}")]
    InvalidOption(String),
}

/// Options of the adaptive methods, validated by [`AdaptiveOptions::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveOptions {
    /// Relative tolerance, in (0, 1).
    pub rtol: Real,
    /// Absolute tolerance, ≥ 0 (the error of component i is scaled by
    /// `atol + rtol·max(|y_i|, |y_new_i|)`).
    pub atol: Real,
    /// First step size; `None` lets the method choose (Hairer's `hinit`).
    pub h_init: Option<Real>,
    /// Largest step size magnitude.
    pub h_max: Real,
    /// Budget of accepted plus rejected steps for the life of the stepper.
    pub max_steps: u64,
}

/// The default step budget: enough for any run the CLI offers, small enough
/// that a hopeless run stops within seconds instead of hanging.
pub const DEFAULT_MAX_STEPS: u64 = 10_000_000;

impl AdaptiveOptions {
    /// Tolerances with defaults for the rest; rejects non-finite or out-of-range values.
    pub fn new(rtol: Real, atol: Real) -> Result<Self, IntegrateError> {
        let opts = Self {
            rtol,
            atol,
            h_init: None,
            h_max: Real::INFINITY,
            max_steps: DEFAULT_MAX_STEPS,
        };
        control::validate_options(&opts)?;
        Ok(opts)
    }
}

// ANCHOR: stepper_trait
/// A one-step method that owns its current time and state.
///
/// The driver calls [`Stepper::step`] until [`Stepper::t`] reaches its goal, and
/// reads values between step points with [`Stepper::dense`].
pub trait Stepper<const N: usize> {
    /// Current time.
    fn t(&self) -> Real;
    /// Current state.
    fn y(&self) -> &State<N>;
    /// Start of the last accepted step (equal to `t()` before the first step).
    fn t_prev(&self) -> Real;
    /// Signed size of the last accepted step (0 before the first step).
    fn last_step(&self) -> Real;
    /// Work done so far.
    fn stats(&self) -> Stats;
    /// Take one accepted step toward `t_stop`, never past it. Rejected attempts
    /// are retried inside and counted in [`Stats::rejected`]. Backward steps are
    /// taken when `t_stop < t()`. Calling it with `t_stop == t()` is a no-op.
    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError>;
    /// The continuous extension of the last accepted step at `t` in
    /// `[t_prev(), t()]` (or the current state before any step).
    fn dense<R: Rhs<N>>(&mut self, rhs: &R, t: Real) -> State<N>;
    /// Replace the current state (same time) after the driver changed it, for
    /// example when a Lie-group method folds its local coordinates into the base
    /// orientation. Cached stages (FSAL) are dropped.
    fn reset(&mut self, y: State<N>);
}
// ANCHOR_END: stepper_trait

// ANCHOR: solve
/// Integrate from the stepper's current time through every time in `times`
/// (all on the same side of the start, in order) and return the states there.
///
/// Adaptive methods step freely toward the last time and read earlier ones from
/// their continuous extension, so output times do not shorten the steps.
pub fn solve<const N: usize, S: Stepper<N>, R: Rhs<N>>(
    stepper: &mut S,
    rhs: &R,
    times: &[Real],
) -> Result<Vec<State<N>>, IntegrateError> {
    let mut out = Vec::with_capacity(times.len());
    let Some(&t_end) = times.last() else {
        return Ok(out);
    };
    let forward = t_end >= stepper.t();
    for &t in times {
        // Step until the output time lies inside the last accepted step.
        while if forward {
            stepper.t() < t
        } else {
            stepper.t() > t
        } {
            stepper.step(rhs, t_end)?;
        }
        out.push(if t == stepper.t() {
            *stepper.y()
        } else {
            stepper.dense(rhs, t)
        });
    }
    Ok(out)
}
// ANCHOR_END: solve
