//! What these tests pin down about the Taylor method (`integrate::taylor`),
//! always against something it does not compute itself:
//!
//! - the recurrences: order 0 of every model's series is its right-hand side
//!   as the physics functions evaluate it, and order 1 is ½ J f (central
//!   differences of those functions); `y' = y²` gives the coefficients of
//!   1/(1 − t), all equal to 1;
//! - the observed order: with the order p fixed and the step capped at H,
//!   halving H divides the global error by 2ᵖ;
//! - accuracy: Ω of the truncated, reduced and general problems (200 points,
//!   T = 200τ, read from the dense output) and the orientation quaternion
//!   against the 40-digit mpmath references, within a few ulps at rtol 1e-15;
//!   the symmetric models against their closed forms (4.7) and (4.15)–(4.16)
//!   over T = 10⁴;
//! - the balance laws along a run of the general top: E changes only by the
//!   power of the radiation torque and |L|² only by 2 L·T, both integrated by
//!   Gauss–Legendre along the dense output;
//! - a top so fast that its coefficients overflow a double unscaled
//!   (|Ω₀| = 10¹⁰ and 10⁵⁰): against (4.7) and against DOP853;
//! - Jorba & Zou's order, the step-size rule (no rejections, fewer steps than
//!   DOP853 at tight tolerances), the cost bookkeeping, backward runs, and
//!   failures: a pole ends in a step-size underflow before it, the step
//!   budget in `TooManySteps`, bad options in `InvalidOption`.

use spintop::integrate::taylor::{
    GeneralReduced, GeneralTruncated, MAX_ORDER, Series, SymmetricReduced, SymmetricTruncated,
    Taylor, TaylorRhs, WithOrientation, cauchy, taylor_order,
};
use spintop::integrate::{AdaptiveOptions, Dop853, IntegrateError, Rhs, Stepper, solve};
use spintop::math::{Mat3, Quat, Real, State, Vec3};
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::{SymmetricTop, reduced_closed_form, truncated_closed_form};
use spintop::workprecision::{OmegaRhs, Problem, ProblemKind, omega_error, rotation_angle};

fn opts(rtol: Real, atol: Real) -> AdaptiveOptions {
    AdaptiveOptions::new(rtol, atol).unwrap()
}

fn general_top() -> GeneralTop {
    GeneralTop::new(Vec3::new(1.0, 1.5, 0.8), Vec3::new(0.2, 0.0, 1.0)).unwrap()
}

/// The normalized Taylor coefficients of orders 0..=2 of `system` at `y0`,
/// from the stepper's own jet after one step.
fn jet_at<S: TaylorRhs<3> + Rhs<3> + Clone>(system: &S, y0: Vec3) -> [Vec3; 3] {
    let mut t = Taylor::new(system.clone(), 0.0, y0, opts(1e-10, 1e-20)).unwrap();
    t.step(system, 1e-3).unwrap();
    let c = t.coefficients();
    [0, 1, 2].map(|k| Vec3::new(c[0][k], c[1][k], c[2][k]))
}

/// Order 0 of the series is y0, order 1 is f(y0) and order 2 is ½ J(y0) f(y0),
/// for every model, at several states (J f by central differences of the
/// physics functions along f).
#[test]
fn recurrences_of_every_model_start_with_f_and_half_j_f() {
    let sym = SymmetricTop::new(0.4, 1.0).unwrap();
    let skew = SymmetricTop::new(1.7, 0.3).unwrap();
    let states = [
        Vec3::new(0.0, 0.1, 0.2),
        Vec3::new(-0.7, 0.4, 1.3),
        Vec3::new(0.3, -0.2, -0.5),
    ];
    fn check<S: TaylorRhs<3> + Rhs<3> + Clone + std::fmt::Debug>(system: S, y0: Vec3) {
        let [c0, c1, c2] = jet_at(&system, y0);
        let f = |y: &Vec3| system.eval(0.0, y);
        let f0 = f(&y0);
        let scale = f0.norm().max(1e-300);
        assert_eq!(c0, y0);
        assert!(
            (c1 - f0).norm() <= 1e-14 * scale,
            "{system:?} {y0}: {c1} vs {f0}"
        );
        let delta = 1e-5 / f0.norm().max(1e-3);
        let jf = (f(&(y0 + f0 * delta)) - f(&(y0 - f0 * delta))) / (2.0 * delta);
        let want = 0.5 * jf;
        assert!(
            (c2 - want).norm() <= 1e-8 * want.norm().max(scale * scale),
            "{system:?} {y0}: {c2} vs {want}"
        );
    }
    for y0 in states {
        check(SymmetricTruncated(sym), y0);
        check(SymmetricTruncated(skew), y0);
        check(SymmetricReduced(sym), y0);
        check(SymmetricReduced(skew), y0);
        check(GeneralTruncated(general_top()), y0);
        check(GeneralReduced(general_top()), y0);
    }
}

