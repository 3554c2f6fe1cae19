//! The splitting methods (`spintop::integrate::splitting`): what they promise,
//! checked against exact solutions, invariants and an independent method.
//!
//! - The free rigid body split into three axis rotations: every sub-flow is an
//!   exact rotation, so one step of any composition keeps |L| and the lab-frame
//!   L = O L (the torque-free (3.2)) and the orthonormality of O to rounding,
//!   for random moments, states and steps (proptest).
//! - Observed orders: Lie–Trotter 1, Strang 2, Yoshida-4 4, measured on the
//!   symmetric free top against its exact solution (the τ = 0 case of (4.7),
//!   (4.9)) and on an asymmetric top against DOP853 at rtol 1e-13 on (L, O).
//! - Backward stepping: backward runs match the exact solution at negative
//!   times, and a symmetric method run forward then backward returns to the start.
//! - The reduced model (4.12)–(4.14): its rotation and damping parts commute and
//!   each is exact, so n steps equal the closed form (4.15)–(4.16) to rounding for
//!   any n, one step over t = 10⁴ and τΩ²t ~ 10⁶ included; the damping flow
//!   matches Φ of (4.16), and stays finite and accurate from τΩ²h ~ 1e-20 to 1e300.
//! - Work counts (sub-flows per step), and failures: bad options, the step
//!   budget, and the blow-up of the reduced model run backward, reported with
//!   its time and never as a NaN state.

use proptest::prelude::*;
use spintop::integrate::splitting::{Composition, yoshida_weights};
use spintop::integrate::{AdaptiveOptions, Dop853, IntegrateError, Rhs, Stepper};
use spintop::math::{Mat3, Real, State, Vec3, exp_so3, hat, orthonormality_error, rot_x, rot_z};
use spintop::physics::ParamError;
use spintop::physics::free_top::{FreeRigidBody, RigidBodyState};
use spintop::physics::symmetric_top::{
    SymmetricTop, reduced_amplitude, reduced_closed_form, truncated_closed_form,
    truncated_orientation,
};
use spintop::physics::symmetric_top::{reduced_damping_flow, reduced_rotation_flow};
use spintop::sim::split::{ReducedFlow, ReducedSplitting, RigidBodySplitting, reduced_split_solve};

const EPS: Real = Real::EPSILON;

fn o0() -> Mat3 {
    rot_z(0.7) * rot_x(0.4) * rot_z(-1.1)
}

/// Run a rigid-body splitting from `start` to `t_end` with step `h`.
fn run(
    body: FreeRigidBody,
    c: Composition,
    start: RigidBodyState,
    h: Real,
    t_end: Real,
) -> RigidBodySplitting {
    let mut s = RigidBodySplitting::new(body, c, 0.0, start, h).unwrap();
    s.advance_to(t_end).unwrap();
    s
}

fn state_distance(a: &RigidBodyState, b: &RigidBodyState) -> Real {
    (a.l_body - b.l_body)
        .amax()
        .max((a.rotation - b.rotation).amax())
}

/// The exact solution of the free symmetric top with moments (1, 1, ratio):
/// Ω from (4.7) and O from (4.9) with τ = 0 (then R = 1 and ϑ = t).
fn symmetric_exact(ratio: Real, omega0: &Vec3, t: Real) -> RigidBodyState {
    let top = SymmetricTop::new(ratio, 0.0).unwrap();
    let omega = truncated_closed_form(&top, omega0, t);
    RigidBodyState {
        l_body: top.inertia().component_mul(&omega),
        rotation: truncated_orientation(&top, omega0, &o0(), t),
    }
}

/// Observed orders log₂(e(h)/e(h/2)) for h, h/2, h/4.
fn orders(err: impl Fn(Real) -> Real, h: Real) -> [Real; 2] {
    let e = [err(h), err(0.5 * h), err(0.25 * h)];
    [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()]
}

fn assert_order(got: [Real; 2], expected: Real, what: &str) {
    for p in got {
        assert!(
            (p - expected).abs() < 0.15,
            "{what}: observed orders {got:?}, expected {expected}"
        );
    }
}

// ---------------------------------------------------------------- invariants

