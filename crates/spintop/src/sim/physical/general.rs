//! The physical (non-runaway) solution of the full ALE (3.4) for any top, and
//! its forward integration with the runaway monitor.
//!
//! The state of (3.4) is (Ω, W = Ω̇) (see
//! [`general_full_ale_rhs`]): six numbers tied by one first-order constraint,
//! so five free ones. Three of them, Ω, are slow; the two components of W
//! across the dipole carry the fast modes that grow forward like e^{t/τ_f},
//! τ_f of the order of [`fast_time`]. The physical solution is the one on the
//! three-dimensional slow manifold W = g(Ω).
//!
//! As for the symmetric top, integrating backward turns the runaway into decay:
//! from final data near the manifold (W from the reduced model, O(τ²) off it)
//! the backward flow lands on the physical solution, with the error of the
//! final data damped by e^{−36} after the margin. Matching a given
//! Ω(t₀) is a shoot on the three numbers Ω(T), solved by Newton's method with a
//! finite-difference Jacobian (the chord variant: one Jacobian per segment).
//! Unlike the symmetric top there is no rotation symmetry left to fix the phase
//! for free, so the shoot is three-dimensional.
//!
//! The horizon is covered in segments: each starts from Ω at the end of the
//! one before and shoots over its own length plus the margin. The margin is
//! 36 e-foldings of the slowest runaway, and the whole shot at most three
//! e-foldings of the slow decay (both rates from the linearisation at the
//! segment's start): a longer shot makes the map Ω(T) → Ω(t₀) badly
//! conditioned (the slow decay compounds backward) and Newton's first guess
//! (the reduced model run forward) blows up backward.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `omega`, `w` | Ω, W = Ω̇ | body rate and its rate | κ = 1 units |
//! | `tau_f` | τ_f = \|d\|²/min Iᵢ | fast time of (3.4) | time |

use super::{ForwardRun, OmegaTable, PhysicalError, forward_with_monitor, grid, table_step};
use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Stats, Stepper};
use crate::math::{Real, State, Vec3};
use crate::physics::full_ale::general_full_ale_rhs;
use crate::physics::general_top::GeneralTop;
use nalgebra::Matrix3;

/// The margin beyond each segment, in e-foldings of the slowest runaway: the
/// error of the final data is damped by e^{−36} ≈ 2e-16 before any output.
const MARGIN_E_FOLDINGS: Real = 36.0;

/// The physical solution is looked for only while the slow modes decay at
/// most this fraction of the slowest runaway rate (scale separation).
const SEPARATION: Real = 0.25;

/// Steps one backward shot may take; a shot that needs more is treated as
/// one that blew up (a runaway the backward flow amplifies, or a final state
/// far off the manifold), never as a run to wait for.
const SHOT_STEPS: u64 = 200_000;

/// The most e-foldings of the slow decay one shot may span: backward, the slow
/// amplitude grows like e^{λ_slow t}, and the shoot's map from Ω(T) to Ω(t₀)
/// with it; beyond a few e-foldings Newton's first guess blows up backward.
const SLOW_E_FOLDINGS: Real = 3.0;

/// The rates of (3.4) linearised at Ω (with W from the reduced model): the
/// slowest runaway (the smallest positive real part of the runaway pair) and
/// the fastest decay or growth of the rest; `None` when the linearisation
/// overflows a double.
fn rates(top: &GeneralTop, omega: &Vec3) -> Option<(Real, Real)> {
    let y0 = near_manifold(top, omega);
    let h = 1e-7 * y0.amax().max(1e-300);
    let mut jac = nalgebra::SMatrix::<Real, 6, 6>::zeros();
    for j in 0..6 {
        let mut e = State::<6>::zeros();
        e[j] = h;
        let col = (general_full_ale_rhs(top, &(y0 + e)) - general_full_ale_rhs(top, &(y0 - e)))
            / (2.0 * h);
        jac.set_column(j, &col);
    }
    // NOTE: nalgebra's eigenvalue iteration never ends on a matrix holding a
    // NaN or an infinity (a dipole of 1e100 in kappa = 1 units overflows the
    // right-hand side): such a linearisation is a numerical failure.
    if !jac.iter().all(|x| x.is_finite()) {
        return None;
    }
    let eig = jac.complex_eigenvalues();
    // The runaway pair is told from the rest by the rates it has at rest,
    // which need not be close to each other (an elongated top).
    let threshold = 0.5 * runaway_rates_at_rest(top)[0];
    let fast = eig
        .iter()
        .map(|l| l.re)
        .filter(|re| *re > threshold)
        .fold(Real::INFINITY, Real::min);
    let slow = eig
        .iter()
        .map(|l| l.re)
        .filter(|re| *re <= threshold)
        .fold(0.0, |m: Real, re| m.max(re.abs()));
    Some((fast, slow))
}

