//! A Taylor-series method of variable order for polynomial right-hand sides,
//! with the order and step of Jorba & Zou.
//!
//! Method: at `(t, y)` the solution's normalized Taylor coefficients
//! `y_k = y⁽ᵏ⁾(t)/k!` are built order by order, `y_{k+1} = f_k / (k + 1)`,
//! where `f_k` is the order-k coefficient of `f(y(t))`. For a right-hand side
//! made of sums and products, `f_k` comes from `y_0 … y_k` by a few Cauchy
//! products `(a·b)_k = Σⱼ a_j b_{k−j}` (automatic differentiation by
//! recurrence, [`TaylorRhs`]); no derivative is ever written down by hand.
//! The step is the polynomial `y(t + h) = Σ_{k≤p} y_k hᵏ`, evaluated by
//! Horner's rule, and the same polynomial is the dense output of the step.
//!
//! Order and step (À. Jorba, M. Zou, "A software package for the numerical
//! integration of ODEs by means of high-order Taylor methods", *Experimental
//! Mathematics* 14 (2005) 99–117, Sec. 3.3; the same rule as heyoka,
//! F. Biscani & D. Izzo, MNRAS 504 (2021) 2614):
//!
//! ```text
//! p = ⌈−½ ln ε + 1⌉                                  (ε = rtol; p ≥ 2)
//! ρ = min over j ∈ {p−1, p} of (‖y‖ / ‖y_j‖)^(1/j)     (‖·‖ the max norm)
//! h = ρ · e^(−0.7/(p−1)) / e²
//! ```
//!
//! ρ estimates the radius of convergence of the series from its last two
//! coefficients; with h = ρ/e² the term of order p is about e^(−2p) ≤ ε e⁻²
//! of ‖y‖, so every step meets the tolerance without an error estimate and
//! without rejections. `‖y‖` is floored at `atol/rtol`, so the control is
//! relative above that size and absolute below it, like the error scale
//! `atol + rtol·|y|` of the Runge–Kutta pairs.
//!
//! Cost: the coefficient of order k costs about k + 1 times the arithmetic of
//! one evaluation of `f` (every product becomes a sum of k + 1 products), so a
//! step of order p costs about p(p + 1)/2 evaluations' worth. That is what
//! [`Stats::rhs_evals`] counts for this method (`p(p+1)/2` per step), so that
//! the work-precision charts compare arithmetic with arithmetic; the method
//! itself never calls [`Rhs::eval`]. [`Stats::rejected`] is always 0. The step
//! budget (`max_steps`) counts accepted steps.
//!
//! Why it wins at tight tolerances: ε enters the order, not the step. Ten
//! times more accuracy costs about one more order (½ ln 10 ≈ 1.15), that is
//! a few percent more work per step and the same number of steps, where a
//! Runge–Kutta method of order q pays 10^(1/q) more steps.
//!
//! Time scale: the coefficient of order k grows like ‖y‖ λᵏ for a rate λ, so
//! a fast top overflows a double at high orders long before its rates do
//! (the truncated top at |Ω| = 10¹² in units of 1/τ has λ ~ 10²⁴, and
//! λ¹⁵ ~ 10³⁶⁰). A jet with a non-finite coefficient is built again in a
//! scaled time s = t/σ, whose coefficients are `y_k σᵏ` (every product of
//! the recurrences keeps its total order, so only `y_{k+1} = σ f_k/(k+1)`
//! changes), with σ ~ 1/λ read off the coefficients that were finite; the
//! step and the dense output convert back. σ is 1 unless the jet overflows.
//!
//! Failure: a coefficient or state that stays non-finite ends the step with
//! [`IntegrateError::NonFinite`] at the time of the last finite state, which is
//! kept; the stepper never holds a non-finite state.

use crate::integrate::control::{
    attempt_allowed, check_start, check_t_stop, clip_step, fixed_step_allowed, stepper_getters,
    validate_options,
};
use crate::integrate::{AdaptiveOptions, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State, all_finite};

pub mod tops;

