//! Section 2's charge in a central field, (2.5)–(2.9), with m = k = 1.
//!
//! Pins down: the balance laws (2.6)–(2.8) along real Abraham–Lorentz motion
//! (L̇ and L̈ by finite differences of the integrated orbit); the corrected
//! (2.9), which holds at every instant under Landau–Lifshitz while the printed
//! dV/dt version does not; the Coulomb circular collapse r³ = r₀³ − 6τ₀t against
//! full integration; the orbit-averaged elliptic decay and its invariant
//! a(1 − e²)e^{−4/3}; the hydrogen collapse time in seconds; the oscillator's
//! roots (references from mpmath at 40 digits: `polyroots([tau, -1, 0, -1])`);
//! the forward runaway of (2.5) and its absence in backward integration.

// NOTE: the mpmath references keep more digits than an f64 holds, as printed.
#![allow(clippy::excessive_precision)]

use approx::assert_relative_eq;
use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::State;
use spintop::physics::central::*;
use spintop::sim::orbit::{Force, OrbitConfig, run_orbit};

fn opts(rtol: f64) -> AdaptiveOptions {
    AdaptiveOptions::new(rtol, rtol * 1e-3).unwrap()
}

fn coulomb(tau0: f64) -> ChargeInField {
    ChargeInField::new(Potential::Coulomb, tau0).unwrap()
}

fn harmonic(tau0: f64) -> ChargeInField {
    ChargeInField::new(Potential::Harmonic, tau0).unwrap()
}

/// (2.6)–(2.8) along forward Abraham–Lorentz motion (short enough that the
/// runaway is still small): L̇ and L̈ by central differences of the integrated L.
#[test]
fn eq_2_6_to_2_8_hold_along_abraham_lorentz_motion() {
    let q = coulomb(0.05);
    let rhs = |_t: f64, y: &State<6>| abraham_lorentz_rhs(&q, y);
    let y0 = State::<6>::new(1.0, 0.0, 0.1, 1.0, -1.0, 0.0);
    // NOTE: the runaway makes L⃛ ~ L̇/τ₀², so the difference error is
    // h²/(6τ₀²) ≈ 7e-7 relative with h = 1e-4.
    let h = 1e-4;
    let times: Vec<f64> = [0.1, 0.2, 0.3]
        .iter()
        .flat_map(|&t| [t - h, t, t + h])
        .collect();
    let mut stepper = Dop853::new(0.0, y0, opts(1e-13)).unwrap();
    let ys = solve(&mut stepper, &rhs, &times).unwrap();
    let l = |y: &State<6>| {
        let (p, v) = pos_vel(y);
        angular_momentum(&p, &v)
    };
    for c in ys.chunks(3) {
        let (ym, y, yp) = (&c[0], &c[1], &c[2]);
        let l_dot = (l(yp) - l(ym)) / (2.0 * h);
        let l_ddot = (l(yp) - 2.0 * l(y) + l(ym)) / (h * h);
        let (p, v) = pos_vel(y);
        let a = nalgebra::Vector2::new(y[4], y[5]);
        let f = rhs(0.0, y);
        let jerk = nalgebra::Vector2::new(f[4], f[5]);
        let torque = torque_2_6(q.tau0(), &p, &jerk);
        assert_relative_eq!(l_dot, torque, max_relative = 1e-5);
        let schott = schott_term_2_7(q.tau0(), &p, &v, &a, &jerk);
        assert_relative_eq!(q.tau0() * l_ddot, schott, max_relative = 1e-4);
        // (2.7): the torque is the Schott term plus the Larmor-like (2.8).
        assert_relative_eq!(
            torque,
            schott + larmor_2_8(q.tau0(), &v, &a),
            epsilon = 1e-15
        );
    }
}