/// The runaway rates of (3.4) linearised about rest (Ω = 0), smaller first:
/// the eigenvalues of [(P I⁻¹ P) restricted to the plane ⊥ d]⁻¹ / |d|² (the
/// physics notes; κ = 1), P the projector across d.
///
/// Paper: Eq. (3.4) (its runaway modes; not in the paper).
pub fn runaway_rates_at_rest(top: &GeneralTop) -> [Real; 2] {
    let (i, d) = (top.inertia(), top.dipole());
    let n = d.normalize();
    // Any unit vector across d, then the one across both.
    let helper = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let e1 = n.cross(&helper).normalize();
    let e2 = n.cross(&e1);
    let m = |a: &Vec3, b: &Vec3| a.component_div(&i).dot(b);
    // The 2×2 matrix of P I⁻¹ P on (e1, e2); its inverse's eigenvalues are
    // the reciprocals of its own.
    let (a, b, c) = (m(&e1, &e1), m(&e1, &e2), m(&e2, &e2));
    let mean = 0.5 * (a + c);
    let spread = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    let d2 = d.norm_squared();
    [1.0 / ((mean + spread) * d2), 1.0 / ((mean - spread) * d2)]
}

/// The fast time of (3.4) for a general top, τ_f = |d|²/min Iᵢ.
///
/// Paper: Eq. (3.4) (the scale of its Ω̈ term).
///
/// The runaway modes grow like e^{λt} with λ ≈ I_⊥/|d|², I_⊥ a moment across
/// the dipole, so 1/λ ≤ τ_f: τ_f is the slowest a runaway can be, which is
/// what a margin must outlast. For a symmetric top with d on its axis it is
/// τ = d²/I₁.
pub fn fast_time(top: &GeneralTop) -> Real {
    top.dipole().norm_squared() / top.inertia().min()
}

/// The physical solution of (3.4) of a general top at the requested times.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneralPhysicalSolution {
    /// The times.
    pub times: Vec<Real>,
    /// Ω at each time.
    pub omega: Vec<Vec3>,
    /// Ω̇ at each time (on the slow manifold).
    pub omega_dot: Vec<Vec3>,
    /// Work of all backward integrations.
    pub stats: Stats,
    /// Number of backward integrations (shots).
    pub shots: u32,
    /// Number of segments the horizon was cut into.
    pub segments: u32,
}

fn pack(omega: &Vec3, w: &Vec3) -> State<6> {
    let mut y = State::<6>::zeros();
    y.fixed_rows_mut::<3>(0).copy_from(omega);
    y.fixed_rows_mut::<3>(3).copy_from(w);
    y
}

fn omega_of(y: &State<6>) -> Vec3 {
    y.fixed_rows::<3>(0).into_owned()
}

fn w_of(y: &State<6>) -> Vec3 {
    y.fixed_rows::<3>(3).into_owned()
}

/// (Ω, W) with W from the reduced model: O(τ²) off the slow manifold, and on
/// the constraint d·(IW + Ω × IΩ) = 0 exactly (the reduced correction is
/// across d).
pub fn near_manifold(top: &GeneralTop, omega: &Vec3) -> State<6> {
    pack(omega, &top.reduced_ale_rhs(omega))
}

