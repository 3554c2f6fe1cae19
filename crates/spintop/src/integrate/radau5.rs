//! Radau IIA of order 5: an implicit, L-stable Runge–Kutta method for stiff
//! problems, adaptive (Hairer's RADAU5) or with a fixed step.
//!
//! Method: the 3-stage collocation method at the right Radau points
//! `c = ((4 − √6)/10, (4 + √6)/10, 1)`; global order 5 (stage order 3), stiffly
//! accurate (the step ends on the last stage) and L-stable: its stability
//! function R(z) tends to 0 as z → −∞, so a step of any size damps a stiff
//! mode, where an explicit method must keep `h|λ|` inside a bounded region.
//! Reference: E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II:
//! Stiff and Differential-Algebraic Problems*, 2nd ed., Springer 1996,
//! Sec. IV.5 (Table 5.6, the coefficients) and IV.8 (the implementation:
//! simplified Newton iteration, error estimate, step-size control), and
//! Hairer's Fortran code `RADAU5` (`radau5.f`), which this module follows.
//!
//! The stage equations `Zᵢ = h Σⱼ aᵢⱼ f(t + cⱼh, y + Zⱼ)` are solved by a
//! simplified Newton iteration with the Jacobian `J = ∂f/∂y` ([`Rhs::jacobian`])
//! at the start of the step. In the variables `W = (T⁻¹ ⊗ I) Z`, where
//! `T⁻¹ A⁻¹ T = diag(γ̂, [[α̂, −β̂], [β̂, α̂]])`, the 3N×3N linear system splits
//! into one real N×N system with `γ̂/h − J` and one complex N×N system with
//! `(α̂ + iβ̂)/h − J`: two LU decompositions per step size, no allocation.
//!
//! Error estimate (adaptive mode): Hairer's embedded estimate of order 3,
//! filtered through `(γ̂/h − J)⁻¹` so that it stays bounded on stiff
//! components (HW II, Sec. IV.8, (8.19)–(8.20)); after a rejection, and before
//! the first accepted step, it is re-evaluated once more as in (8.20').
//!
//! Step-size control (adaptive mode): Hairer's, with the predictive
//! (Gustafsson) controller, the Newton-dependent safety factor, the reuse of
//! the Jacobian while the Newton iteration converges fast (θ ≤ 10⁻³), and of
//! the LU decompositions when the step size would change by less than 20 %.
//! The tolerances are those of [`AdaptiveOptions`], transformed as RADAU5 does
//! (`rtol' = 0.1·rtol^(2/3)`, `atol' = rtol'·atol/rtol`) because the estimate
//! is of order 3 while the method is of order 5. The global error then
//! depends on the problem: `cargo bench -p spintop-benches --bench stiff` measures the end-point
//! error of Van der Pol (μ = 1000, t = 3000) at 0.7–60 × rtol (growing as rtol
//! shrinks), and of Robertson (t = 10¹¹) at 0.04–0.08 × rtol.
//!
//! The Newton loop and the Jacobian follow RADAU5: FACCON^0.8 and θ reset to
//! the reuse threshold at the start of every loop; a fresh Jacobian after any
//! rejection made with an old one; the step divided by 10 on every rejection
//! before the first accepted step. With RADAU5's threshold for small systems
//! (θ ≤ 10⁻³) the Jacobian is evaluated on 28–76 % of the steps of Van der
//! Pol and 42–97 % of Robertson's; a threshold of 0.1 (RADAU5's advice when a
//! Jacobian is costly) cuts that to 2–28 % but costs more Newton iterations,
//! and these solves, whose Jacobians are cheap, take 0.9–1.3× as long (the
//! bench and the README give the table). The threshold stays at 10⁻³.
//!
//! Fixed-step mode ([`Radau5::fixed`]): no error estimate; a fresh Jacobian at
//! the start of every step and the Newton iteration run to rounding level, so
//! that the observed global order is the method's 5.
//!
//! Continuous extension: the collocation polynomial of the last step (degree
//! 3, through `y₀` and the three stages), which is also the starting guess of
//! the next step's Newton iteration. It costs no evaluation. Its error is
//! O(h⁴) (stage order 3), one order lower than the step points.
//!
//! Counting ([`Stats`]): `rhs_evals` counts the calls of [`Rhs::eval`] the
//! stepper makes: 3 per Newton iteration ([`Radau5::newton_iterations`]), and
//! in adaptive mode 1 for `f(t, y)` at the start of each step (kept across the
//! rejected attempts of that step, dropped by [`Stepper::reset`]), 1 for the
//! initial step-size guess (when `h_init` is `None`) and 1 for each second
//! error estimate. Jacobians are counted by [`Radau5::jacobian_evals`]; the
//! default forward-difference [`Rhs::jacobian`] makes `N + 1` further calls of
//! [`Rhs::eval`] each, which the stepper does not see. LU decompositions (one
//! real plus one complex) are counted by [`Radau5::lu_decompositions`].
//! [`Stats::rejected`] counts every rejected attempt: error too large, Newton
//! iteration diverging or too slow, singular matrix, non-finite stage. The
//! step budget counts accepted plus rejected attempts (adaptive) or accepted
//! steps (fixed).
//!
//! Failure: the stepper never holds a non-finite state. A non-finite Jacobian
//! is reported as [`IntegrateError::NonFinite`]; in fixed-step mode a Newton
//! iteration that fails is reported as [`IntegrateError::NoConvergence`]
//! (there is no smaller step to fall back to).