/// `y' = y²`, y(0) = 1: y = 1/(1 − t) = Σ tᵏ, every coefficient 1; a pole at t = 1.
#[derive(Clone, Copy, Debug)]
struct Riccati;

impl TaylorRhs<1> for Riccati {
    type Aux = ();
    fn aux(&self) {}
    fn coefficient(&self, _: &mut (), y: &[Series], k: usize) -> [Real; 1] {
        [cauchy(&y[0], &y[0], k)]
    }
}

impl Rhs<1> for Riccati {
    fn eval(&self, _t: Real, y: &State<1>) -> State<1> {
        State::<1>::new(y[0] * y[0])
    }
}

#[test]
fn riccati_series_has_every_coefficient_one_and_its_pole_stops_the_run() {
    let mut t = Taylor::new(Riccati, 0.0, State::<1>::new(1.0), opts(1e-14, 0.0)).unwrap();
    t.step(&Riccati, 1e-6).unwrap();
    let c = &t.coefficients()[0];
    for (k, &ck) in c[..=t.order()].iter().enumerate() {
        assert!(
            (ck - 1.0).abs() < 1e-15 * (k as Real + 1.0),
            "order {k}: {ck}"
        );
    }
    // Up to the pole the answer is right; the pole itself is reported, with
    // the time, as a step size the time axis cannot resolve: no NaN, no hang.
    let mut t = Taylor::new(Riccati, 0.0, State::<1>::new(1.0), opts(1e-12, 0.0)).unwrap();
    let y = solve(&mut t, &Riccati, &[0.5, 0.9, 0.99]).unwrap();
    for (y, x) in y.iter().zip([0.5, 0.9, 0.99]) {
        let exact = 1.0 / (1.0 - x);
        assert!((y[0] - exact).abs() < 1e-10 * exact, "{x}: {}", y[0]);
    }
    let err = solve(&mut t, &Riccati, &[2.0]).unwrap_err();
    match err {
        IntegrateError::StepSizeUnderflow { t, .. } | IntegrateError::NonFinite { t } => {
            // The pole of the computed solution is within rounding of 1.
            assert!(t > 0.99 && t < 1.0 + 1e-12, "{t}")
        }
        other => panic!("{other:?}"),
    }
    assert!(t.y()[0].is_finite());
}

#[test]
fn order_follows_jorba_and_zou() {
    assert_eq!(taylor_order(1e-8), 11);
    assert_eq!(taylor_order(1e-14), 18);
    assert_eq!(taylor_order(1e-15), 19);
    assert_eq!(taylor_order(0.5), 2);
    assert_eq!(taylor_order(1e-300), MAX_ORDER);
    for p in 2..=MAX_ORDER {
        // The tolerance at which ⌈−½ ln ε + 1⌉ = p: ε = e^{−2(p − 1.5)}.
        let eps = (-2.0 * (p as Real - 1.5)).exp();
        assert_eq!(taylor_order(eps), p);
    }
}

/// The stability interval of the order-p series on the negative real axis:
/// |T_p(−x)| ≤ 1 just inside it and > 1 just outside (T_p summed here term
/// by term, not by the library's Horner loop), 5.45 at order 11 and 8.07
/// at order 18 (a scan in steps of 1e-3, documented in the function).
#[test]
fn stability_interval_is_where_the_series_stops_damping_a_decay() {
    use spintop::integrate::taylor::stability_interval;
    let t_p = |p: usize, x: Real| {
        let mut term = 1.0;
        let mut sum = 1.0;
        for k in 1..=p {
            term *= -x / k as Real;
            sum += term;
        }
        sum
    };
    for (rtol, near) in [(1e-8, 5.45), (1e-14, 8.07)] {
        let p = taylor_order(rtol);
        let x = stability_interval(rtol);
        assert!((x - near).abs() < 0.01, "{rtol:e}: {x}");
        assert!((1..=1000).all(|j| t_p(p, x * j as Real / 1000.0).abs() <= 1.0 + 1e-12));
        assert!(t_p(p, x * 1.001).abs() > 1.0, "{rtol:e}");
    }
}

