//! What these tests pin down about the three integrators (`Rk4`, `Dopri5`,
//! `Dop853`), always against closed-form solutions, never against the code's own
//! earlier output:
//!
//! - the observed convergence orders: global order 4 / 5 / 8 of the raw steps
//!   (`step_once` at h, h/2, h/4, …), the local order of the embedded error
//!   estimates (h⁵ for Dormand–Prince, h⁸ for DOP853's combined estimate) and of
//!   the continuous extensions (local error h⁴ for RK4's cubic Hermite, h⁵ for
//!   Shampine's order-4 interpolant, h⁸ for DOP853's order-7 interpolant);
//!   a wrong coefficient anywhere in a tableau breaks one of these;
//! - that the adaptive methods, driven by `solve`, meet their tolerance within a
//!   modest factor and spend more work for tighter tolerances;
//! - backward integration (forward-then-back recovers y0; backward-only runs match
//!   the exact solution);
//! - failure reporting: a blow-up ends in `StepSizeUnderflow` / `NonFinite` at a
//!   finite time before the pole, never in a NaN sample; the step budget ends in
//!   `TooManySteps`; bad options give `InvalidOption`;
//! - the exact bookkeeping of right-hand-side evaluations (FSAL, `hinit`, lazy
//!   dense stages, `reset` dropping the cache);
//! - landing exactly on `t_stop`, and `step` to the current time being a no-op.
//!
//! Problems: `y' = −2 t y²` (y = 1/(1+t²), non-autonomous), a damped rotation in
//! the plane with constant rate (`y' = A y`, y = e^{−δt} R(ωt) y0) and with a
//! time-varying rate (non-autonomous, y = e^{−δt} R(θ(t)) y0), the logistic
//! equation (y = 1/(1 + 9e^{−t})), and `y' = y²` (y = 1/(1 − t), a pole at t = 1).

use spintop::integrate::{
    AdaptiveOptions, Dop853, Dopri5, IntegrateError, Rhs, Rk4, Stepper, solve,
};
use spintop::math::{Real, State};

type S1 = State<1>;
type S2 = State<2>;

// ---------------------------------------------------------------- problems

/// y' = −2 t y², y(0) = 1: y = 1/(1 + t²).
fn nonaut(t: Real, y: &S1) -> S1 {
    S1::new(-2.0 * t * y[0] * y[0])
}
fn nonaut_exact(t: Real) -> S1 {
    S1::new(1.0 / (1.0 + t * t))
}

const OMEGA: Real = 3.0;
const DAMP: Real = 0.2;

/// y' = A y with A = [[−δ, −ω], [ω, −δ]], y(0) = (1, 0): y = e^{−δt}(cos ωt, sin ωt).
fn rot(_t: Real, y: &S2) -> S2 {
    S2::new(-DAMP * y[0] - OMEGA * y[1], OMEGA * y[0] - DAMP * y[1])
}
fn rot_exact(t: Real) -> S2 {
    let e = (-DAMP * t).exp();
    S2::new(e * (OMEGA * t).cos(), e * (OMEGA * t).sin())
}

/// The same rotation with the rate ω(t) = ω (1 + ½ cos t):
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

/// y' = y (1 − y), y(0) = 0.1: y = 1/(1 + 9 e^{−t}).
fn logistic(_t: Real, y: &S1) -> S1 {
    S1::new(y[0] * (1.0 - y[0]))
}
fn logistic_exact(t: Real) -> S1 {
    S1::new(1.0 / (1.0 + 9.0 * (-t).exp()))
}

/// y' = y², y(0) = 1: y = 1/(1 − t), which blows up at t = 1.
fn blowup(_t: Real, y: &S1) -> S1 {
    S1::new(y[0] * y[0])
}

// ---------------------------------------------------------------- helpers

