//! What these tests pin down about the implicit method `Radau5` (Radau IIA of
//! order 5, Hairer & Wanner, *Solving ODEs II*, Sec. IV.8), always against
//! closed-form solutions:
//!
//! - the observed global order 5 of the fixed-step mode, and the local order 4
//!   of its continuous extension (the collocation polynomial, stage order 3);
//!   a wrong coefficient in T, T⁻¹, γ̂, α̂, β̂ or the nodes breaks one of these;
//! - the adaptive mode meets its tolerance against the closed form (4.15)–(4.16)
//!   of the reduced model, with the analytic Jacobian of (4.12)–(4.14) and with
//!   the default forward-difference one, and spends more work for tighter
//!   tolerances;
//! - L-stability at work: on `y' = λ(y − cos t) − sin t` with λ = −10⁶ it takes
//!   a few dozen steps, where Dormand–Prince needs about |λ|·T/3.3 (its
//!   stability interval on the negative real axis is [−3.3, 0]);
//! - backward stepping, landing on `t_stop`, the step budget, `reset`, refusal
//!   of bad options, and a blow-up reported at a finite time with a finite state;
//! - the bookkeeping: 3 evaluations per Newton iteration, one Jacobian per
//!   fixed step.

use spintop::integrate::{
    AdaptiveOptions, Dopri5, IntegrateError, Radau5, Rhs, Stepper, forward_difference_jacobian,
    solve,
};
use spintop::math::{Real, State, Vec3};
use spintop::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs, reduced_closed_form};
use spintop::stability::stiffness::ReducedAle;

type S1 = State<1>;
type S2 = State<2>;

// ---------------------------------------------------------------- problems

const OMEGA: Real = 3.0;
const DAMP: Real = 0.2;

/// A damped rotation with the rate ω(t) = ω (1 + ½ cos t), non-autonomous:
/// y = e^{−δt}(cos θ, sin θ), θ(t) = ω (t + ½ sin t).
fn rot_t(t: Real, y: &S2) -> S2 {
    let w = OMEGA * (1.0 + 0.5 * t.cos());
    S2::new(-DAMP * y[0] - w * y[1], w * y[0] - DAMP * y[1])
}
fn rot_t_exact(t: Real) -> S2 {
    let e = (-DAMP * t).exp();
    let theta = OMEGA * (t + 0.5 * t.sin());
    S2::new(e * theta.cos(), e * theta.sin())
}

/// y' = −2 t y², y(0) = 1: y = 1/(1 + t²).
fn nonaut(t: Real, y: &S1) -> S1 {
    S1::new(-2.0 * t * y[0] * y[0])
}
fn nonaut_exact(t: Real) -> S1 {
    S1::new(1.0 / (1.0 + t * t))
}

/// The stiff test problem y' = λ(y − cos t) − sin t: y = cos t + (y₀ − 1)e^{λt}.
struct Stiff {
    lambda: Real,
}
impl Rhs<1> for Stiff {
    fn eval(&self, t: Real, y: &S1) -> S1 {
        S1::new(self.lambda * (y[0] - t.cos()) - t.sin())
    }
    fn jacobian(&self, _t: Real, _y: &S1) -> nalgebra::SMatrix<Real, 1, 1> {
        nalgebra::SMatrix::<Real, 1, 1>::new(self.lambda)
    }
}
fn stiff_exact(lambda: Real, y0: Real, t: Real) -> Real {
    t.cos() + (y0 - 1.0) * (lambda * t).exp()
}

/// y' = y², y(0) = 1: y = 1/(1 − t), a pole at t = 1.
fn blowup(_t: Real, y: &S1) -> S1 {
    S1::new(y[0] * y[0])
}

/// The figure top and Ω₀ of the paper.
fn figure() -> (SymmetricTop, Vec3) {
    (SymmetricTop::figure(), Vec3::new(0.0, 0.1, 0.2))
}

// ---------------------------------------------------------------- helpers

