//! Row 3: the reduced model (4.12)–(4.14) becomes stiff when τΩ² ≫ 1, and
//! explicit methods pay for it; an L-stable implicit method does not.
//!
//! The experiment: the figure top (I₃/I₁ = 2/5, τ = 1) from Ω₀ = S·(0, 0.1, 0.2)
//! for S = 1, 10, 100, 1000 (τΩ₀² = 0.05 … 5·10⁴), over the fixed span
//! t ∈ [0, 10], against the closed form (4.15)–(4.16).
//!
//! Why it is stiff: the Jacobian [`reduced_ale_jacobian`] has eigenvalues
//! close to −τ(3Ω⊥² + k²) at the start and −τk² ± iΩ̃₃ once Ω⊥ has decayed
//! (k = (I₃/I₁)Ω₃ stays constant). Both grow like S², while the solution itself
//! decays onto Ω⊥ = 0 and then does nothing: a fast transient, then a long,
//! smooth, uninteresting stretch that an explicit method must still cross with
//! steps h ≲ 3/|λ|.
//!
//! - Fixed-step RK4: the largest stable step h* is found by bisection (stable:
//!   finite, and |Ω⊥| never above Ω⊥₀, the closed form's bound, over the span).
//!   Linear stability brackets it: the RK4 region (|R(hλ)| ≤ 1) with the
//!   Jacobian's eigenvalues at Ω₀ gives a lower bound, at Ω⊥ → 0 an upper one;
//!   both fall like S⁻². The fitted exponent of h* against S is reported.
//! - DP5 (adaptive, rtol 10⁻⁶, atol = rtol·|Ω₀|): the step count against S, and
//!   the same run under a step budget, which it exhausts at the largest S.
//! - Radau5 (Radau IIA 5, the analytic Jacobian, same tolerances): few steps at
//!   every S, and the error against the closed form within the tolerance.
//!
//! The exact splitting of the reduced flow into rotation and damping (they
//! commute, so the split is exact for any step) is the second fix: its runs
//! go in [`Measurement::splitting`], [`SPLIT_STEPS`] steps over the span at
//! every S.

use super::{Outcome, Row, RowError};
use crate::integrate::{AdaptiveOptions, Dopri5, IntegrateError, Radau5, Rhs, Rk4, Stats, Stepper};
use crate::math::{Real, State, Vec3};
use crate::physics::symmetric_top::{
    SymmetricTop, reduced_ale_jacobian, reduced_ale_rhs, reduced_closed_form,
};
use crate::sim::split::reduced_split_solve;
use nalgebra::{Complex, SMatrix};

/// The reduced ALE (4.12)–(4.14) as a right-hand side `Ω̇ = F(Ω)` with its
/// analytic Jacobian, for the implicit method.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedAle(pub SymmetricTop);

impl Rhs<3> for ReducedAle {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        reduced_ale_rhs(&self.0, y)
    }

    fn jacobian(&self, _t: Real, y: &State<3>) -> SMatrix<Real, 3, 3> {
        reduced_ale_jacobian(&self.0, y)
    }
}

/// The scale factors S of Ω₀ = S·(0, 0.1, 0.2).
pub const LADDER: [Real; 4] = [1.0, 10.0, 100.0, 1000.0];
/// The scale factors at which the RK4 stability limit is measured (τΩ₀² ≥ 1;
/// at S = 1 the problem is not stiff and RK4 is stable for any step up to the
/// span).
pub const RK4_LADDER: [Real; 3] = [10.0, 100.0, 1000.0];
/// Ω₀ at S = 1: the paper's figure.
pub const OMEGA0_UNIT: [Real; 3] = [0.0, 0.1, 0.2];
/// The span [0, SPAN] of every run, in units of τ.
pub const SPAN: Real = 10.0;
/// The relative tolerance of DP5 and Radau5; atol = RTOL·|Ω₀|∞.
pub const RTOL: Real = 1e-6;
/// A run is accurate when its largest error at the step points, relative to
/// |Ω₀|∞, is at most this many times [`RTOL`].
pub const ACCURATE_FACTOR: Real = 10.0;
/// The step budget of the budgeted runs.
// NOTE: about ten times what DP5 needs over this span at S = 100 (a few hundred
// steps) and some sixty times what Radau5 needs at any S (about 30).
pub const BUDGET: u64 = 2000;
/// RK4 is shown failing at this multiple of its measured limit h*.
pub const ABOVE: Real = 1.1;