/// Observed orders log₂(e_k / e_{k+1}) of errors measured at h, h/2, h/4, …
fn slopes(errs: &[Real]) -> Vec<Real> {
    errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

fn assert_orders(what: &str, errs: &[Real], expected: Real, tol: Real) {
    let s = slopes(errs);
    // Shown with `cargo test -- --nocapture`.
    let shown: Vec<String> = errs.iter().map(|e| format!("{e:.2e}")).collect();
    eprintln!("{what}: errors {shown:?}, observed orders {s:.3?}");
    for (i, p) in s.iter().enumerate() {
        assert!(
            (p - expected).abs() <= tol,
            "{what}: observed order {p:.3} (pair {i}) is not {expected} ± {tol}; errors {errs:?}, orders {s:.3?}"
        );
    }
}

/// The error at `t1` of `n` raw steps of size `t1/n` from the exact `y(0)`.
fn global_error<const N: usize>(
    one_step: impl Fn(Real, &State<N>, Real) -> State<N>,
    exact: impl Fn(Real) -> State<N>,
    t1: Real,
    n: usize,
) -> Real {
    let h = t1 / n as Real;
    let mut y = exact(0.0);
    for i in 0..n {
        y = one_step(i as Real * h, &y, h);
    }
    (y - exact(t1)).amax()
}

/// Options that accept any reasonable step (for one-step dense-output tests).
fn loose(h: Real) -> AdaptiveOptions {
    let mut o = AdaptiveOptions::new(0.5, 1.0).unwrap();
    o.h_init = Some(h);
    o
}

/// Take exactly one step of size `h` from the exact state at `t0` and return
/// the largest error of the continuous extension at 9 interior points.
fn dense_error<const N: usize, S: Stepper<N>, R: Rhs<N>>(
    mut s: S,
    rhs: &R,
    exact: impl Fn(Real) -> State<N>,
    t0: Real,
    h: Real,
) -> Real {
    s.step(rhs, t0 + h).unwrap();
    assert_eq!(s.stats().steps, 1);
    assert_eq!(
        s.stats().rejected,
        0,
        "the dense test needs one accepted step"
    );
    assert_eq!(s.t(), t0 + h);
    (1..10)
        .map(|i| {
            let t = t0 + h * i as Real / 10.0;
            (s.dense(rhs, t) - exact(t)).amax()
        })
        .fold(0.0, Real::max)
}

fn tight(rtol: Real) -> AdaptiveOptions {
    AdaptiveOptions::new(rtol, 1e-14 * rtol).unwrap()
}

// ---------------------------------------------------------------- global orders

#[test]
fn rk4_global_order_is_4() {
    let step = |t, y: &S2, h| Rk4::<2>::step_once(&rot_t, t, y, h);
    let errs: Vec<Real> = [64, 128, 256, 512]
        .iter()
        .map(|&n| global_error(step, rot_t_exact, 4.0, n))
        .collect();
    assert_orders("RK4, time-varying rotation", &errs, 4.0, 0.3);
    let step = |t, y: &S1, h| Rk4::<1>::step_once(&nonaut, t, y, h);
    let errs: Vec<Real> = [20, 40, 80, 160]
        .iter()
        .map(|&n| global_error(step, nonaut_exact, 2.0, n))
        .collect();
    assert_orders("RK4, y' = -2ty²", &errs, 4.0, 0.3);
}

#[test]
fn dopri5_global_order_is_5() {
    let step = |t, y: &S2, h| Dopri5::<2>::step_once(&rot_t, t, y, h).0;
    let errs: Vec<Real> = [64, 128, 256, 512]
        .iter()
        .map(|&n| global_error(step, rot_t_exact, 4.0, n))
        .collect();
    assert_orders("DP5, time-varying rotation", &errs, 5.0, 0.3);
    let step = |t, y: &S1, h| Dopri5::<1>::step_once(&nonaut, t, y, h).0;
    let errs: Vec<Real> = [80, 160, 320]
        .iter()
        .map(|&n| global_error(step, nonaut_exact, 2.0, n))
        .collect();
    assert_orders("DP5, y' = -2ty²", &errs, 5.0, 0.3);
}

#[test]
fn dop853_global_order_is_8() {
    // Errors 3.5e-7 … 2e-14: above rounding, in the asymptotic regime.
    let step = |t, y: &S2, h| Dop853::<2>::step_once(&rot_t, t, y, h).0;
    let errs: Vec<Real> = [16, 32, 64, 128]
        .iter()
        .map(|&n| global_error(step, rot_t_exact, 4.0, n))
        .collect();
    assert_orders("DOP853, time-varying rotation", &errs, 8.0, 0.3);
    let step = |t, y: &S2, h| Dop853::<2>::step_once(&rot, t, y, h).0;
    let errs: Vec<Real> = [16, 32, 64]
        .iter()
        .map(|&n| global_error(step, rot_exact, 4.0, n))
        .collect();
    assert_orders("DOP853, constant rotation", &errs, 8.0, 0.3);
}

// ---------------------------------------------------------------- error estimates

#[test]
fn dopri5_error_estimate_is_y5_minus_y4_of_local_order_5() {
    let t0 = 0.5;
    let y0 = rot_t_exact(t0);
    let mut est = Vec::new();
    for h in [0.1, 0.05, 0.025, 0.0125] {
        let (y5, err) = Dopri5::<2>::step_once(&rot_t, t0, &y0, h);
        est.push(err.amax());
        // y5 is an order more accurate than y4 = y5 − err, so the estimate must
        // match the true local error of y4 (sign included) to leading order.
        let y4_err = (y5 - err) - rot_t_exact(t0 + h);
        let rel = (y4_err + err).amax() / err.amax();
        assert!(rel < 2.0 * h, "h = {h}: estimate off by a relative {rel}");
    }
    assert_orders("DP5 local error estimate", &est, 5.0, 0.3);
}

#[test]
fn dop853_error_estimate_is_local_order_8_and_conservative() {
    let t0 = 0.5;
    let y0 = rot_exact(t0);
    let mut est = Vec::new();
    for h in [0.1, 0.05, 0.025, 0.0125] {
        let (y8, err) = Dop853::<2>::step_once(&rot, t0, &y0, h);
        est.push(err.amax());
        let true_err = (y8 - rot_exact(t0 + h)).amax();
        if h >= 0.05 {
            // Below that the true local error is at rounding level.
            assert!(
                true_err <= err.amax(),
                "h = {h}: {true_err:e} > estimate {:e}",
                err.amax()
            );
        }
    }
    assert_orders("DOP853 combined error estimate", &est, 8.0, 0.3);
}

// ---------------------------------------------------------------- dense output

#[test]
fn rk4_hermite_dense_output_has_local_error_order_4() {
    let t0 = 0.3;
    let errs: Vec<Real> = [0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            dense_error(
                Rk4::new(t0, rot_exact(t0), h).unwrap(),
                &rot,
                rot_exact,
                t0,
                h,
            )
        })
        .collect();
    assert_orders("RK4 Hermite dense output", &errs, 4.0, 0.3);
}