/// Integrate (3.4) backward from Ω(T) = `a` near the manifold to the times
/// `desc` (descending, ≤ T), stepping exactly onto each.
///
/// NOTE: as for the symmetric top, between step ends the interpolant still
/// carries a trace of the damped fast modes; the step ends are clean.
fn backward(
    top: &GeneralTop,
    t_final: Real,
    a: &Vec3,
    desc: &[Real],
    (rtol, refine): (Real, Real),
) -> Result<(Vec<State<6>>, Stats), IntegrateError> {
    let rhs = |_t: Real, y: &State<6>| general_full_ale_rhs(top, y);
    let mut opts = AdaptiveOptions::new(rtol, rtol * 1e-6 * a.norm().max(1e-300))?;
    opts.max_steps = SHOT_STEPS;
    // NOTE: the margin damps the final data's error only if the steps
    // follow the fast modes' decay; at a loose rtol DOP853 would stride over
    // it (hλ of several, where its stability function is far from e^{hλ})
    // and leave ~1e-7 of |Ω| off the manifold at each segment's end, which
    // the motion then amplifies (1.7e-2 of |Ω₀| by t = 300 at rtol 1e-2).
    // Half an e-folding of the faster runaway per step keeps e^{−36}.
    // `refine` (½ for the second run of an error estimate) halves the cap:
    // where the cap holds the steps, a tighter rtol alone takes the same
    // steps, and the two runs agreed to 1e-14 while both were 5.2e-14 off
    // (I = (0.5, 1, 1.2), d = e₂, at rtol 1e-10 and 1e-12).
    opts.h_max = 0.5 * refine / runaway_rates_at_rest(top)[1];
    let mut stepper = Dop853::new(t_final, near_manifold(top, a), opts)?;
    let mut out = Vec::with_capacity(desc.len());
    for &t in desc {
        while stepper.t() > t {
            stepper.step(&rhs, t)?;
        }
        out.push(*stepper.y());
    }
    Ok((out, stepper.stats()))
}

/// The reduced model run forward from `omega` over `span`: Newton's first
/// guess for Ω at the end of a shot.
fn reduced_guess(
    top: &GeneralTop,
    omega: &Vec3,
    span: Real,
    rtol: Real,
) -> Result<Vec3, IntegrateError> {
    let rhs = |_t: Real, y: &State<3>| top.reduced_ale_rhs(y);
    let opts = AdaptiveOptions::new(rtol, rtol * 1e-6 * omega.norm().max(1e-300))?;
    let mut stepper = Dop853::new(0.0, *omega, opts)?;
    while stepper.t() < span {
        stepper.step(&rhs, span)?;
    }
    Ok(*stepper.y())
}

/// Counts the work of the shots.
struct Shooter<'a> {
    top: &'a GeneralTop,
    rtol: Real,
    /// The share of its usual size the step cap takes (see [`backward`]).
    refine: Real,
    stats: Stats,
    shots: u32,
    /// The chord Jacobian of the last [`Shooter::solve`], d Ω(0) / d Ω(span).
    jacobian: Option<Matrix3<Real>>,
}

/// The most output passes [`Shooter::output`] makes.
const OUTPUT_PASSES: u32 = 8;