/// On a stiff reduced top (stability row 3's: Ω₀ = (0, 100, 200)/τ, so Ω⊥
/// decays at τk² = 6400/τ) the Taylor method's steps settle at its
/// stability interval, as DOP853's do at the edge of its region: over
/// t = 10 it takes about 10·6400/5.45 steps at rtol 1e-8, within 25 % of the
/// cost estimate that refuses a stiff run before it starts, and within a
/// factor 1.5 of DOP853's.
#[test]
fn a_stiff_top_holds_the_step_at_the_stability_interval() {
    use spintop::sim::cost::estimate;
    use spintop::sim::{InitialState, Method, MethodOptions, Model, Simulation};
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 100.0, 200.0);
    let initial = InitialState {
        omega: omega0,
        rotation: Mat3::identity(),
    };
    let options = MethodOptions::default().with_rtol(1e-8).unwrap();
    let model = Model::Reduced(top);
    let times: Vec<Real> = (1..=10).map(Real::from).collect();
    let steps = |method: Method| {
        let mut sim = Simulation::with_method(model, method, options, initial, Some(10.0)).unwrap();
        sim.run(&times).unwrap();
        sim.stats().steps as Real
    };
    let (taylor, dop853) = (steps(Method::Taylor), steps(Method::Dop853));
    let e = estimate(&model, Method::Taylor, &options, &omega0, 10.0).unwrap();
    assert!(e.what.contains("stiff"), "{e:?}");
    assert!(
        (e.steps / (10.0 * 6400.0 / 5.45) - 1.0).abs() < 1e-3,
        "{e:?}"
    );
    assert!(
        (taylor / e.steps - 1.0).abs() < 0.25,
        "{taylor} against {e:?}"
    );
    assert!(
        taylor < 1.5 * dop853 && dop853 < 1.5 * taylor,
        "{taylor} {dop853}"
    );
}

/// With the order fixed by the tolerance and the step capped well below the
/// series' own, halving the cap divides the error at T = 20 by 2ᵖ (the
/// reduced model against its closed form (4.15)–(4.16)).
#[test]
fn observed_order_equals_the_order_of_the_series() {
    let top = SymmetricTop::figure();
    let system = SymmetricReduced(top);
    let y0 = Vec3::new(0.3, 0.4, 2.0);
    let exact = reduced_closed_form(&top, &y0, 20.0);
    for p in [3usize, 4, 5, 6] {
        let eps = (-2.0 * (p as Real - 1.5)).exp();
        let error = |h_max: Real| {
            let mut o = opts(eps, 0.0);
            o.h_max = h_max;
            let mut t = Taylor::new(system, 0.0, y0, o).unwrap();
            assert_eq!(t.order(), p);
            let y = solve(&mut t, &system, &[20.0]).unwrap()[0];
            (y - exact).norm() / exact.norm()
        };
        let (e1, e2) = (error(0.05), error(0.025));
        let observed = (e1 / e2).log2();
        assert!(
            (observed - p as Real).abs() < 0.3,
            "p = {p}: errors {e1:e}, {e2:e}, observed order {observed}"
        );
    }
}

/// Ω of each problem from the model's series.
fn taylor_omega(problem: &Problem, rtol: Real) -> (Vec<Vec3>, u64) {
    let y0 = problem.initial().omega;
    let o = opts(rtol, problem.atol(rtol));
    fn run<S: TaylorRhs<3> + Rhs<3> + Copy>(
        s: S,
        y0: Vec3,
        o: AdaptiveOptions,
        times: &[Real],
    ) -> (Vec<Vec3>, u64) {
        let mut t = Taylor::new(s, 0.0, y0, o).unwrap();
        let out = solve(&mut t, &s, times).unwrap();
        (out, t.stats().steps)
    }
    match problem.omega_rhs().unwrap() {
        OmegaRhs::Truncated(top) => run(SymmetricTruncated(top), y0, o, problem.times()),
        OmegaRhs::Reduced(top) => run(SymmetricReduced(top), y0, o, problem.times()),
        OmegaRhs::General(top) => run(GeneralTruncated(top), y0, o, problem.times()),
    }
}