/// RK4's stability limit at one S.
#[derive(Clone, Debug, PartialEq)]
pub struct Rk4Limit {
    /// The scale factor S.
    pub s: Real,
    /// τΩ₀².
    pub tau_omega_sq: Real,
    /// The measured limit: the largest step for which RK4 stays finite and
    /// within |Ω⊥| ≤ Ω⊥₀ over the span (bisection to a relative 1e-4).
    pub h_star: Real,
    /// The linear-stability limit with the Jacobian's eigenvalues at Ω₀.
    pub h_linear_start: Real,
    /// The linear-stability limit with the eigenvalues at Ω⊥ → 0 (−τk² ± iΩ̃₃).
    pub h_linear_late: Real,
}

/// RK4 run just above its limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Rk4Failure {
    /// The scale factor S.
    pub s: Real,
    /// The step, [`ABOVE`]·h*.
    pub h: Real,
    /// First time |Ω⊥| exceeded Ω⊥₀ (`None`: never).
    pub t_left_envelope: Option<Real>,
    /// How the run ended: `None` when it reached the end of the span.
    pub failure: Option<IntegrateError>,
    /// Largest |Ω⊥|/Ω⊥₀ seen at a finite state.
    pub peak_ratio: Real,
}

/// One adaptive run over the span at one S.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodRun {
    /// The scale factor S.
    pub s: Real,
    /// Work done.
    pub stats: Stats,
    /// Largest error at the step points against the closed form (4.15)–(4.16),
    /// relative to |Ω₀|∞.
    pub max_error: Real,
    /// The time reached.
    pub t_reached: Real,
    /// How the run ended early (`None`: it reached the end of the span).
    pub failure: Option<IntegrateError>,
}

impl MethodRun {
    /// Reached the end of the span within [`ACCURATE_FACTOR`]·[`RTOL`].
    pub fn accurate(&self) -> bool {
        self.failure.is_none() && self.max_error <= ACCURATE_FACTOR * RTOL
    }
}

/// A Radau5 run with its implicit-method counters.
#[derive(Clone, Debug, PartialEq)]
pub struct Radau5Run {
    /// Steps, evaluations, error.
    pub run: MethodRun,
    /// Jacobian evaluations (analytic).
    pub jacobian_evals: u64,
    /// LU decompositions (one real and one complex 3×3 each).
    pub lu_decompositions: u64,
    /// Newton iterations.
    pub newton_iterations: u64,
}

/// The measurement of row 3.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The top (the figure's).
    pub top: SymmetricTop,
    /// RK4's limit at each S of [`RK4_LADDER`].
    pub rk4: Vec<Rk4Limit>,
    /// Least-squares slope of ln h* against ln S (expected −2).
    pub rk4_exponent: Real,
    /// RK4 at [`ABOVE`]·h* at the largest S.
    pub rk4_above: Rk4Failure,
    /// DP5 at each S of [`LADDER`], with the default step budget.
    pub dp5: Vec<MethodRun>,
    /// Slope of ln(steps) against ln S between the two largest S.
    pub dp5_exponent: Real,
    /// What linear stability predicts for DP5 at the largest S: the span over
    /// DP5's stability limit for the late eigenvalues −τk² ± iΩ̃₃.
    pub dp5_predicted_steps: Real,
    /// DP5 at the largest S under the step budget [`BUDGET`].
    pub dp5_budgeted: MethodRun,
    /// Radau5 with the analytic Jacobian at each S of [`LADDER`].
    pub radau5: Vec<Radau5Run>,
    /// Slope of ln(steps) against ln S between the two largest S.
    pub radau5_exponent: Real,
    /// The exact rotation ∘ damping splitting of the reduced flow at each S
    /// of [`LADDER`], [`SPLIT_STEPS`] steps over the same span, compared the
    /// same way.
    pub splitting: Vec<MethodRun>,
}

/// Ω₀ = S·(0, 0.1, 0.2).
pub fn omega0(s: Real) -> Vec3 {
    Vec3::from(OMEGA0_UNIT) * s
}

/// The stability function of classical RK4, R(z) = 1 + z + z²/2 + z³/6 + z⁴/24.
pub fn rk4_stability_function(z: Complex<Real>) -> Complex<Real> {
    Complex::new(1.0, 0.0) + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)))
}