pub use tops::{
    GeneralReduced, GeneralTruncated, SymmetricReduced, SymmetricTruncated, WithOrientation,
};

/// The highest order the method uses. Jorba & Zou's rule gives order 40 at
/// ε ≈ 10⁻³³, far below what a double resolves: a tighter rtol changes
/// neither the order nor the step (ρ/e² with the terms at order 40 about
/// e⁻⁸⁰ ≈ 2·10⁻³⁵ of ‖y‖), only the floor atol/rtol of the state's size.
pub const MAX_ORDER: usize = 40;

/// How many times a step builds its jet in a shorter time unit before a
/// non-finite coefficient ends the run (each time the unit shrinks by the
/// growth the finite orders show, so one is usually enough).
const MAX_RESCALES: usize = 4;

/// Coefficients of orders 0 to [`MAX_ORDER`].
const CAP: usize = MAX_ORDER + 1;

/// The normalized Taylor coefficients `x_k = x⁽ᵏ⁾(t)/k!`, k = 0 …
/// [`MAX_ORDER`], of one scalar function of time about the start of a step.
pub type Series = [Real; CAP];

/// A series of zeros.
pub const ZERO_SERIES: Series = [0.0; CAP];

// ANCHOR: cauchy
/// Order k of the product of two series: `(a·b)_k = Σ_{j=0}^{k} a_j b_{k−j}`.
#[inline(always)]
pub fn cauchy(a: &Series, b: &Series, k: usize) -> Real {
    dot_reversed(&a[..=k], &b[..=k])
}
// ANCHOR_END: cauchy

/// Order k of several products at once: `[(a·b)_k for (a, b) in pairs]`.
///
/// NOTE: one pass over j for all of them: the M running sums are independent,
/// so the processor overlaps them, and the loop's overhead is paid once.
#[inline(always)]
pub fn cauchy_many<const M: usize>(pairs: [(&Series, &Series); M], k: usize) -> [Real; M] {
    let k = k.min(MAX_ORDER);
    let mut acc = [0.0; M];
    for j in 0..=k {
        for (s, (a, b)) in acc.iter_mut().zip(&pairs) {
            *s += a[j] * b[k - j];
        }
    }
    acc
}

/// `Σⱼ a_j b_{n−1−j}` over two slices of the same length n.
///
/// NOTE: four partial sums instead of one: a single running sum makes every
/// addition wait for the one before, and at the orders used (10–20) that
/// latency, not the arithmetic, set the cost of a step.
#[inline(always)]
pub(crate) fn dot_reversed(a: &[Real], b: &[Real]) -> Real {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0; 4];
    let chunks = a.chunks_exact(4).zip(b.rchunks_exact(4));
    for (x, y) in chunks {
        acc[0] += x[0] * y[3];
        acc[1] += x[1] * y[2];
        acc[2] += x[2] * y[1];
        acc[3] += x[3] * y[0];
    }
    let done = n - n % 4;
    let tail = a[done..]
        .iter()
        .zip(b[..n - done].iter().rev())
        .fold(0.0, |s, (x, y)| s + x * y);
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}
// ANCHOR_END: cauchy

// ANCHOR: taylor_rhs
/// An autonomous right-hand side `y' = f(y)` on ℝᴺ whose Taylor coefficients
/// come by recurrence: given the solution's coefficients of orders `0..=k`, the
/// coefficient of order k of `f(y(t))`.
///
/// The auxiliary series (a product kept because later orders need it again)
/// live in [`TaylorRhs::Aux`], which the stepper keeps between orders of one
/// step and hands back at order 0 of the next.
pub trait TaylorRhs<const N: usize> {
    /// The auxiliary series of the recurrences.
    type Aux: Clone + std::fmt::Debug;

    /// Where the blocks of components that are measured on a scale of their
    /// own end (ascending, the last one `N`); empty: all N together.
    const BLOCK_ENDS: &'static [usize] = &[];

    /// Fresh auxiliary storage.
    fn aux(&self) -> Self::Aux;