#[test]
fn dopri5_dense_output_has_local_error_order_5() {
    // The interpolant has order 4, so its error inside one step is O(h⁵).
    let t0 = 0.3;
    let errs: Vec<Real> = [0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            dense_error(
                Dopri5::new(t0, rot_exact(t0), loose(h)).unwrap(),
                &rot,
                rot_exact,
                t0,
                h,
            )
        })
        .collect();
    assert_orders("DP5 dense output, rotation", &errs, 5.0, 0.3);
    let errs: Vec<Real> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&h| {
            let s = Dopri5::new(t0, nonaut_exact(t0), loose(h)).unwrap();
            dense_error(s, &nonaut, nonaut_exact, t0, h)
        })
        .collect();
    assert_orders("DP5 dense output, y' = -2ty²", &errs, 5.0, 0.3);
}

#[test]
fn dop853_dense_output_has_local_error_order_8() {
    // The interpolant has order 7, so its error inside one step is O(h⁸).
    let t0 = 0.3;
    let errs: Vec<Real> = [0.4, 0.2, 0.1, 0.05]
        .iter()
        .map(|&h| {
            dense_error(
                Dop853::new(t0, rot_exact(t0), loose(h)).unwrap(),
                &rot,
                rot_exact,
                t0,
                h,
            )
        })
        .collect();
    assert_orders("DOP853 dense output, rotation", &errs, 8.0, 0.3);
    let errs: Vec<Real> = [0.4, 0.2, 0.1]
        .iter()
        .map(|&h| {
            let s = Dop853::new(t0, rot_t_exact(t0), loose(h)).unwrap();
            dense_error(s, &rot_t, rot_t_exact, t0, h)
        })
        .collect();
    assert_orders(
        "DOP853 dense output, time-varying rotation",
        &errs,
        8.0,
        0.3,
    );
}

#[test]
fn dense_output_matches_the_step_end_points() {
    let h = 0.2;
    let mut a = Rk4::new(0.0, rot_exact(0.0), h).unwrap();
    let mut b = Dopri5::new(0.0, rot_exact(0.0), loose(h)).unwrap();
    let mut c = Dop853::new(0.0, rot_exact(0.0), loose(h)).unwrap();
    a.step(&rot, 1.0).unwrap();
    b.step(&rot, 1.0).unwrap();
    c.step(&rot, 1.0).unwrap();
    let y0 = rot_exact(0.0);
    for (name, d0, d1, y1) in [
        ("rk4", a.dense(&rot, 0.0), a.dense(&rot, 0.2), *a.y()),
        ("dp5", b.dense(&rot, 0.0), b.dense(&rot, 0.2), *b.y()),
        ("dop853", c.dense(&rot, 0.0), c.dense(&rot, 0.2), *c.y()),
    ] {
        assert!((d0 - y0).amax() < 1e-15, "{name}: dense(t_prev) != y_prev");
        assert!((d1 - y1).amax() < 1e-15, "{name}: dense(t) != y");
    }
}

// ---------------------------------------------------------------- adaptive accuracy

/// Largest error of `solve` at the output times, relative to the size of the
/// solution (max norm), and the work spent.
fn adaptive_run<const N: usize, S: Stepper<N>, R: Rhs<N>>(
    mut s: S,
    rhs: &R,
    exact: impl Fn(Real) -> State<N>,
    times: &[Real],
) -> (Real, u64) {
    let ys = solve(&mut s, rhs, times).unwrap();
    let err = times
        .iter()
        .zip(&ys)
        .map(|(&t, y)| (y - exact(t)).amax() / exact(t).amax())
        .fold(0.0, Real::max);
    (err, s.stats().rhs_evals)
}

