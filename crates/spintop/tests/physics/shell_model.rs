//! The appendix's shell model (A.1)–(A.3) as a delay equation: the solver
//! reproduces exact modes, the acceleration jumps as the equation says, the
//! exact flux identity behind (A.2) holds, L − J tends to the Schott term
//! (A.3), the solution converges to the Abraham–Lorentz physical one as the
//! delay shrinks (phase like δ, angular momentum like δ² to leading order in
//! τ₀), and the three stability regimes of a neutral delay equation appear
//! where the characteristic roots say, with the growth rate they predict.

use nalgebra::Complex;
use spintop::physics::central::abraham_lorentz_oscillator_roots;
use spintop::physics::shell::{C, CHAIN_SEARCH, Regime, ShellModel};
use spintop::sim::shell::{History, ShellSample, ShellSolver, default_steps_per_delay, run_shell};

fn model(tau0: f64, delta: f64) -> ShellModel {
    ShellModel::new(tau0, delta).expect("valid parameters")
}

fn run(tau0: f64, delta: f64, history: History, times: &[f64]) -> Vec<ShellSample> {
    run_shell(
        model(tau0, delta),
        history,
        default_steps_per_delay(delta),
        times,
    )
    .expect("the run stays finite")
}

fn c(v: [f64; 2]) -> C {
    Complex::new(v[0], v[1])
}

fn order(e1: f64, e2: f64, d1: f64, d2: f64) -> f64 {
    (e1 / e2).ln() / (d1 / d2).ln()
}

/// With an exact mode e^{st} of (A.1) as history there is no jump at t = 0,
/// and the solution must stay on the mode. With the Abraham–Lorentz mode as
/// history (not a root of (A.1)) it must not: the check can fail.
#[test]
fn eq_a_1_exact_mode_is_reproduced_to_1e_10() {
    for (tau0, delta) in [(1e-3, 0.1), (1e-3, 0.03), (0.03, 0.1), (0.01, 0.5)] {
        let m = model(tau0, delta);
        let s = m.root_near_al().expect("a root near s_AL");
        assert!(
            m.characteristic(s).norm() < 1e-13,
            "P(s) = {}",
            m.characteristic(s)
        );
        let times = [0.37, 5.0, 13.1, 20.0];
        for sample in run(tau0, delta, History::mode(s), &times) {
            let exact = (s * sample.t).exp();
            let err = (c(sample.z) - exact).norm() + (c(sample.z_dot) - exact * s).norm();
            assert!(
                err < 1e-10,
                "tau0 {tau0}, delta {delta}, t {}: {err:e}",
                sample.t
            );
        }
        let off = run(tau0, delta, History::abraham_lorentz(tau0), &[20.0])[0];
        let miss = (c(off.z) - (s * 20.0).exp()).norm();
        assert!(
            miss > 1e-6,
            "the AL history should leave the shell mode: {miss:e}"
        );
    }
}

/// Z is continuous and (A.1) fixes Z'' from Z''(t − δ), so the jump of Z'' at
/// t = nδ is the jump at (n − 1)δ times −m_em/m₀.
#[test]
fn eq_a_1_acceleration_jumps_scale_by_minus_m_em_over_m0() {
    for (tau0, delta) in [(1e-3, 0.1), (0.06, 0.1), (0.03, 0.05)] {
        let m = model(tau0, delta);
        let ratio = -m.m_em() / m.m0();
        let mut solver = ShellSolver::new(m, History::abraham_lorentz(tau0), 64).expect("solver");
        let mut jump = solver.jump();
        // The first jump: the history's Z'' at 0⁻ against (A.1) at 0⁺.
        let h = History::abraham_lorentz(tau0);
        let expected0 = m.acceleration(h.jet(0.0).z, h.jet(-delta).z_ddot) - h.jet(0.0).z_ddot;
        assert!((jump - expected0).norm() < 1e-15);
        for _ in 0..10 {
            solver.advance().unwrap();
            let next = solver.jump();
            // Each jump is a difference of two accelerations of size |Z''|, so
            // it carries their rounding.
            let tol = 1e-9 * jump.norm() + 1e-14 * solver.current()[0].z_ddot.norm();
            assert!(
                (next - jump * ratio).norm() <= tol,
                "{next} vs {}",
                jump * ratio
            );
            jump = next;
        }
    }
}