proptest! {
    /// One step of any composition keeps |L|, the lab L (torque-free (3.2):
    /// d(OL)/dt = O(L̇ + Ω × L) = 0) and OᵀO = 1 to rounding, whatever the step.
    #[test]
    fn eq_3_2_one_step_keeps_l_norm_and_lab_l_to_rounding(
        i1 in 0.5..2.0f64, i2 in 0.5..2.0f64, i3f in 0.1..1.0f64,
        l in prop::array::uniform3(-2.0..2.0f64),
        sigma in prop::array::uniform3(-3.0..3.0f64),
        h in -5.0..5.0f64,
        which in 0usize..3,
    ) {
        let i3 = (i1 + i2) * i3f;
        prop_assume!(i3 >= (i1 - i2).abs());
        let body = FreeRigidBody::new(Vec3::new(i1, i2, i3)).unwrap();
        let start = RigidBodyState {
            l_body: Vec3::from(l),
            rotation: exp_so3(&Vec3::from(sigma)).to_rotation_matrix().into_inner(),
        };
        let c = [Composition::LieTrotter, Composition::Strang, Composition::Yoshida4][which];
        let s = RigidBodySplitting::new(body, c, 0.0, start, 1.0).unwrap();
        let end = s.step_once(&start, h).unwrap();
        let scale = start.l_body.norm().max(1e-300);
        prop_assert!((end.l_body.norm() - start.l_body.norm()).abs() <= 64.0 * EPS * scale);
        prop_assert!((end.l_lab() - start.l_lab()).norm() <= 64.0 * EPS * scale);
        prop_assert!(orthonormality_error(&end.rotation) <= 64.0 * EPS);
    }
}

/// Each axis flow solves its own part: L̇ = L × Ω and Ȯ = OΩ̂ with Ω = (L_i/I_i)e_i,
/// checked by central differences in h.
#[test]
fn eq_3_1_eq_3_2_each_axis_flow_solves_its_part() {
    let body = FreeRigidBody::new(Vec3::new(1.0, 2.0, 2.5)).unwrap();
    let start = RigidBodyState {
        l_body: Vec3::new(0.3, -1.1, 0.8),
        rotation: o0(),
    };
    let d = 1e-5;
    for axis in 0..3 {
        let p = body.axis_flow(axis, d, &start);
        let m = body.axis_flow(axis, -d, &start);
        let omega = Vec3::ith(axis, start.l_body[axis] / body.inertia()[axis]);
        let l_dot = (p.l_body - m.l_body) / (2.0 * d);
        let o_dot = (p.rotation - m.rotation) / (2.0 * d);
        assert!(
            (l_dot - start.l_body.cross(&omega)).amax() < 1e-9,
            "axis {axis}"
        );
        assert!(
            (o_dot - start.rotation * hat(&omega)).amax() < 1e-9,
            "axis {axis}"
        );
    }
    // The three parts add up to the whole: the sum of their vector fields is the
    // Euler equation L̇ = L × I⁻¹L.
    let total: Vec3 = (0..3)
        .map(|axis| {
            let p = body.axis_flow(axis, d, &start);
            let m = body.axis_flow(axis, -d, &start);
            (p.l_body - m.l_body) / (2.0 * d)
        })
        .sum();
    assert!((total - body.l_dot(&start.l_body)).amax() < 1e-9);
}

// ---------------------------------------------------------------- orders

/// Orders 1, 2, 4 against the exact solution of the free symmetric top, (4.7)
/// and (4.9) at τ = 0.
#[test]
fn eq_4_7_eq_4_9_orders_1_2_4_on_the_free_symmetric_top() {
    let ratio = 0.4;
    let omega0 = Vec3::new(0.3, 0.5, 1.2);
    let body = FreeRigidBody::new(Vec3::new(1.0, 1.0, ratio)).unwrap();
    let start = symmetric_exact(ratio, &omega0, 0.0);
    let t_end = 5.0;
    let exact = symmetric_exact(ratio, &omega0, t_end);
    for (c, h, p) in [
        (Composition::LieTrotter, 0.01, 1.0),
        (Composition::Strang, 0.05, 2.0),
        (Composition::Yoshida4, 0.1, 4.0),
    ] {
        let got = orders(
            |h| state_distance(run(body, c, start, h, t_end).state(), &exact),
            h,
        );
        assert_order(got, p, c.name());
        assert_eq!(c.order() as Real, p);
    }
}

/// The free asymmetric top (L̇ = L × Ω, Ȯ = OΩ̂) as 12 numbers, for DOP853.
struct FreeTop(Vec3);

