//! The physical (non-runaway) solution of the full ALE (3.4) for the symmetric
//! top, and what happens when (3.4) is integrated forward.
//!
//! With z = Ω₁ + iΩ₂, (3.4) reads τz̈ = ż + iΩ̃₃z + τ(|z|² + Ω₃²)z − 2iτΩ₃ż (see
//! [`crate::physics::full_ale`]). Its solutions form a 4-dimensional family, but
//! only a 2-dimensional "slow manifold" ż = f(|z|²) z is physical; every other
//! solution leaves it at a rate of about 1/τ (the runaway).
//!
//! - **Forward integration** from any start off the manifold runs away; a
//!   monitor watches the distance from the manifold and stops the run with the
//!   time and the measured growth rate.
//! - **Backward integration** turns the runaway into decay (deviations shrink as
//!   e^{−(T−t)/τ}), so integrating back from final data near the manifold lands
//!   on the physical solution. Matching a given Ω(0) then needs a shoot on one
//!   number, the final amplitude |z(T)|; the phase follows from the symmetry
//!   z → e^{iα}z of the equation.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `u` | \|z\|² = Ω⊥² | squared perpendicular rate | 1/τ² |
//! | `k` | (I₃/I₁)Ω₃ | spin term | 1/τ |
//! | `f` | f(u) | ż/z on the slow manifold (complex) | 1/τ |
//! | `sigma_phys` | σ_phys | exact late-time decay time of \|z\| | τ |

pub mod general;
pub mod series;
pub mod slow;

use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Stats, Stepper};
use crate::math::{Real, State, Vec3};
use crate::physics::full_ale::symmetric_full_ale_rhs;
use crate::physics::symmetric_top::SymmetricTop;
use nalgebra::Complex;
use thiserror::Error;

// ANCHOR: slow_manifold_rate
/// ż/z on the slow manifold of (3.4), as a series in τ (the physics notes,
/// carried two orders further).
///
/// Paper: Eq. (3.4) (its physical solution; the series is not in the paper).
///
/// ```text
/// Re f = −τs + τ³s(3u + 5k²) − 2τ⁵s(3k² + 4u)(7k² + 3u) + O(τ⁷)
/// Im f = −Ω̃₃ − 2τ²ks + 14τ⁴ks² + O(τ⁶),        s = u + k²
/// ```
///
/// Each order follows from the invariance equation
/// τ(f² + 2uf′ Re f) = f + iΩ̃₃ + τ(u + Ω₃²) − 2iτΩ₃f, order by order in τ
/// (the book's `auto` section derives the first three). The first terms are
/// the reduced model (4.12)–(4.13): it is right through O(τ); its precession
/// rate is off at O(τ²) and its decay rate at O(τ³), and each correction's
/// next term has the opposite sign.
pub fn slow_manifold_rate(top: &SymmetricTop, omega3: Real, u: Real) -> Complex<Real> {
    let tau = top.tau();
    let k = top.ratio() * omega3;
    let (k2, s) = (k * k, u + k * k);
    let (t2, t3) = (tau * tau, tau * tau * tau);
    Complex::new(
        -tau * s + t3 * s * (3.0 * u + 5.0 * k2)
            - 2.0 * t3 * t2 * s * (3.0 * k2 + 4.0 * u) * (7.0 * k2 + 3.0 * u),
        -top.omega3_tilde(omega3) - 2.0 * t2 * k * s + 14.0 * t2 * t2 * k * s * s,
    )
}
// ANCHOR_END: slow_manifold_rate

/// The exact late-time decay time of |z| on the slow manifold, where u → 0.
///
/// Paper: Eq. (3.4) (compare σ of (4.16), which it exceeds by about 5τ).
///
/// ```text
/// σ_phys = 2τ / (√((1 + √(1 + 16τ²k²))/2) − 1)
/// ```
///
/// As u → 0, f tends to the slow root of τf² − (1 − 2iτΩ₃)f − (iΩ̃₃ + τΩ₃²) = 0,
/// f = (1 − 2iτΩ₃ − √(1 − 4iτk))/(2τ), whose real part is −1/σ_phys.
pub fn late_time_decay_time(top: &SymmetricTop, omega3: Real) -> Real {
    let tau = top.tau();
    let k = top.ratio() * omega3;
    let a = ((1.0 + (1.0 + 16.0 * tau * tau * k * k).sqrt()) / 2.0).sqrt();
    2.0 * tau / (a - 1.0)
}