use crate::integrate::control::{
    NONFINITE_CUT, attempt_allowed, check_start, check_t_stop, clip_step, rms_scaled, start_step,
    stepper_getters, validate_options,
};
use crate::integrate::{AdaptiveOptions, DEFAULT_MAX_STEPS, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State, all_finite};
use nalgebra::{Complex, ComplexField, SMatrix, SVector};

// NOTE: the constants are given to more digits than an f64 holds (computed at
// 40 digits from their closed forms) so they can be checked by eye; the unit
// tests below check T, T⁻¹ and (γ̂, α̂, β̂) against A⁻¹ at rounding level.
#[allow(clippy::excessive_precision)]
mod coefficients {
    use crate::math::Real;

    /// c₁ = (4 − √6)/10.
    pub const C1: Real = 0.155_051_025_721_682_190_180_271_592_529_410_860_8;
    /// c₂ = (4 + √6)/10.
    pub const C2: Real = 0.644_948_974_278_317_809_819_728_407_470_589_139_2;
    /// c₁ − 1.
    pub const C1M1: Real = C1 - 1.0;
    /// c₂ − 1.
    pub const C2M1: Real = C2 - 1.0;
    /// c₁ − c₂.
    pub const C1MC2: Real = C1 - C2;
    /// γ̂: the real eigenvalue of A⁻¹.
    pub const GAMMA: Real = 3.637_834_252_744_495_732_208_418_513_577_775_797_945;
    /// α̂: real part of the complex eigenvalues of A⁻¹.
    pub const ALPHA: Real = 2.681_082_873_627_752_133_895_790_743_211_112_101_026;
    /// β̂: imaginary part of the complex eigenvalues of A⁻¹.
    pub const BETA: Real = 3.050_430_199_247_410_569_426_377_624_787_567_904_440;
    /// Error-estimate weights e/γ₀: −(13 + 7√6)/3, (−13 + 7√6)/3, −1/3.
    pub const DD1: Real = -10.048_809_399_827_415_562_460_329_507_647_079_914_59;
    /// See [`DD1`].
    pub const DD2: Real = 1.382_142_733_160_748_895_793_662_840_980_413_247_92;
    /// See [`DD1`].
    pub const DD3: Real = -1.0 / 3.0;
    /// T, with `T⁻¹ A⁻¹ T = diag(γ̂, [[α̂, −β̂], [β̂, α̂]])` (RADAU5's T11…T31;
    /// T32 = 1, T33 = 0).
    pub const T: [[Real; 3]; 3] = [
        [
            9.123_239_487_089_294_279_2e-2,
            -0.141_255_295_020_954_208_43,
            -3.002_919_410_514_742_449_2e-2,
        ],
        [
            0.241_717_932_707_107_018_96,
            0.204_129_352_293_799_931_99,
            0.382_942_112_757_261_937_79,
        ],
        [0.966_048_182_615_092_936_19, 1.0, 0.0],
    ];
    /// T⁻¹ (RADAU5's TI11…TI33).
    pub const TI: [[Real; 3]; 3] = [
        [
            4.325_579_890_063_155_351,
            0.339_199_251_815_809_869_54,
            0.541_770_539_935_874_871_19,
        ],
        [
            -4.178_718_591_551_904_727_3,
            -0.327_682_820_761_062_387_08,
            0.476_623_554_500_550_451_96,
        ],
        [
            -0.502_872_634_945_786_875_95,
            2.571_926_949_855_605_429_2,
            -0.596_039_204_828_224_924_97,
        ],
    ];
}

use coefficients::*;

/// The nodes c₁, c₂, c₃.
const NODES: [Real; 3] = [C1, C2, 1.0];

// Newton iteration and step-size control of RADAU5 (default parameters).
/// Largest number of Newton iterations per attempt (adaptive mode).
const NIT: u32 = 7;
/// Largest number of Newton iterations per step (fixed mode).
const NIT_FIXED: u32 = 40;
const SAFETY: Real = 0.9;
/// Smallest step ratio h_new/h is 1/FAC_L; largest is 1/FAC_R.
const FAC_L: Real = 5.0;
const FAC_R: Real = 0.125;
/// Keep the Jacobian for the next step when the Newton contraction θ is below this.
const THETA_REUSE: Real = 1e-3;
/// Keep the step size (and the LU decompositions) when h_new/h lies in [1, 1.2].
const QUOT1: Real = 1.0;
const QUOT2: Real = 1.2;
/// Newton stopping tolerance of the fixed-step mode, in the norm scaled by 1 + |y|.
const FNEWT_FIXED: Real = 1e-14;