/// At rtol 1e-15 Ω is within 2e-15 of the 40-digit references at all 200
/// points (most of them read from the step polynomials), and the error falls
/// with the tolerance.
#[test]
fn eq_3_3_eq_4_2_eq_4_12_omega_matches_the_40_digit_references_to_the_last_digits() {
    for kind in [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ] {
        let problem = Problem::new(kind).unwrap();
        let reference = &problem.reference().omega;
        let errors: Vec<Real> = [1e-6, 1e-10, 1e-15]
            .iter()
            .map(|&rtol| omega_error(reference, &taylor_omega(&problem, rtol).0))
            .collect();
        assert!(errors[2] < 2e-15, "{kind:?}: {errors:?}");
        assert!(
            errors[1] < 1e-10 && errors[0] < 1e-6,
            "{kind:?}: {errors:?}"
        );
        assert!(
            errors[0] > errors[1] && errors[1] > errors[2],
            "{kind:?}: {errors:?}"
        );
    }
}

/// Ω and the orientation quaternion together (7 components) against the
/// references' orientation, within 1e-14 rad over T = 200 (and Ω within
/// 3e-15: the quaternion's block makes the steps a little shorter, so a few
/// more roundings add up).
#[test]
fn eq_3_3_eq_4_2_eq_4_12_orientation_quaternion_matches_the_40_digit_references() {
    for kind in [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ] {
        let problem = Problem::new(kind).unwrap();
        let y0 = problem.initial().omega;
        let mut s0 = State::<7>::zeros();
        s0.fixed_rows_mut::<3>(0).copy_from(&y0);
        s0[3] = 1.0;
        let o = opts(1e-15, problem.atol(1e-15));
        fn run<M: TaylorRhs<3> + Rhs<3> + Copy>(
            m: M,
            s0: State<7>,
            o: AdaptiveOptions,
            times: &[Real],
        ) -> Vec<State<7>> {
            let system = WithOrientation(m);
            let mut t = Taylor::new(system, 0.0, s0, o).unwrap();
            solve(&mut t, &system, times).unwrap()
        }
        let states = match problem.omega_rhs().unwrap() {
            OmegaRhs::Truncated(top) => run(SymmetricTruncated(top), s0, o, problem.times()),
            OmegaRhs::Reduced(top) => run(SymmetricReduced(top), s0, o, problem.times()),
            OmegaRhs::General(top) => run(GeneralTruncated(top), s0, o, problem.times()),
        };
        let reference = problem.reference().rotation.as_ref().unwrap();
        let worst = states
            .iter()
            .zip(reference)
            .map(|(s, r)| {
                let q = Quat::from_quaternion(nalgebra::Quaternion::new(s[3], s[4], s[5], s[6]));
                let m: Mat3 = q.to_rotation_matrix().into_inner();
                rotation_angle(r, &m)
            })
            .fold(0.0, Real::max);
        assert!(worst < 1e-14, "{kind:?}: {worst:e}");
        let omega: Vec<Vec3> = states.iter().map(|s| Vec3::new(s[0], s[1], s[2])).collect();
        let e = omega_error(&problem.reference().omega, &omega);
        assert!(e < 3e-15, "{kind:?} {e:e}");
    }
}

/// The symmetric models over T = 10⁴ (about 1200 rad of body-frame
/// precession for the reduced top) against (4.7) and (4.15)–(4.16), at 100
/// points: the error stays within 1e-12, most of it the rounding of the
/// closed forms' own phase (ε times about 10³ rad).
#[test]
fn eq_4_7_and_eq_4_16_closed_forms_hold_over_t_1e4() {
    let top = SymmetricTop::figure();
    let y0 = Vec3::new(0.05, 0.1, 0.2);
    let times: Vec<Real> = (1..=100).map(|i| 100.0 * i as Real).collect();
    let o = opts(1e-15, 1e-22);
    let mut t = Taylor::new(SymmetricTruncated(top), 0.0, y0, o).unwrap();
    let got = solve(&mut t, &SymmetricTruncated(top), &times).unwrap();
    let want: Vec<Vec3> = times
        .iter()
        .map(|&x| truncated_closed_form(&top, &y0, x))
        .collect();
    let e_truncated = omega_error(&want, &got);
    let mut t = Taylor::new(SymmetricReduced(top), 0.0, y0, o).unwrap();
    let got = solve(&mut t, &SymmetricReduced(top), &times).unwrap();
    let want: Vec<Vec3> = times
        .iter()
        .map(|&x| reduced_closed_form(&top, &y0, x))
        .collect();
    let e_reduced = omega_error(&want, &got);
    assert!(
        e_truncated < 1e-12 && e_reduced < 1e-12,
        "{e_truncated:e} {e_reduced:e}"
    );
}