/// The slow root of linear theory: the physical solution of (3.4) near
/// z = 0 is exactly z(t) = z(t₀) e^{f₀(t − t₀)}, up to O(τ|z|²) in the rate.
///
/// Paper: Eq. (3.4) (its linearisation about z = 0; not in the paper).
///
/// ```text
/// f₀ = (1 − 2iτΩ₃ − √(1 − 4iτk))/(2τ) = −iΩ₃ + 2ik/(1 + √(1 − 4iτk))
/// ```
///
/// The second form has no cancellation as τk → 0, where it tends to the
/// reduced model's −iΩ̃₃ − τk²; its real part is −1/σ_phys
/// ([`late_time_decay_time`]).
pub fn linear_theory_rate(top: &SymmetricTop, omega3: Real) -> Complex<Real> {
    let tau = top.tau();
    let k = top.ratio() * omega3;
    let i = Complex::new(0.0, 1.0);
    let root = (Complex::new(1.0, -4.0 * tau * k)).sqrt();
    -i * omega3 + 2.0 * i * k / (1.0 + root)
}

/// ż/z on the slow manifold of (3.4) near rest, exact in τk: the slow root
/// f₀ of linear theory ([`linear_theory_rate`]) and its first change with
/// u = |z|².
///
/// Paper: Eq. (3.4) (its slow manifold; not in the paper).
///
/// ```text
/// f(u) = f₀ + f′(0)u + O(u²),    f′(0) = τ / (2τf₀ + 2τ Re f₀ − 1 + 2iτΩ₃)
/// ```
///
/// (the invariance equation differentiated once at u = 0; for small τk,
/// f′(0) = −τ(1 + 2iτk) + O(τ³), the u-terms of [`slow_manifold_rate`]).
/// Unlike that series, whose τ⁴ and τ⁵ terms grow like (τk)⁴ and (τk)⁶ and
/// swamp it once τk ≳ 1, it holds at every spin where u is small, as it is
/// at the end of a shot.
pub fn near_rest_rate(top: &SymmetricTop, omega3: Real, u: Real) -> Complex<Real> {
    let tau = top.tau();
    let f0 = linear_theory_rate(top, omega3);
    let slope =
        tau / (2.0 * tau * f0 + 2.0 * tau * f0.re - 1.0 + Complex::new(0.0, 2.0 * tau * omega3));
    f0 + slope * u
}

/// Why the physical solution could not be found.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PhysicalError {
    /// The backward integration failed.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// The shoot on the final amplitude did not bracket or converge.
    #[error("the shoot on the final amplitude did not converge ({0})")]
    NoConvergence(&'static str),
    /// Bad request.
    #[error("{0}")]
    BadInput(&'static str),
    /// The runaway and the slow motion are not separated: no slow manifold
    /// to shoot onto (a general top spun so fast that τ_f|Ω| is of order 1).
    #[error(
        "(3.4) has no slow manifold to find here at t = {}: the slow motion decays at {} per time unit, too close to the runaway's {} (the physical solution needs the first well below the second)",
        crate::numbers::fmt_time(*t),
        crate::numbers::fmt_num(*slow),
        crate::numbers::fmt_num(*fast)
    )]
    NotSeparated {
        /// When.
        t: Real,
        /// The fastest decay of the slow modes.
        slow: Real,
        /// The slowest runaway rate.
        fast: Real,
    },
}

/// The physical solution of (3.4) sampled at the requested times.
#[derive(Clone, Debug, PartialEq)]
pub struct PhysicalSolution {
    /// The times.
    pub times: Vec<Real>,
    /// z = Ω₁ + iΩ₂ at each time.
    pub z: Vec<Complex<Real>>,
    /// ż at each time.
    pub z_dot: Vec<Complex<Real>>,
    /// Work of the final backward integration plus all shots.
    pub stats: Stats,
    /// Number of backward integrations (shots).
    pub shots: u32,
}

/// The slow decay rate the bracket of the shoot starts from: the physical
/// solution's own late-time rate 1/σ_phys (exact as u → 0, linear theory),
/// and the reduced model's τΩ⊥² on top of it for the amplitude.
///
/// ```text
/// ln(a/|z₀|) ≈ −T/σ_phys − ½ ln(1 + 2τΩ⊥₀² T g),   g = (1 − e^{−2T/σ_phys})/(2T/σ_phys)
/// ```
///
/// (the reduced amplitude (4.16) with τk² replaced by 1/σ_phys: the two agree
/// while τk is small, and at τk ≳ 1 the reduced model decays far too fast).
pub(super) fn guessed_log_amplitude(top: &SymmetricTop, omega0: &Vec3, span: Real) -> Real {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let rate = 1.0 / late_time_decay_time(top, omega0.z);
    let s = 2.0 * rate * span;
    let g = if s > 0.0 { -(-s).exp_m1() / s } else { 1.0 };
    0.5 * u0.ln() - 0.5 * s - 0.5 * (2.0 * top.tau() * u0 * span * g).ln_1p()
}