type Mat<const N: usize> = SMatrix<Real, N, N>;
type CMat<const N: usize> = SMatrix<Complex<Real>, N, N>;
type CState<const N: usize> = SVector<Complex<Real>, N>;

/// How the step size is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Adaptive {
        opts: AdaptiveOptions,
        /// RADAU5's transformed tolerances and Newton tolerance.
        rtol: Real,
        atol: Real,
        fnewt: Real,
    },
    Fixed {
        h: Real,
    },
}

/// Where the stored Jacobian was evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Jac {
    /// None yet (or dropped): evaluate before the next attempt.
    Missing,
    /// At the current `(t, y)`.
    Current,
    /// At an earlier point, kept because Newton converged fast.
    Old,
}

/// An LU decomposition with partial pivoting of a fixed-size matrix, real or
/// complex.
// NOTE: nalgebra's `LU` needs `DimMin` bounds that a generic `const N` cannot
// satisfy; Doolittle with row pivoting on an N×N array is a dozen lines.
#[derive(Clone, Debug)]
struct SmallLu<T, const N: usize> {
    /// L (unit lower, below the diagonal) and U (on and above it) of P·M.
    lu: SMatrix<T, N, N>,
    /// Row `i` of P·M is row `perm[i]` of M.
    perm: [usize; N],
}

impl<T: ComplexField<RealField = Real> + Copy, const N: usize> SmallLu<T, N> {
    /// Decompose `m`; `None` when a pivot is zero or not finite (singular).
    fn new(mut m: SMatrix<T, N, N>) -> Option<Self> {
        let mut perm: [usize; N] = std::array::from_fn(|i| i);
        for k in 0..N {
            let mut p = k;
            for i in k + 1..N {
                if m[(i, k)].modulus() > m[(p, k)].modulus() {
                    p = i;
                }
            }
            let pivot = m[(p, k)].modulus();
            if !(pivot > 0.0 && pivot.is_finite()) {
                return None;
            }
            if p != k {
                m.swap_rows(p, k);
                perm.swap(p, k);
            }
            let akk = m[(k, k)];
            for i in k + 1..N {
                let l = m[(i, k)] / akk;
                m[(i, k)] = l;
                for j in k + 1..N {
                    let akj = m[(k, j)];
                    m[(i, j)] -= l * akj;
                }
            }
        }
        Some(Self { lu: m, perm })
    }

    /// Solve `M x = b`.
    fn solve(&self, b: &SVector<T, N>) -> SVector<T, N> {
        let mut x = SVector::<T, N>::from_fn(|i, _| b[self.perm[i]]);
        for i in 0..N {
            for j in 0..i {
                let lij = self.lu[(i, j)];
                let xj = x[j];
                x[i] -= lij * xj;
            }
        }
        for i in (0..N).rev() {
            for j in i + 1..N {
                let uij = self.lu[(i, j)];
                let xj = x[j];
                x[i] -= uij * xj;
            }
            x[i] /= self.lu[(i, i)];
        }
        x
    }
}

/// The two decompositions for one signed step size.
#[derive(Clone, Debug)]
struct Lus<const N: usize> {
    h: Real,
    real: SmallLu<Real, N>,
    complex: SmallLu<Complex<Real>, N>,
}

/// Why a Newton iteration stopped without converging.
#[derive(Clone, Copy, Debug, PartialEq)]
enum NewtonFailure {
    /// A stage or an increment stopped being finite.
    NonFinite,
    /// Contraction θ ≥ 0.99, a singular solve, or the iteration limit.
    Diverged,
    /// Converging, but too slowly to finish in time: retry with `factor · h`.
    Slow { factor: Real },
}

/// What one attempt at an adaptive step gave.
enum Attempt<const N: usize> {
    /// No error estimate (a singular matrix, a Newton iteration that failed, a
    /// result that is not finite): the step is rejected; try this magnitude.
    Retry(Real),
    /// The stages, the Newton iterations they took, and the scaled error
    /// (finite, at least 1e-10).
    Estimated {
        z: [State<N>; 3],
        newt: u32,
        err: Real,
    },
}

/// The settings of one Newton iteration.
#[derive(Clone, Copy, Debug)]
struct NewtonSettings<const N: usize> {
    scale: State<N>,
    fnewt: Real,
    nit: u32,
    /// Give up early when the predicted error after `nit` iterations is too large.
    predict: bool,
}