/// Nodes and weights of 5-point Gauss–Legendre on [−1, 1].
const GAUSS: [(Real, Real); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
];

/// Run `system` to `t_end`, step by step, and integrate `rate(Ω)` along the
/// dense output of every step (Gauss–Legendre in 4 pieces per step).
fn integrate_along<S: TaylorRhs<3> + Rhs<3> + Copy>(
    system: S,
    y0: Vec3,
    t_end: Real,
    rate: impl Fn(&Vec3) -> Real,
) -> (Vec3, Real) {
    let mut t = Taylor::new(system, 0.0, y0, opts(1e-15, 1e-22)).unwrap();
    let mut integral = 0.0;
    while t.t() < t_end {
        t.step(&system, t_end).unwrap();
        let (a, b) = (t.t_prev(), t.t());
        for piece in 0..4 {
            let lo = a + (b - a) * piece as Real / 4.0;
            let half = (b - a) / 8.0;
            for (x, w) in GAUSS {
                let omega = t.dense(&system, lo + half * (1.0 + x));
                integral += w * half * rate(&omega);
            }
        }
    }
    (*t.y(), integral)
}

/// Along a run of the general top, E changes only by the power of the
/// radiation torque, Ω·T, and |L|² only by 2 L·T (the gyroscopic term does
/// no work and turns L without stretching it); checked for (3.3) and the
/// reduced (3.4) with each model's own torque, to 1e-13 of E and |L|².
#[test]
fn energy_and_angular_momentum_follow_the_radiation_torque_along_a_run() {
    let top = general_top();
    let i = top.inertia();
    let y0 = Vec3::new(0.05, 0.1, 0.2);
    let energy = |w: &Vec3| 0.5 * w.dot(&i.component_mul(w));
    let l2 = |w: &Vec3| i.component_mul(w).norm_squared();
    let t_end = 200.0;
    type Torque = fn(&GeneralTop, &Vec3) -> Vec3;
    let cases: [(&str, Torque); 2] = [
        ("(3.3)", GeneralTop::truncated_torque),
        ("reduced (3.4)", GeneralTop::reduced_torque),
    ];
    for (name, torque) in cases {
        let power = |w: &Vec3| w.dot(&torque(&top, w));
        let l_rate = |w: &Vec3| 2.0 * i.component_mul(w).dot(&torque(&top, w));
        let runs = if name == "(3.3)" {
            [
                integrate_along(GeneralTruncated(top), y0, t_end, power),
                integrate_along(GeneralTruncated(top), y0, t_end, l_rate),
            ]
        } else {
            [
                integrate_along(GeneralReduced(top), y0, t_end, power),
                integrate_along(GeneralReduced(top), y0, t_end, l_rate),
            ]
        };
        let [(w_end, lost_e), (_, lost_l2)] = runs;
        let de = energy(&w_end) - energy(&y0);
        let dl2 = l2(&w_end) - l2(&y0);
        assert!(
            de < -0.1 * energy(&y0),
            "{name}: the top must lose energy: {de}"
        );
        assert!(
            (de - lost_e).abs() < 1e-13 * energy(&y0),
            "{name}: {de:e} vs {lost_e:e}"
        );
        assert!(
            (dl2 - lost_l2).abs() < 1e-13 * l2(&y0),
            "{name}: {dl2:e} vs {lost_l2:e}"
        );
    }
}