impl Rhs<12> for FreeTop {
    fn eval(&self, _t: Real, y: &State<12>) -> State<12> {
        let l = Vec3::new(y[0], y[1], y[2]);
        let o = Mat3::from_column_slice(&y.as_slice()[3..12]);
        let omega = l.component_div(&self.0);
        let mut out = State::<12>::zeros();
        out.fixed_rows_mut::<3>(0).copy_from(&l.cross(&omega));
        out.fixed_rows_mut::<9>(3)
            .copy_from_slice((o * hat(&omega)).as_slice());
        out
    }
}

fn dop853_reference(inertia: Vec3, start: &RigidBodyState, t_end: Real) -> RigidBodyState {
    let mut y0 = State::<12>::zeros();
    y0.fixed_rows_mut::<3>(0).copy_from(&start.l_body);
    y0.fixed_rows_mut::<9>(3)
        .copy_from_slice(start.rotation.as_slice());
    let mut s = Dop853::new(0.0, y0, AdaptiveOptions::new(1e-13, 1e-16).unwrap()).unwrap();
    let rhs = FreeTop(inertia);
    while s.t() != t_end {
        s.step(&rhs, t_end).unwrap();
    }
    let y = s.y();
    RigidBodyState {
        l_body: Vec3::new(y[0], y[1], y[2]),
        rotation: Mat3::from_column_slice(&y.as_slice()[3..12]),
    }
}

/// Orders 2 and 4 on a tumbling asymmetric top, against DOP853 at rtol 1e-13
/// (an independent Runge–Kutta solution of L̇ = L × Ω, Ȯ = OΩ̂).
#[test]
fn eq_3_2_strang_and_yoshida_orders_on_the_asymmetric_top_against_dop853() {
    let inertia = Vec3::new(1.0, 2.0, 3.0);
    let body = FreeRigidBody::new(inertia).unwrap();
    let start = RigidBodyState {
        l_body: Vec3::new(1.0, 1.0, 0.9),
        rotation: o0(),
    };
    let t_end = 10.0;
    let reference = dop853_reference(inertia, &start, t_end);
    // Forward and backward (the backward reference starts from the same state).
    let reference_back = dop853_reference(inertia, &start, -t_end);
    for (c, h, p) in [
        (Composition::Strang, 0.1, 2.0),
        (Composition::Yoshida4, 0.2, 4.0),
    ] {
        let got = orders(
            |h| state_distance(run(body, c, start, h, t_end).state(), &reference),
            h,
        );
        assert_order(got, p, c.name());
        let back = orders(
            |h| state_distance(run(body, c, start, h, -t_end).state(), &reference_back),
            h,
        );
        assert_order(back, p, c.name());
    }
}

// ---------------------------------------------------------------- backward

/// Backward runs match the exact solution at negative times; forward then
/// backward returns to the start (symmetric methods: S₋ₕ = Sₕ⁻¹ up to rounding).
#[test]
fn backward_runs_match_the_exact_solution_and_retrace_forward_runs() {
    let ratio = 1.6;
    let omega0 = Vec3::new(-0.4, 0.2, 0.7);
    let body = FreeRigidBody::new(Vec3::new(1.0, 1.0, ratio)).unwrap();
    let start = symmetric_exact(ratio, &omega0, 0.0);
    let exact = symmetric_exact(ratio, &omega0, -3.0);
    let s = run(body, Composition::Yoshida4, start, 0.01, -3.0);
    assert_eq!(s.t(), -3.0);
    assert_eq!(s.stats().steps, 300);
    assert!(state_distance(s.state(), &exact) < 1e-8);

    let inertia = Vec3::new(1.0, 2.0, 3.0);
    let body = FreeRigidBody::new(inertia).unwrap();
    let start = RigidBodyState {
        l_body: Vec3::new(1.0, 1.0, 0.9),
        rotation: o0(),
    };
    for c in [Composition::Strang, Composition::Yoshida4] {
        let mut s = RigidBodySplitting::new(body, c, 0.0, start, 0.05).unwrap();
        s.advance_to(50.0).unwrap();
        s.advance_to(0.0).unwrap();
        assert_eq!(s.t(), 0.0);
        assert_eq!(s.stats().steps, 2000);
        assert!(state_distance(s.state(), &start) < 1e-12, "{c:?}");
    }
}

// ---------------------------------------------------------------- work counts