/// Observed orders log₂(e_k / e_{k+1}) of errors measured at h, h/2, h/4, …
fn slopes(errs: &[Real]) -> Vec<Real> {
    errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The error at `t1` of `n` fixed Radau5 steps from the exact `y(0)`.
fn fixed_error<const N: usize, R: Rhs<N>>(
    rhs: &R,
    exact: fn(Real) -> State<N>,
    t1: Real,
    n: usize,
) -> Real {
    let mut s = Radau5::fixed(0.0, exact(0.0), t1 / n as Real).unwrap();
    while s.t() < t1 {
        s.step(rhs, t1).unwrap();
    }
    assert_eq!(s.stats().steps, n as u64);
    (s.y() - exact(t1)).amax()
}

fn opts(rtol: Real, atol: Real) -> AdaptiveOptions {
    AdaptiveOptions::new(rtol, atol).unwrap()
}

// ---------------------------------------------------------------- order

#[test]
fn radau5_fixed_step_global_order_is_5() {
    let ns = [8, 16, 32, 64];
    let errs: Vec<Real> = ns
        .iter()
        .map(|&n| fixed_error(&rot_t, rot_t_exact, 2.0, n))
        .collect();
    let s = slopes(&errs);
    eprintln!("rot_t errors {errs:?} slopes {s:?}");
    for (k, &p) in s.iter().enumerate().skip(1) {
        assert!(
            (4.7..=5.3).contains(&p),
            "observed order {p:.3} between n = {} and {} (errors {errs:?})",
            ns[k],
            ns[k + 1]
        );
    }
    let errs: Vec<Real> = ns
        .iter()
        .map(|&n| fixed_error(&nonaut, nonaut_exact, 3.0, n))
        .collect();
    let s = slopes(&errs);
    eprintln!("nonaut errors {errs:?} slopes {s:?}");
    let last = s[s.len() - 1];
    assert!(
        (4.7..=5.3).contains(&last),
        "observed order {last:.3} ({errs:?})"
    );
}

/// One fixed step from the exact state; the largest error of the collocation
/// polynomial at interior points. Stage order 3 gives a local error O(h⁴).
#[test]
fn radau5_collocation_polynomial_has_local_order_4() {
    let errs: Vec<Real> = [0.2, 0.1, 0.05, 0.025]
        .iter()
        .map(|&h| {
            let t0 = 0.3;
            let mut s = Radau5::fixed(t0, rot_t_exact(t0), h).unwrap();
            s.step(&rot_t, t0 + h).unwrap();
            (1..10)
                .map(|i| {
                    let t = t0 + h * i as Real / 10.0;
                    (s.dense(&rot_t, t) - rot_t_exact(t)).amax()
                })
                .fold(0.0, Real::max)
        })
        .collect();
    let s = slopes(&errs);
    eprintln!("dense errors {errs:?} slopes {s:?}");
    for &p in &s[1..] {
        assert!((3.7..=4.4).contains(&p), "dense order {p:.3} ({errs:?})");
    }
}

// ---------------------------------------------------------------- adaptive

/// Largest error of `solve` at `times` against the reduced closed form.
fn reduced_max_error<S: Stepper<3>, R: Rhs<3>>(
    stepper: &mut S,
    rhs: &R,
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
) -> Real {
    let ys = solve(stepper, rhs, times).unwrap();
    ys.iter()
        .zip(times)
        .map(|(y, &t)| (y - reduced_closed_form(top, omega0, t)).amax())
        .fold(0.0, Real::max)
}

/// RADAU5's tolerance transformation (`rtol' = 0.1·rtol^(2/3)`, with an
/// order-3 estimate of an order-5 method) makes the global error of the order
/// of rtol, growing like rtol^(5/6): the error should meet the tolerance within
/// a modest factor, and the factor should drift like rtol^(−1/6).
#[test]
fn radau5_meets_its_tolerance_against_the_reduced_closed_form_eq_4_15() {
    let (top, omega0) = figure();
    let times: Vec<Real> = (1..=200).map(|i| 5.0 * i as Real).collect();
    let scale = omega0.amax();
    let rtols = [1e-4, 1e-6, 1e-8];
    let mut last_steps = 0;
    let mut errs = Vec::new();
    for rtol in rtols {
        let mut s = Radau5::new(0.0, omega0, opts(rtol, rtol * scale)).unwrap();
        let err = reduced_max_error(&mut s, &ReducedAle(top), &top, &omega0, &times);
        eprintln!(
            "rtol {rtol:e}: err {err:e} ({:.2} tol), {:?}, jac {}, lu {}, newton {}",
            err / (rtol * scale),
            s.stats(),
            s.jacobian_evals(),
            s.lu_decompositions(),
            s.newton_iterations()
        );
        assert!(
            err <= 20.0 * rtol * scale,
            "rtol {rtol:e}: error {err:e} is more than 20× the tolerance"
        );
        assert!(
            s.stats().steps > last_steps,
            "tighter tolerance, more steps"
        );
        last_steps = s.stats().steps;
        errs.push(err);
    }
    let slope = (errs[0] / errs[2]).log10() / (rtols[0] / rtols[2]).log10();
    assert!(
        (0.75..=0.95).contains(&slope),
        "error ∝ rtol^{slope:.3}, expected ≈ rtol^(5/6) ({errs:?})"
    );
}

/// The closure has no Jacobian: the default forward differences stand in.
#[test]
fn radau5_with_forward_difference_jacobian_meets_the_same_tolerance() {
    let (top, omega0) = figure();
    let rhs = |_t: Real, y: &State<3>| reduced_ale_rhs(&top, y);
    let times: Vec<Real> = (1..=100).map(|i| 10.0 * i as Real).collect();
    let rtol = 1e-7;
    let mut s = Radau5::new(0.0, omega0, opts(rtol, rtol * 0.2)).unwrap();
    let err = reduced_max_error(&mut s, &rhs, &top, &omega0, &times);
    assert!(err <= 10.0 * rtol * 0.2, "error {err:e}");
    assert!(s.jacobian_evals() >= 1);
}

#[test]
fn default_jacobian_is_forward_differences_close_to_the_analytic_one() {
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let rhs = |_t: Real, y: &State<3>| reduced_ale_rhs(&top, y);
    for omega in [Vec3::new(0.0, 0.1, 0.2), Vec3::new(3.0, -20.0, 40.0)] {
        let analytic = ReducedAle(top).jacobian(0.0, &omega);
        let by_default = rhs.jacobian(0.0, &omega);
        let direct = forward_difference_jacobian(&rhs, 0.0, &omega);
        assert_eq!(by_default, direct);
        let tol = 1e-6 * analytic.amax();
        assert!(
            (by_default - analytic).amax() <= tol,
            "{by_default} vs {analytic}"
        );
    }
}

// ---------------------------------------------------------------- stiffness

#[test]
fn radau5_solves_a_stiff_linear_problem_in_few_steps_where_dopri5_needs_lambda_t_over_3_3() {
    let lambda = -1e6;
    let y0 = 2.0;
    let t1 = 1.0;
    let rhs = Stiff { lambda };
    let rtol = 1e-6;
    let mut r = Radau5::new(0.0, S1::new(y0), opts(rtol, rtol)).unwrap();
    // NOTE: compared at the step points. Between them the collocation
    // polynomial is only of order 3 and not error-controlled; the filtered
    // estimate lets the steps grow to ~1 here, and the polynomial's error
    // inside such a step is ~1e-4 (see the module doc of `radau5`).
    let mut err: Real = 0.0;
    while r.t() < t1 {
        r.step(&rhs, t1).unwrap();
        err = err.max((r.y()[0] - stiff_exact(lambda, y0, r.t())).abs());
    }
    eprintln!(
        "radau5 stiff: {:?} err {err:e} jac {} lu {}",
        r.stats(),
        r.jacobian_evals(),
        r.lu_decompositions()
    );
    assert!(err <= 10.0 * rtol, "error {err:e}");
    assert!(
        r.stats().steps <= 60,
        "Radau5 took {} steps",
        r.stats().steps
    );

    let mut d = Dopri5::new(0.0, S1::new(y0), opts(rtol, rtol)).unwrap();
    let yd = solve(&mut d, &rhs, &[t1]).unwrap();
    let predicted = lambda.abs() * t1 / 3.3;
    eprintln!("dopri5 stiff: {:?} predicted {predicted}", d.stats());
    assert!((yd[0][0] - stiff_exact(lambda, y0, t1)).abs() <= 10.0 * rtol);
    let steps = d.stats().steps as Real;
    assert!(
        (0.9 * predicted..=1.5 * predicted).contains(&steps),
        "DP5 took {steps} steps, stability predicts ≈ {predicted}"
    );
}

// ---------------------------------------------------------------- directions

#[test]
fn radau5_steps_backward_and_returns_to_the_start() {
    // Backward only: from the exact y(3) down to 0.
    let mut s = Radau5::new(3.0, nonaut_exact(3.0), opts(1e-9, 1e-12)).unwrap();
    let times = [2.0, 1.0, 0.5, 0.0];
    let ys = solve(&mut s, &nonaut, &times).unwrap();
    for (y, &t) in ys.iter().zip(&times) {
        assert!((y - nonaut_exact(t)).amax() < 1e-8, "t = {t}: {y} vs exact");
    }
    assert!(s.last_step() < 0.0);
    // Forward then back on the reduced model (backward it gains energy, briefly).
    let (top, omega0) = figure();
    let mut s = Radau5::new(0.0, omega0, opts(1e-10, 1e-12)).unwrap();
    let rhs = ReducedAle(top);
    let there = solve(&mut s, &rhs, &[50.0]).unwrap()[0];
    assert!((there - reduced_closed_form(&top, &omega0, 50.0)).amax() < 1e-9);
    let back = solve(&mut s, &rhs, &[0.0]).unwrap()[0];
    assert!((back - omega0).amax() < 1e-8, "back at {back}");
    assert_eq!(s.t(), 0.0);
}

#[test]
fn radau5_lands_on_t_stop_and_a_step_to_now_is_a_no_op() {
    for mut s in [
        Radau5::new(0.0, nonaut_exact(0.0), opts(1e-6, 1e-9)).unwrap(),
        Radau5::fixed(0.0, nonaut_exact(0.0), 0.3).unwrap(),
    ] {
        while s.t() < 1.0 {
            s.step(&nonaut, 1.0).unwrap();
        }
        assert_eq!(s.t(), 1.0);
        let before = s.stats();
        s.step(&nonaut, 1.0).unwrap();
        assert_eq!(s.stats(), before);
    }
}

// ---------------------------------------------------------------- failures

#[test]
fn radau5_refuses_bad_options() {
    let y0 = S1::new(1.0);
    for (rtol, atol) in [(0.0, 1e-9), (1.0, 1e-9), (Real::NAN, 1e-9), (1e-6, -1.0)] {
        let bad = AdaptiveOptions {
            rtol,
            atol,
            h_init: None,
            h_max: Real::INFINITY,
            max_steps: 100,
        };
        assert!(matches!(
            Radau5::new(0.0, y0, bad),
            Err(IntegrateError::InvalidOption(_))
        ));
    }
    let mut o = opts(1e-6, 1e-9);
    o.h_init = Some(-0.1);
    assert!(matches!(
        Radau5::new(0.0, y0, o),
        Err(IntegrateError::InvalidOption(_))
    ));
    let mut o = opts(1e-6, 1e-9);
    o.h_max = 0.0;
    assert!(matches!(
        Radau5::new(0.0, y0, o),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        Radau5::new(0.0, S1::new(Real::NAN), opts(1e-6, 1e-9)),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        Radau5::new(Real::INFINITY, y0, opts(1e-6, 1e-9)),
        Err(IntegrateError::InvalidOption(_))
    ));
    for h in [0.0, -0.1, Real::NAN, Real::INFINITY] {
        assert!(matches!(
            Radau5::fixed(0.0, y0, h),
            Err(IntegrateError::InvalidOption(_))
        ));
    }
    let mut s = Radau5::new(0.0, y0, opts(1e-6, 1e-9)).unwrap();
    assert!(matches!(
        s.step(&nonaut, Real::NAN),
        Err(IntegrateError::InvalidOption(_))
    ));
}

#[test]
fn radau5_reports_a_blow_up_at_a_finite_time_with_a_finite_state() {
    let rtol = 1e-6;
    let mut s = Radau5::new(0.0, S1::new(1.0), opts(rtol, 1e-9)).unwrap();
    let mut failure = None;
    while s.t() < 2.0 {
        if let Err(e) = s.step(&blowup, 2.0) {
            failure = Some(e);
            break;
        }
        // y = 1/(1 − t) > 0 before the pole: a step onto the other branch
        // (y < 0 beyond it) would be a silent wrong answer.
        assert!(
            s.y()[0].is_finite() && s.y()[0] > 0.0,
            "y = {} at t = {}",
            s.y()[0],
            s.t()
        );
    }
    let e = failure.expect("the pole at t = 1 must stop the run");
    eprintln!("blow-up: {e}");
    match e {
        // The numerical solution's pole sits within the tolerance of the true one.
        IntegrateError::StepSizeUnderflow { t, .. } | IntegrateError::NonFinite { t } => {
            assert!((t - 1.0).abs() <= rtol, "stopped at t = {t}")
        }
        other => panic!("unexpected {other}"),
    }
    assert!(s.y()[0].is_finite());
    // The fixed-step mode cannot shorten its step: a Newton failure is reported.
    let mut s = Radau5::fixed(0.0, S1::new(1.0), 0.3).unwrap();
    let mut last = Ok(());
    for _ in 0..10 {
        last = s.step(&blowup, 3.0);
        if last.is_err() {
            break;
        }
    }
    eprintln!("fixed blow-up: {last:?} at t = {}, y = {}", s.t(), s.y()[0]);
    assert!(
        matches!(
            last,
            Err(IntegrateError::NoConvergence { .. } | IntegrateError::NonFinite { .. })
        ),
        "{last:?}"
    );
    assert!(s.y()[0].is_finite());
}

#[test]
fn radau5_step_budget_ends_in_too_many_steps() {
    let (top, omega0) = figure();
    let mut s = Radau5::new(0.0, omega0, opts(1e-10, 1e-12))
        .unwrap()
        .with_max_steps(5);
    let e = solve(&mut s, &ReducedAle(top), &[1000.0]).unwrap_err();
    assert!(matches!(e, IntegrateError::TooManySteps { max_steps: 5, t } if t > 0.0 && t < 1000.0));
    let mut f = Radau5::fixed(0.0, omega0, 0.1).unwrap().with_max_steps(3);
    let e = solve(&mut f, &ReducedAle(top), &[1.0]).unwrap_err();
    assert!(matches!(
        e,
        IntegrateError::TooManySteps { max_steps: 3, .. }
    ));
    assert_eq!(f.stats().steps, 3);
}

#[test]
fn radau5_reset_restarts_from_the_new_state() {
    // Run to t = 1, replace the state by the exact one at t = 1 of another
    // start, and continue: the result is that start's solution.
    let mut s = Radau5::new(0.0, S2::new(0.5, 0.5), opts(1e-9, 1e-12)).unwrap();
    solve(&mut s, &rot_t, &[1.0]).unwrap();
    s.reset(rot_t_exact(1.0));
    assert_eq!(s.last_step(), 0.0);
    assert_eq!(s.dense(&rot_t, 0.5), rot_t_exact(1.0));
    let y = solve(&mut s, &rot_t, &[2.0]).unwrap()[0];
    assert!((y - rot_t_exact(2.0)).amax() < 1e-8);
}

// ---------------------------------------------------------------- counting

#[test]
fn radau5_counts_three_evaluations_per_newton_iteration_and_one_jacobian_per_fixed_step() {
    let mut s = Radau5::fixed(0.0, rot_t_exact(0.0), 0.1).unwrap();
    solve(&mut s, &rot_t, &[2.0]).unwrap();
    let st = s.stats();
    assert_eq!(st.steps, 20);
    assert_eq!(st.rejected, 0);
    assert_eq!(st.rhs_evals, 3 * s.newton_iterations());
    assert_eq!(s.jacobian_evals(), 20);
    assert_eq!(s.lu_decompositions(), 20);
    // Adaptive: f(t, y) once per step start, the initial guess, the Newton
    // iterations, and at most one second estimate per attempt.
    let (top, omega0) = figure();
    let mut a = Radau5::new(0.0, omega0, opts(1e-8, 1e-10)).unwrap();
    solve(&mut a, &ReducedAle(top), &[500.0]).unwrap();
    let st = a.stats();
    let base = 3 * a.newton_iterations() + st.steps + 1;
    assert!(st.rhs_evals >= base && st.rhs_evals <= base + st.steps + st.rejected + 1);
    assert!(a.jacobian_evals() >= 1 && a.jacobian_evals() <= st.steps + st.rejected + 1);
    assert!(a.lu_decompositions() >= a.jacobian_evals());
}