impl Shooter<'_> {
    /// Ω(0) of the backward run from Ω(span) = a, or `None` when that run blew
    /// up (too large a final amplitude grows without bound backward).
    fn shoot(&mut self, span: Real, a: &Vec3) -> Result<Option<Vec3>, PhysicalError> {
        self.shots += 1;
        match backward(self.top, span, a, &[0.0], (self.rtol, self.refine)) {
            Ok((out, s)) => {
                self.stats += s;
                Ok(Some(omega_of(&out[0])))
            }
            Err(
                IntegrateError::NonFinite { .. }
                | IntegrateError::StepSizeUnderflow { .. }
                | IntegrateError::TooManySteps { .. },
            ) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// Ω(span) whose backward run reaches `start` at 0, by chord Newton.
    fn solve(&mut self, start: &Vec3, span: Real) -> Result<Vec3, PhysicalError> {
        let scale = start.norm();
        let tol = 0.1 * self.rtol * scale;
        let mut a = reduced_guess(self.top, start, span, self.rtol)?;
        let residual = |s: &mut Self, a: &Vec3| -> Result<Option<Vec3>, PhysicalError> {
            Ok(s.shoot(span, a)?.map(|w| w - start))
        };
        let mut r = residual(self, &a)?.ok_or(PhysicalError::NoConvergence(
            "the reduced model's guess blew up backward",
        ))?;
        let mut jacobian: Option<Matrix3<Real>> = None;
        let mut best = r.norm();
        for _ in 0..40 {
            if r.norm() <= tol {
                self.jacobian = jacobian;
                return Ok(a);
            }
            let j = match jacobian {
                Some(j) => j,
                None => {
                    let m = self.jacobian_at(span, &a, &(r + start))?;
                    jacobian = Some(m);
                    m
                }
            };
            let delta = j
                .lu()
                .solve(&(-r))
                .ok_or(PhysicalError::NoConvergence("a singular Jacobian"))?;
            // Damped: halve the step while the shot blows up or gets worse.
            let mut lambda = 1.0;
            let mut next = None;
            for _ in 0..30 {
                let trial = a + delta * lambda;
                if let Some(rt) = residual(self, &trial)?
                    && rt.norm() < r.norm()
                {
                    next = Some((trial, rt));
                    break;
                }
                lambda *= 0.5;
            }
            match next {
                Some((trial, rt)) => {
                    // A slow contraction means the chord Jacobian is stale.
                    if rt.norm() > 0.25 * r.norm() {
                        jacobian = None;
                    }
                    a = trial;
                    r = rt;
                    best = best.min(r.norm());
                }
                None if jacobian.is_some() && lambda < 1e-8 => {
                    // No descent along the chord step: at the level of the
                    // integrator's own noise, accept; else refresh once more.
                    if best <= 100.0 * self.rtol * scale {
                        self.jacobian = None;
                        return Ok(a);
                    }
                    jacobian = None;
                }
                None => return Err(PhysicalError::NoConvergence("no descent")),
            }
        }
        if best <= 100.0 * self.rtol * scale {
            self.jacobian = jacobian;
            Ok(a)
        } else {
            Err(PhysicalError::NoConvergence(
                "Newton's method on the final rate",
            ))
        }
    }
}

impl Shooter<'_> {
    /// d Ω(0) / d Ω(span) at `a`, whose shot reached `at_zero`, by forward
    /// differences of shots.
    fn jacobian_at(
        &mut self,
        span: Real,
        a: &Vec3,
        at_zero: &Vec3,
    ) -> Result<Matrix3<Real>, PhysicalError> {
        let h = 1e-6 * a.norm().max(1e-300);
        let mut m = Matrix3::zeros();
        for k in 0..3 {
            let mut ak = *a;
            ak[k] += h;
            let wk = self.shoot(span, &ak)?.ok_or(PhysicalError::NoConvergence(
                "a shot of the Jacobian blew up backward",
            ))?;
            m.set_column(k, &((wk - at_zero) / h));
        }
        Ok(m)
    }

    /// The output pass, from Ω(span) = `a` back to every time of `desc`
    /// (descending, ending at 0), corrected by chord Newton until its own
    /// Ω(0) is `start`.
    ///
    /// NOTE: the shots stop only at 0 and the output pass at every table
    /// time, so their steps differ; at a loose rtol the pass from the shots'
    /// a began off the segment's start by the shots' own error, and segment
    /// after segment those jumps added up (2.3e-2 of |Ω₀| by t = 300 at
    /// rtol 1e-2). The shots' Jacobian serves the output pass too.
    fn output(
        &mut self,
        start: &Vec3,
        span: Real,
        mut a: Vec3,
        desc: &[Real],
    ) -> Result<Vec<State<6>>, PhysicalError> {
        let scale = start.norm();
        let mut best: Option<(Real, Vec<State<6>>)> = None;
        let mut stalled = 0;
        for _ in 0..OUTPUT_PASSES {
            self.shots += 1;
            let out = match backward(self.top, span, &a, desc, (self.rtol, self.refine)) {
                Ok((out, s)) => {
                    self.stats += s;
                    out
                }
                Err(
                    IntegrateError::NonFinite { .. }
                    | IntegrateError::StepSizeUnderflow { .. }
                    | IntegrateError::TooManySteps { .. },
                ) => break,
                Err(e) => return Err(e.into()),
            };
            let at_zero = omega_of(out.last().expect("0 is an output time"));
            let miss = (at_zero - start).norm();
            if miss.is_nan() {
                break;
            }
            let better = best.as_ref().is_none_or(|(b, _)| miss < *b);
            stalled = if better { 0 } else { stalled + 1 };
            if better {
                best = Some((miss, out));
            }
            // NOTE: the miss at the segment's start carries into every
            // sample after it; a floor of 1e-13 held alike for rtol 1e-10
            // and 1e-12 left both runs of the error estimate 5.2e-14 off
            // (I = (0.5, 1, 1.2), d = e₂) while they agreed to 1e-14, and the
            // error printed was below the real one. A stalled pass stops.
            if miss <= (1e-3 * self.rtol).max(4.0 * Real::EPSILON) * scale || stalled >= 2 {
                break;
            }
            let j = match self.jacobian {
                Some(j) => j,
                None => {
                    let j = self.jacobian_at(span, &a, &at_zero)?;
                    self.jacobian = Some(j);
                    j
                }
            };
            match j.lu().solve(&(start - at_zero)) {
                Some(delta) => a += delta,
                None => break,
            }
        }
        match best {
            Some((miss, out)) if miss <= self.rtol * scale => Ok(out),
            _ => Err(PhysicalError::NoConvergence(
                "no output pass reaches the segment's start",
            )),
        }
    }
}

