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

fn to_state(z: Complex<Real>, v: Complex<Real>) -> State<4> {
    State::<4>::new(z.re, z.im, v.re, v.im)
}

/// Integrate (3.4) backward from z(T) = a (real), ż(T) = f(a²)a, to the times
/// (descending from T), returning (z, ż) there and the work done.
///
/// NOTE: the integrator steps exactly onto every requested time instead of
/// reading them from its continuous extension: integrating backward, the
/// interpolant still carries about 1e-7 of the damped fast mode between step
/// ends, while the step ends themselves are clean.
fn backward(
    top: &SymmetricTop,
    omega3: Real,
    t_final: Real,
    a: Real,
    times_desc: &[Real],
    rtol: Real,
) -> Result<(Vec<State<4>>, Stats), IntegrateError> {
    let z = Complex::new(a, 0.0);
    // NOTE: the final data need not be exact (the margin damps their error
    // by e^{−40}), but they must be sane at every spin: the series
    // [`slow_manifold_rate`] gives ż/z ~ −10⁹ at τk = 18, whose transient
    // stalled the first backward step.
    let v = near_rest_rate(top, omega3, a * a) * z;
    let rhs = |_t: Real, y: &State<4>| symmetric_full_ale_rhs(top, omega3, y);
    let opts = AdaptiveOptions::new(rtol, rtol * 1e-6 * a.max(1e-300))?;
    let mut stepper = Dop853::new(t_final, to_state(z, v), opts)?;
    let mut out = Vec::with_capacity(times_desc.len());
    for &t in times_desc {
        while stepper.t() > t {
            stepper.step(&rhs, t)?;
        }
        out.push(*stepper.y());
    }
    Ok((out, stepper.stats()))
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
fn guessed_log_amplitude(top: &SymmetricTop, omega0: &Vec3, span: Real) -> Real {
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
fn final_margin(top: &SymmetricTop, omega3: Real) -> Real {
    let tau = top.tau();
    let k = top.ratio() * omega3;
    let alpha = ((1.0 + (1.0 + 16.0 * tau * tau * k * k).sqrt()) / 2.0).sqrt();
    40.0 * tau / alpha
}

/// The most the slow amplitude may fall (in e-foldings) over one segment of
/// the shoot, margin included: e^{−250} ≈ 10⁻¹⁰⁹, well inside a double,
/// whatever the guess misses by.
const SEGMENT_E_FOLDINGS: Real = 250.0;

/// The physical solution of (3.4) through Ω₀ (symmetric top), at `times`
/// (finite, ≥ 0, ascending).
///
/// The final time T lies a margin beyond the last requested time
/// ([`final_margin`], 40τ for a slow spin), so the error of the approximate
/// final data has decayed by e^{−40} before any sample. The final amplitude is found by bisection on ln a (|z(0)| grows
/// monotonically with a), from a bracket around the guess of
/// [`guessed_log_amplitude`] widened by doubling steps, then matched once
/// more by the pass that outputs the times ([`match_output_pass`]); the
/// result is rotated so that z(0) = Ω₁₀ + iΩ₂₀.
///
/// A horizon over which the amplitude falls by more than
/// [`SEGMENT_E_FOLDINGS`] is cut into segments, each shot from the state the
/// one before ended in (the slow manifold is invariant, so the pieces join
/// into one physical solution); once τ|z|² is a hundredth of rtol times the
/// slow rate, the rest is the slow mode of linear theory
/// ([`linear_theory_rate`]) in closed form.
pub fn physical_solution(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<PhysicalSolution, PhysicalError> {
    let tau = top.tau();
    if tau <= 0.0 {
        return Err(PhysicalError::BadInput("the full ALE needs tau > 0"));
    }
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] < w[0]) {
        return Err(PhysicalError::BadInput(
            "times must be finite, >= 0 and ascending",
        ));
    }
    let mut sol = PhysicalSolution {
        times: times.to_vec(),
        z: Vec::with_capacity(times.len()),
        z_dot: Vec::with_capacity(times.len()),
        stats: Stats::default(),
        shots: 0,
    };
    let margin = final_margin(top, omega0.z);
    let start_norm = omega0.x.hypot(omega0.y);
    let mut start = *omega0;
    let mut t0 = 0.0;
    let mut next = 0;
    while next < times.len() {
        let z_start = start.x.hypot(start.y);
        if z_start <= 1e-300 * start_norm || z_start == 0.0 {
            // z ≡ 0 is the physical solution: the top spins steadily about its axis.
            sol.z.resize(times.len(), Complex::new(0.0, 0.0));
            sol.z_dot.resize(times.len(), Complex::new(0.0, 0.0));
            break;
        }
        // Once τ|z|² is far below the slow rate, (3.4) is linear in z for the
        // rest of the run: its physical solution is the slow mode of linear
        // theory, in closed form, to a part in 100 of rtol.
        let f0 = linear_theory_rate(top, omega0.z);
        if tau * z_start * z_start <= 0.01 * rtol * (-f0.re) {
            let z_t0 = Complex::new(start.x, start.y);
            for &t in &times[next..] {
                let z = z_t0 * (f0 * (t - t0)).exp();
                sol.z.push(z);
                sol.z_dot.push(f0 * z);
            }
            break;
        }
        // The segment: as long as the guessed fall over it and the margin
        // stays within SEGMENT_E_FOLDINGS (the guess falls monotonically).
        let t_last = times[times.len() - 1];
        let fall = |span: Real| z_start.ln() - guessed_log_amplitude(top, &start, span);
        let end = if fall(t_last - t0 + margin) <= SEGMENT_E_FOLDINGS {
            t_last
        } else {
            let (mut lo, mut hi) = (0.0, t_last - t0);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if fall(mid + margin) <= SEGMENT_E_FOLDINGS {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            t0 + lo.max(margin)
        };
        let last = times[next..].partition_point(|&t| t <= end) + next;
        let mut local: Vec<Real> = times[next..last].iter().map(|t| t - t0).collect();
        if last < times.len() {
            local.push(end - t0);
        }
        let piece = shoot_segment(top, &start, &local, rtol)?;
        sol.stats += piece.stats;
        sol.shots += piece.shots;
        let kept = last - next;
        sol.z.extend_from_slice(&piece.z[..kept]);
        sol.z_dot.extend_from_slice(&piece.z_dot[..kept]);
        if last == times.len() {
            break;
        }
        let z_end = piece.z[piece.z.len() - 1];
        start = Vec3::new(z_end.re, z_end.im, omega0.z);
        t0 = end;
        next = last;
    }
    Ok(sol)
}

/// One segment of [`physical_solution`]: the physical solution through
/// `omega0` at `times` (ascending from 0), by one shoot.
fn shoot_segment(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<PhysicalSolution, PhysicalError> {
    let z0 = Complex::new(omega0.x, omega0.y);
    let target = z0.norm();
    let omega3 = omega0.z;
    let t_last = times.last().copied().unwrap_or(0.0);
    let t_final = t_last + final_margin(top, omega3);
    let mut stats = Stats::default();
    let mut shots = 0;
    // NOTE: backward in time the slow amplitude grows, and too large a final
    // amplitude blows up before t = 0 (backward, du/dt ≈ 2τu², a finite-time
    // blow-up). Such a shot overshoots the target by definition, so it counts as
    // +∞, not as an error.
    let mut amplitude_at_zero = |ln_a: Real| -> Result<Real, PhysicalError> {
        shots += 1;
        match backward(top, omega3, t_final, ln_a.exp(), &[0.0], rtol) {
            Ok((out, s)) => {
                stats += s;
                Ok(out[0][0].hypot(out[0][1]))
            }
            Err(IntegrateError::NonFinite { .. } | IntegrateError::StepSizeUnderflow { .. }) => {
                Ok(Real::INFINITY)
            }
            Err(e) => Err(e.into()),
        }
    };
    // NOTE: bracket ln a around the guess, widening by doubling steps (the
    // guess may miss by tens of e-foldings at τk ≳ 1, where the slow decay
    // is far from the reduced model's), never below the smallest normal double.
    let guess = guessed_log_amplitude(top, omega0, t_final);
    let floor = Real::MIN_POSITIVE.ln();
    let (mut lo, mut hi) = ((guess - 1.0).max(floor), (guess + 1.0).max(floor + 2.0));
    let mut widen = 1.0;
    while amplitude_at_zero(lo)? > target {
        if lo <= floor {
            return Err(PhysicalError::NoConvergence("no lower bracket"));
        }
        hi = lo;
        lo = (lo - widen).max(floor);
        widen *= 2.0;
    }
    widen = 1.0;
    while amplitude_at_zero(hi)? < target {
        lo = hi;
        hi += widen;
        widen *= 2.0;
        if widen > 1e4 {
            return Err(PhysicalError::NoConvergence("no upper bracket"));
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if amplitude_at_zero(mid)? < target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-15 * (1.0 + mid.abs()) {
            break;
        }
    }
    let mut desc: Vec<Real> = times.iter().rev().copied().collect();
    if desc.last() != Some(&0.0) {
        desc.push(0.0);
    }
    let (out, s, passes) = match_output_pass(
        |ln_a| backward(top, omega3, t_final, ln_a.exp(), &desc, rtol),
        0.5 * (lo + hi),
        target,
        rtol,
    )?;
    stats += s;
    shots += passes;
    let at_zero = out.last().expect("t = 0 was requested");
    let rotation = z0 / Complex::new(at_zero[0], at_zero[1]);
    let rotation = rotation / rotation.norm();
    let mut z = Vec::with_capacity(times.len());
    let mut z_dot = Vec::with_capacity(times.len());
    for y in out.iter().take(times.len()).rev() {
        z.push(rotation * Complex::new(y[0], y[1]));
        z_dot.push(rotation * Complex::new(y[2], y[3]));
    }
    Ok(PhysicalSolution {
        times: times.to_vec(),
        z,
        z_dot,
        stats,
        shots,
    })
}

/// The most output passes [`match_output_pass`] makes.
const OUTPUT_PASSES: u32 = 8;

/// The output pass whose own z(0) has the target amplitude: `pass(ln a)`
/// integrates back from the final amplitude a to every output time, ending at
/// t = 0. Returns its states, the work of all passes and their number; an
/// error when none lands within `rtol` (relative) of the target.
///
/// NOTE: the bisection's shots stop only at t = 0, the output pass at every
/// requested time, so the two take different steps; at a loose rtol the
/// output pass from the shots' a misses |z(0)| by far more than rtol (35 % at
/// rtol 1e-3 over 4000 τ) or blows up backward. A few secant steps on ln a
/// with the output pass itself close that gap; d ln|z(0)|/d ln a = 1 where
/// (3.4) is linear in z, so that is the first slope. A pass that blows up
/// asked for too large an a: the next one goes halfway back.
fn match_output_pass(
    mut pass: impl FnMut(Real) -> Result<(Vec<State<4>>, Stats), IntegrateError>,
    ln_a: Real,
    target: Real,
    rtol: Real,
) -> Result<(Vec<State<4>>, Stats, u32), PhysicalError> {
    let ln_target = target.ln();
    let mut stats = Stats::default();
    let (mut x, mut slope) = (ln_a, 1.0);
    let mut last: Option<(Real, Real)> = None;
    let mut best: Option<(Real, Vec<State<4>>)> = None;
    let (mut passes, mut stalled) = (0, 0);
    while passes < OUTPUT_PASSES {
        passes += 1;
        match pass(x) {
            Ok((out, s)) => {
                stats += s;
                let y = out.last().expect("t = 0 is an output time");
                let miss = y[0].hypot(y[1]).ln() - ln_target;
                if miss.is_nan() {
                    return Err(PhysicalError::NoConvergence("an output pass gave NaN"));
                }
                if let Some((x0, miss0)) = last {
                    let secant = (miss - miss0) / (x - x0);
                    if secant.is_finite() && secant > 0.0 {
                        slope = secant;
                    }
                }
                // Done at rounding, or when the passes' own noise (their
                // steps move with a) stops the secant from gaining.
                let better = best.as_ref().is_none_or(|(b, _)| miss.abs() < *b);
                stalled = if better { 0 } else { stalled + 1 };
                if better {
                    best = Some((miss.abs(), out));
                }
                if miss.abs() <= 1e-14 || !miss.is_finite() || stalled >= 2 {
                    break;
                }
                last = Some((x, miss));
                x -= miss / slope;
            }
            Err(IntegrateError::NonFinite { .. } | IntegrateError::StepSizeUnderflow { .. }) => {
                x = match last {
                    Some((x0, _)) => 0.5 * (x + x0),
                    None => x - 1.0,
                };
            }
            Err(e) => return Err(e.into()),
        }
    }
    match best {
        Some((miss, out)) if miss <= rtol.max(1e-10) => Ok((out, stats, passes)),
        Some(_) => Err(PhysicalError::NoConvergence(
            "no final amplitude reaches the given Omega_perp at t = 0",
        )),
        None => Err(PhysicalError::NoConvergence(
            "every output pass blew up backward",
        )),
    }
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
        }
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

/// The physical solution of (3.4) through Ω₀ as a table on [0, t_end].
pub fn physical_table(
    top: &SymmetricTop,
    omega0: &Vec3,
    t_end: Real,
    rtol: Real,
) -> Result<(OmegaTable, PhysicalSolution), PhysicalError> {
    let rate = omega0.norm().max(top.omega3_tilde(omega0.z).abs());
    let step = table_step(top.tau(), rate);
    let sol = physical_solution(top, omega0, &grid(step, t_end), rtol)?;
    let table = OmegaTable::symmetric(
        step,
        omega0.z,
        sol.z.iter().copied(),
        sol.z_dot.iter().copied(),
    );
    Ok((table, sol))
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
