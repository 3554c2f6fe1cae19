//! The stability suite, one test per row: each asserts that the naive method
//! really fails and that spintop's method succeeds, against closed forms,
//! invariants, independent predictions or documented high-precision values,
//! never against numbers the code printed.
//!
//! Rows 3 and 4 (stiffness, long runs) live in `tests/numerics/stability_stiffness.rs`
//! and `tests/numerics/stability_long_run.rs`.

use spintop::physics::shell::Regime;
use spintop::stability::{closed_forms, delay, pole, runaway};

/// Row 1. Forward integration of (3.4) runs away at the frozen rate (the
/// notes: 1.025); backward shooting stays bounded, sits on the slow manifold
/// closer than the reduced model, and drifts from the reduced model as the
/// series says: the precession rate differs at O(τ²), the decay rate at O(τ³).
/// With τk = 1 the reduced model's decay is wrong by orders of magnitude.
#[test]
fn eq_3_4_row_1_forward_runs_away_backward_and_reduced_do_not() {
    let m = runaway::measure().unwrap();
    let r = m.forward.expect("the runaway is detected");
    assert!((m.frozen_rate - 1.025).abs() < 5e-4, "{}", m.frozen_rate);
    assert!((r.growth_rate / m.frozen_rate - 1.0).abs() < 0.05, "{r}");
    assert!(r.t < 10.0, "{r}");

    // The physical solution never grows (|z| decays monotonically).
    assert!(m.physical_max_growth <= 1.0 + 1e-12);
    // On the slow manifold: the series (through τ⁵) misses by its next term,
    // 12τ⁶ks(11k⁴ + 26k²u + 13u²) in the precession (s = u + k²; the book's
    // `auto` section derives the series), within a factor 2; the reduced
    // model by 2τ²ks.
    let (k, u): (f64, f64) = (0.4 * 0.2, 0.01);
    let s = u + k * k;
    let next = 12.0 * k * s * (11.0 * k.powi(4) + 26.0 * k * k * u + 13.0 * u * u);
    assert!(
        m.physical_off_manifold < 2.0 * next && m.physical_off_manifold > 0.5 * next,
        "{:e} vs {next:e}",
        m.physical_off_manifold
    );
    assert!((m.reduced_off_manifold / (2.0 * k * s) - 1.0).abs() < 0.15);

    // Drift: through O(τ) they agree; the phase slips at the O(τ²) precession
    // difference −2τ²k s (within its next term, ~11%); the amplitude ratio grows
    // at the O(τ³) decay difference, 5τ³k⁴ at late times (u ≪ k²).
    let d1 = m.drift[0];
    assert_eq!(d1.t, 1.0);
    assert!((d1.amplitude_ratio - 1.0).abs() < 2e-3);
    assert!((d1.phase_difference / (-2.0 * k * s) - 1.0).abs() < 0.15);
    let late: Vec<_> = m.drift.iter().filter(|d| d.t >= 300.0).collect();
    let slope = (late[1].amplitude_ratio / late[0].amplitude_ratio).ln() / (late[1].t - late[0].t);
    assert!((slope / (5.0 * k.powi(4)) - 1.0).abs() < 0.1, "{slope:e}");

    // τk = 1: the late decay rate 1/σ_phys from the slow root, checked by the
    // integrated physical solution (u₀ = 1e-4 ≪ k², linear regime), and
    // the reduced model's e^{−τk²t} is 1e6 times too small by t = 20.
    let ss = m.strong_spin;
    assert_eq!(ss.tau_k, 1.0);
    let slow = runaway::slow_root(&m.top, ss.omega0.z);
    assert!((ss.physical_decay_rate + slow.re).abs() < 1e-12);
    let predicted = (-ss.physical_decay_rate * ss.t).exp();
    assert!(
        (ss.physical_amplitude / predicted - 1.0).abs() < 0.02,
        "{} vs {predicted}",
        ss.physical_amplitude
    );
    assert!(ss.reduced_amplitude < 1e-5 * ss.physical_amplitude);
    assert!(m.row().holds());
}