/// How far beyond the last requested time the shoot starts: backward, the
/// fast mode of (3.4) dies at (1 + α)/(2τ) and the slow one grows at
/// (α − 1)/(2τ), α = Re √(1 − 4iτk) = √((1 + √(1 + 16τ²k²))/2) (the roots of
/// linear theory, [`late_time_decay_time`]); their ratio falls at α/τ, and
/// 40τ/α damps the error of the final data by e^{−40}.
pub(super) fn final_margin(top: &SymmetricTop, omega3: Real) -> Real {
    let tau = top.tau();
    let k = top.ratio() * omega3;
    let alpha = ((1.0 + (1.0 + 16.0 * tau * tau * k * k).sqrt()) / 2.0).sqrt();
    40.0 * tau / alpha
}

/// The physical solution of (3.4) through Ω₀ (symmetric top), at `times`
/// (finite, ≥ 0, ascending), by [`slow::slow_table`]: shots backward from
/// final data near the slow manifold while |z| is large, the slow manifold's
/// own series once it is small, its closed form at the end; the first
/// sample is Ω₀ itself.
pub fn physical_solution(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<PhysicalSolution, PhysicalError> {
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] < w[0]) {
        return Err(PhysicalError::BadInput(
            "times must be finite, >= 0 and ascending",
        ));
    }
    let span = times.last().copied().unwrap_or(0.0);
    let mut budget = slow::Budget {
        rtol: internal_rtol(rtol),
        steps: crate::integrate::DEFAULT_MAX_STEPS,
        refine: 1.0,
    };
    let table = slow::slow_table(top, omega0, span, &mut budget)?;
    let alpha = table.precession();
    let mut sol = PhysicalSolution {
        times: times.to_vec(),
        z: Vec::with_capacity(times.len()),
        z_dot: Vec::with_capacity(times.len()),
        stats: table.stats,
        shots: table.shots,
    };
    for &t in times {
        let (w, w1) = table.w_at(t);
        let turn = Complex::from_polar(1.0, -alpha * t);
        sol.z.push(w * turn);
        sol.z_dot.push((w1 - w * Complex::new(0.0, alpha)) * turn);
    }
    Ok(sol)
}

/// The tolerance the physical solution's integrators run at: the user's, at
/// most 1e-6 (looser, DOP853 no longer damps the backward passes' fast mode
/// step by step, and the shoot on the final amplitude fails to converge).
pub fn internal_rtol(rtol: Real) -> Real {
    rtol.min(1e-6)
}

/// A runaway detected by [`integrate_forward`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Runaway {
    /// When the monitor stopped the run.
    pub t: Real,
    /// The measured growth rate of the distance from the slow manifold.
    pub growth_rate: Real,
}

impl std::fmt::Display for Runaway {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "runaway detected at t = {:.3}: the state leaves the physical solution at rate {:.4}/tau (an e-folding time of {:.3} tau); integrate backward or use the reduced model",
            self.t,
            self.growth_rate,
            1.0 / self.growth_rate
        )
    }
}

/// What a forward integration of (3.4) produced before it stopped: for the
/// symmetric top the state is (z, ż) (N = 4), for a general top (Ω, Ω̇) (N = 6).
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardRun<const N: usize = 4> {
    /// Times and states reached, one entry per monitoring interval.
    pub trace: Vec<(Real, State<N>)>,
    /// The runaway, if the monitor stopped the run.
    pub runaway: Option<Runaway>,
    /// Work done.
    pub stats: Stats,
}

/// Integrate (3.4) forward from (z, ż) = `y0` with DOP853, sampling every τ/4,
/// and stop when the state has visibly left the slow manifold, |ż − f(|z|²)z|
/// above 5% of |z|·(1/τ), while that distance grows faster than 1/(2τ).
///
/// The growth rate is the least-squares slope of ln|ż − f z| over the last 2τ.
/// NOTE: the threshold is relative and absolute on purpose. A start off the
/// manifold (say the reduced model's slope) crosses it within a few τ; a start
/// on the physical solution carries only rounding-size deviations, and those
/// need about ln(1e10) ≈ 23 τ of e^{t/τ} growth to get there.
pub fn integrate_forward(
    top: &SymmetricTop,
    omega3: Real,
    y0: State<4>,
    t_end: Real,
    rtol: Real,
) -> Result<ForwardRun, PhysicalError> {
    let tau = top.tau();
    if tau <= 0.0 {
        return Err(PhysicalError::BadInput("the full ALE needs tau > 0"));
    }
    let rhs = |_t: Real, y: &State<4>| symmetric_full_ale_rhs(top, omega3, y);
    let distance = |y: &State<4>| {
        let z = Complex::new(y[0], y[1]);
        let v = Complex::new(y[2], y[3]);
        (
            (v - slow_manifold_rate(top, omega3, z.norm_sqr()) * z).norm(),
            z.norm(),
        )
    };
    forward_with_monitor(&rhs, y0, tau, t_end, rtol, distance)
}