/// The stability function of Dormand–Prince 5(4) (the order-5 solution):
/// R(z) = Σₖ₌₀⁵ zᵏ/k! + z⁶/600 (Hairer, Nørsett & Wanner, *Solving ODEs I*,
/// Sec. IV.2 / HW II Sec. IV.2).
pub fn dopri5_stability_function(z: Complex<Real>) -> Complex<Real> {
    let one = Complex::new(1.0, 0.0);
    one + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0 + z * (1.0 / 120.0 + z / 600.0)))))
}

/// The largest h with |R(h'λ)| ≤ 1 for every h' ≤ h: the linear stability
/// limit of a method with stability function `r` for the eigenvalue λ.
/// `None` when there is no such limit: λ = 0 (every step is stable), Re λ > 0
/// (none is), or the ray stays in the domain up to |hλ| = 4.
///
/// Reference: Hairer & Wanner, *Solving ODEs II*, Sec. IV.2 (RK4's domain
/// reaches −2.785 on the real axis, DP5's −3.307).
pub fn stability_limit(
    r: fn(Complex<Real>) -> Complex<Real>,
    lambda: Complex<Real>,
) -> Option<Real> {
    let size = lambda.norm();
    if size == 0.0 || lambda.re > 0.0 {
        return None;
    }
    // NOTE: both domains lie inside |z| < 4, so scanning |z| ∈ (0, 4] finds the
    // first exit along the ray; bisection then sharpens it.
    let dir = lambda / size;
    let stable = |x: Real| r(dir * x).norm() <= 1.0;
    let n = 4000;
    let dx = 4.0 / n as Real;
    let mut lo = 0.0;
    for i in 1..=n {
        let x = dx * i as Real;
        if !stable(x) {
            let mut hi = x;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if stable(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(lo / size);
        }
        lo = x;
    }
    None
}

/// The eigenvalues of the reduced ALE's Jacobian that are not zero: those of
/// its upper-left 2×2 block (the third row of (4.12)–(4.14)'s Jacobian is zero).
pub fn jacobian_eigenvalues(top: &SymmetricTop, omega: &Vec3) -> [Complex<Real>; 2] {
    let j = reduced_ale_jacobian(top, omega);
    let half_trace = 0.5 * (j[(0, 0)] + j[(1, 1)]);
    let det = j[(0, 0)] * j[(1, 1)] - j[(0, 1)] * j[(1, 0)];
    let disc = Complex::new(half_trace * half_trace - det, 0.0).sqrt();
    [
        Complex::new(half_trace, 0.0) + disc,
        Complex::new(half_trace, 0.0) - disc,
    ]
}

/// A method's linear stability limit at Ω: the smallest limit over the
/// Jacobian's eigenvalues there.
pub fn linear_limit(
    r: fn(Complex<Real>) -> Complex<Real>,
    top: &SymmetricTop,
    omega: &Vec3,
) -> Option<Real> {
    jacobian_eigenvalues(top, omega)
        .into_iter()
        .filter_map(|lambda| stability_limit(r, lambda))
        .reduce(Real::min)
}

/// Ω⊥ = √(Ω₁² + Ω₂²).
fn omega_perp(y: &State<3>) -> Real {
    y.x.hypot(y.y)
}

/// RK4 with step `h` from Ω₀ over the span: the first time |Ω⊥| > Ω⊥₀, how
/// the run ended, and the peak |Ω⊥|/Ω⊥₀. Stops at the first excursion when
/// `stop_early`.
fn rk4_run(top: &SymmetricTop, s: Real, h: Real, stop_early: bool) -> Result<Rk4Failure, RowError> {
    let w0 = omega0(s);
    let perp0 = omega_perp(&w0);
    let rhs = ReducedAle(*top);
    let mut rk4 = Rk4::new(0.0, w0, h).map_err(|e| RowError::new(3, e))?;
    let mut out = Rk4Failure {
        s,
        h,
        t_left_envelope: None,
        failure: None,
        peak_ratio: 1.0,
    };
    while rk4.t() < SPAN {
        if let Err(e) = rk4.step(&rhs, SPAN) {
            out.failure = Some(e);
            break;
        }
        let ratio = omega_perp(rk4.y()) / perp0;
        out.peak_ratio = out.peak_ratio.max(ratio);
        if ratio > 1.0 && out.t_left_envelope.is_none() {
            out.t_left_envelope = Some(rk4.t());
            if stop_early {
                break;
            }
        }
    }
    Ok(out)
}

/// Whether RK4 with step `h` stays finite and inside |Ω⊥| ≤ Ω⊥₀ over the span.
fn rk4_stable(top: &SymmetricTop, s: Real, h: Real) -> Result<bool, RowError> {
    let run = rk4_run(top, s, h, true)?;
    Ok(run.failure.is_none() && run.t_left_envelope.is_none())
}

/// The measured RK4 limit at S, bracketed by the linear predictions.
fn rk4_limit(top: &SymmetricTop, s: Real) -> Result<Rk4Limit, RowError> {
    let w0 = omega0(s);
    let late = Vec3::new(0.0, 0.0, w0.z);
    let missing = || RowError::new(3, format!("no RK4 stability limit at S = {s}"));
    let h_linear_start = linear_limit(rk4_stability_function, top, &w0).ok_or_else(missing)?;
    let h_linear_late = linear_limit(rk4_stability_function, top, &late).ok_or_else(missing)?;
    let mut lo = 0.5 * h_linear_start;
    let mut hi = (2.0 * h_linear_late).min(SPAN);
    if !rk4_stable(top, s, lo)? || rk4_stable(top, s, hi)? {
        return Err(RowError::new(
            3,
            format!("RK4's limit at S = {s} is not inside [{lo:e}, {hi:e}]"),
        ));
    }
    while hi / lo > 1.0 + 1e-4 {
        let mid = (lo * hi).sqrt();
        if rk4_stable(top, s, mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(Rk4Limit {
        s,
        tau_omega_sq: top.tau() * w0.norm_squared(),
        h_star: lo,
        h_linear_start,
        h_linear_late,
    })
}

/// Step an adaptive method over the span, comparing every accepted state with
/// the closed form.
fn adaptive_run<S: Stepper<3>>(stepper: &mut S, top: &SymmetricTop, s: Real) -> MethodRun {
    let w0 = omega0(s);
    let size = w0.amax();
    let rhs = ReducedAle(*top);
    let mut max_error: Real = 0.0;
    let mut failure = None;
    while stepper.t() < SPAN {
        if let Err(e) = stepper.step(&rhs, SPAN) {
            failure = Some(e);
            break;
        }
        let exact = reduced_closed_form(top, &w0, stepper.t());
        max_error = max_error.max((stepper.y() - exact).amax() / size);
    }
    MethodRun {
        s,
        stats: stepper.stats(),
        max_error,
        t_reached: stepper.t(),
        failure,
    }
}

/// The tolerances at S: rtol [`RTOL`], atol = RTOL·|Ω₀|∞, and a step budget.
fn options(s: Real, budget: Option<u64>) -> Result<AdaptiveOptions, RowError> {
    let mut opts =
        AdaptiveOptions::new(RTOL, RTOL * omega0(s).amax()).map_err(|e| RowError::new(3, e))?;
    if let Some(b) = budget {
        opts.max_steps = b;
    }
    Ok(opts)
}

fn dp5_run(top: &SymmetricTop, s: Real, budget: Option<u64>) -> Result<MethodRun, RowError> {
    let mut dp5 =
        Dopri5::new(0.0, omega0(s), options(s, budget)?).map_err(|e| RowError::new(3, e))?;
    Ok(adaptive_run(&mut dp5, top, s))
}

fn radau5_run(top: &SymmetricTop, s: Real) -> Result<Radau5Run, RowError> {
    let mut radau =
        Radau5::new(0.0, omega0(s), options(s, None)?).map_err(|e| RowError::new(3, e))?;
    let run = adaptive_run(&mut radau, top, s);
    Ok(Radau5Run {
        run,
        jacobian_evals: radau.jacobian_evals(),
        lu_decompositions: radau.lu_decompositions(),
        newton_iterations: radau.newton_iterations(),
    })
}

/// Least-squares slope of ln y against ln x.
pub fn log_log_slope(points: &[(Real, Real)]) -> Real {
    crate::math::least_squares_slope(points.iter().map(|&(x, y)| (x.ln(), y.ln())))
}

/// Slope of ln(steps) against ln S between the two largest S of `runs`.
fn step_exponent<'a>(runs: impl Iterator<Item = &'a MethodRun>) -> Real {
    let points: Vec<(Real, Real)> = runs.map(|r| (r.s, r.stats.steps as Real)).collect();
    log_log_slope(&points[points.len().saturating_sub(2)..])
}

/// Steps of the exact splitting over the span, at every S.
pub const SPLIT_STEPS: u64 = 10;

/// The exact rotation ∘ damping splitting over the span in [`SPLIT_STEPS`]
/// steps, compared with the closed form at every step point.
fn splitting_run(top: &SymmetricTop, s: Real) -> MethodRun {
    let w0 = omega0(s);
    let size = w0.amax();
    let h = SPAN / SPLIT_STEPS as Real;
    let mut max_error: Real = 0.0;
    let mut stats = Stats::default();
    let mut failure = None;
    let mut t_reached = 0.0;
    for k in 1..=SPLIT_STEPS {
        let t = h * k as Real;
        match reduced_split_solve(top, &w0, t, k) {
            Ok((w, st)) => {
                max_error = max_error.max((w - reduced_closed_form(top, &w0, t)).amax() / size);
                stats = st;
                t_reached = t;
            }
            Err(e) => {
                failure = Some(e);
                break;
            }
        }
    }
    MethodRun {
        s,
        stats,
        max_error,
        t_reached,
        failure,
    }
}

/// Run the experiment of row 3.
pub fn measure() -> Result<Measurement, RowError> {
    let top = SymmetricTop::figure();
    let rk4 = RK4_LADDER
        .iter()
        .map(|&s| rk4_limit(&top, s))
        .collect::<Result<Vec<_>, _>>()?;
    let rk4_exponent = log_log_slope(&rk4.iter().map(|l| (l.s, l.h_star)).collect::<Vec<_>>());
    let largest = rk4.last().ok_or_else(|| RowError::new(3, "no RK4 runs"))?;
    let rk4_above = rk4_run(&top, largest.s, ABOVE * largest.h_star, false)?;
    let dp5 = LADDER
        .iter()
        .map(|&s| dp5_run(&top, s, None))
        .collect::<Result<Vec<_>, _>>()?;
    let s_max = LADDER[LADDER.len() - 1];
    let dp5_budgeted = dp5_run(&top, s_max, Some(BUDGET))?;
    let late = Vec3::new(0.0, 0.0, omega0(s_max).z);
    let dp5_predicted_steps = SPAN
        / linear_limit(dopri5_stability_function, &top, &late)
            .ok_or_else(|| RowError::new(3, "no DP5 stability limit"))?;
    let radau5 = LADDER
        .iter()
        .map(|&s| radau5_run(&top, s))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(bad) = dp5
        .iter()
        .chain(radau5.iter().map(|r| &r.run))
        .find(|r| r.failure.is_some())
    {
        return Err(RowError::new(
            3,
            format!(
                "an unbudgeted run failed at S = {}: {:?}",
                bad.s, bad.failure
            ),
        ));
    }
    Ok(Measurement {
        top,
        rk4_exponent,
        rk4_above,
        dp5_exponent: step_exponent(dp5.iter()),
        dp5_predicted_steps,
        radau5_exponent: step_exponent(radau5.iter().map(|r| &r.run)),
        rk4,
        dp5,
        dp5_budgeted,
        radau5,
        splitting: LADDER.iter().map(|&s| splitting_run(&top, s)).collect(),
    })
}

/// "a, b, c" of the items.
fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    items.iter().map(f).collect::<Vec<_>>().join(", ")
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        Row {
            number: 3,
            problem: "Stiffness: reduced ALE (4.12)-(4.14) at tau Omega^2 >> 1".into(),
            naive: self.naive(),
            fix: self.fixes(),
            notes: self.notes(),
        }
    }

    /// The naive methods: RK4 just above its limit h*, DP5 under a budget.
    fn naive(&self) -> Vec<Outcome> {
        let s_max = LADDER[LADDER.len() - 1];
        let above = &self.rk4_above;
        let h_star = self.rk4.last().map_or(Real::NAN, |l| l.h_star);
        let rk4_result = match (&above.t_left_envelope, &above.failure) {
            (Some(t), Some(e)) => {
                format!("leaves |Omega_perp| <= Omega_perp0 at t = {t:.3e}, then {e}")
            }
            (Some(t), None) => format!(
                "leaves |Omega_perp| <= Omega_perp0 at t = {t:.3e} (peak ratio {:.3e})",
                above.peak_ratio
            ),
            (None, Some(e)) => e.to_string(),
            (None, None) => "stays bounded".into(),
        };
        let rk4_ok = above.t_left_envelope.is_none() && above.failure.is_none();
        let dp5 = &self.dp5_budgeted;
        let dp5_full = self.dp5.last();
        let dp5_result = match &dp5.failure {
            Some(e) => format!(
                "{e} (of {SPAN}); unbudgeted it takes {} steps",
                dp5_full.map_or(0, |r| r.stats.steps)
            ),
            None => format!(
                "{} steps, error {:.1e} |Omega0|",
                dp5.stats.steps, dp5.max_error
            ),
        };
        vec![
            Outcome {
                method: format!("RK4, h = {ABOVE} h* = {:.3e}, S = {}", above.h, above.s),
                ok: rk4_ok,
                result: format!("{rk4_result}; h* = {h_star:.3e}"),
            },
            Outcome {
                method: format!("DP5, rtol {RTOL:e}, budget {BUDGET} steps, S = {s_max}"),
                ok: dp5.accurate(),
                result: dp5_result,
            },
        ]
    }

    /// The fixes at the largest S: Radau IIA 5, then the exact splitting.
    fn fixes(&self) -> Vec<Outcome> {
        let s_max = LADDER[LADDER.len() - 1];
        let mut fix: Vec<Outcome> = self
            .radau5
            .last()
            .map(|r| Outcome {
                method: format!("Radau IIA 5, analytic Jacobian, rtol {RTOL:e}, S = {s_max}"),
                ok: r.run.accurate() && r.run.stats.steps <= BUDGET,
                result: format!(
                    "{} steps, {} evals, {} Jacobians, {} LUs; error {:.1e} |Omega0|",
                    r.run.stats.steps,
                    r.run.stats.rhs_evals,
                    r.jacobian_evals,
                    r.lu_decompositions,
                    r.run.max_error
                ),
            })
            .into_iter()
            .collect();
        // The exact splitting is the second fix.
        if let Some(r) = self.splitting.last() {
            fix.push(Outcome {
                method: format!("exact rotation o damping splitting, S = {}", r.s),
                ok: r.accurate() && r.stats.steps <= BUDGET,
                result: format!(
                    "{} steps, error {:.1e} |Omega0|",
                    r.stats.steps, r.max_error
                ),
            });
        }
        fix
    }

    /// The measurements behind the outcomes, at every S.
    fn notes(&self) -> Vec<String> {
        let s_max = LADDER[LADDER.len() - 1];
        let mut notes = vec![
            format!(
                "Omega0 = S (0, 0.1, 0.2), I3/I1 = {}, tau = {}, t in [0, {SPAN}]; errors at the step points against (4.15)-(4.16)",
                self.top.ratio(),
                self.top.tau()
            ),
            format!(
                "RK4 h* at S = {}: {}; S^2 h* = {}",
                list(&self.rk4, |l| format!("{}", l.s)),
                list(&self.rk4, |l| format!("{:.3e}", l.h_star)),
                list(&self.rk4, |l| format!("{:.1}", l.s * l.s * l.h_star)),
            ),
            format!(
                "  linear stability brackets it: S^2 h at Omega0 {}, at Omega_perp -> 0 {}; fitted h* ~ S^{:.3} (expected -2)",
                list(&self.rk4, |l| format!(
                    "{:.1}",
                    l.s * l.s * l.h_linear_start
                )),
                list(&self.rk4, |l| format!("{:.1}", l.s * l.s * l.h_linear_late)),
                self.rk4_exponent
            ),
            format!(
                "DP5 steps at S = {}: {}; steps ~ S^{:.2} (last two S); errors {}",
                list(&self.dp5, |r| format!("{}", r.s)),
                list(&self.dp5, |r| r.stats.steps.to_string()),
                self.dp5_exponent,
                list(&self.dp5, |r| format!("{:.1e}", r.max_error)),
            ),
            format!(
                "  DP5's stability limit with the late eigenvalues -tau k^2 +- i Omega3~ predicts {:.0} steps at S = {s_max}",
                self.dp5_predicted_steps
            ),
            format!(
                "Radau5 steps at S = {}: {}; steps ~ S^{:.2} (last two S); errors {}",
                list(&self.radau5, |r| format!("{}", r.run.s)),
                list(&self.radau5, |r| r.run.stats.steps.to_string()),
                self.radau5_exponent,
                list(&self.radau5, |r| format!("{:.1e}", r.run.max_error)),
            ),
        ];
        if !self.splitting.is_empty() {
            notes.push(format!(
                "splitting steps at S = {}: {}",
                list(&self.splitting, |r| format!("{}", r.s)),
                list(&self.splitting, |r| r.stats.steps.to_string()),
            ));
        }
        notes
    }
}