#[test]
fn adaptive_methods_meet_the_tolerance_and_work_grows() {
    let times: Vec<Real> = (1..=16).map(|i| 0.5 * i as Real).collect();
    for method in ["dp5", "dop853"] {
        for (pname, is_rot) in [("time-varying rotation", true), ("logistic", false)] {
            let mut last_work = 0;
            for rtol in [1e-6, 1e-9, 1e-12] {
                let o = tight(rtol);
                let (err, work) = match (method, is_rot) {
                    ("dp5", true) => adaptive_run(
                        Dopri5::new(0.0, rot_t_exact(0.0), o).unwrap(),
                        &rot_t,
                        rot_t_exact,
                        &times,
                    ),
                    ("dp5", false) => adaptive_run(
                        Dopri5::new(0.0, logistic_exact(0.0), o).unwrap(),
                        &logistic,
                        logistic_exact,
                        &times,
                    ),
                    (_, true) => adaptive_run(
                        Dop853::new(0.0, rot_t_exact(0.0), o).unwrap(),
                        &rot_t,
                        rot_t_exact,
                        &times,
                    ),
                    (_, false) => adaptive_run(
                        Dop853::new(0.0, logistic_exact(0.0), o).unwrap(),
                        &logistic,
                        logistic_exact,
                        &times,
                    ),
                };
                eprintln!(
                    "{method} on {pname} at rtol {rtol:e}: error {err:.2e}, {work} evaluations"
                );
                assert!(
                    err <= 20.0 * rtol,
                    "{method} on {pname} at rtol {rtol:e}: relative error {err:e}"
                );
                assert!(
                    work > last_work,
                    "{method} on {pname}: work did not grow at rtol {rtol:e}"
                );
                last_work = work;
            }
        }
    }
}

#[test]
fn h_max_bounds_every_step() {
    let mut o = tight(1e-6);
    o.h_max = 0.01;
    let mut a = Dopri5::new(0.0, rot_exact(0.0), o).unwrap();
    let mut b = Dop853::new(0.0, rot_exact(0.0), o).unwrap();
    while a.t() < 1.0 {
        a.step(&rot, 1.0).unwrap();
        assert!(a.last_step().abs() <= 0.01 * (1.0 + 1e-12));
    }
    while b.t() < 1.0 {
        b.step(&rot, 1.0).unwrap();
        assert!(b.last_step().abs() <= 0.01 * (1.0 + 1e-12));
    }
    assert!(a.stats().steps >= 100 && b.stats().steps >= 100);
}

#[test]
fn no_step_growth_right_after_a_rejection() {
    // A first step of 2 time units at rtol 1e-10 must be rejected.
    let mut o = tight(1e-10);
    o.h_init = Some(2.0);
    let mut a = Dopri5::new(0.0, rot_exact(0.0), o).unwrap();
    a.step(&rot, 10.0).unwrap();
    assert!(a.stats().rejected > 0);
    assert!(a.next_step_size().unwrap() <= a.last_step().abs());
    let mut b = Dop853::new(0.0, rot_exact(0.0), o).unwrap();
    b.step(&rot, 10.0).unwrap();
    assert!(b.stats().rejected > 0);
    assert!(b.next_step_size().unwrap() <= b.last_step().abs());
}

#[test]
fn a_non_finite_attempt_is_a_rejection_with_a_cut_and_no_regrowth() {
    // y' = 1 (every Runge–Kutta method is exact, error estimate 0) until t = 0.5,
    // NaN after it. A first attempt of 1.0 sees NaN, is rejected and cut to 0.2;
    // the retry has zero error but must not grow the step right after a rejection.
    let rhs = |t: Real, _y: &S1| S1::new(if t > 0.5 { Real::NAN } else { 1.0 });
    let mut o = tight(1e-8);
    o.h_init = Some(1.0);
    let mut a = Dopri5::new(0.0, S1::new(0.0), o).unwrap();
    a.step(&rhs, 10.0).unwrap();
    assert_eq!((a.stats().steps, a.stats().rejected), (1, 1));
    assert_eq!(a.last_step(), 0.2);
    assert_eq!(a.next_step_size(), Some(0.2));
    assert!((a.y()[0] - 0.2).abs() < 1e-15);
    let mut b = Dop853::new(0.0, S1::new(0.0), o).unwrap();
    b.step(&rhs, 10.0).unwrap();
    assert_eq!((b.stats().steps, b.stats().rejected), (1, 1));
    assert_eq!(b.last_step(), 0.2);
    assert_eq!(b.next_step_size(), Some(0.2));
    assert!((b.y()[0] - 0.2).abs() < 1e-15);
}

// ---------------------------------------------------------------- backward