/// Radau IIA of order 5 (3 stages), implicit and L-stable, adaptive or with a
/// fixed step, stepping forward or backward.
#[derive(Clone, Debug)]
pub struct Radau5<const N: usize> {
    t: Real,
    y: State<N>,
    t_prev: Real,
    /// Signed size of the last accepted step (0 before the first step / after reset).
    h_last: Real,
    /// The collocation polynomial of the last accepted step, in Newton form
    /// about its end point (RADAU5's `CONT`).
    cont: [State<N>; 3],
    /// `f(t, y)` when known.
    f: Option<State<N>>,
    jac: Mat<N>,
    jac_state: Jac,
    lus: Option<Lus<N>>,
    /// Magnitude of the next step to try (adaptive; None: guess it).
    h_next: Option<Real>,
    mode: Mode,
    max_steps: u64,
    /// Newton contraction factor of the last iteration.
    theta: Real,
    /// θ/(1 − θ), carried from step to step (RADAU5's `FACCON`).
    faccon: Real,
    /// Step and error of the last accepted step (predictive controller); 0: none yet.
    h_acc: Real,
    err_acc: Real,
    stats: Stats,
    jacobian_evals: u64,
    lu_decompositions: u64,
    newton_iterations: u64,
}

/// `Σⱼ m[i][j] vⱼ` for i = 0, 1, 2 (the transformations T and T⁻¹).
fn transform<const N: usize>(m: &[[Real; 3]; 3], v: &[State<N>; 3]) -> [State<N>; 3] {
    std::array::from_fn(|i| v[0] * m[i][0] + v[1] * m[i][1] + v[2] * m[i][2])
}

/// The Newton scale `atol + rtol·|yᵢ|`; a component whose scale is 0 (`atol =
/// 0` and `yᵢ = 0`) gets `rtol·max|y|` instead (or `rtol` when y = 0).
// NOTE: with a zero scale any increment of that component would count as an
// infinite Newton error and the iteration could never converge.
fn newton_scale<const N: usize>(atol: Real, rtol: Real, y: &State<N>) -> State<N> {
    let floor = rtol * if y.amax() > 0.0 { y.amax() } else { 1.0 };
    y.map(|v| {
        let s = atol + rtol * v.abs();
        if s > 0.0 { s } else { floor }
    })
}

/// The error scale `atol + rtol·max(|yᵢ|, |y_newᵢ|)`, with the same floor.
fn error_scale<const N: usize>(atol: Real, rtol: Real, y: &State<N>, y_new: &State<N>) -> State<N> {
    let big = y.zip_map(y_new, |a, b| a.abs().max(b.abs()));
    newton_scale(atol, rtol, &big)
}

impl<const N: usize> Radau5<N> {
    fn build(t0: Real, y0: State<N>, mode: Mode, max_steps: u64) -> Result<Self, IntegrateError> {
        check_start(t0, all_finite(&y0))?;
        let h_next = match mode {
            Mode::Adaptive { opts, .. } => opts.h_init,
            Mode::Fixed { h } => Some(h),
        };
        Ok(Self {
            t: t0,
            y: y0,
            t_prev: t0,
            h_last: 0.0,
            cont: [State::zeros(); 3],
            f: None,
            jac: Mat::zeros(),
            jac_state: Jac::Missing,
            lus: None,
            h_next,
            mode,
            max_steps,
            theta: 1.0,
            faccon: 1.0,
            h_acc: 0.0,
            err_acc: 1e-2,
            stats: Stats::default(),
            jacobian_evals: 0,
            lu_decompositions: 0,
            newton_iterations: 0,
        })
    }