/// The step rule never rejects, its cost is p(p+1)/2 evaluations' worth per
/// step, and at tight tolerances it takes several times fewer steps than
/// DOP853 (the reduced problem at rtol 1e-14).
#[test]
fn steps_are_never_rejected_and_cost_is_counted_per_order() {
    let problem = Problem::new(ProblemKind::Reduced).unwrap();
    let top = SymmetricTop::figure();
    let y0 = problem.initial().omega;
    let o = opts(1e-14, problem.atol(1e-14));
    let mut t = Taylor::new(SymmetricReduced(top), 0.0, y0, o).unwrap();
    solve(&mut t, &SymmetricReduced(top), problem.times()).unwrap();
    let s = t.stats();
    let p = t.order() as u64;
    assert_eq!(s.rejected, 0);
    assert_eq!(s.rhs_evals, s.steps * p * (p + 1) / 2);
    let mut d = Dop853::new(0.0, y0, o).unwrap();
    let f = SymmetricReduced(top);
    solve(&mut d, &f, problem.times()).unwrap();
    assert!(d.stats().steps > 5 * s.steps, "{:?} vs {s:?}", d.stats());
}

#[test]
fn forward_then_backward_returns_to_the_start() {
    let system = GeneralTruncated(general_top());
    let y0 = Vec3::new(0.05, 0.1, 0.2);
    let mut t = Taylor::new(system, 0.0, y0, opts(1e-14, 1e-22)).unwrap();
    solve(&mut t, &system, &[50.0]).unwrap();
    assert!(t.last_step() > 0.0);
    let back = solve(&mut t, &system, &[25.0, 0.0]).unwrap();
    assert!(t.last_step() < 0.0);
    assert!((back[1] - y0).norm() < 1e-13 * y0.norm(), "{}", back[1]);
    // Stepping to the current time does nothing; a step lands exactly on t_stop.
    let steps = t.stats().steps;
    t.step(&system, 0.0).unwrap();
    assert_eq!(t.stats().steps, steps);
    t.step(&system, 1e-3).unwrap();
    assert_eq!(t.t(), 1e-3);
}

#[test]
fn budget_and_bad_options_are_reported() {
    let system = SymmetricTruncated(SymmetricTop::figure());
    let y0 = Vec3::new(0.0, 0.1, 0.2);
    let mut o = opts(1e-12, 0.0);
    o.max_steps = 3;
    let mut t = Taylor::new(system, 0.0, y0, o).unwrap();
    match solve(&mut t, &system, &[1e4]) {
        Err(IntegrateError::TooManySteps {
            t: at,
            max_steps: 3,
        }) => assert!(at > 0.0),
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        Taylor::new(system, Real::NAN, y0, opts(1e-8, 0.0)),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        Taylor::new(
            system,
            0.0,
            Vec3::new(Real::INFINITY, 0.0, 0.0),
            opts(1e-8, 0.0)
        ),
        Err(IntegrateError::InvalidOption(_))
    ));
    let mut bad = opts(1e-8, 0.0);
    bad.h_max = -1.0;
    assert!(matches!(
        Taylor::new(system, 0.0, y0, bad),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        Taylor::new(system, 0.0, y0, opts(1e-8, 0.0))
            .unwrap()
            .step(&system, Real::NAN),
        Err(IntegrateError::InvalidOption(_))
    ));
    // A top at rest: every coefficient beyond order 0 vanishes, the
    // polynomial is exact and one step reaches the end.
    let mut t = Taylor::new(system, 0.0, Vec3::zeros(), opts(1e-8, 0.0)).unwrap();
    solve(&mut t, &system, &[1e6]).unwrap();
    assert_eq!((t.stats().steps, *t.y()), (1, Vec3::zeros()));
}