/// The physical solution of (3.4) through Ω₀ for any top, at `times` (finite,
/// ≥ 0, ascending).
///
/// Paper: Eq. (3.4) (its physical solution; not in the paper).
///
/// Ω̇ is returned with Ω: on the slow manifold it is the state's W, the rate
/// the manifold itself assigns, not a difference of outputs.
pub fn general_physical_solution(
    top: &GeneralTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<GeneralPhysicalSolution, PhysicalError> {
    general_physical_solution_refined(top, omega0, times, rtol, 1.0)
}

/// [`general_physical_solution`] with the backward passes' step cap scaled
/// by `refine` in (0, 1] (½ for the second run of an error estimate:
/// [`crate::sim::claim`]).
///
/// Paper: Eq. (3.4) (its physical solution; not in the paper).
pub fn general_physical_solution_refined(
    top: &GeneralTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
    refine: Real,
) -> Result<GeneralPhysicalSolution, PhysicalError> {
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] < w[0]) {
        return Err(PhysicalError::BadInput(
            "times must be finite, >= 0 and ascending",
        ));
    }
    if !(rtol > 0.0 && rtol < 1.0) {
        return Err(PhysicalError::BadInput("rtol must lie in (0, 1)"));
    }
    let mut sol = GeneralPhysicalSolution {
        times: times.to_vec(),
        omega: Vec::with_capacity(times.len()),
        omega_dot: Vec::with_capacity(times.len()),
        stats: Stats::default(),
        shots: 0,
        segments: 0,
    };
    if *omega0 == Vec3::zeros() {
        // A top at rest stays at rest: Ω ≡ 0 is the physical solution.
        sol.omega = vec![Vec3::zeros(); times.len()];
        sol.omega_dot = vec![Vec3::zeros(); times.len()];
        return Ok(sol);
    }
    let t_last = times.last().copied().unwrap_or(0.0);
    let mut shooter = Shooter {
        top,
        rtol,
        refine: refine.clamp(1e-3, 1.0),
        stats: Stats::default(),
        shots: 0,
        jacobian: None,
    };
    let mut start = *omega0;
    let mut t0 = 0.0;
    let mut next = 0; // the first time not yet output
    loop {
        // The margin outlasts the slowest runaway; the segment keeps the shot
        // within a few e-foldings of the slow decay (shorter still if the
        // shoot fails: halved up to five times).
        let (fast, slow) =
            rates(top, &start).ok_or(PhysicalError::Integrate(IntegrateError::NonFinite {
                t: t0,
            }))?;
        if !(fast.is_finite() && fast > 0.0 && slow <= SEPARATION * fast) {
            return Err(PhysicalError::NotSeparated { t: t0, slow, fast });
        }
        let margin = MARGIN_E_FOLDINGS / fast;
        let mut length = if slow > 0.0 {
            (SLOW_E_FOLDINGS / slow - margin).clamp(0.25 * margin, margin)
        } else {
            margin
        };
        let mut tries = 0;
        let (t1, last, out) = loop {
            let t1 = (t0 + length).min(t_last);
            let span = (t1 - t0) + margin;
            // Output the times in [t0, t1] (each once), and t1 to start the next.
            let last = next + times[next..].partition_point(|&t| t <= t1);
            let mut desc: Vec<Real> = vec![t1 - t0];
            desc.extend(times[next..last].iter().rev().map(|t| t - t0));
            desc.push(0.0);
            let shot = shooter
                .solve(&start, span)
                .and_then(|a| shooter.output(&start, span, a, &desc));
            match shot {
                Ok(out) => break (t1, last, out),
                Err(PhysicalError::NoConvergence(_)) if tries < 5 && t1 > t0 => {
                    tries += 1;
                    length *= 0.5;
                }
                Err(e) => return Err(e),
            }
        };
        next = last;
        sol.segments += 1;
        // out[1..=n] are the requested times, descending.
        for y in out[1..out.len() - 1].iter().rev() {
            sol.omega.push(omega_of(y));
            sol.omega_dot.push(w_of(y));
        }
        start = omega_of(&out[0]);
        t0 = t1;
        if next >= times.len() || t1 >= t_last {
            break;
        }
    }
    sol.stats = shooter.stats;
    sol.shots = shooter.shots;
    // The first sample is the input itself (the shoot meets it to its
    // tolerance).
    if times.first() == Some(&0.0) {
        sol.omega[0] = *omega0;
    }
    Ok(sol)
}