/// The runaway monitor of [`integrate_forward`], for any full-ALE system:
/// `distance(y)` gives the distance of `y` from the slow manifold and the size
/// of the slow amplitude it is compared with (5% of size/τ).
pub(crate) fn forward_with_monitor<const N: usize>(
    rhs: &impl crate::integrate::Rhs<N>,
    y0: State<N>,
    tau: Real,
    t_end: Real,
    rtol: Real,
    distance: impl Fn(&State<N>) -> (Real, Real),
) -> Result<ForwardRun<N>, PhysicalError> {
    let opts = AdaptiveOptions::new(rtol, 1e-300)?;
    let mut stepper = Dop853::new(0.0, y0, opts)?;
    let dt = 0.25 * tau;
    let window = 8; // 2τ
    let mut trace = vec![(0.0, y0)];
    let mut log_dist = vec![distance(&y0).0.max(1e-300).ln()];
    let mut t = 0.0;
    while t < t_end {
        t = (t + dt).min(t_end);
        let y = crate::integrate::solve(&mut stepper, rhs, &[t])?[0];
        trace.push((t, y));
        let (d, size) = distance(&y);
        let d = d.max(1e-300);
        log_dist.push(d.ln());
        let n = log_dist.len();
        if n > window && d > 0.05 * size / tau {
            let rate = least_squares_slope(&log_dist[n - 1 - window..], dt);
            if rate > 0.5 / tau {
                let runaway = Runaway {
                    t,
                    growth_rate: rate,
                };
                return Ok(ForwardRun {
                    trace,
                    runaway: Some(runaway),
                    stats: stepper.stats(),
                });
            }
        }
    }
    Ok(ForwardRun {
        trace,
        runaway: None,
        stats: stepper.stats(),
    })
}

/// Slope of equally spaced samples `ys` (spacing `dt`) by least squares.
fn least_squares_slope(ys: &[Real], dt: Real) -> Real {
    crate::math::least_squares_slope(ys.iter().enumerate().map(|(i, &y)| (i as Real * dt, y)))
}

/// Ω(t) of the full ALE sampled on a uniform grid, with Ω and Ω̇ at every
/// node, read back by cubic Hermite interpolation. It drives the orientation
/// of the full model (the orientation has no influence on Ω).
#[derive(Clone, Debug, PartialEq)]
pub struct OmegaTable {
    /// The time of the first node.
    origin: Real,
    step: Real,
    omega: Vec<Vec3>,
    omega_dot: Vec<Vec3>,
    /// Ω̈ at the nodes, where known: then the interpolant is quintic.
    omega_ddot: Option<Vec<Vec3>>,
}

impl OmegaTable {
    /// A table of Ω and Ω̇ at t = 0, step, 2·step, … (equal, non-empty lengths).
    pub(crate) fn new(step: Real, omega: Vec<Vec3>, omega_dot: Vec<Vec3>) -> Self {
        debug_assert!(!omega.is_empty() && omega.len() == omega_dot.len());
        Self {
            origin: 0.0,
            step,
            omega,
            omega_dot,
            omega_ddot: None,
        }
    }

    /// The same table with Ω̈ at every node: read back by quintic Hermite
    /// interpolation, whose error is about (hΩ)⁶|Ω|/46080, 3e-13 at hΩ = 0.05.
    pub(crate) fn with_second(mut self, omega_ddot: Vec<Vec3>) -> Self {
        debug_assert_eq!(omega_ddot.len(), self.omega.len());
        self.omega_ddot = Some(omega_ddot);
        self
    }

    /// The same table starting at `origin` instead of 0 (Ω(t) is autonomous:
    /// a table built from the state at `origin` continues the motion there).
    pub(crate) fn starting_at(mut self, origin: Real) -> Self {
        self.origin = origin;
        self
    }