/// The corrected (2.9), −τ₀(1/r)(dV/dr)L, is the exact instantaneous L̇ of the
/// Landau–Lifshitz orbit; the printed −τ₀(1/r)(dV/dt)L is not (zero at the
/// pericentre, where L̇ is largest).
#[test]
fn eq_2_9_corrected_law_holds_at_every_instant_under_landau_lifshitz() {
    for q in [coulomb(1e-2), harmonic(1e-2)] {
        let rhs = |_t: f64, y: &State<4>| landau_lifshitz_rhs(&q, y);
        let v0 = q.potential().pericentre_speed(1.0, 0.5);
        let y0 = State::<4>::new(1.0, 0.0, 0.0, v0);
        let h = 1e-3;
        let times: Vec<f64> = [0.0 + h, 1.3, 2.9]
            .iter()
            .flat_map(|&t| [t - h, t, t + h])
            .collect();
        let mut stepper = Dop853::new(0.0, y0, opts(1e-13)).unwrap();
        let ys = solve(&mut stepper, &rhs, &times).unwrap();
        let l = |y: &State<4>| {
            let (p, v) = pos_vel(y);
            angular_momentum(&p, &v)
        };
        for c in ys.chunks(3) {
            let l_dot = (l(&c[2]) - l(&c[0])) / (2.0 * h);
            let (p, _) = pos_vel(&c[1]);
            let corrected = eq_2_9_rate(&q, &p, l(&c[1]));
            assert_relative_eq!(l_dot, corrected, max_relative = 1e-6);
        }
        // At the pericentre dV/dt = V'(r) ṙ = 0, so the printed law predicts no loss.
        let (p, v) = pos_vel(&y0);
        let dv_dt = q.potential().dv_dr(p.norm()) * p.dot(&v) / p.norm();
        assert_eq!(dv_dt, 0.0);
        assert!(eq_2_9_rate(&q, &p, angular_momentum(&p, &v)).abs() > 1e-3);
    }
}

/// Full Landau–Lifshitz integration reaches r = 0.5, 0.2, 0.1 within 0.2% of
/// the adiabatic prediction t = (r₀³ − r³)/(6τ₀) for τ₀ = 1e-3.
#[test]
fn eq_2_9_coulomb_circular_collapse_matches_full_integration() {
    let tau0 = 1e-3;
    let config = OrbitConfig::new(coulomb(tau0), 1.0, 0.0, Force::LandauLifshitz).unwrap();
    let run = run_orbit(&config, &[0.0, 100.0, 166.6]).unwrap();
    for c in run.first_crossing.unwrap() {
        let predicted = (1.0 - c.r.powi(3)) / (6.0 * tau0);
        assert_relative_eq!(c.averaged.unwrap(), predicted, max_relative = 1e-15);
        let measured = c.t.expect("reached");
        assert!(
            (measured / predicted - 1.0).abs() < 2e-3,
            "r = {}: {measured} vs {predicted}",
            c.r
        );
    }
    let r100 = run.samples[1].r;
    assert_relative_eq!(
        r100,
        coulomb_circular_radius(tau0, 1.0, 100.0),
        max_relative = 2e-3
    );
    assert_eq!(config.collapse_time(), Some(1.0 / (6.0 * tau0)));
    // Past the collapse the run stops with the time, instead of integrating into r = 0.
    assert!(run_orbit(&config, &[0.0, 200.0]).is_err());
}

/// The averaged (a, e) flow conserves a(1 − e²)e^{−4/3}, and the time it takes
/// from e₀ to e₁ is the closed form behind `coulomb_collapse_time`.
#[test]
fn eq_2_9_averaged_elliptic_decay_conserves_its_invariant() {
    let tau0 = 1e-3;
    let (a0, e0) = (1.0_f64, 0.6_f64);
    let p0 = a0 * (1.0 - e0 * e0);
    let rhs = |_t: f64, y: &State<2>| coulomb_averaged_rhs(tau0, y);
    // t(e) = (2p₀³/(3τ₀e₀⁴)) [I(e₀) − I(e)], I(e) = (1 − √(1 − e²))²/√(1 − e²).
    let i = |e: f64| (1.0 - (1.0 - e * e).sqrt()).powi(2) / (1.0 - e * e).sqrt();
    let t_of = |e: f64| 2.0 * p0.powi(3) / (3.0 * tau0 * e0.powi(4)) * (i(e0) - i(e));
    let times = [t_of(0.4), t_of(0.2), t_of(0.05)];
    let mut stepper = Dop853::new(0.0, State::<2>::new(a0, e0), opts(1e-12)).unwrap();
    let ys = solve(&mut stepper, &rhs, &times).unwrap();
    let inv0 = coulomb_averaged_invariant(a0, e0);
    for (y, e_expected) in ys.iter().zip([0.4, 0.2, 0.05]) {
        assert_relative_eq!(
            coulomb_averaged_invariant(y[0], y[1]),
            inv0,
            max_relative = 1e-9
        );
        assert_relative_eq!(y[1], e_expected, max_relative = 1e-8);
    }
    // t_c is the limit e → 0, and reduces to r₀³/(6τ₀) on a circle.
    assert_relative_eq!(
        coulomb_collapse_time(tau0, p0, e0),
        t_of(0.0),
        max_relative = 1e-14
    );
    assert_relative_eq!(
        coulomb_collapse_time(tau0, 2.0, 0.0),
        8.0 / (6.0 * tau0),
        max_relative = 1e-15
    );
}