#[test]
fn work_is_counted_in_sub_flows_and_steps() {
    let body = FreeRigidBody::new(Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let start = RigidBodyState {
        l_body: Vec3::new(1.0, 1.0, 0.9),
        rotation: Mat3::identity(),
    };
    for (c, per_step) in [
        (Composition::LieTrotter, 3),
        (Composition::Strang, 5),
        (Composition::Yoshida4, 13),
    ] {
        let s = run(body, c, start, 0.1, 10.0);
        assert_eq!(s.flows_per_step(), per_step);
        assert_eq!(s.stats().steps, 100, "{c:?}");
        assert_eq!(s.stats().rhs_evals, 100 * per_step as u64, "{c:?}");
        assert_eq!(s.stats().rejected, 0);
    }
    // A step that does not divide the span: the last step is shorter.
    let s = run(body, Composition::Strang, start, 0.3, 1.0);
    assert_eq!(s.stats().steps, 4);
    assert_eq!(s.t(), 1.0);
    // Stepping to the current time is a no-op.
    let mut s = RigidBodySplitting::new(body, Composition::Strang, 2.0, start, 0.1).unwrap();
    s.step(2.0).unwrap();
    assert_eq!(s.stats().steps, 0);
    assert_eq!(*s.state(), start);
    // Yoshida's weights: 2w₁ + w₀ = 1 and 2w₁³ + w₀³ = 0 (the order-4 condition).
    let (w1, w0) = yoshida_weights();
    assert!((2.0 * w1 + w0 - 1.0).abs() < 1e-15);
    assert!((2.0 * w1.powi(3) + w0.powi(3)).abs() < 1e-14);
}

// ---------------------------------------------------------------- the reduced model

fn rounding_tol(top: &SymmetricTop, omega0: &Vec3, t: Real, steps: u64, scale: Real) -> Real {
    // Each step rounds the amplitude and the phase by a few ulps; the closed form
    // itself carries a phase error of ~ε|Ω̃₃t|, and its decay factor e^{−x}
    // an error of ~ε|x| (the rounding of the exponent x, here ln of the
    // amplitude's fall, is amplified by e^{−x}'s own slope).
    let phase = top.omega3_tilde(omega0.z).abs() * t.abs();
    let perp0 = omega0.x.hypot(omega0.y);
    let decay = if scale > 0.0 && perp0 > 0.0 {
        (scale / perp0).ln().abs()
    } else {
        0.0
    };
    16.0 * EPS * (steps as Real + phase + decay + 1.0)
}

fn assert_matches_closed_form(top: &SymmetricTop, omega0: &Vec3, t: Real, steps: u64) {
    let (got, stats) = reduced_split_solve(top, omega0, t, steps).unwrap();
    let exact = reduced_closed_form(top, omega0, t);
    let scale = exact.x.hypot(exact.y);
    // NOTE: the floor covers results deep in the subnormals, where a product of
    // step factors keeps fewer bits than one closed-form factor.
    let tol = rounding_tol(top, omega0, t, steps, scale) * scale + 1e-290;
    let err = (got.x - exact.x).hypot(got.y - exact.y);
    assert!(
        err <= tol,
        "tau {} ratio {} omega0 {omega0:?} t {t} steps {steps}: {got:?} vs {exact:?} (err {err:e} > {tol:e})",
        top.tau(),
        top.ratio()
    );
    assert_eq!(got.z, omega0.z);
    assert_eq!(stats.steps, steps);
    assert_eq!(stats.rhs_evals, 2 * steps);
}

proptest! {
    /// n steps of the exact split equal the closed form (4.15)–(4.16) to rounding,
    /// for any top, start, time and number of steps.
    #[test]
    fn eq_4_12_eq_4_15_reduced_split_equals_the_closed_form_for_any_step_count(
        ratio in 0.05..2.0f64, log_tau in -6.0..2.0f64,
        w in prop::array::uniform3(-1.0..1.0f64),
        log_t in -2.0..3.0f64, steps in 1u64..3000,
    ) {
        let top = SymmetricTop::new(ratio, 10f64.powf(log_tau)).unwrap();
        let omega0 = Vec3::from(w);
        prop_assume!(omega0.x.hypot(omega0.y) > 1e-3);
        assert_matches_closed_form(&top, &omega0, 10f64.powf(log_t), steps);
    }

    /// The two parts commute: rotation∘damping = damping∘rotation.
    #[test]
    fn eq_4_12_rotation_and_damping_commute(
        ratio in 0.05..2.0f64, tau in 0.0..3.0f64,
        w in prop::array::uniform3(-2.0..2.0f64), h in 0.0..5.0f64,
    ) {
        let top = SymmetricTop::new(ratio, tau).unwrap();
        let omega = Vec3::from(w);
        let a = reduced_damping_flow(&top, &reduced_rotation_flow(&top, &omega, h), h).unwrap();
        let b = reduced_rotation_flow(&top, &reduced_damping_flow(&top, &omega, h).unwrap(), h);
        prop_assert!((a - b).amax() <= 1e-14 * omega.amax());
    }
}

/// The paper's figure top: one step over t = 10⁴, and a thousand, and a million.
#[test]
fn eq_4_12_one_step_over_a_long_span_is_the_closed_form() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    for steps in [1, 7, 1000, 1_000_000] {
        assert_matches_closed_form(&top, &omega0, 1e4, steps);
    }
}