/// dJ/dt = m_em Im(conj(Z(t − δ) − Z(t)) Z''(t − δ)) exactly; integrated with
/// Simpson's rule it matches J(t) − J(0) to 1e-10, on and off the grid, for
/// stable and unstable runs (relative to the size of J in the latter).
#[test]
fn eq_a_2_exact_flux_identity_holds_to_1e_10() {
    let times = [0.0, 0.05, 0.1, 1.234_567, 7.0, 20.0];
    for (tau0, delta) in [(1e-3, 0.1), (1e-3, 0.01), (0.03, 0.1), (0.01, 0.5)] {
        for s in run(tau0, delta, History::abraham_lorentz(tau0), &times) {
            let residual = s.j_change - s.flux_exact;
            assert!(
                residual.abs() < 1e-10,
                "tau0 {tau0}, delta {delta}, t {}: {residual:e}",
                s.t
            );
        }
    }
    // Unstable: J grows like e^{4.08 t}; the identity holds relative to it.
    for s in run(0.06, 0.1, History::abraham_lorentz(0.06), &[0.5, 1.0, 3.0]) {
        let residual = s.j_change - s.flux_exact;
        assert!(
            residual.abs() < 1e-10 * (1.0 + s.j.abs()),
            "t {}: {residual:e}",
            s.t
        );
    }
}

/// The paper's right-hand side of (A.2) replaces Z − Z_ret by δŻ_ret. The δ²Z̈
/// term drops out of Im(conj(·) Z̈_ret), so the error starts at δ³Z⃛/6:
/// d(exact − paper)/dt = τ₀δ²/6 |Z|² on the circular mode, O(r₀²).
#[test]
fn eq_a_2_paper_right_hand_side_is_off_by_tau0_delta_squared() {
    let (tau0, t) = (1e-3, 20.0);
    let mut misses = Vec::new();
    for delta in [0.1, 0.03, 0.01] {
        let s = run(tau0, delta, History::abraham_lorentz(tau0), &[t])[0];
        let miss = s.j_change - s.flux_paper;
        // ∫₀ᵗ |Z|² dt = (1 − e^{−τ₀t})/τ₀ for |Z|² = e^{−τ₀t}.
        let predicted = tau0 * delta * delta / 6.0 * (1.0 - (-tau0 * t).exp()) / tau0;
        assert!(
            (miss / predicted - 1.0).abs() < 0.02,
            "delta {delta}: {miss:e} vs {predicted:e}"
        );
        misses.push((delta, miss));
    }
    let p = order(misses[0].1, misses[2].1, misses[0].0, misses[2].0);
    assert!((p - 2.0).abs() < 0.02, "order {p}");
}

/// L − J = m_em (l(t) − l(t − δ)) = τ₀ l̇ − τ₀δ l̈/2 + …: the Schott angular
/// momentum τ₀L̇ of (A.3), here −τ₀²L at leading order (L decays at τ₀).
#[test]
fn eq_a_3_l_minus_j_tends_to_the_schott_term() {
    let tau0 = 1e-3;
    for delta in [0.1, 0.03, 0.01] {
        for s in run(tau0, delta, History::abraham_lorentz(tau0), &[5.0, 20.0]) {
            assert!(
                (s.l_minus_j - s.l_schott).abs() < 1e-4 * s.l_schott.abs(),
                "delta {delta}, t {}: {} vs {}",
                s.t,
                s.l_minus_j,
                s.l_schott
            );
            assert!((s.l_schott / (-tau0 * tau0 * s.l) - 1.0).abs() < 0.01);
        }
    }
}

/// Expanding e^{−sδ} in P(s) gives s² + 1 − τ₀s³ + τ₀δs⁴/2 − τ₀δ²s⁵/6 + … = 0,
/// so the root moves from s_AL by iτ₀δ/4 + τ₀δ²/12 − 3τ₀²δ/4 + …: imaginary at
/// leading order (a phase error growing like δ·t), with a real part that has
/// the zero near δ = 9τ₀.
#[test]
fn appendix_root_near_al_shifts_by_i_tau0_delta_over_4() {
    let tau0 = 1e-3;
    for delta in [0.1, 0.03, 0.01, 0.003] {
        let s = model(tau0, delta).root_near_al().unwrap();
        let ds = s - abraham_lorentz_oscillator_roots(tau0).0;
        assert!((ds.im / (tau0 * delta / 4.0) - 1.0).abs() < 1e-3, "{ds}");
        let re = tau0 * delta * delta / 12.0 - 0.75 * tau0 * tau0 * delta;
        assert!(
            (ds.re - re).abs() < 0.02 * re.abs(),
            "delta {delta}: {} vs {re:e}",
            ds.re
        );
    }
}