    /// An adaptive stepper at `(t0, y0)` with the given tolerances and options.
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0`/`y0` or an
    /// invalid option.
    pub fn new(t0: Real, y0: State<N>, opts: AdaptiveOptions) -> Result<Self, IntegrateError> {
        validate_options(&opts)?;
        // RADAU5's tolerance transformation (see the module doc).
        let rtol = 0.1 * opts.rtol.powf(2.0 / 3.0);
        let atol = rtol * (opts.atol / opts.rtol);
        let fnewt = (10.0 * Real::EPSILON / rtol).max(0.03_f64.min(rtol.sqrt()));
        Self::build(
            t0,
            y0,
            Mode::Adaptive {
                opts,
                rtol,
                atol,
                fnewt,
            },
            opts.max_steps,
        )
    }

    /// A fixed-step stepper at `(t0, y0)` with step size `h` (finite and > 0; the
    /// direction of each step comes from its `t_stop`), for measuring the order.
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0` or `y0`, or
    /// an `h` that is not finite and positive.
    pub fn fixed(t0: Real, y0: State<N>, h: Real) -> Result<Self, IntegrateError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(IntegrateError::InvalidOption(format!(
                "the Radau5 step size must be finite and > 0, got {h}"
            )));
        }
        Self::build(t0, y0, Mode::Fixed { h }, DEFAULT_MAX_STEPS)
    }

    /// Change the largest step magnitude from the next step on (adaptive mode;
    /// the SO(3) driver caps the rotation per step this way). A NaN or
    /// non-positive value is ignored, as is a fixed-step stepper.
    pub fn set_h_max(&mut self, h_max: Real) {
        if let Mode::Adaptive { opts, .. } = &mut self.mode
            && h_max > 0.0
        {
            opts.h_max = h_max;
        }
    }

    /// Replace the step budget (adaptive: accepted plus rejected attempts;
    /// fixed: accepted steps; over the life of the stepper).
    pub fn with_max_steps(mut self, n: u64) -> Self {
        self.max_steps = n;
        if let Mode::Adaptive { opts, .. } = &mut self.mode {
            opts.max_steps = n;
        }
        self
    }

    /// The options of an adaptive stepper (`None` in fixed-step mode).
    pub fn options(&self) -> Option<&AdaptiveOptions> {
        match &self.mode {
            Mode::Adaptive { opts, .. } => Some(opts),
            Mode::Fixed { .. } => None,
        }
    }

    /// Magnitude of the next step to try (`None` until it has been chosen).
    pub fn next_step_size(&self) -> Option<Real> {
        self.h_next
    }

    /// Jacobians evaluated so far (calls of [`Rhs::jacobian`]).
    pub fn jacobian_evals(&self) -> u64 {
        self.jacobian_evals
    }

    /// LU decompositions so far (each is one real and one complex N×N matrix).
    pub fn lu_decompositions(&self) -> u64 {
        self.lu_decompositions
    }

    /// Newton iterations so far, over all attempts (3 evaluations each).
    pub fn newton_iterations(&self) -> u64 {
        self.newton_iterations
    }

    /// Evaluate the Jacobian at the current point when there is none.
    fn ensure_jacobian<R: Rhs<N>>(&mut self, rhs: &R) -> Result<(), IntegrateError> {
        if self.jac_state != Jac::Missing {
            return Ok(());
        }
        let jac = rhs.jacobian(self.t, &self.y);
        self.jacobian_evals += 1;
        if !all_finite(&jac) {
            return Err(IntegrateError::NonFinite { t: self.t });
        }
        self.jac = jac;
        self.jac_state = Jac::Current;
        self.lus = None;
        Ok(())
    }

    /// Decompose `γ̂/h − J` and `(α̂ + iβ̂)/h − J` for the signed step `h`
    /// unless they already are; false when either is singular.
    fn ensure_lus(&mut self, h: Real) -> bool {
        if let Some(lus) = &self.lus
            && lus.h == h
        {
            return true;
        }
        let real = SmallLu::new(Mat::<N>::identity() * (GAMMA / h) - self.jac);
        let shift = Complex::new(ALPHA / h, BETA / h);
        let complex =
            SmallLu::new(CMat::<N>::identity() * shift - self.jac.map(|x| Complex::new(x, 0.0)));
        self.lu_decompositions += 1;
        self.lus = match (real, complex) {
            (Some(real), Some(complex)) => Some(Lus { h, real, complex }),
            _ => None,
        };
        self.lus.is_some()
    }

    /// The Newton starting guess for a step of signed size `h`: the last step's
    /// collocation polynomial extrapolated (zero before any step).
    fn starting_values(&self, h: Real) -> [State<N>; 3] {
        if self.h_last == 0.0 {
            return [State::zeros(); 3];
        }
        let q = h / self.h_last;
        std::array::from_fn(|i| {
            let s = NODES[i] * q;
            (self.cont[0] + (self.cont[1] + self.cont[2] * (s - C1M1)) * (s - C2M1)) * s
        })
    }

    /// The simplified Newton iteration for the stages `Z` of a step of signed
    /// size `h` from the current point; returns `Z` and the iterations used.
    fn newton<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        h: Real,
        settings: &NewtonSettings<N>,
    ) -> Result<([State<N>; 3], u32), NewtonFailure> {
        let Some(lus) = &self.lus else {
            return Err(NewtonFailure::Diverged);
        };
        let (t, y) = (self.t, self.y);
        let mut z = self.starting_values(h);
        let mut w = transform(&TI, &z);
        let (gamma_h, alpha_h, beta_h) = (GAMMA / h, ALPHA / h, BETA / h);
        // NOTE: as RADAU5 does at the start of every Newton loop (accepted
        // step or not): FACCON decays as FACCON^0.8, and θ starts from the
        // reuse threshold, so a loop that converges in one iteration (no
        // contraction measured) leaves θ small and the Jacobian is kept.
        let mut faccon = self.faccon.max(Real::EPSILON).powf(0.8);
        let mut theta = THETA_REUSE;
        let mut dynold: Real = 0.0;
        let mut thq_old: Real = 0.0;
        let mut outcome = Err(NewtonFailure::Diverged);
        for newt in 1..=settings.nit {
            let f: [State<N>; 3] = std::array::from_fn(|i| rhs.eval(t + NODES[i] * h, &(y + z[i])));
            self.stats.rhs_evals += 3;
            self.newton_iterations += 1;
            if !f.iter().all(all_finite) {
                outcome = Err(NewtonFailure::NonFinite);
                break;
            }
            let g = transform(&TI, &f);
            let r1 = g[0] - w[0] * gamma_h;
            let r2 = g[1] - w[1] * alpha_h + w[2] * beta_h;
            let r3 = g[2] - w[1] * beta_h - w[2] * alpha_h;
            let rc: CState<N> = r2.zip_map(&r3, Complex::new);
            let dw1 = lus.real.solve(&r1);
            let dwc = lus.complex.solve(&rc);
            let dw2 = dwc.map(|c| c.re);
            let dw3 = dwc.map(|c| c.im);
            let dyno = if N == 0 {
                0.0
            } else {
                let sum: Real = (0..N)
                    .map(|i| {
                        let s = settings.scale[i];
                        (dw1[i] / s).powi(2) + (dw2[i] / s).powi(2) + (dw3[i] / s).powi(2)
                    })
                    .sum();
                (sum / (3 * N) as Real).sqrt()
            };
            if !dyno.is_finite() {
                outcome = Err(NewtonFailure::NonFinite);
                break;
            }
            // NOTE: increments at rounding level carry no information on the
            // contraction; the iteration has converged as far as it can.
            let at_rounding = dyno <= 4.0 * Real::EPSILON;
            if newt > 1 && newt < settings.nit && !at_rounding {
                let thq = dyno / dynold;
                theta = if newt == 2 {
                    thq
                } else {
                    (thq * thq_old).sqrt()
                };
                thq_old = thq;
                if theta < 0.99 {
                    faccon = theta / (1.0 - theta);
                    let left = (settings.nit - 1 - newt) as i32;
                    let dyth = faccon * dyno * theta.powi(left) / settings.fnewt;
                    if settings.predict && dyth >= 1.0 {
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        let factor = 0.8 * qnewt.powf(-1.0 / (4.0 + left as Real));
                        outcome = Err(NewtonFailure::Slow { factor });
                        break;
                    }
                } else {
                    break;
                }
            }
            dynold = dyno.max(Real::EPSILON);
            w[0] += dw1;
            w[1] += dw2;
            w[2] += dw3;
            z = transform(&T, &w);
            if faccon * dyno <= settings.fnewt || at_rounding {
                outcome = Ok((z, newt));
                break;
            }
        }
        self.theta = theta;
        self.faccon = faccon;
        outcome
    }

    /// Accept a step of signed size `h` ending at `t_new` with stages `z`.
    fn accept(&mut self, h: Real, t_new: Real, z: &[State<N>; 3]) {
        // The collocation polynomial in Newton form about the new point, on the
        // nodes s = 0, c₂ − 1, c₁ − 1, −1 (RADAU5's CONT).
        let c0 = (z[1] - z[2]) / C2M1;
        let ak = (z[0] - z[1]) / C1MC2;
        let acont3 = (ak - z[0] / C1) / C2;
        let c1 = (ak - c0) / C1M1;
        let c2 = c1 - acont3;
        self.cont = [c0, c1, c2];
        self.t_prev = self.t;
        self.h_last = h;
        self.t = t_new;
        self.y += z[2];
        self.f = None;
        self.stats.steps += 1;
    }

    fn step_fixed<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        t_stop: Real,
        h_fixed: Real,
    ) -> Result<(), IntegrateError> {
        if self.stats.steps >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        let remaining = t_stop - self.t;
        // NOTE: as in `Rk4`, the last step is stretched by up to a relative 1e-9
        // (plus a few ulps of t) rather than leaving a sliver of a step behind.
        let slack = 1e-9 * h_fixed + 64.0 * Real::EPSILON * self.t.abs().max(t_stop.abs());
        let (h, t_new) = if remaining.abs() <= h_fixed + slack {
            (remaining, t_stop)
        } else {
            let h = h_fixed.copysign(remaining);
            (h, self.t + h)
        };
        self.jac_state = Jac::Missing;
        self.ensure_jacobian(rhs)?;
        if !self.ensure_lus(h) {
            return Err(IntegrateError::NoConvergence { t: self.t, h });
        }
        let settings = NewtonSettings {
            scale: self.y.map(|v| 1.0 + v.abs()),
            fnewt: FNEWT_FIXED,
            nit: NIT_FIXED,
            predict: false,
        };
        match self.newton(rhs, h, &settings) {
            Ok((z, _)) if all_finite(&(self.y + z[2])) => {
                self.accept(h, t_new, &z);
                Ok(())
            }
            Ok(_) | Err(NewtonFailure::NonFinite) => Err(IntegrateError::NonFinite { t: self.t }),
            Err(_) => Err(IntegrateError::NoConvergence { t: self.t, h }),
        }
    }

    /// One attempt at a step of signed size `hs` from the current point: the
    /// Newton iteration for the stages, then Hairer's filtered error
    /// estimate. `after_rejection`: a step was rejected since the last
    /// accepted one.
    fn attempt<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        hs: Real,
        f0: State<N>,
        settings: &NewtonSettings<N>,
        (atol, rtol): (Real, Real),
        after_rejection: bool,
    ) -> Result<Attempt<N>, IntegrateError> {
        self.ensure_jacobian(rhs)?;
        if !self.ensure_lus(hs) {
            return Ok(Attempt::Retry(0.5 * hs.abs()));
        }
        let (z, newt) = match self.newton(rhs, hs, settings) {
            Ok(ok) => ok,
            Err(failure) => {
                // NOTE: RADAU5's "unexpected step rejection": shorten the
                // step, and evaluate a fresh Jacobian if the one in use is
                // from an earlier point.
                if self.jac_state == Jac::Old {
                    self.jac_state = Jac::Missing;
                }
                let cut = match failure {
                    NewtonFailure::Slow { factor } => factor,
                    NewtonFailure::Diverged => 0.5,
                    NewtonFailure::NonFinite => NONFINITE_CUT,
                };
                return Ok(Attempt::Retry(hs.abs() * cut));
            }
        };
        let y_new = self.y + z[2];
        let Some(lus) = &self.lus else {
            // Unreachable (the Newton iteration needs the decompositions),
            // but never a loop that does not shorten the step.
            return Ok(Attempt::Retry(0.5 * hs.abs()));
        };
        // Hairer's filtered error estimate (HW II, (8.19)–(8.20)).
        let v = (z[0] * DD1 + z[1] * DD2 + z[2] * DD3) / hs;
        let scale = error_scale(atol, rtol, &self.y, &y_new);
        let err_vec = lus.real.solve(&(f0 + v));
        let mut err = rms_scaled(&err_vec, &scale);
        if (err >= 1.0 || err.is_nan()) && (self.h_acc == 0.0 || after_rejection) {
            // NOTE: (8.20'): on a stiff problem the first estimate can be
            // far too pessimistic after a rejection or at the start; one
            // more evaluation at y + err sharpens it.
            let f1 = rhs.eval(self.t, &(self.y + err_vec));
            self.stats.rhs_evals += 1;
            err = rms_scaled(&lus.real.solve(&(f1 + v)), &scale);
        }
        if !err.is_finite() || !all_finite(&y_new) {
            return Ok(Attempt::Retry(hs.abs() * NONFINITE_CUT));
        }
        Ok(Attempt::Estimated {
            z,
            newt,
            err: err.max(1e-10),
        })
    }

    /// The step magnitude that the scaled error `err` of a step of magnitude
    /// `h`, whose Newton iteration took `newt` iterations, asks for next.
    fn proposed_step(&self, h: Real, err: Real, newt: u32) -> Real {
        let fac = SAFETY.min(SAFETY * (1 + 2 * NIT) as Real / (newt + 2 * NIT) as Real);
        let mut quot = (err.powf(0.25) / fac).clamp(FAC_R, FAC_L);
        if err < 1.0 && self.h_acc > 0.0 {
            // NOTE: the predictive controller of Gustafsson (HW II, (8.25)),
            // which RADAU5 uses by default: it avoids the rejections the
            // classical controller makes when the error jumps.
            let facgus = (self.h_acc / h) * (err * err / self.err_acc).powf(0.25) / SAFETY;
            quot = quot.max(facgus.clamp(FAC_R, FAC_L));
        }
        h / quot
    }

    #[allow(clippy::too_many_arguments)]
    fn step_adaptive<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        t_stop: Real,
        opts: AdaptiveOptions,
        rtol: Real,
        atol: Real,
        fnewt: Real,
    ) -> Result<(), IntegrateError> {
        let dir = (t_stop - self.t).signum();
        let (f0, h) = start_step(
            rhs,
            self.t,
            &self.y,
            &mut self.f,
            &mut self.stats,
            self.h_next,
            dir,
            5,
            &opts,
        )?;
        let mut h = h.min(opts.h_max);
        let settings = NewtonSettings {
            scale: newton_scale(atol, rtol, &self.y),
            fnewt,
            nit: NIT,
            predict: true,
        };
        let mut rejected_here = false;
        loop {
            if let Err(e) = attempt_allowed(&self.stats, self.max_steps, self.t, h, dir) {
                self.h_next = Some(h);
                return Err(e);
            }
            let (hs, t_new, clipped) = clip_step(self.t, t_stop, h);
            let tolerances = (atol, rtol);
            let (z, newt, err) =
                match self.attempt(rhs, hs, f0, &settings, tolerances, rejected_here)? {
                    Attempt::Estimated { z, newt, err } => (z, newt, err),
                    Attempt::Retry(shorter) => {
                        self.stats.rejected += 1;
                        rejected_here = true;
                        h = shorter;
                        continue;
                    }
                };
            let mut h_new = self.proposed_step(hs.abs(), err, newt);
            if err < 1.0 {
                self.h_acc = hs.abs();
                self.err_acc = err.max(1e-2);
                self.accept(hs, t_new, &z);
                h_new = h_new.min(opts.h_max);
                if rejected_here {
                    h_new = h_new.min(hs.abs());
                }
                if clipped && !rejected_here {
                    h_new = h_new.max(h);
                }
                if self.theta <= THETA_REUSE {
                    // Fast convergence: keep the Jacobian, and the step size
                    // too (with its LU) when it would grow by less than 20 %.
                    self.jac_state = Jac::Old;
                    let q = h_new / hs.abs();
                    if (QUOT1..=QUOT2).contains(&q) {
                        h_new = hs.abs();
                    }
                } else {
                    self.jac_state = Jac::Missing;
                }
                self.h_next = Some(h_new);
                return Ok(());
            }
            self.stats.rejected += 1;
            h = if self.h_acc == 0.0 {
                // NOTE: RADAU5 divides the step by 10 on every rejection
                // before the first accepted step.
                0.1 * hs.abs()
            } else {
                h_new
            };
            // NOTE: RADAU5 again: a step rejected by the error test with a
            // Jacobian from an earlier point evaluates a fresh one.
            if self.jac_state == Jac::Old {
                self.jac_state = Jac::Missing;
            }
            rejected_here = true;
        }
    }
}