/// Row 2. (4.8) cannot start on the pole and, with the crate's fixed step,
/// loses the orientation when started near it; DOP853 copes near the pole
/// but pays for it. On SO(3) both methods are accurate from the pole itself.
#[test]
fn eq_4_8_row_2_euler_angles_fail_at_the_pole_so3_does_not() {
    let m = pole::measure().unwrap();
    let at_pole = &m.euler[0];
    assert_eq!(at_pole.theta0, 0.0);
    assert_eq!(
        at_pole.result,
        Err(spintop::integrate::IntegrateError::NonFinite { t: 0.0 })
    );
    let rk4 = |theta0: f64| {
        m.euler
            .iter()
            .find(|r| r.method.starts_with("RK4") && r.theta0 == theta0)
            .unwrap()
    };
    let dop = |theta0: f64| {
        m.euler
            .iter()
            .find(|r| r.method == "DOP853" && r.theta0 == theta0)
            .unwrap()
    };
    for theta0 in [1e-5, 1e-8] {
        assert!(*rk4(theta0).result.as_ref().unwrap() > 1e-4);
    }
    // Away from the pole the same RK4 is fine: the failure is the pole's.
    assert!(*rk4(1e-2).result.as_ref().unwrap() < 1e-7);
    // DOP853 stays accurate but its work grows as the start nears the pole,
    // and exceeds twice what SO(3) needs from the pole itself.
    let evals: Vec<u64> = [1e-2, 1e-5, 1e-8]
        .iter()
        .map(|&t0| dop(t0).rhs_evals)
        .collect();
    assert!(evals[0] < evals[1] && evals[1] < evals[2], "{evals:?}");
    let so3_dop = m.so3.iter().find(|s| s.0 == "DOP853").unwrap();
    assert!(evals[2] > 2 * so3_dop.2);
    for (name, error, _) in &m.so3 {
        assert!(*error < 1e-9, "{name}: {error:e}");
    }
    assert!(m.row().holds());
}

#[allow(clippy::excessive_precision)] // the mpmath digits are kept as printed
/// Row 5. The printed (4.9) and (4.16) return 0 or lose digits where the
/// careful forms stay exact; checked against 60-digit mpmath values (the
/// script and the values are in tests/physics/closed_forms.rs: REFS[7] and REFS[6]),
/// and against the series ϑ = t(1 − x/2 + …) at x = 1e-20.
#[test]
fn eq_4_9_eq_4_16_row_5_printed_closed_forms_fail_careful_forms_do_not() {
    let m = closed_forms::measure().unwrap();
    let [vartheta, overflow, slow] = m.cases.as_slice() else {
        panic!("three cases");
    };
    assert_eq!(vartheta.printed, 0.0, "R - 1 loses every digit");
    assert!(vartheta.careful_error() < 1e-15);
    assert_eq!(overflow.printed, 0.0, "beta e^(2t/sigma) overflows");
    let mpmath_overflow = 4.333372109644324623e-218; // REFS[7].phi_amp
    assert!((overflow.careful / mpmath_overflow - 1.0).abs() < 1e-12);
    assert!((overflow.reference / mpmath_overflow - 1.0).abs() < 1e-12);
    let mpmath_slow = 0.0006558896830372125927; // REFS[6].phi_amp
    assert!((slow.printed / mpmath_slow - 1.0).abs() > 1e-11);
    assert!((slow.careful / mpmath_slow - 1.0).abs() < 1e-14);
    assert!((slow.reference / mpmath_slow - 1.0).abs() < 1e-14);
    assert!(m.row().holds());
}

/// Row 6. (A.1) with m₀ < m_em grows at the rate its characteristic roots
/// predict (to 5%), known before the first step; a larger shell is stable.
/// `spintop shell` prints the warning before any output.
#[test]
fn eq_a_1_row_6_delay_equation_grows_as_predicted_and_is_warned() {
    let m = delay::measure().unwrap();
    assert!(m.m0 < m.m_em);
    assert_eq!(m.regime, Regime::GrowingOscillation);
    assert!((m.measured_rate / m.predicted_rate - 1.0).abs() < 0.05);
    // Independent of the root search: the chain asymptote ln(m_em/m₀)/δ.
    assert!(((m.m_em / m.m0).ln() / m.delta / m.measured_rate - 1.0).abs() < 0.05);
    assert!(m.unstable_peak > 1e6);
    assert_eq!(m.stable_regime, Regime::Stable);
    assert!(m.stable_peak < 1e-3);
    assert!(m.row().holds());
}