#[test]
fn forward_then_backward_recovers_the_initial_state() {
    let y0 = rot_t_exact(0.0);
    let rtol = 1e-10;
    let mut a = Dopri5::new(0.0, y0, tight(rtol)).unwrap();
    let mut b = Dop853::new(0.0, y0, tight(rtol)).unwrap();
    let mut c = Rk4::new(0.0, y0, 1e-3).unwrap();
    solve(&mut a, &rot_t, &[3.0]).unwrap();
    solve(&mut b, &rot_t, &[3.0]).unwrap();
    solve(&mut c, &rot_t, &[3.0]).unwrap();
    let back = [2.0, 1.0, 0.0];
    let ya = solve(&mut a, &rot_t, &back).unwrap();
    let yb = solve(&mut b, &rot_t, &back).unwrap();
    let yc = solve(&mut c, &rot_t, &back).unwrap();
    assert!(a.last_step() < 0.0 && b.last_step() < 0.0 && c.last_step() < 0.0);
    assert_eq!((a.t(), b.t(), c.t()), (0.0, 0.0, 0.0));
    assert!(
        (ya[2] - y0).amax() < 100.0 * rtol,
        "dp5: {:e}",
        (ya[2] - y0).amax()
    );
    assert!(
        (yb[2] - y0).amax() < 100.0 * rtol,
        "dop853: {:e}",
        (yb[2] - y0).amax()
    );
    // RK4, h = 1e-3 over 6 time units: global error ~ C h⁴ ≈ 1e-10.
    assert!((yc[2] - y0).amax() < 1e-8, "rk4: {:e}", (yc[2] - y0).amax());
    for (i, &t) in back.iter().enumerate() {
        let e = rot_t_exact(t);
        assert!((ya[i] - e).amax() < 100.0 * rtol);
        assert!((yb[i] - e).amax() < 100.0 * rtol);
        assert!((yc[i] - e).amax() < 1e-8);
    }
}

#[test]
fn backward_only_runs_match_the_exact_solution() {
    let t0 = 3.0;
    let times = [2.7, 2.0, 1.25, 0.5, 0.0];
    let rtol = 1e-9;
    let mut a = Dopri5::new(t0, nonaut_exact(t0), tight(rtol)).unwrap();
    let mut b = Dop853::new(t0, nonaut_exact(t0), tight(rtol)).unwrap();
    let mut c = Rk4::new(t0, nonaut_exact(t0), 0.01).unwrap();
    let ya = solve(&mut a, &nonaut, &times).unwrap();
    let yb = solve(&mut b, &nonaut, &times).unwrap();
    let yc = solve(&mut c, &nonaut, &times).unwrap();
    for (i, &t) in times.iter().enumerate() {
        let e = nonaut_exact(t)[0];
        assert!(
            (ya[i][0] - e).abs() < 100.0 * rtol * e,
            "dp5 at {t}: {} vs {e}",
            ya[i][0]
        );
        assert!(
            (yb[i][0] - e).abs() < 100.0 * rtol * e,
            "dop853 at {t}: {} vs {e}",
            yb[i][0]
        );
        assert!(
            (yc[i][0] - e).abs() < 1e-7,
            "rk4 at {t}: {} vs {e}",
            yc[i][0]
        );
    }
    assert_eq!(c.t(), 0.0);
}

// ---------------------------------------------------------------- failures

/// The numerical solution of `y' = y²` has its own pole at `1 + ε`, with `ε` of
/// the size of the accumulated error (measured: |ε| ≲ 1e-2·rtol); no adaptive
/// method can know the exact pole, so the failure must come within `rtol` of it.
fn assert_stopped_at_pole(
    name: &str,
    rtol: Real,
    r: Result<(), IntegrateError>,
    t_now: Real,
    y: &S1,
) {
    let t_fail = match r {
        Err(IntegrateError::StepSizeUnderflow { t, h }) => {
            assert!(h.is_finite() && h > 0.0, "{name}: h = {h}");
            t
        }
        Err(IntegrateError::NonFinite { t }) => t,
        other => panic!("{name}: expected a failure near t = 1, got {other:?}"),
    };
    assert_eq!(
        t_fail, t_now,
        "{name}: the error must carry the stepper's time"
    );
    assert!(
        t_fail > 0.9 && (t_fail - 1.0).abs() <= rtol,
        "{name} at rtol {rtol:e}: failure at t = {t_fail}"
    );
    assert!(
        y[0].is_finite() && y[0] > 1e6,
        "{name}: the stepper holds {y:?}"
    );
}

#[test]
fn adaptive_methods_stop_at_the_blow_up() {
    let y0 = S1::new(1.0);
    for rtol in [1e-3, 1e-6, 1e-9] {
        let mut a = Dopri5::new(0.0, y0, tight(rtol)).unwrap();
        let r = loop {
            match a.step(&blowup, 2.0) {
                Ok(()) => assert!(a.t() < 1.0 + rtol, "dp5 stepped to {}", a.t()),
                e => break e,
            }
        };
        assert_stopped_at_pole("dp5", rtol, r, a.t(), a.y());
        let mut b = Dop853::new(0.0, y0, tight(rtol)).unwrap();
        let r = loop {
            match b.step(&blowup, 2.0) {
                Ok(()) => assert!(b.t() < 1.0 + rtol, "dop853 stepped to {}", b.t()),
                e => break e,
            }
        };
        assert_stopped_at_pole("dop853", rtol, r, b.t(), b.y());
    }
}