    /// `f_k`: the order-k coefficient of `f(y(t))`, from `y[i][0..=k]` (one
    /// series per component, `y.len() ≥ N`; later orders are not read). May
    /// write order k of the auxiliary series.
    fn coefficient(&self, aux: &mut Self::Aux, y: &[Series], k: usize) -> [Real; N];
}
// ANCHOR_END: taylor_rhs

/// Jorba & Zou's order for a tolerance ε: ⌈−½ ln ε + 1⌉, at least 2 and at
/// most [`MAX_ORDER`].
pub fn taylor_order(eps: Real) -> usize {
    let p = (-0.5 * eps.ln() + 1.0).ceil();
    if p.is_nan() {
        return MAX_ORDER;
    }
    (p.max(2.0) as usize).min(MAX_ORDER)
}

/// The factor e^(−0.7/(p−1))/e² of Jorba & Zou's step at order p.
fn step_factor(order: usize) -> Real {
    (-0.7 / (order as Real - 1.0)).exp() / std::f64::consts::E.powi(2)
}

/// The longest step, in units of 1/λ, at which the order-p series of the
/// method at `rtol` still damps a decay `y' = −λy`: the largest x with
/// |T_p(−x')| ≤ 1 for every x' in [0, x], where `T_p(z) = Σ_{k≤p} zᵏ/k!`
/// (about 5.45 at rtol 1e-8, order 11; 8.07 at 1e-14, order 18; DOP853's is
/// about 6).
///
/// On a stiff problem this, not the tolerance, holds the step: a fast decay
/// whose component is small against the state (Ω⊥ beside a large Ω₃ on the
/// reduced top) is measured against the state's size, so the series does
/// not resolve it; a longer step would amplify it until its coefficients
/// shorten the step again, so the steps settle at this limit, as an explicit
/// Runge–Kutta method's do at the edge of its stability region.
pub fn stability_interval(rtol: Real) -> Real {
    let p = taylor_order(rtol);
    let t_p = |x: Real| {
        let mut c = [0.0; CAP];
        c[0] = 1.0;
        for k in 1..=p {
            c[k] = c[k - 1] / k as Real;
        }
        c[..=p].iter().rev().fold(0.0, |acc, ck| acc * -x + ck)
    };
    // Walk out in steps of 1/64 to the first x where |T_p| exceeds 1, then
    // halve the bracket.
    let (mut lo, mut hi) = (0.0, 0.0);
    while hi < 100.0 {
        hi += 1.0 / 64.0;
        if t_p(hi).abs() > 1.0 {
            break;
        }
        lo = hi;
    }
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if t_p(mid).abs() > 1.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The Taylor method on a [`TaylorRhs`], which it owns.
#[derive(Clone, Debug)]
pub struct Taylor<const N: usize, S: TaylorRhs<N>> {
    system: S,
    aux: S::Aux,
    /// The coefficients of the last accepted step (its dense output), in
    /// units of `scale`.
    jet: [Series; N],
    /// The time unit σ of the jet (1 unless the coefficients in units of 1
    /// overflow).
    scale: Real,
    t: Real,
    y: State<N>,
    t_prev: Real,
    h_last: Real,
    order: usize,
    /// The step factor e^(−0.7/(p−1))/e².
    rho_factor: Real,
    opts: AdaptiveOptions,
    stats: Stats,
}

impl<const N: usize, S: TaylorRhs<N>> Taylor<N, S> {
    /// A stepper for `system` at `(t0, y0)`; the order comes from `opts.rtol`
    /// ([`taylor_order`]), `opts.h_init` is not used (every step size comes
    /// from the series).
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0`/`y0` or
    /// an invalid option.
    pub fn new(
        system: S,
        t0: Real,
        y0: State<N>,
        opts: AdaptiveOptions,
    ) -> Result<Self, IntegrateError> {
        validate_options(&opts)?;
        check_start(t0, all_finite(&y0))?;
        let order = taylor_order(opts.rtol);
        let aux = system.aux();
        Ok(Self {
            system,
            aux,
            jet: [ZERO_SERIES; N],
            scale: 1.0,
            t: t0,
            y: y0,
            t_prev: t0,
            h_last: 0.0,
            order,
            rho_factor: step_factor(order),
            opts,
            stats: Stats::default(),
        })
    }

    /// The order p of every step.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The system being integrated.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// The options the stepper was built with.
    pub fn options(&self) -> &AdaptiveOptions {
        &self.opts
    }

    /// Change the largest step magnitude from the next step on (ignored
    /// unless positive).
    pub fn set_h_max(&mut self, h_max: Real) {
        if h_max > 0.0 {
            self.opts.h_max = h_max;
        }
    }

    /// The normalized Taylor coefficients of the last accepted step about its
    /// start, component `i` and order `k` at `[i][k]` (orders above
    /// [`Taylor::order`] are not meaningful), in the time unit
    /// [`Taylor::time_scale`]: `y⁽ᵏ⁾(t) σᵏ/k!`.
    pub fn coefficients(&self) -> &[Series; N] {
        &self.jet
    }

    /// The time unit σ of [`Taylor::coefficients`]: 1, unless the
    /// coefficients in units of 1 overflowed a double (see the module notes).
    pub fn time_scale(&self) -> Real {
        self.scale
    }

    /// One step toward `t_stop`, of the size the series allows, never past
    /// it ([`Stepper::step`] without a right-hand side: the stepper owns its
    /// system). Calling it with `t_stop == t()` is a no-op.
    pub fn advance(&mut self, t_stop: Real) -> Result<(), IntegrateError> {
        check_t_stop(t_stop)?;
        if t_stop == self.t {
            return Ok(());
        }
        // No attempt is ever rejected: the budget counts accepted steps.
        fixed_step_allowed(self.stats.steps, self.opts.max_steps, self.t)?;
        let order_p = self.order;
        let p = order_p as u64;
        // After a scaled step, the last step's length is the natural unit
        // (its coefficients then fall off like e^(−2k)); otherwise 1.
        let mut scale = if self.scale < 1.0 && self.h_last != 0.0 {
            self.h_last.abs().min(1.0)
        } else {
            1.0
        };
        // The jet about to be built replaces the last step's polynomial: until
        // this step is taken the dense output holds at the current state only.
        self.h_last = 0.0;
        self.t_prev = self.t;
        let mut finite = false;
        for _ in 0..MAX_RESCALES {
            self.build_jet(scale);
            self.stats.rhs_evals += p * (p + 1) / 2;
            match self.rescaled(scale) {
                None => {
                    finite = true;
                    break;
                }
                Some(s) if s > 0.0 && s < scale => scale = s,
                Some(_) => break,
            }
        }
        if !finite {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        self.scale = scale;
        let h = self.scale * self.step_size().min(self.opts.h_max / self.scale);
        let dir = (t_stop - self.t).signum();
        attempt_allowed(&self.stats, self.opts.max_steps, self.t, h, dir)?;
        let (h, t_new, _) = clip_step(self.t, t_stop, h);
        let y_new = self.horner(h);
        if !all_finite(&y_new) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        self.stats.steps += 1;
        self.t_prev = self.t;
        self.t = t_new;
        self.y = y_new;
        self.h_last = h;
        Ok(())
    }

    /// The last step's own polynomial at `t` in `[t_prev(), t()]` (the
    /// current state before any step): as accurate as the step, for one
    /// Horner evaluation ([`Stepper::dense`] without a right-hand side).
    pub fn value_at(&self, t: Real) -> State<N> {
        if self.h_last == 0.0 || t == self.t {
            return self.y;
        }
        self.horner(t - self.t_prev)
    }

    /// Fill the jet at the current state, orders 0 to p, in the time unit
    /// `scale`.
    fn build_jet(&mut self, scale: Real) {
        for (series, &y) in self.jet.iter_mut().zip(self.y.iter()) {
            series[0] = y;
        }
        for k in 0..self.order {
            let f = self.system.coefficient(&mut self.aux, &self.jet, k);
            let inv = scale / (k as Real + 1.0);
            for (series, fk) in self.jet.iter_mut().zip(f) {
                series[k + 1] = fk * inv;
            }
        }
    }

    /// `None` when the jet just built in units of `scale` is finite; else
    /// a smaller time unit under which its growth, read off the orders that
    /// are finite, is about 1 per order (`Some(scale)` when there is none:
    /// already order 1 is not finite, the rate itself overflows).
    fn rescaled(&self, scale: Real) -> Option<Real> {
        let finite = |k: usize| self.jet.iter().all(|s| s[k].is_finite());
        let last = (0..=self.order).take_while(|&k| finite(k)).last()?;
        if last == self.order {
            return None;
        }
        let max_abs = |k: usize| self.jet.iter().fold(0.0 as Real, |m, s| m.max(s[k].abs()));
        let size = max_abs(0).max(self.opts.atol / self.opts.rtol);
        let size = if size > 0.0 { size } else { 1.0 };
        let rate = (1..=last)
            .map(|k| (max_abs(k) / size).powf(1.0 / k as Real))
            .fold(0.0, Real::max);
        // NOTE: e² more than the rate, so that the last orders are small
        // rather than about ‖y‖ (they must not overflow in the products).
        let shrink = std::f64::consts::E.powi(2) * rate;
        Some(if shrink.is_finite() && shrink > 1.0 {
            scale / shrink
        } else {
            scale / 1e8
        })
    }

    /// The step magnitude, in units of the jet's time scale, of Jorba & Zou
    /// from the jet (infinite when the two
    /// last coefficients vanish: the polynomial is then the exact solution).
    ///
    /// NOTE: each block of [`TaylorRhs::BLOCK_ENDS`] gets its own scale ‖y‖
    /// and the shortest of the blocks' steps is taken: the orientation
    /// quaternion has length 1 whatever |Ω| is, and one max norm over both
    /// would measure Ω's error against the quaternion's size.
    fn step_size(&self) -> Real {
        let p = self.order;
        let floor = self.opts.atol / self.opts.rtol;
        let ends: &[usize] = if S::BLOCK_ENDS.is_empty() {
            &[N]
        } else {
            S::BLOCK_ENDS
        };
        let mut rho = Real::INFINITY;
        let mut start = 0;
        for &end in ends {
            let block = &self.jet[start.min(N)..end.min(N)];
            start = end;
            let max_abs = |k: usize| block.iter().fold(0.0 as Real, |m, s| m.max(s[k].abs()));
            // NOTE: a state of size 0 with atol = 0 has no scale at all; it is
            // measured in absolute units then, as heyoka does below size 1.
            let size = match max_abs(0).max(floor) {
                0.0 => 1.0,
                s => s,
            };
            for k in [p - 1, p] {
                let c = max_abs(k);
                if c > 0.0 {
                    rho = rho.min((size / c).powf(1.0 / k as Real));
                }
            }
        }
        rho * self.rho_factor
    }

    /// The jet's polynomial at signed offset `dt` from the start of its step
    /// (Horner's rule, the N components side by side).
    fn horner(&self, dt: Real) -> State<N> {
        let dt = dt / self.scale;
        let mut acc = [0.0; N];
        for k in (0..=self.order).rev() {
            for (a, s) in acc.iter_mut().zip(&self.jet) {
                *a = *a * dt + s[k];
            }
        }
        State::<N>::from(acc)
    }
}

impl<const N: usize, S: TaylorRhs<N>> Stepper<N> for Taylor<N, S> {
    stepper_getters!();

    /// One step toward `t_stop` ([`Taylor::advance`]).
    ///
    /// NOTE: the method steps the recurrences of the system it owns; `rhs` is
    /// not called (pass the same system's [`Rhs`] view, as
    /// [`crate::integrate::solve`] needs one).
    fn step<R: Rhs<N>>(&mut self, _rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        self.advance(t_stop)
    }

    /// The step's own polynomial at `t` ([`Taylor::value_at`]).
    fn dense<R: Rhs<N>>(&mut self, _rhs: &R, t: Real) -> State<N> {
        self.value_at(t)
    }

    fn reset(&mut self, y: State<N>) {
        self.y = y;
        self.t_prev = self.t;
        self.h_last = 0.0;
    }
}