/// What a forward integration of a general top's (3.4) produced: times and
/// (Ω, W) every τ_f/4, the runaway if the monitor stopped the run, the work.
pub type GeneralForwardRun = ForwardRun<6>;

/// Integrate (3.4) of a general top forward from (Ω, W) = `y0` with DOP853 and
/// stop at the runaway: the distance |W − F_red(Ω)| from the reduced model's
/// rate passes 5% of |Ω|/τ_f while growing faster than 1/(2τ_f) (as
/// [`super::integrate_forward`] does for the symmetric top).
///
/// Paper: Eq. (3.4) (integrated forward, it runs away).
pub fn general_integrate_forward(
    top: &GeneralTop,
    y0: State<6>,
    t_end: Real,
    rtol: Real,
) -> Result<GeneralForwardRun, PhysicalError> {
    let rhs = |_t: Real, y: &State<6>| general_full_ale_rhs(top, y);
    let distance = |y: &State<6>| {
        let omega = omega_of(y);
        ((w_of(y) - top.reduced_ale_rhs(&omega)).norm(), omega.norm())
    };
    forward_with_monitor(&rhs, y0, fast_time(top), t_end, rtol, distance)
}

/// The physical solution of a general top's (3.4) through Ω₀ as a table on
/// [0, t_end].
pub fn general_physical_table(
    top: &GeneralTop,
    omega0: &Vec3,
    t_end: Real,
    rtol: Real,
    refine: Real,
) -> Result<(OmegaTable, GeneralPhysicalSolution), PhysicalError> {
    let step = refine * table_step(fast_time(top), omega0.norm());
    let sol = general_physical_solution_refined(top, omega0, &grid(step, t_end), rtol, refine)?;
    let second = sol
        .omega
        .iter()
        .zip(&sol.omega_dot)
        .map(|(w, wd)| w_of(&general_full_ale_rhs(top, &pack(w, wd))))
        .collect();
    let table = OmegaTable::new(step, sol.omega.clone(), sol.omega_dot.clone()).with_second(second);
    Ok((table, sol))
}