/// Stiff: τΩ⊥²t ~ 10⁶ and τk²t ~ 10⁶ (Ω⊥ ends ~1e-3 of its start, or below
/// 1e-300), where explicit methods need steps ≲ 1/(τΩ²); one step is exact.
#[test]
fn eq_4_12_stiff_tau_omega_squared_t_1e6_is_exact_in_any_number_of_steps() {
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let omega0 = Vec3::new(300.0, -800.0, 1e-3); // τΩ⊥² ≈ 7.3e5
    for steps in [1, 3, 100, 10_000] {
        assert_matches_closed_form(&top, &omega0, 1.0, steps);
    }
    // τk²t = 1e6 with k = 1: Ω⊥ falls by e^{−10⁶}, to exactly 0 in doubles.
    let top = SymmetricTop::new(1.0, 1.0).unwrap();
    let omega0 = Vec3::new(0.5, 0.5, 1.0);
    for steps in [1, 10, 1000] {
        let (got, _) = reduced_split_solve(&top, &omega0, 1e6, steps).unwrap();
        assert_eq!(got, Vec3::new(0.0, 0.0, 1.0));
    }
}

/// The damping part against Φ(h) of (4.16), from τΩ⊥²h ~ 1e-20 (where 1 − Φ is
/// ~1e-20 and must not round to 0 in its derivative) to ~1e300 (where the
/// product overflows unless handled).
#[test]
fn eq_4_16_damping_flow_matches_the_amplitude_factor_at_every_scale() {
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    for (omega, h) in [
        (Vec3::new(3e-11, 4e-11, 1e-10), 1.0),
        (Vec3::new(0.06, 0.08, 0.2), 1e-9),
        (Vec3::new(0.06, 0.08, 0.2), 1e3),
        (Vec3::new(3e5, 4e5, 0.0), 1.0),
        (Vec3::new(3e100, 4e100, 0.0), 1e100),
    ] {
        let got = reduced_damping_flow(&top, &omega, h).unwrap();
        let phi = reduced_amplitude(&top, &omega, h);
        let expected = omega.xy() * phi;
        assert!(
            (got.xy() - expected).norm() <= 4.0 * EPS * expected.norm(),
            "{omega:?}, h = {h}: {got:?} vs {expected:?}"
        );
    }
    // τΩ⊥²h = 1e300: the late-time form Ω⊥ = 1/√(2τh), independent of Ω⊥₀.
    let got = reduced_damping_flow(&top, &Vec3::new(3e100, 4e100, 0.0), 2e100).unwrap();
    let expected = 1.0 / (2.0 * 2e100f64).sqrt();
    assert!((got.xy().norm() - expected).abs() <= 4.0 * EPS * expected);
    assert!((got.x / got.y - 0.75).abs() < 1e-15);
    // Past overflow of τΩ⊥²h (the closed form's product is infinite there and
    // returns 0): the late-time form still holds.
    let got = reduced_damping_flow(&top, &Vec3::new(3e200, 4e200, 0.0), 2e100).unwrap();
    let expected = 1.0 / (2.0 * 2e100f64).sqrt();
    assert!((got.xy().norm() - expected).abs() <= 4.0 * EPS * expected);
}