    /// The symmetric top's table: z and ż at the nodes, Ω₃ constant.
    fn symmetric(
        step: Real,
        omega3: Real,
        z: impl Iterator<Item = Complex<Real>>,
        z_dot: impl Iterator<Item = Complex<Real>>,
    ) -> Self {
        Self::new(
            step,
            z.map(|z| Vec3::new(z.re, z.im, omega3)).collect(),
            z_dot.map(|v| Vec3::new(v.re, v.im, 0.0)).collect(),
        )
    }

    /// The last time covered.
    pub fn t_end(&self) -> Real {
        self.origin + self.step * (self.omega.len().saturating_sub(1)) as Real
    }

    /// Ω at time `t` in [origin, t_end()] (clamped to that range).
    ///
    /// NOTE: cubic Hermite with the exact Ω̇ at both nodes: the error is
    /// h⁴|Ω⁗|/384 ≈ (hΩ)⁴|Ω|/384, below 1e-9 relative for the grid spacing
    /// chosen by the constructors (hΩ ≤ 0.05).
    pub fn omega_at(&self, t: Real) -> Vec3 {
        let last = self.omega.len() - 1;
        if last == 0 {
            return self.omega[0];
        }
        let x = ((t - self.origin) / self.step).clamp(0.0, last as Real);
        let i = (x.floor() as usize).min(last - 1);
        let s = x - i as Real;
        let h = self.step;
        if let Some(acc) = &self.omega_ddot {
            let (s2, s3) = (s * s, s * s * s);
            let (s4, s5) = (s3 * s, s3 * s2);
            let h0 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5;
            let h1 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5;
            let h2 = 0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5;
            let h4 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5;
            let h5 = 0.5 * s3 - s4 + 0.5 * s5;
            return self.omega[i] * h0
                + self.omega_dot[i] * (h * h1)
                + acc[i] * (h * h * h2)
                + self.omega[i + 1] * (1.0 - h0)
                + self.omega_dot[i + 1] * (h * h4)
                + acc[i + 1] * (h * h * h5);
        }
        let (h00, h10, h01, h11) = (
            (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s),
            s * (1.0 - s) * (1.0 - s),
            s * s * (3.0 - 2.0 * s),
            s * s * (s - 1.0),
        );
        self.omega[i] * h00
            + self.omega_dot[i] * (h10 * h)
            + self.omega[i + 1] * h01
            + self.omega_dot[i + 1] * (h11 * h)
    }
}

/// Grid spacing for an [`OmegaTable`]: a quarter of the fast time `fast`
/// (τ, or τ_f for a general top), and at most 0.05/`rate` (hΩ ≤ 0.05).
pub(crate) fn table_step(fast: Real, rate: Real) -> Real {
    let step = 0.25 * fast;
    if rate > 0.0 {
        step.min(0.05 / rate)
    } else {
        step
    }
}

pub(crate) fn grid(step: Real, t_end: Real) -> Vec<Real> {
    let n = (t_end / step).ceil().max(1.0) as usize;
    (0..=n).map(|i| i as Real * step).collect()
}

/// The physical solution of (3.4) through Ω₀ as a table on [0, t_end] (and,
/// where it has reached its closed form, beyond), built within `max_steps`
/// at the tolerance and refinement of `options`.
pub fn physical_table(
    top: &SymmetricTop,
    omega0: &Vec3,
    t_end: Real,
    options: &crate::sim::MethodOptions,
    max_steps: u64,
) -> Result<slow::SlowTable, PhysicalError> {
    let mut budget = slow::Budget {
        rtol: internal_rtol(options.rtol()),
        steps: max_steps,
        refine: options.refine(),
    };
    slow::slow_table(top, omega0, t_end, &mut budget)
}

/// (3.4) integrated forward from Ω₀ with the reduced model's slope as ż(0), the
/// natural but wrong guess, as a table up to t_end or up to the runaway.
pub fn forward_table(
    top: &SymmetricTop,
    omega0: &Vec3,
    t_end: Real,
    rtol: Real,
) -> Result<(OmegaTable, ForwardRun), PhysicalError> {
    let slope = crate::physics::symmetric_top::reduced_ale_rhs(top, omega0);
    let y0 = State::<4>::new(omega0.x, omega0.y, slope.x, slope.y);
    let run = integrate_forward(top, omega0.z, y0, t_end, rtol)?;
    let step = 0.25 * top.tau();
    let table = OmegaTable::symmetric(
        step,
        omega0.z,
        run.trace.iter().map(|(_, y)| Complex::new(y[0], y[1])),
        run.trace.iter().map(|(_, y)| Complex::new(y[2], y[3])),
    );
    Ok((table, run))
}
