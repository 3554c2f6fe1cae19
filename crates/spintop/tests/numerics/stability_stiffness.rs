//! Row 3 of the stability suite: the reduced model (4.12)–(4.14) with
//! Ω₀ = S·(0, 0.1, 0.2) is stiff when τΩ² ≫ 1. These tests pin down both
//! halves of the row:
//!
//! - the naive methods really fail: RK4 just above its measured limit h* leaves
//!   the closed form's bound |Ω⊥| ≤ Ω⊥₀ and overflows, while just below it
//!   stays bounded and decays like the closed form; h* falls like S⁻², inside
//!   the bracket that linear stability predicts from the Jacobian's asymptotic
//!   eigenvalues (−τ(3Ω⊥₀² + k²) at the start, −τk² at the end) and RK4's
//!   real stability interval, which the tests compute themselves; DP5's step
//!   count grows faster than S and matches τk²T / 3.307 (its own stability
//!   interval), and under a step budget it runs out;
//! - the fix succeeds: Radau IIA 5 with the analytic Jacobian takes a few dozen
//!   steps at every S, and its states agree with the closed form (4.15)–(4.16)
//!   within the tolerance.
//!
//! Every check runs the integrators again here, or compares with a value
//! derived here; the measurement only supplies h* and the run counts that the
//! checks then test.

use spintop::integrate::{AdaptiveOptions, IntegrateError, Radau5, Rk4, Stepper};
use spintop::math::{Real, State, Vec3};
use spintop::physics::symmetric_top::{
    SymmetricTop, reduced_ale_rhs, reduced_amplitude, reduced_closed_form,
};
use spintop::stability::stiffness::{
    ABOVE, BUDGET, LADDER, Measurement, RK4_LADDER, RTOL, ReducedAle, SPAN, measure, omega0,
};
use std::sync::OnceLock;

fn measured() -> &'static Measurement {
    static M: OnceLock<Measurement> = OnceLock::new();
    M.get_or_init(|| measure().expect("row 3 runs"))
}

/// The real root of x³ + 4x² + 12x + 24 = 0, i.e. R(x) = 1 for RK4's
/// R = 1 + x + x²/2 + x³/6 + x⁴/24 with x ≠ 0: the left end of RK4's real
/// stability interval (≈ −2.785).
fn rk4_real_boundary() -> Real {
    bisect(|x| x * x * x + 4.0 * x * x + 12.0 * x + 24.0, -4.0, -2.0)
}

/// The left end of DP5's real stability interval, where |R(x)| first exceeds 1
/// going left from 0, for R = Σₖ₌₀⁵ xᵏ/k! + x⁶/600 (≈ −3.307).
fn dp5_real_boundary() -> Real {
    let r = |x: Real| {
        1.0 + x
            + x * x / 2.0
            + x.powi(3) / 6.0
            + x.powi(4) / 24.0
            + x.powi(5) / 120.0
            + x.powi(6) / 600.0
    };
    // Scan left until |R| > 1, then bisect on |R| − 1.
    let mut x = 0.0;
    while r(x - 1e-3).abs() <= 1.0 {
        x -= 1e-3;
    }
    bisect(|y| r(y).abs() - 1.0, x - 1e-3, x)
}