/// The full Landau–Lifshitz orbit with e₀ = 0.5 follows the averaged law: its
/// osculating invariant stays put while p itself falls by several percent.
#[test]
fn eq_2_9_full_landau_lifshitz_follows_the_averaged_elliptic_decay() {
    let tau0 = 1e-3;
    let config = OrbitConfig::new(coulomb(tau0), 1.0, 0.5, Force::LandauLifshitz).unwrap();
    let (x0, v0) = config.initial();
    let (a_start, e_start) = osculating_elements(&x0, &v0);
    assert_relative_eq!(a_start, 2.0, max_relative = 1e-14); // a = r₀/(1 − e)
    assert_relative_eq!(e_start, 0.5, max_relative = 1e-14);
    // Sample at pericentre-like times is not needed: the osculating invariant
    // only wobbles at O(τ₀) within an orbit.
    let run = run_orbit(&config, &[0.0, 150.0]).unwrap();
    let end = run.samples[1];
    let (pos, vel) = (
        nalgebra::Vector2::new(end.position[0], end.position[1]),
        nalgebra::Vector2::new(end.velocity[0], end.velocity[1]),
    );
    let (a, e) = osculating_elements(&pos, &vel);
    let p_start = a_start * (1.0 - e_start * e_start);
    let p_end = a * (1.0 - e * e);
    assert!(p_end / p_start < 0.95, "p fell only to {}", p_end / p_start);
    let drift =
        coulomb_averaged_invariant(a, e) / coulomb_averaged_invariant(a_start, e_start) - 1.0;
    assert!(drift.abs() < 5e-3, "invariant drifted by {drift}");
}

/// Hydrogen from the Bohr radius: τ₀ = 6.266e-24 s and t_c = 1.556e-11 s
/// (mpmath, 40 digits, from CODATA 2022 a₀, r_e and c: τ₀ = 2r_e/(3c),
/// t_c = a₀³/(4r_e²c)).
#[test]
fn sec2_hydrogen_collapses_in_sixteen_picoseconds() {
    assert_relative_eq!(
        electron_tau0_seconds(),
        6.266424755533153984e-24,
        max_relative = 1e-15
    );
    assert_relative_eq!(
        bohr_collapse_time_seconds(),
        1.556177462585719502e-11,
        max_relative = 1e-14
    );
}

#[test]
fn eq_2_5_oscillator_roots_match_mpmath() {
    // (τ₀, runaway root, Re s, |Im s|) from mpmath.polyroots at 40 digits.
    let refs = [
        (
            1e-3,
            1000.000999998000007,
            -0.0004999990000034999850,
            0.9999993750018046803780,
        ),
        (
            0.1,
            10.09806713608741849,
            -0.04903356804370924402,
            0.9939236556494045300266,
        ),
        (
            0.5,
            2.359304085971776421,
            -0.1796520429858882104,
            0.9030131458570041866323,
        ),
        (
            1.5,
            1.161137966648159308,
            -0.2472356499907463208,
            0.7162568905078928160,
        ),
    ];
    for (tau0, run, re, im) in refs {
        let (s, s_run) = abraham_lorentz_oscillator_roots(tau0);
        assert_relative_eq!(s_run, run, max_relative = 1e-15);
        assert_relative_eq!(s.re, re, max_relative = 1e-14);
        assert_relative_eq!(s.im, im, max_relative = 1e-15);
    }
}