/// τ₀ = 1e-3, δ ∈ {0.1, 0.03, 0.01}, t = 20: |Z − Z_AL| falls like δ (the
/// phase error τ₀δt/4), |L − L_AL| at least like δ². The L error is
/// 2t L (τ₀δ²/12 − 3τ₀²δ/4): quadratic in δ to leading order in τ₀, and since
/// stability needs δ > 2τ₀ the second term never takes over (below 9τ₀ it
/// only bends the curve). At τ₀ = 1e-5 the order is 2.00.
#[test]
fn appendix_converges_to_abraham_lorentz_phase_order_1_angular_momentum_order_2() {
    let t = 20.0;
    let errors = |tau0: f64, deltas: &[f64]| -> Vec<(f64, f64, f64)> {
        deltas
            .iter()
            .map(|&d| {
                let s = run(tau0, d, History::abraham_lorentz(tau0), &[t])[0];
                (d, c(s.z_minus_z_al).norm(), (s.l - s.l_al).abs())
            })
            .collect()
    };
    let tau0 = 1e-3;
    let e = errors(tau0, &[0.1, 0.03, 0.01]);
    for w in e.windows(2) {
        let pz = order(w[0].1, w[1].1, w[0].0, w[1].0);
        let pl = order(w[0].2, w[1].2, w[0].0, w[1].0);
        assert!((pz - 1.0).abs() < 0.02, "phase order {pz}");
        assert!(pl > 1.95, "angular momentum order {pl}");
    }
    for &(d, ez, el) in &e {
        assert!(
            (ez / (tau0 * d * t / 4.0) - 1.0).abs() < 0.05,
            "delta {d}: {ez:e}"
        );
        let l = (-tau0 * t).exp();
        let predicted = 2.0 * t * l * (tau0 * d * d / 12.0 - 0.75 * tau0 * tau0 * d);
        assert!(
            (el / predicted.abs() - 1.0).abs() < 0.03,
            "delta {d}: {el:e} vs {predicted:e}"
        );
    }
    let e = errors(1e-5, &[0.1, 0.03, 0.01]);
    for w in e.windows(2) {
        let pl = order(w[0].2, w[1].2, w[0].0, w[1].0);
        assert!(
            (pl - 2.0).abs() < 0.05,
            "angular momentum order {pl} at tau0 = 1e-5"
        );
    }
}

/// τ₀ = 0.06, δ = 0.1: m_em = 0.6 > m₀ = 0.4. The deviation from the
/// Abraham–Lorentz motion, measured by its largest size over two windows of
/// one time unit, grows at ln(m_em/m₀)/δ = 4.05 within 5%.
#[test]
fn appendix_growth_rate_is_observed_within_5_percent() {
    let (tau0, delta) = (0.06, 0.1);
    let m = model(tau0, delta);
    let predicted = (m.m_em() / m.m0()).ln() / delta;
    assert!((predicted - 1.5_f64.ln() / 0.1).abs() < 1e-12);
    let window = |a: f64| -> Vec<f64> { (0..=400).map(|k| a + k as f64 / 400.0).collect() };
    let peak = |a: f64| {
        run(tau0, delta, History::abraham_lorentz(tau0), &window(a))
            .iter()
            .map(|s| c(s.z_minus_z_al).norm())
            .fold(0.0, f64::max)
    };
    let (t1, t2) = (2.0, 6.0);
    let measured = (peak(t2) / peak(t1)).ln() / (t2 - t1);
    assert!(
        (measured / predicted - 1.0).abs() < 0.05,
        "measured {measured}, predicted {predicted}"
    );
    // And the root search's growth rate (the lowest chain root) is what is seen.
    let root = m.growth_rate().expect("unstable");
    assert!(
        (measured / root - 1.0).abs() < 0.02,
        "measured {measured}, root {root}"
    );
}