fn bisect(f: impl Fn(Real) -> Real, mut a: Real, mut b: Real) -> Real {
    let fa = f(a);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if (f(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// RK4 with step `h` from Ω₀(S) over the span, on the plain right-hand side:
/// (left the bound |Ω⊥| ≤ Ω⊥₀ or overflowed, final state).
fn rk4_escapes(top: &SymmetricTop, s: Real, h: Real) -> (bool, State<3>) {
    let w0 = omega0(s);
    let perp0 = w0.xy().norm();
    let rhs = |_t: Real, y: &State<3>| reduced_ale_rhs(top, y);
    let mut rk4 = Rk4::new(0.0, w0, h).unwrap();
    while rk4.t() < SPAN {
        match rk4.step(&rhs, SPAN) {
            Err(IntegrateError::NonFinite { .. }) => return (true, *rk4.y()),
            Err(e) => panic!("unexpected {e}"),
            Ok(()) => {
                if rk4.y().xy().norm() > perp0 {
                    return (true, *rk4.y());
                }
            }
        }
    }
    (false, *rk4.y())
}

#[test]
fn row3_holds_the_naive_methods_fail_and_radau5_succeeds() {
    let row = measured().row();
    assert_eq!(row.number, 3);
    assert!(
        row.naive.len() >= 2 && row.naive.iter().all(|o| !o.ok),
        "{row:#?}"
    );
    assert!(
        !row.fix.is_empty() && row.fix.iter().all(|o| o.ok),
        "{row:#?}"
    );
    assert!(row.holds());
}

#[test]
fn row3_rk4_above_its_limit_leaves_the_closed_form_bound_and_below_it_decays() {
    let m = measured();
    let top = SymmetricTop::figure();
    for limit in &m.rk4 {
        let s = limit.s;
        let (escaped, _) = rk4_escapes(&top, s, 1.02 * limit.h_star);
        assert!(escaped, "S = {s}: RK4 at 1.02 h* stayed bounded");
        let (escaped, y) = rk4_escapes(&top, s, 0.98 * limit.h_star);
        assert!(!escaped, "S = {s}: RK4 at 0.98 h* left the bound");
        // Stable means it decays with the true solution: the closed form has
        // fallen below 1 % of Ω⊥₀ by the end of the span, and so has RK4.
        let w0 = omega0(s);
        assert!(reduced_amplitude(&top, &w0, SPAN) < 0.01);
        assert!(y.xy().norm() < 0.01 * w0.xy().norm(), "S = {s}: {y}");
        assert_eq!(y.z, w0.z, "Ω₃ is constant under (4.14)");
    }
    // The row's own failing run is real: above the limit RK4 overflows.
    let above = &m.rk4_above;
    assert_eq!(above.h, ABOVE * m.rk4.last().unwrap().h_star);
    assert!(matches!(
        above.failure,
        Some(IntegrateError::NonFinite { .. })
    ));
    assert!(above.t_left_envelope.is_some());
}

#[test]
fn row3_rk4_limit_falls_like_s_minus_2_inside_the_linear_stability_bracket() {
    let m = measured();
    assert_eq!(
        m.rk4.iter().map(|l| l.s).collect::<Vec<_>>(),
        RK4_LADDER.to_vec()
    );
    assert!(
        (m.rk4_exponent + 2.0).abs() <= 0.1,
        "h* ~ S^{}",
        m.rk4_exponent
    );
    // Independent fit from the two largest S.
    let (a, b) = (&m.rk4[1], &m.rk4[2]);
    let slope = (b.h_star / a.h_star).ln() / (b.s / a.s).ln();
    assert!((slope + 2.0).abs() <= 0.02, "slope {slope}");
    // Linear stability with the asymptotic eigenvalues (valid once
    // τΩ² ≫ Ω̃₃, i.e. S ≥ 100): the amplitude mode at the start has
    // λ = −τ(3Ω⊥₀² + k²), the late modes −τk² (± a rotation that is
    // negligible here). With RK4's real interval [x*, 0], x* ≈ −2.785:
    // x*/λ_start ≤ h* ≤ x*/λ_late.
    let x_star = rk4_real_boundary();
    assert!((x_star + 2.7853).abs() < 1e-3);
    let top = SymmetricTop::figure();
    for l in m.rk4.iter().filter(|l| l.s >= 100.0) {
        let w0 = omega0(l.s);
        let k = top.ratio() * w0.z;
        let perp2 = w0.xy().norm_squared();
        let lambda_start = -top.tau() * (3.0 * perp2 + k * k);
        let lambda_late = -top.tau() * k * k;
        let (lo, hi) = (x_star / lambda_start, x_star / lambda_late);
        assert!(
            0.98 * lo <= l.h_star && l.h_star <= hi,
            "S = {}: h* = {:e} outside [{lo:e}, {hi:e}]",
            l.s,
            l.h_star
        );
        // The row's own linear limits agree with these asymptotic ones.
        assert!((l.h_linear_start / lo - 1.0).abs() < 0.01);
        assert!((l.h_linear_late / hi - 1.0).abs() < 0.01);
    }
}

#[test]
fn row3_dp5_steps_grow_faster_than_s_and_follow_its_stability_interval() {
    let m = measured();
    let steps: Vec<u64> = m.dp5.iter().map(|r| r.stats.steps).collect();
    assert_eq!(m.dp5.len(), LADDER.len());
    // The work grows with S, and at least linearly at the stiff end (S = 100
    // to 1000); at S ≤ 10 DP5 is held by accuracy, not stability.
    assert!(steps.windows(2).all(|w| w[1] > w[0]), "steps {steps:?}");
    let (a, b) = (&m.dp5[2], &m.dp5[3]);
    assert!(
        b.stats.steps as Real / a.stats.steps as Real >= b.s / a.s,
        "steps {steps:?}"
    );
    assert!(m.dp5_exponent >= 1.0, "steps ~ S^{}", m.dp5_exponent);
    // At S = 1000 DP5 is held at its stability limit for the late
    // eigenvalue −τk²: about τk²·T/3.307 steps.
    let top = SymmetricTop::figure();
    let last = m.dp5.last().unwrap();
    let k = top.ratio() * omega0(last.s).z;
    let predicted = top.tau() * k * k * SPAN / -dp5_real_boundary();
    let ratio = last.stats.steps as Real / predicted;
    assert!(
        (0.95..=1.3).contains(&ratio),
        "DP5 took {} steps, stability predicts {predicted:.0}",
        last.stats.steps
    );
    // Under the budget it runs out well before the end of the span.
    let b = &m.dp5_budgeted;
    assert!(
        matches!(b.failure, Some(IntegrateError::TooManySteps { max_steps, .. }) if max_steps == BUDGET)
    );
    assert!(b.t_reached < 0.5 * SPAN);
}

#[test]
fn row3_radau5_takes_few_steps_at_every_s_and_matches_the_closed_form() {
    let top = SymmetricTop::figure();
    let mut steps = Vec::new();
    for &s in &LADDER {
        let w0: Vec3 = omega0(s);
        let opts = AdaptiveOptions::new(RTOL, RTOL * w0.amax()).unwrap();
        let mut radau = Radau5::new(0.0, w0, opts).unwrap();
        let rhs = ReducedAle(top);
        let mut err: Real = 0.0;
        while radau.t() < SPAN {
            radau.step(&rhs, SPAN).unwrap();
            let exact = reduced_closed_form(&top, &w0, radau.t());
            err = err.max((radau.y() - exact).amax() / w0.amax());
        }
        assert!(err <= 10.0 * RTOL, "S = {s}: error {err:e}");
        assert!(radau.stats().steps <= 60, "S = {s}: {:?}", radau.stats());
        steps.push(radau.stats().steps);
    }
    // Flat in S: the largest S costs no more than twice the first stiff one.
    assert!(steps[3] <= 2 * steps[1], "steps {steps:?}");
    // The row reports the same kind of run.
    let m = measured();
    assert!(m.radau5.iter().all(|r| r.run.accurate()));
    assert!(
        m.radau5_exponent.abs() < 0.3,
        "steps ~ S^{}",
        m.radau5_exponent
    );
    assert!(m.splitting.is_empty() || m.splitting.iter().all(|r| r.accurate()));
}

/// The second fix: the reduced flow split into its rotation and its damping,
/// each solved exactly. The two commute, so ten steps over the span land on the
/// closed form (4.15)–(4.16) to rounding at every S, stiff or not, while DP5
/// needs ~S² steps.
#[test]
fn eq_4_12_row3_exact_splitting_takes_ten_steps_at_every_scale() {
    let m = measured();
    assert_eq!(m.splitting.len(), m.dp5.len());
    for (split, dp5) in m.splitting.iter().zip(&m.dp5) {
        assert_eq!(split.s, dp5.s);
        assert_eq!(
            split.stats.steps,
            spintop::stability::stiffness::SPLIT_STEPS
        );
        assert!(split.failure.is_none());
        assert!(
            split.max_error < 1e-13,
            "S = {}: {:e}",
            split.s,
            split.max_error
        );
    }
    let last = m.splitting.last().unwrap();
    assert!(m.dp5.last().unwrap().stats.steps > 1000 * last.stats.steps);
}