/// s_AL − s_LL = −(i/2)τ₀² + O(τ₀³): the reduction is right through O(τ₀) only.
#[test]
fn eq_2_5_oscillator_exact_root_differs_from_landau_lifshitz_at_tau0_squared() {
    for tau0 in [1e-2, 1e-3, 1e-4] {
        let (s, _) = abraham_lorentz_oscillator_roots(tau0);
        let diff = (s - landau_lifshitz_oscillator_root(tau0)) / (tau0 * tau0);
        assert!((diff.im + 0.5).abs() < 2.0 * tau0, "tau0 = {tau0}: {diff}");
        assert!(diff.re.abs() < 2.0 * tau0, "tau0 = {tau0}: {diff}");
        // O(τ₀) terms agree: both decay at τ₀/2.
        assert_relative_eq!(s.re, -0.5 * tau0, max_relative = 3.0 * tau0 * tau0);
    }
}

/// The exact solutions built from the roots solve their equations: the
/// Abraham–Lorentz one (2.5) (jerk by differences of the acceleration) and the
/// Landau–Lifshitz one, checked against integration of `landau_lifshitz_rhs`.
#[test]
fn eq_2_5_oscillator_exact_solutions_solve_their_equations() {
    let tau0 = 0.05;
    let (s, _) = abraham_lorentz_oscillator_roots(tau0);
    let (x0, v0) = (
        nalgebra::Vector2::new(1.0, 0.2),
        nalgebra::Vector2::new(-0.3, 1.1),
    );
    let h = 1e-4;
    for t in [0.5, 3.0, 10.0] {
        let (x, _, a) = oscillator_mode(s, &x0, &v0, t);
        let jerk = (oscillator_mode(s, &x0, &v0, t + h).2 - oscillator_mode(s, &x0, &v0, t - h).2)
            / (2.0 * h);
        // m v̇ = F + m τ₀ v̈ with F = −x.
        assert_relative_eq!(a, -x + tau0 * jerk, epsilon = 1e-8);
    }
    let q = harmonic(tau0);
    let s_ll = landau_lifshitz_oscillator_root(tau0);
    let rhs = |_t: f64, y: &State<4>| landau_lifshitz_rhs(&q, y);
    let mut stepper =
        Dop853::new(0.0, State::<4>::new(x0.x, x0.y, v0.x, v0.y), opts(1e-12)).unwrap();
    let ys = solve(&mut stepper, &rhs, &[3.0, 10.0]).unwrap();
    for (y, t) in ys.iter().zip([3.0, 10.0]) {
        let (x, v, _) = oscillator_mode(s_ll, &x0, &v0, t);
        assert_relative_eq!(pos_vel(y).0, x, epsilon = 1e-10);
        assert_relative_eq!(pos_vel(y).1, v, epsilon = 1e-10);
    }
}

/// Forward integration of (2.5) from the Newtonian acceleration runs away at
/// the rate of the real root (oscillator) or 1/τ₀ (Coulomb), within ~20 τ₀.
#[test]
fn eq_2_5_forward_runaway_is_detected_with_its_rate() {
    for (q, tol) in [
        (harmonic(1e-2), 5e-3),
        (coulomb(1e-2), 1e-2),
        (harmonic(1e-3), 5e-3),
    ] {
        let config = OrbitConfig::new(q, 1.0, 0.0, Force::AbrahamLorentzForward).unwrap();
        let run = run_orbit(&config, &[0.0, 1.0, 5.0]).unwrap();
        let r = run.runaway.expect("a runaway");
        let rate = r.growth_rate.expect("measured");
        assert_relative_eq!(rate, r.predicted_rate, max_relative = tol);
        assert!(r.t < 20.0 * q.tau0(), "detected only at {}", r.t);
        assert_eq!(
            run.samples.len(),
            1,
            "samples after the runaway are omitted"
        );
    }
    // The physical solution has no runaway to detect: the LL flow stays bounded.
    let ll = OrbitConfig::new(harmonic(1e-2), 1.0, 0.0, Force::LandauLifshitz).unwrap();
    assert!(run_orbit(&ll, &[0.0, 5.0]).unwrap().runaway.is_none());
}