#[test]
fn rk4_reports_non_finite_at_a_finite_time() {
    let mut s = Rk4::new(0.0, S1::new(1.0), 0.05).unwrap();
    let r = loop {
        match s.step(&blowup, 10.0) {
            Ok(()) => assert!(s.y()[0].is_finite()),
            e => break e,
        }
    };
    match r {
        Err(IntegrateError::NonFinite { t }) => {
            assert!(t.is_finite() && t > 0.9 && t < 10.0, "t = {t}");
            assert_eq!(t, s.t(), "t must be the time of the last finite state");
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert!(s.y()[0].is_finite());
}

#[test]
fn solve_never_returns_a_non_finite_state() {
    let times: Vec<Real> = (1..=20).map(|i| 0.1 * i as Real).collect();
    let y0 = S1::new(1.0);
    let r = solve(&mut Rk4::new(0.0, y0, 0.05).unwrap(), &blowup, &times);
    assert!(matches!(r, Err(IntegrateError::NonFinite { .. })), "{r:?}");
    let r = solve(
        &mut Dopri5::new(0.0, y0, tight(1e-8)).unwrap(),
        &blowup,
        &times,
    );
    assert!(r.is_err(), "{r:?}");
    let r = solve(
        &mut Dop853::new(0.0, y0, tight(1e-8)).unwrap(),
        &blowup,
        &times,
    );
    assert!(r.is_err(), "{r:?}");
    // Up to 0.95 the run is fine, finite and accurate.
    let ok: Vec<Real> = (1..=19).map(|i| 0.05 * i as Real).collect();
    for ys in [
        solve(
            &mut Dopri5::new(0.0, y0, tight(1e-8)).unwrap(),
            &blowup,
            &ok,
        )
        .unwrap(),
        solve(
            &mut Dop853::new(0.0, y0, tight(1e-8)).unwrap(),
            &blowup,
            &ok,
        )
        .unwrap(),
    ] {
        for (y, &t) in ys.iter().zip(&ok) {
            let e = 1.0 / (1.0 - t);
            assert!(
                y[0].is_finite() && (y[0] - e).abs() < 1e-5 * e,
                "at {t}: {} vs {e}",
                y[0]
            );
        }
    }
}

#[test]
fn step_budget_gives_too_many_steps() {
    let mut o = tight(1e-8);
    o.max_steps = 5;
    let mut a = Dopri5::new(0.0, rot_exact(0.0), o).unwrap();
    let r = solve(&mut a, &rot, &[10.0]);
    assert_eq!(
        r,
        Err(IntegrateError::TooManySteps {
            t: a.t(),
            max_steps: 5
        })
    );
    assert_eq!(a.stats().steps + a.stats().rejected, 5);
    let mut b = Dop853::new(0.0, rot_exact(0.0), o).unwrap();
    let r = solve(&mut b, &rot, &[100.0]);
    assert_eq!(
        r,
        Err(IntegrateError::TooManySteps {
            t: b.t(),
            max_steps: 5
        })
    );
    assert_eq!(b.stats().steps + b.stats().rejected, 5);
    let mut c = Rk4::new(0.0, rot_exact(0.0), 0.1)
        .unwrap()
        .with_max_steps(5);
    let r = solve(&mut c, &rot, &[1.0]);
    assert_eq!(
        r,
        Err(IntegrateError::TooManySteps {
            t: c.t(),
            max_steps: 5
        })
    );
    assert_eq!(c.stats().steps, 5);
    assert!((c.t() - 0.5).abs() < 1e-12);
}

#[test]
fn invalid_options_are_rejected() {
    let invalid =
        |r: Result<(), IntegrateError>| matches!(r, Err(IntegrateError::InvalidOption(_)));
    let y0 = S1::new(1.0);
    for rtol in [0.0, -1e-6, Real::NAN, Real::INFINITY, 1.0] {
        assert!(
            invalid(AdaptiveOptions::new(rtol, 1e-9).map(|_| ())),
            "rtol {rtol}"
        );
        // A hand-built struct is checked again by the constructors.
        let o = AdaptiveOptions {
            rtol,
            ..tight(1e-6)
        };
        assert!(
            invalid(Dopri5::new(0.0, y0, o).map(|_| ())),
            "dp5 rtol {rtol}"
        );
        assert!(
            invalid(Dop853::new(0.0, y0, o).map(|_| ())),
            "dop853 rtol {rtol}"
        );
    }
    for atol in [-1.0, Real::NAN, Real::INFINITY] {
        assert!(
            invalid(AdaptiveOptions::new(1e-6, atol).map(|_| ())),
            "atol {atol}"
        );
    }
    for h in [0.0, -0.1, Real::INFINITY, Real::NEG_INFINITY, Real::NAN] {
        assert!(invalid(Rk4::new(0.0, y0, h).map(|_| ())), "rk4 h {h}");
        let o = AdaptiveOptions {
            h_init: Some(h),
            ..tight(1e-6)
        };
        assert!(
            invalid(Dopri5::new(0.0, y0, o).map(|_| ())),
            "dp5 h_init {h}"
        );
        assert!(
            invalid(Dop853::new(0.0, y0, o).map(|_| ())),
            "dop853 h_init {h}"
        );
    }
    for h_max in [0.0, -1.0, Real::NAN] {
        let o = AdaptiveOptions {
            h_max,
            ..tight(1e-6)
        };
        assert!(
            invalid(Dopri5::new(0.0, y0, o).map(|_| ())),
            "h_max {h_max}"
        );
    }
    let nan = S1::new(Real::NAN);
    assert!(invalid(Rk4::new(0.0, nan, 0.1).map(|_| ())));
    assert!(invalid(Dopri5::new(0.0, nan, tight(1e-6)).map(|_| ())));
    assert!(invalid(Dop853::new(Real::NAN, y0, tight(1e-6)).map(|_| ())));
}

// ---------------------------------------------------------------- counting

#[test]
fn dopri5_counts_six_per_attempt_plus_start_plus_hinit() {
    // Guessed first step: 1 (f(t0, y0)) + 1 (hinit) + 6 per attempt; dense output is free.
    let times: Vec<Real> = (1..=40).map(|i| 0.25 * i as Real).collect();
    let mut a = Dopri5::new(0.0, rot_t_exact(0.0), tight(1e-9)).unwrap();
    solve(&mut a, &rot_t, &times).unwrap();
    let s = a.stats();
    assert!(s.steps > 10);
    assert_eq!(s.rhs_evals, 6 * (s.steps + s.rejected) + 2);
    // Given first step (too long, so there are rejections): no hinit evaluation.
    let mut o = tight(1e-9);
    o.h_init = Some(3.0);
    let mut b = Dopri5::new(0.0, rot_t_exact(0.0), o).unwrap();
    solve(&mut b, &rot_t, &times).unwrap();
    let s = b.stats();
    assert!(s.rejected > 0);
    assert_eq!(s.rhs_evals, 6 * (s.steps + s.rejected) + 1);
}

#[test]
fn dop853_counts_twelve_per_attempt_and_three_per_dense_step() {
    let mut o = tight(1e-9);
    o.h_init = Some(3.0);
    let mut a = Dop853::new(0.0, rot_t_exact(0.0), o).unwrap();
    for _ in 0..5 {
        a.step(&rot_t, 10.0).unwrap();
    }
    let s = a.stats();
    assert!(s.rejected > 0);
    assert_eq!(s.rhs_evals, 12 * (s.steps + s.rejected) + 1);
    // Dense output inside the last step: 3 extra evaluations, once.
    let (t0, t1) = (a.t_prev(), a.t());
    let before = a.stats().rhs_evals;
    let mid = a.dense(&rot_t, 0.5 * (t0 + t1));
    assert_eq!(a.stats().rhs_evals, before + 3);
    a.dense(&rot_t, 0.25 * t0 + 0.75 * t1);
    assert_eq!(a.stats().rhs_evals, before + 3);
    assert!((mid - rot_t_exact(0.5 * (t0 + t1))).amax() < 1e-7);
    // Through `solve`, with hinit: 1 + 1 + 12 per attempt + 3 per step that
    // contained an output time (output every 0.25, steps are longer here).
    let times: Vec<Real> = (1..=40).map(|i| 0.25 * i as Real).collect();
    let mut b = Dop853::new(0.0, rot_t_exact(0.0), tight(1e-6)).unwrap();
    let mut dense_steps = 0;
    let mut last_dense_in: Option<u64> = None;
    // The loop of `solve`, counting the accepted steps that served an output time.
    for &t in &times {
        while b.t() < t {
            b.step(&rot_t, 10.0).unwrap();
        }
        if t != b.t() {
            b.dense(&rot_t, t);
            if last_dense_in != Some(b.stats().steps) {
                dense_steps += 1;
                last_dense_in = Some(b.stats().steps);
            }
        }
    }
    let s = b.stats();
    assert!(dense_steps > 0);
    assert_eq!(
        s.rhs_evals,
        12 * (s.steps + s.rejected) + 2 + 3 * dense_steps
    );
}

#[test]
fn rk4_counts_four_per_step_and_reuses_the_end_slope() {
    let mut a = Rk4::new(0.0, rot_exact(0.0), 0.1).unwrap();
    solve(&mut a, &rot, &[0.35, 0.75, 1.0]).unwrap();
    // 10 steps; each dense call evaluates f at the step end, which the next step reuses.
    let s = a.stats();
    assert_eq!((s.steps, s.rejected), (10, 0));
    assert_eq!(s.rhs_evals, 40);
    // A dense call inside the final step adds the one evaluation no step reuses.
    a.dense(&rot, 0.95);
    assert_eq!(a.stats().rhs_evals, 41);
    a.dense(&rot, 0.92);
    assert_eq!(a.stats().rhs_evals, 41);
}

#[test]
fn reset_drops_the_cached_first_stage() {
    // DP5: a step costs 6 with the FSAL stage, 7 after reset.
    let mut a = Dopri5::new(0.0, rot_exact(0.0), tight(1e-8)).unwrap();
    a.step(&rot, 10.0).unwrap();
    let e0 = a.stats().rhs_evals;
    a.step(&rot, 10.0).unwrap();
    let e1 = a.stats().rhs_evals;
    assert_eq!(e1 - e0, 6 * (1 + a.stats().rejected));
    let y = *a.y();
    let r0 = a.stats().rejected;
    a.reset(y);
    assert_eq!((a.t_prev(), a.last_step()), (a.t(), 0.0));
    assert_eq!(a.dense(&rot, a.t()), y);
    a.step(&rot, 10.0).unwrap();
    assert_eq!(
        a.stats().rhs_evals - e1,
        1 + 6 * (1 + a.stats().rejected - r0)
    );
    // DOP853: 12 vs 13.
    let mut b = Dop853::new(0.0, rot_exact(0.0), tight(1e-8)).unwrap();
    b.step(&rot, 10.0).unwrap();
    let y = *b.y();
    let (e, r) = (b.stats().rhs_evals, b.stats().rejected);
    b.reset(y);
    b.step(&rot, 10.0).unwrap();
    assert_eq!(
        b.stats().rhs_evals - e,
        1 + 12 * (1 + b.stats().rejected - r)
    );
    // RK4: the end slope cached by `dense` makes the next step cost 3; after
    // reset it costs 4 again.
    let mut c = Rk4::new(0.0, rot_exact(0.0), 0.1).unwrap();
    c.step(&rot, 1.0).unwrap();
    c.dense(&rot, 0.05);
    let e = c.stats().rhs_evals;
    c.step(&rot, 1.0).unwrap();
    assert_eq!(c.stats().rhs_evals - e, 3);
    c.dense(&rot, 0.15);
    let y = *c.y();
    c.reset(y);
    let e = c.stats().rhs_evals;
    c.step(&rot, 1.0).unwrap();
    assert_eq!(c.stats().rhs_evals - e, 4);
    // Reset to a different state really restarts from it (same time).
    let mut d = Dopri5::new(0.0, S2::new(5.0, 5.0), tight(1e-10)).unwrap();
    while d.t() != 0.1 {
        d.step(&rot, 0.1).unwrap();
    }
    d.reset(rot_exact(0.1));
    let ys = solve(&mut d, &rot, &[1.0]).unwrap();
    // rot_exact(0.1) evolved by the linear flow for 0.9 equals rot_exact(1.0).
    assert!((ys[0] - rot_exact(1.0)).amax() < 1e-8);
}

// ---------------------------------------------------------------- landing on t_stop

#[test]
fn steps_land_exactly_on_t_stop_and_never_past_it() {
    for t_stop in [1.0, 0.3, -0.7, 2.0_f64.sqrt()] {
        let dir = t_stop.signum();
        let mut a = Dopri5::new(0.0, rot_exact(0.0), tight(1e-7)).unwrap();
        let mut b = Dop853::new(0.0, rot_exact(0.0), tight(1e-7)).unwrap();
        let mut c = Rk4::new(0.0, rot_exact(0.0), 0.1).unwrap();
        while a.t() != t_stop {
            a.step(&rot, t_stop).unwrap();
            assert!(dir * (a.t() - t_stop) <= 0.0);
        }
        while b.t() != t_stop {
            b.step(&rot, t_stop).unwrap();
            assert!(dir * (b.t() - t_stop) <= 0.0);
        }
        while c.t() != t_stop {
            c.step(&rot, t_stop).unwrap();
            assert!(dir * (c.t() - t_stop) <= 0.0);
        }
        assert!((c.y() - rot_exact(t_stop)).amax() < 1e-3);
    }
    // RK4 with h = 0.1 reaches 1.0 in exactly 10 steps (no rounding sliver).
    let mut c = Rk4::new(0.0, rot_exact(0.0), 0.1).unwrap();
    while c.t() != 1.0 {
        c.step(&rot, 1.0).unwrap();
    }
    assert_eq!(c.stats().steps, 10);
}

#[test]
fn step_to_the_current_time_is_a_no_op() {
    let y0 = rot_exact(0.0);
    let mut a = Dopri5::new(0.0, y0, tight(1e-7)).unwrap();
    let mut b = Dop853::new(0.0, y0, tight(1e-7)).unwrap();
    let mut c = Rk4::new(0.0, y0, 0.1).unwrap();
    a.step(&rot, 0.0).unwrap();
    b.step(&rot, 0.0).unwrap();
    c.step(&rot, 0.0).unwrap();
    assert_eq!((a.stats(), a.t(), *a.y()), (Default::default(), 0.0, y0));
    assert_eq!((b.stats(), b.t(), *b.y()), (Default::default(), 0.0, y0));
    assert_eq!((c.stats(), c.t(), *c.y()), (Default::default(), 0.0, y0));
    a.step(&rot, 1.0).unwrap();
    let (s, t, y) = (a.stats(), a.t(), *a.y());
    a.step(&rot, t).unwrap();
    assert_eq!((a.stats(), a.t(), *a.y()), (s, t, y));
    // Nothing before the first step: dense output is the state itself.
    assert_eq!(b.dense(&rot, 0.5), y0);
}