/// `auto` integrates an asymmetric top with the Taylor method exactly where
/// the measured crossover puts it (rtol ≤ `TAYLOR_AUTO_RTOL`) and with
/// DOP853 above; a scene's plan names the same method as the simulation
/// runs, and the symmetric tops keep their closed forms at any rtol.
#[test]
fn auto_uses_the_taylor_method_only_below_the_measured_crossover() {
    use spintop::sim::{
        InitialState, MethodChoice, MethodOptions, Model, Simulation, TAYLOR_AUTO_RTOL,
    };
    let initial = InitialState {
        omega: Vec3::new(0.0, 0.1, 0.2),
        rotation: Mat3::identity(),
    };
    let label = |model: Model, rtol: Real| {
        let options = MethodOptions::default().with_rtol(rtol).unwrap();
        Simulation::new(model, MethodChoice::Auto, options, initial, Some(10.0))
            .unwrap()
            .method()
            .label()
    };
    let scene = |model: &str, rtol: Real| {
        let text = format!(
            "[scene]\nname = \"x\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"{model}\"\ninertia = [1.0, 1.5, 0.8]\ndipole = [0.2, 0.0, 1.0]\nomega = [0.0, 0.1, 0.2]\n[solve]\nt_end = 10.0\nsamples = 11\nrtol = {rtol:e}\n"
        );
        spintop::scene::parse(&text, "x.toml")
            .unwrap()
            .chosen
            .method
    };
    for (rtol, want) in [
        (1e-6, "dop853"),
        (2.0 * TAYLOR_AUTO_RTOL, "dop853"),
        (TAYLOR_AUTO_RTOL, "taylor"),
        (1e-12, "taylor"),
    ] {
        for model in [
            Model::General(general_top()),
            Model::GeneralReduced(general_top()),
        ] {
            assert_eq!(label(model, rtol), want, "{model:?} at {rtol:e}");
        }
        assert_eq!(scene("general", rtol), want, "scene at {rtol:e}");
        let top = SymmetricTop::figure();
        assert_eq!(label(Model::Truncated(top), rtol), "exact");
        assert_eq!(label(Model::Reduced(top), rtol), "exact+dop853");
    }
}

/// The rule `auto` follows (`sim::auto_integrator`) is the measured
/// crossover: at every rtol of the committed run of `cargo bench -p
/// spintop-benches --bench crossover` (Ω and the orientation of three
/// asymmetric tops, both general models, 5 and 1000 outputs), `auto` takes
/// the Taylor method exactly where its median time was below DOP853's in
/// every case, and DOP853 where it was not.
#[test]
fn auto_rule_is_the_measured_crossover() {
    use spintop::sim::{Method, auto_integrator};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../benches/results/crossover-2026-11-26.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    // rtol -> (cases, cases where the Taylor method was the faster)
    let mut by_rtol: Vec<(Real, usize, usize)> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let rtol: Real = cells[3].parse().unwrap();
        let ratio: Real = cells[6].parse().unwrap();
        let at = match by_rtol.iter().position(|r| r.0 == rtol) {
            Some(i) => i,
            None => {
                by_rtol.push((rtol, 0, 0));
                by_rtol.len() - 1
            }
        };
        by_rtol[at].1 += 1;
        by_rtol[at].2 += usize::from(ratio > 1.0);
    }
    assert!(by_rtol.len() >= 6, "{by_rtol:?}");
    let mut both = [false; 2];
    for (rtol, cases, taylor_faster) in by_rtol {
        assert_eq!(cases, 12, "rtol {rtol:e}");
        let wins_everywhere = taylor_faster == cases;
        let chosen = auto_integrator(rtol);
        assert_eq!(
            chosen == Method::Taylor,
            wins_everywhere,
            "rtol {rtol:e}: auto takes {chosen:?}, the Taylor method was the faster in {taylor_faster} of {cases} cases"
        );
        both[usize::from(wins_everywhere)] = true;
    }
    // The run holds both sides of the crossover, so the rule is pinned.
    assert_eq!(both, [true, true]);
}

/// The simulation's Taylor engine (Ω and the orientation quaternion) against
/// the 40-digit references, Ω and O at all 200 points, at rtol 1e-14; and it
/// refuses the full ALE by name.
#[test]
fn eq_3_3_eq_4_2_eq_4_12_simulation_with_the_taylor_method_matches_the_references() {
    use spintop::sim::{MethodChoice, MethodOptions, Model, SimError, Simulation};
    for kind in [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ] {
        let problem = Problem::new(kind).unwrap();
        let options = MethodOptions::default().with_rtol(1e-14).unwrap();
        let mut sim = Simulation::new(
            *problem.model(),
            MethodChoice::Taylor,
            options,
            *problem.initial(),
            Some(problem.t_end()),
        )
        .unwrap();
        let samples = sim.run(problem.times()).unwrap();
        let omega: Vec<Vec3> = samples.iter().map(|s| s.omega_vec()).collect();
        let reference = problem.reference();
        let e_omega = omega_error(&reference.omega, &omega);
        let e_rot = reference
            .rotation
            .as_ref()
            .unwrap()
            .iter()
            .zip(&samples)
            .map(|(r, s)| rotation_angle(r, &s.rotation_matrix()))
            .fold(0.0, Real::max);
        assert!(
            e_omega < 1e-14 && e_rot < 1e-13,
            "{kind:?}: {e_omega:e} {e_rot:e}"
        );
        assert_eq!(sim.method().label(), "taylor");
        assert!(sim.stats().steps > 0 && sim.stats().rejected == 0);
    }
    let full = Simulation::new(
        Model::Full(SymmetricTop::figure()),
        MethodChoice::Taylor,
        MethodOptions::default(),
        *Problem::new(ProblemKind::Truncated).unwrap().initial(),
        Some(10.0),
    );
    assert!(
        matches!(&full, Err(SimError::Refused(r)) if r.model == "full"),
        "{full:?}"
    );
}