/// Backward integration of (2.5) damps the runaway: started at T with the
/// wrong (Newtonian) acceleration, it falls within a few τ₀ onto the physical
/// solutions (where v̇ is the function of (r, v) the physical root dictates),
/// while forward integration from the *exact* physical data still runs away.
#[test]
fn eq_2_5_runaway_is_absent_backward() {
    let tau0 = 1e-2;
    let q = harmonic(tau0);
    let (s, _) = abraham_lorentz_oscillator_roots(tau0);
    // The physical acceleration at (x, v): that of the exact mode through them.
    let physical_a =
        |x: &nalgebra::Vector2<f64>, v: &nalgebra::Vector2<f64>| oscillator_mode(s, x, v, 0.0).2;
    let (x0, v0) = (
        nalgebra::Vector2::new(1.0, 0.0),
        nalgebra::Vector2::new(0.0, 1.0),
    );
    let t_final = 5.0;
    let (xf, vf, af) = oscillator_mode(s, &x0, &v0, t_final);
    let newtonian = -xf;
    assert!(
        (newtonian - af).norm() > 5e-3,
        "the final data are off the physical solutions"
    );
    let y_final = State::<6>::new(xf.x, xf.y, vf.x, vf.y, newtonian.x, newtonian.y);
    let rhs = |_t: f64, y: &State<6>| abraham_lorentz_rhs(&q, y);
    // NOTE: one run per time, so each state is at a step end; DOP853's
    // continuous extension between step ends carries ~1e-7 of the damped mode.
    for t in [4.9, 4.0, 2.0, 0.0] {
        let mut back = Dop853::new(t_final, y_final, opts(1e-12)).unwrap();
        let y = &solve(&mut back, &rhs, &[t]).unwrap()[0];
        let (x, v) = pos_vel(y);
        let off = (nalgebra::Vector2::new(y[4], y[5]) - physical_a(&x, &v)).norm();
        // e^{-(T-t)/τ₀}, down to what the last steps leave of the damped
        // mode: DOP853 steps it near its stability limit, where a step damps
        // little, so its size is a matter of where the steps fall. Across
        // rtol 0.9e-12 to 1.2e-12 it was 1e-14 to 2.3e-10 at t = 4 (6.8e-12
        // at t = 0 once, 1.3e-10 at t = 4 once the clock advanced by the
        // rounded step): bounded by 1000 × rtol, 6.6 decades below 5e-3.
        assert!(
            off < 1e-2 * (-(t_final - t) / tau0).exp() + 1e-9,
            "t = {t}: {off}"
        );
        // It is a nearby physical solution: the wrong datum shifted it by O(τ₀²).
        let (x_exact, _, _) = oscillator_mode(s, &x0, &v0, t);
        assert!((x - x_exact).norm() < 3.0 * tau0 * tau0);
    }
    // Forward from the exact physical state: rounding seeds the runaway.
    let (_, _, a0) = oscillator_mode(s, &x0, &v0, 0.0);
    let y0 = State::<6>::new(x0.x, x0.y, v0.x, v0.y, a0.x, a0.y);
    let mut fwd = Dop853::new(0.0, y0, opts(1e-12)).unwrap();
    let y = solve(&mut fwd, &rhs, &[1.0]).unwrap()[0];
    let (x1, _, _) = oscillator_mode(s, &x0, &v0, 1.0);
    assert!((pos_vel(&y).0 - x1).norm() > 1.0);
}

/// Coulomb `al`: backward shooting converges onto a solution through the given
/// start that agrees with Landau–Lifshitz to O(τ₀²) per unit time.
#[test]
fn eq_2_5_coulomb_physical_solution_by_backward_shooting() {
    let tau0 = 1e-3;
    let times = [0.0, 10.0, 30.0];
    let al = OrbitConfig::new(coulomb(tau0), 1.0, 0.3, Force::AbrahamLorentz).unwrap();
    let ll = OrbitConfig::new(coulomb(tau0), 1.0, 0.3, Force::LandauLifshitz).unwrap();
    let run_al = run_orbit(&al, &times).unwrap();
    let run_ll = run_orbit(&ll, &times).unwrap();
    let (iterations, mismatch) = run_al.shooting.unwrap();
    assert!(iterations <= 12 && mismatch < 1e-9);
    assert_relative_eq!(run_al.samples[0].position[0], 1.0, epsilon = 1e-8);
    for (a, l) in run_al.samples.iter().zip(&run_ll.samples) {
        let dr = ((a.position[0] - l.position[0]).powi(2)
            + (a.position[1] - l.position[1]).powi(2))
        .sqrt();
        assert!(dr < 50.0 * tau0 * tau0 * (1.0 + a.t), "t = {}: {dr}", a.t);
    }
}