/// (3.4) of a general top integrated forward from Ω₀ with the reduced model's
/// rate as Ω̇(0), the natural but wrong guess, as a table up to t_end or up to
/// the runaway.
pub fn general_forward_table(
    top: &GeneralTop,
    omega0: &Vec3,
    t_end: Real,
    rtol: Real,
) -> Result<(OmegaTable, GeneralForwardRun), PhysicalError> {
    let run = general_integrate_forward(top, near_manifold(top, omega0), t_end, rtol)?;
    let table = OmegaTable::new(
        0.25 * fast_time(top),
        run.trace.iter().map(|(_, y)| omega_of(y)).collect(),
        run.trace.iter().map(|(_, y)| w_of(y)).collect(),
    );
    Ok((table, run))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Matrix3x2};

    /// The physics notes give the runaway rates of (3.4) for any top: the
    /// eigenvalues of [(P I⁻¹ P) restricted to the plane ⊥ d]⁻¹ / |d|² (κ = 1).
    /// Built here with nalgebra's symmetric eigensolver on an explicit basis,
    /// they must equal `runaway_rates_at_rest`, the two largest real parts of
    /// the Jacobian of (3.4) near rest (finite differences, complex eigenvalues),
    /// and `rates`' choice of the slower; `fast_time` bounds the slower's time.
    #[test]
    fn eq_3_4_runaway_rates_are_the_notes_eigenvalues() {
        for (i, d) in [
            (Vec3::new(1.0, 2.0, 2.5), Vec3::new(1.0, 0.5, 0.2)),
            (Vec3::new(1.0, 1.5, 0.8), Vec3::new(0.2, 0.0, 1.0)),
            (Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0)),
            // An elongated top: its two runaway rates differ fivefold.
            (Vec3::new(1.0, 5.0, 5.5), Vec3::new(0.3, 1.0, 0.6)),
        ] {
            let top = GeneralTop::new(i, d).unwrap();
            let n = d.normalize();
            let e1 = n
                .cross(&Vec3::z())
                .try_normalize(1e-9)
                .unwrap_or_else(|| n.cross(&Vec3::x()).normalize());
            let e2 = n.cross(&e1);
            let basis = Matrix3x2::from_columns(&[e1, e2]);
            let i_inv = nalgebra::Matrix3::from_diagonal(&i.map(|x| 1.0 / x));
            let restricted: Matrix2<Real> = basis.transpose() * i_inv * basis;
            let mut notes: Vec<Real> = restricted
                .try_inverse()
                .unwrap()
                .symmetric_eigenvalues()
                .iter()
                .map(|l| l / d.norm_squared())
                .collect();
            notes.sort_by(Real::total_cmp);
            let ours = runaway_rates_at_rest(&top);
            for k in 0..2 {
                assert!(
                    (ours[k] - notes[k]).abs() < 1e-12 * notes[k],
                    "{ours:?} vs {notes:?}"
                );
            }
            let (fast, _) = rates(&top, &(Vec3::new(1.0, -0.5, 0.3) * 1e-4)).expect("finite");
            assert!(
                (fast - notes[0]).abs() < 1e-5 * notes[0],
                "{fast} vs the notes' {notes:?}"
            );
            assert!(
                1.0 / notes[0] <= fast_time(&top) * (1.0 + 1e-12),
                "tau_f bounds the runaway time"
            );
        }
    }
}