impl<const N: usize> Stepper<N> for Radau5<N> {
    stepper_getters!();

    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        check_t_stop(t_stop)?;
        if t_stop == self.t {
            return Ok(());
        }
        match self.mode {
            Mode::Fixed { h } => self.step_fixed(rhs, t_stop, h),
            Mode::Adaptive {
                opts,
                rtol,
                atol,
                fnewt,
            } => self.step_adaptive(rhs, t_stop, opts, rtol, atol, fnewt),
        }
    }

    fn dense<R: Rhs<N>>(&mut self, _rhs: &R, t: Real) -> State<N> {
        if self.h_last == 0.0 || t == self.t {
            return self.y;
        }
        let s = (t - self.t) / self.h_last;
        self.y + (self.cont[0] + (self.cont[1] + self.cont[2] * (s - C1M1)) * (s - C2M1)) * s
    }

    fn reset(&mut self, y: State<N>) {
        self.y = y;
        self.f = None;
        self.t_prev = self.t;
        self.h_last = 0.0;
        self.jac_state = Jac::Missing;
        self.lus = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// The Radau IIA coefficient matrix A from its closed form (HW II, Table IV.5.6).
    fn butcher_a() -> Matrix3<Real> {
        let s6 = 6.0_f64.sqrt();
        Matrix3::new(
            (88.0 - 7.0 * s6) / 360.0,
            (296.0 - 169.0 * s6) / 1800.0,
            (-2.0 + 3.0 * s6) / 225.0,
            (296.0 + 169.0 * s6) / 1800.0,
            (88.0 + 7.0 * s6) / 360.0,
            (-2.0 - 3.0 * s6) / 225.0,
            (16.0 - s6) / 36.0,
            (16.0 + s6) / 36.0,
            1.0 / 9.0,
        )
    }

    fn m(rows: &[[Real; 3]; 3]) -> Matrix3<Real> {
        Matrix3::from_fn(|i, j| rows[i][j])
    }

    #[test]
    fn transformation_block_diagonalises_the_inverse_coefficient_matrix() {
        let t = m(&T);
        let ti = m(&TI);
        assert!((ti * t - Matrix3::identity()).amax() < 1e-15);
        let a_inv = butcher_a().try_inverse().expect("A is invertible");
        let lambda = Matrix3::new(GAMMA, 0.0, 0.0, 0.0, ALPHA, -BETA, 0.0, BETA, ALPHA);
        assert!((ti * a_inv * t - lambda).amax() < 1e-13);
    }

    #[test]
    fn nodes_and_error_weights_match_their_closed_forms() {
        let s6 = 6.0_f64.sqrt();
        assert!((C1 - (4.0 - s6) / 10.0).abs() < 1e-16);
        assert!((C2 - (4.0 + s6) / 10.0).abs() < 1e-16);
        assert!((DD1 + (13.0 + 7.0 * s6) / 3.0).abs() < 1e-14);
        assert!((DD2 - (-13.0 + 7.0 * s6) / 3.0).abs() < 1e-14);
        // The nodes are the row sums of A (collocation).
        let rows = butcher_a() * nalgebra::Vector3::repeat(1.0);
        assert!((rows - nalgebra::Vector3::new(C1, C2, 1.0)).amax() < 1e-15);
    }

    #[test]
    fn small_lu_solves_real_and_complex_systems_with_pivoting() {
        // A zero in the leading position forces a row exchange.
        let m = Matrix3::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 4.0);
        let x = nalgebra::Vector3::new(1.0, -2.0, 0.5);
        let lu = SmallLu::new(m).expect("invertible");
        assert!((lu.solve(&(m * x)) - x).amax() < 1e-15);
        let mc = m.map(|v| Complex::new(v, 0.3 * v - 1.0));
        let xc = x.map(|v| Complex::new(v, -v));
        let luc = SmallLu::new(mc).expect("invertible");
        let back = luc.solve(&(mc * xc));
        assert!((back - xc).iter().all(|d| d.norm() < 1e-14));
        assert!(SmallLu::new(Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0)).is_none());
    }
}