/// Stable for m₀ > m_em (up to a strip of width kδ²/π²), growing oscillation for
/// 0 < m₀ < m_em, a real runaway for m₀ < 0, which tends to the
/// Abraham–Lorentz runaway 1/τ₀ as δ → 0.
#[test]
fn appendix_stability_separates_the_three_regimes() {
    let delta = 0.1;
    // Stable: every root in the left half plane; the chain decays at ln(m₀/m_em)/δ.
    let stable = model(1e-3, delta);
    assert_eq!(stable.regime(), Regime::Stable);
    assert!(stable.growth_rate().is_none());
    assert!(stable.chain_rate() < 0.0);
    let s = run(1e-3, delta, History::abraham_lorentz(1e-3), &[20.0])[0];
    assert!(c(s.z_minus_z_al).norm() < 1e-3);

    // Growing oscillation: 0 < m₀ < m_em, a chain of complex roots near
    // (ln(m_em/m₀) + (2n + 1)πi)/δ, the lowest slightly faster.
    let growing = model(0.06, delta);
    assert_eq!(growing.regime(), Regime::GrowingOscillation);
    let rate = growing.growth_rate().unwrap();
    assert!(rate > growing.chain_rate() && rate < 1.01 * growing.chain_rate());
    let lowest = growing.chain_root(0).unwrap();
    assert!((lowest.im * delta / std::f64::consts::PI - 1.0).abs() < 0.01);
    assert!(growing.runaway_root().is_none());

    // Runaway: m₀ < 0 (δ < τ₀), a real positive root.
    for (tau0, d) in [(1e-3, 5e-4), (1e-3, 1e-5), (1e-3, 1e-7)] {
        let runaway = model(tau0, d);
        assert_eq!(runaway.regime(), Regime::Runaway);
        let r = runaway.runaway_root().unwrap();
        assert_eq!(runaway.chain_root(0).unwrap().im, 0.0);
        assert_eq!(runaway.growth_rate(), Some(r));
        if d <= 1e-5 {
            let al = abraham_lorentz_oscillator_roots(tau0).1;
            assert!((r / al - 1.0).abs() < d / tau0, "{r} vs AL {al}");
        }
    }

    // The strip: with the force the lowest chain root crosses Re s = 0 at
    // m₀ − m_em = δ²/π², not at m₀ = m_em.
    let threshold = delta * delta / std::f64::consts::PI.powi(2);
    let tau0_for = |gap: f64| delta * (1.0 - gap) / 2.0; // m₀ − m_em = 1 − 2τ₀/δ
    assert_eq!(
        model(tau0_for(2.0 * threshold), delta).regime(),
        Regime::Stable
    );
    let inside = model(tau0_for(0.5 * threshold), delta);
    assert_eq!(inside.regime(), Regime::GrowingOscillation);
    assert!(
        inside.chain_rate() < 0.0,
        "the asymptotic chain still decays"
    );
    assert_eq!(
        model(tau0_for(0.0), delta).regime(),
        Regime::GrowingOscillation
    );
}

/// The root search finds the largest Re s: searching 200 chain members gives
/// the same answer as the CHAIN_SEARCH used, and every root found is a root.
#[test]
fn appendix_chain_search_finds_the_largest_root() {
    for (tau0, delta) in [
        (1e-3, 0.1),
        (0.06, 0.1),
        (0.05, 0.1),
        (0.3, 1.0),
        (1e-3, 5e-4),
        (0.9, 0.5),
    ] {
        let m = model(tau0, delta);
        let wide = m.roots(200);
        assert!(wide.len() >= 150, "found {} roots", wide.len());
        for s in &wide {
            let scale = s.norm_sqr() * (m.m0().abs() + m.m_em() * (-s.re * delta).exp()) + 1.0;
            assert!(m.characteristic(*s).norm() < 1e-10 * scale, "{s}");
        }
        let max_wide = wide.iter().map(|s| s.re).fold(f64::NEG_INFINITY, f64::max);
        let max_narrow = m
            .roots(CHAIN_SEARCH)
            .iter()
            .map(|s| s.re)
            .fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(max_wide, max_narrow, "tau0 {tau0}, delta {delta}");
    }
}

/// The chapter's electron number: stability needs δ = r₀/c > 2τ₀, i.e. a shell
/// larger than 2cτ₀ = (4/3) r_e ≈ 3.76e-15 m, since τ₀ = (2/3) r_e/c.
#[test]
fn appendix_electron_shell_must_exceed_four_thirds_classical_radius() {
    use spintop::physics::central::{
        CLASSICAL_ELECTRON_RADIUS_M, SPEED_OF_LIGHT_M_S, electron_tau0_seconds,
    };
    let r_min = 2.0 * SPEED_OF_LIGHT_M_S * electron_tau0_seconds();
    assert!((r_min / CLASSICAL_ELECTRON_RADIUS_M - 4.0 / 3.0).abs() < 1e-12);
    assert!((r_min - 3.757e-15).abs() < 1e-18, "{r_min:e}");
}