/// Backward: from the closed form at T back to Ω₀; and past the blow-up of the
/// backward flow (Ω⊥ → ∞ at a finite negative time) an error with its time.
#[test]
fn eq_4_12_backward_split_retraces_the_closed_form_and_reports_the_blow_up() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.02, 0.1, 0.2);
    let t = 300.0;
    let end = reduced_closed_form(&top, &omega0, t);
    for steps in [1, 50, 3000] {
        let (back, stats) = reduced_split_solve(&top, &end, -t, steps).unwrap();
        assert!(
            (back - omega0).amax()
                <= rounding_tol(&top, &omega0, t, steps, omega0.x.hypot(omega0.y)) * 0.1,
            "{steps}: {back:?}"
        );
        assert_eq!(stats.steps, steps);
    }
    // Backward blow-up: with k = 0, 1/Ω⊥² = 1/Ω⊥₀² + 2τt, zero at t* = −1/(2τΩ⊥₀²) = −50.
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let omega0 = Vec3::new(0.0, 0.1, 0.0);
    // Steps of 7.5: the state at −45 is finite, the step to −52.5 crosses t*.
    let err = reduced_split_solve(&top, &omega0, -60.0, 8).unwrap_err();
    assert_eq!(err, IntegrateError::NonFinite { t: -45.0 });
    let mut s =
        ReducedSplitting::new(ReducedFlow(top), Composition::Strang, 0.0, omega0, 7.5).unwrap();
    assert_eq!(
        s.advance_to(-60.0),
        Err(IntegrateError::NonFinite { t: -45.0 })
    );
    assert_eq!(s.t(), -45.0);
    assert_eq!(s.stats().steps, 6);
    assert!(s.state().iter().all(|x| x.is_finite()));
    assert!((s.state().y - 1.0 / (1.0f64 / 0.01 - 90.0).sqrt()).abs() < 1e-14);
}

// ---------------------------------------------------------------- bad input

#[test]
fn bad_options_and_budgets_are_refused_with_errors() {
    let body = FreeRigidBody::new(Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let start = RigidBodyState {
        l_body: Vec3::new(1.0, 1.0, 0.9),
        rotation: Mat3::identity(),
    };
    let new = |t0: Real, s: RigidBodyState, h: Real| {
        RigidBodySplitting::new(body, Composition::Strang, t0, s, h)
    };
    for h in [0.0, -0.1, Real::NAN, Real::INFINITY] {
        assert!(matches!(
            new(0.0, start, h),
            Err(IntegrateError::InvalidOption(_))
        ));
    }
    assert!(matches!(
        new(Real::NAN, start, 0.1),
        Err(IntegrateError::InvalidOption(_))
    ));
    let mut bad = start;
    bad.l_body.y = Real::NAN;
    assert!(matches!(
        new(0.0, bad, 0.1),
        Err(IntegrateError::InvalidOption(_))
    ));
    bad = start;
    bad.rotation[(1, 2)] = Real::INFINITY;
    assert!(matches!(
        new(0.0, bad, 0.1),
        Err(IntegrateError::InvalidOption(_))
    ));
    let mut s = new(0.0, start, 0.1).unwrap();
    assert!(matches!(
        s.step(Real::NAN),
        Err(IntegrateError::InvalidOption(_))
    ));
    let mut s = new(0.0, start, 0.1).unwrap().with_max_steps(5);
    assert_eq!(
        s.advance_to(1.0),
        Err(IntegrateError::TooManySteps {
            t: 0.5,
            max_steps: 5
        })
    );

    assert!(matches!(
        FreeRigidBody::new(Vec3::new(1.0, 0.0, 1.0)),
        Err(ParamError::MomentNotPositive { index: 2, .. })
    ));
    assert!(matches!(
        FreeRigidBody::new(Vec3::new(1.0, 1.0, 2.5)),
        Err(ParamError::TriangleInequality(..))
    ));
    assert!(matches!(
        FreeRigidBody::new(Vec3::new(Real::NAN, 1.0, 1.0)),
        Err(ParamError::NotFinite { name: "I1", .. })
    ));

    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    assert!(matches!(
        reduced_split_solve(&top, &omega0, 1.0, 0),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        reduced_split_solve(&top, &omega0, Real::INFINITY, 10),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert!(matches!(
        reduced_split_solve(&top, &Vec3::new(Real::NAN, 0.0, 0.0), 1.0, 10),
        Err(IntegrateError::InvalidOption(_))
    ));
    assert_eq!(
        reduced_split_solve(&top, &omega0, 0.0, 0),
        Ok((omega0, Default::default()))
    );
}