/// A top this fast has rates a double holds (τΩ⊥²Ω⊥ = 10³⁰) but Taylor
/// coefficients it does not: the one of order k grows like Ω⊥ (τΩ⊥²)ᵏ, past
/// 10³⁰⁸ from order 15 on. The method builds such a jet in a shorter time
/// unit and must still follow the closed form (4.7) through the collapse of
/// Ω⊥ (by 10¹⁰) and after it, where DOP853 does (it failed at t = 0 with
/// "non-finite").
#[test]
fn eq_4_7_holds_for_a_top_whose_unscaled_taylor_coefficients_overflow() {
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let omega0 = Vec3::new(1e10, 0.0, 1.0);
    let rtol = 1e-12;
    let system = SymmetricTruncated(top);
    let mut taylor = Taylor::new(system, 0.0, omega0, opts(rtol, 1e-300)).unwrap();
    assert!(taylor_order(rtol) >= 15);
    for t in [1e-25, 1e-20, 1e-15, 1e-10, 1e-5, 1.0, 10.0, 100.0] {
        while taylor.t() < t {
            taylor
                .advance(t)
                .unwrap_or_else(|e| panic!("t = {t:e}: {e}"));
        }
        let y = taylor.value_at(t);
        let exact = truncated_closed_form(&top, &omega0, t);
        let error = (y - exact).amax() / exact.amax();
        assert!(error < 100.0 * rtol, "t = {t:e}: relative error {error:e}");
    }
    // Order and cost as for any other run: no step was taken twice.
    let steps = taylor.stats().steps;
    assert!(steps > 10 && steps < 10_000, "{steps} steps");
}

/// `auto` takes the Taylor method on a general top at rtol ≤ 1e-10, so it
/// must reach wherever a Runge–Kutta method does: at |Ω₀| = 10⁵⁰ (κ = 1
/// units), through the collapse of Ω across d over the first 10⁻⁴⁹ u, a
/// simulation by `auto` agrees with DOP853 run with relative control
/// throughout (the Taylor run ended at t = 0 with "the rates overflow a
/// double", then, with its coefficients scaled, crawled at the stability
/// limit with Ω flipping sign each step inside an atol tied to |Ω₀|).
#[test]
fn auto_on_a_fast_general_top_agrees_with_dop853() {
    use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
    let top = GeneralTop::new(Vec3::new(1.0, 1.2, 0.5), Vec3::new(0.2, 0.0, 0.3)).unwrap();
    let omega0 = Vec3::new(1e50, 1.0, 1.0);
    let initial = InitialState {
        omega: omega0,
        rotation: Mat3::identity(),
    };
    let options = MethodOptions::default().with_rtol(1e-12).unwrap();
    let times: Vec<Real> = (0..=10).map(|i| i as Real * 1e-50).collect();
    let mut sim = Simulation::new(
        Model::General(top),
        MethodChoice::Auto,
        options,
        initial,
        Some(1e-49),
    )
    .unwrap();
    let samples = sim.run(&times).unwrap();
    assert_eq!(sim.method().label(), "taylor");
    let system = GeneralTruncated(top);
    let mut dop853 = Dop853::new(0.0, omega0, opts(1e-13, 1e-300)).unwrap();
    let reference = solve(&mut dop853, &system, &times).unwrap();
    for (a, b) in samples.iter().zip(&reference) {
        let error = (a.omega_vec() - b).amax() / b.amax();
        assert!(error < 1e-9, "t = {:e}: {error:e}", a.t);
    }
}
