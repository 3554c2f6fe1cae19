//! Section 4: the symmetric top's two models, integrated and in closed form.
//!
//! These tests pin down the claims spintop's Section 4 chapter rests on:
//! DOP853 integration of (4.2)–(4.4) and (4.12)–(4.14) agrees with the closed
//! forms (4.7) and (4.15)–(4.16) to 1e-10 up to t = 1000; the truncated top keeps
//! the direction of L and shrinks |L| as 1/R(t); the reduced top keeps Ω₃; the
//! energy never rises; orientations integrated on SO(3) stay rotations; erratum
//! (4.11) (the printed tilt is not constant, the corrected one is); and the two
//! end states: the truncated tilt stays fixed while the reduced top stands up
//! along L (but not along lab z, erratum (4.18)).

use proptest::prelude::*;
use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::{State, Vec3, orthonormality_error};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::rigid_body::{angular_momentum_body, energy};
use spintop::physics::symmetric_top::{
    SymmetricTop, precession_tilt, printed_tilt_4_11, reduced_ale_rhs, reduced_closed_form,
    reduced_decay_time, truncated_ale_rhs, truncated_clock, truncated_closed_form,
    truncated_orientation, truncated_poisson_rhs,
};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

/// The figure parameters plus four more: Ω₁₀ ≠ 0, a needle, a disc (I₃ = 2I₁),
/// a sphere (Ω̃₃ = 0) and a top spinning backwards.
fn parameter_sets() -> Vec<(f64, Vec3)> {
    vec![
        (0.4, Vec3::new(0.0, 0.1, 0.2)), // the paper's figures
        (1.5, Vec3::new(0.3, -0.2, 0.5)),
        (0.05, Vec3::new(-0.05, 0.02, 1.0)),
        (2.0, Vec3::new(0.1, 0.1, -0.3)),
        (1.0, Vec3::new(0.2, 0.0, 0.2)),
    ]
}

fn times(t_end: f64, n: usize) -> Vec<f64> {
    (1..=n).map(|i| t_end * i as f64 / n as f64).collect()
}

fn dop853_omega<F: Fn(&Vec3) -> Vec3>(f: F, omega0: Vec3, times: &[f64], rtol: f64) -> Vec<Vec3> {
    // State<3> and Vec3 are the same type.
    let rhs = |_t: f64, y: &State<3>| -> State<3> { f(y) };
    let opts = AdaptiveOptions::new(rtol, 1e-20).unwrap();
    let mut stepper = Dop853::new(0.0, State::<3>::from(omega0), opts).unwrap();
    solve(&mut stepper, &rhs, times).unwrap()
}

fn max_rel_error(got: &[Vec3], want: impl Fn(usize) -> Vec3) -> f64 {
    got.iter()
        .enumerate()
        .map(|(i, g)| (g - want(i)).norm() / want(i).norm())
        .fold(0.0, f64::max)
}

#[test]
fn eq_4_7_truncated_closed_form_matches_dop853_to_1e_10_up_to_t_1000() {
    let ts = times(1000.0, 200);
    for (ratio, omega0) in parameter_sets() {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let got = dop853_omega(|w| truncated_ale_rhs(&top, w), omega0, &ts, 1e-12);
        let err = max_rel_error(&got, |i| truncated_closed_form(&top, &omega0, ts[i]));
        assert!(
            err < 1e-10,
            "I3/I1 = {ratio}, omega0 = {omega0:?}: max rel error {err:e}"
        );
    }
}

#[test]
fn eq_4_15_reduced_closed_form_matches_dop853_to_1e_10_up_to_t_1000() {
    let ts = times(1000.0, 200);
    for (ratio, omega0) in parameter_sets() {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let got = dop853_omega(|w| reduced_ale_rhs(&top, w), omega0, &ts, 1e-12);
        let err = max_rel_error(&got, |i| reduced_closed_form(&top, &omega0, ts[i]));
        assert!(
            err < 1e-10,
            "I3/I1 = {ratio}, omega0 = {omega0:?}: max rel error {err:e}"
        );
        // The perpendicular part alone, where it is still well above the error floor.
        for (g, &t) in got.iter().zip(&ts) {
            let want = reduced_closed_form(&top, &omega0, t);
            if want.xy().norm() > 1e-6 * omega0.norm() {
                let e = (g.xy() - want.xy()).norm() / want.xy().norm();
                assert!(e < 1e-9, "Omega_perp at t = {t}: rel error {e:e}");
            }
        }
    }
}

fn simulation(
    model: Model,
    method: MethodChoice,
    omega0: Vec3,
    euler: EulerAngles,
    horizon: f64,
) -> Simulation {
    let options = MethodOptions::new(1e-12, 0.02).expect("valid options");
    let initial = InitialState::new(omega0, euler).unwrap();
    Simulation::new(model, method, options, initial, Some(horizon)).unwrap()
}

/// The orientation integrated on SO(3) along the truncated model reproduces
/// the closed form Rot(n_L, |L₀|ϑ)·O₀·R_z(Ω̃₃₀ϑ).
#[test]
fn eq_4_9_truncated_orientation_closed_form_matches_integration_on_so3() {
    let euler = EulerAngles::new(0.3, 1.0, -0.7);
    for (ratio, omega0) in parameter_sets() {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let mut sim = simulation(
            Model::Truncated(top),
            MethodChoice::Dop853,
            omega0,
            euler,
            1000.0,
        );
        let o0 = euler.to_rotation();
        for s in sim.run(&times(1000.0, 50)).unwrap() {
            let want = truncated_orientation(&top, &omega0, &o0, s.t);
            let err = (s.rotation_matrix() - want).amax();
            assert!(
                err < 1e-9,
                "I3/I1 = {ratio}: orientation error {err:e} at t = {}",
                s.t
            );
        }
    }
}

#[test]
fn sec4_truncated_l_lab_keeps_its_direction_and_shrinks_as_1_over_r() {
    let euler = EulerAngles::new(-1.2, 0.6, 2.0);
    for (ratio, omega0) in parameter_sets() {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let l0 = euler.to_rotation() * angular_momentum_body(&top.inertia(), &omega0);
        for method in [MethodChoice::Exact, MethodChoice::Dop853] {
            let mut sim = simulation(Model::Truncated(top), method, omega0, euler, 1000.0);
            for s in sim.run(&times(1000.0, 40)).unwrap() {
                let l = Vec3::from(s.l_lab);
                let r = truncated_clock(&top, omega0.xy().norm(), s.t).r;
                let dir_err = (l.normalize() - l0.normalize()).norm();
                assert!(
                    dir_err < 1e-9,
                    "{method:?}: L turned by {dir_err:e} at t = {}",
                    s.t
                );
                let mag_err = (l.norm() * r / l0.norm() - 1.0).abs();
                assert!(mag_err < 1e-10, "{method:?}: |L| R/|L0| - 1 = {mag_err:e}");
            }
        }
    }
}

#[test]
fn eq_4_14_reduced_omega3_stays_constant_under_every_method() {
    for method in [
        MethodChoice::Exact,
        MethodChoice::Rk4,
        MethodChoice::Dopri5,
        MethodChoice::Dop853,
    ] {
        let (ratio, omega0) = (0.4, Vec3::new(0.05, 0.1, 0.2));
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let mut sim = simulation(
            Model::Reduced(top),
            method,
            omega0,
            EulerAngles::new(0.0, 0.5, 0.0),
            200.0,
        );
        for s in sim.run(&times(200.0, 40)).unwrap() {
            assert_eq!(s.omega[2], omega0.z, "{method:?} at t = {}", s.t);
        }
    }
}

/// dE/dt = −2τΩ⊥²E (truncated) and −2τ(Ω⊥² + k²)(E − I₃Ω₃²/2) (reduced) are
/// never positive; checked along dense integrated trajectories.
#[test]
fn sec4_energy_never_increases_along_integrated_trajectories() {
    for (ratio, omega0) in parameter_sets() {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        for model in [Model::Truncated(top), Model::Reduced(top)] {
            for method in [MethodChoice::Rk4, MethodChoice::Dop853] {
                let mut sim = simulation(
                    model,
                    method,
                    omega0,
                    EulerAngles::new(0.0, 0.4, 0.0),
                    500.0,
                );
                let samples = sim.run(&times(500.0, 1000)).unwrap();
                for pair in samples.windows(2) {
                    assert!(
                        pair[1].energy <= pair[0].energy * (1.0 + 1e-13),
                        "{} {method:?}: E rose from {} to {} at t = {}",
                        model.name(),
                        pair[0].energy,
                        pair[1].energy,
                        pair[1].t
                    );
                }
            }
        }
    }
}

proptest! {
    /// The closed forms never raise E between any two times, for any top.
    #[test]
    fn sec4_energy_never_increases_along_the_closed_forms(
        ratio in 0.01..2.0f64,
        w in prop::array::uniform3(-3.0..3.0f64),
        t1 in 0.0..100.0f64, dt in 0.0..100.0f64,
    ) {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let omega0 = Vec3::from(w);
        let i = top.inertia();
        for f in [truncated_closed_form, reduced_closed_form] {
            let e1 = energy(&i, &f(&top, &omega0, t1));
            let e2 = energy(&i, &f(&top, &omega0, t1 + dt));
            prop_assert!(e2 <= e1 * (1.0 + 1e-14), "E rose from {} to {}", e1, e2);
        }
    }
}

#[test]
fn sec3_orientation_stays_orthonormal_to_1e_12_under_every_method() {
    let general = spintop::physics::general_top::GeneralTop::new(
        Vec3::new(1.0, 1.6, 0.9),
        Vec3::new(0.3, -0.2, 0.8),
    )
    .unwrap();
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.1, 0.3, 0.5);
    for model in [
        Model::Truncated(top),
        Model::Reduced(top),
        Model::General(general),
    ] {
        for method in [
            MethodChoice::Auto,
            MethodChoice::Rk4,
            MethodChoice::Dopri5,
            MethodChoice::Dop853,
        ] {
            let mut sim = simulation(
                model,
                method,
                omega0,
                EulerAngles::new(0.2, 0.9, -0.4),
                1000.0,
            );
            for s in sim.run(&times(1000.0, 100)).unwrap() {
                let err = orthonormality_error(&s.rotation_matrix());
                assert!(
                    err < 1e-12,
                    "{} {method:?}: |OᵀO − I| = {err:e} at t = {}",
                    model.name(),
                    s.t
                );
            }
        }
    }
}

/// The general model (3.3), given symmetric inputs, follows the truncated
/// closed form in Ω and in orientation (with τ = d²/I₁ = 1).
#[test]
fn eq_3_3_general_model_with_symmetric_inputs_follows_the_truncated_closed_form() {
    let top = SymmetricTop::figure();
    let general = spintop::physics::general_top::GeneralTop::new(
        Vec3::new(1.0, 1.0, 0.4),
        Vec3::new(0.0, 0.0, 1.0),
    )
    .unwrap();
    let omega0 = Vec3::new(0.02, 0.1, 0.2);
    let euler = EulerAngles::new(0.5, 0.7, 0.1);
    let mut sim = simulation(
        Model::General(general),
        MethodChoice::Auto,
        omega0,
        euler,
        300.0,
    );
    for s in sim.run(&times(300.0, 30)).unwrap() {
        let w = truncated_closed_form(&top, &omega0, s.t);
        assert!((s.omega_vec() - w).norm() < 1e-10 * w.norm());
        let o = truncated_orientation(&top, &omega0, &euler.to_rotation(), s.t);
        assert!((s.rotation_matrix() - o).amax() < 1e-9);
    }
}

/// Erratum 4: along the particular solution (4.11) the tilt is the angle
/// between the axis and L, arctan(I₁Ω₂₀/(I₃Ω₃₀)) = 0.8961 rad for the figure
/// parameters; the printed arctan(Ω₂₀/Ω̃₃₀) = 0.6947 rad is not constant.
#[test]
fn eq_4_10_eq_4_11_erratum_corrected_tilt_is_constant_and_printed_is_not() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let corrected = precession_tilt(&top, &omega0);
    let printed = printed_tilt_4_11(&top, &omega0);
    assert!((corrected - 0.8961).abs() < 5e-5 && (printed - 0.6947).abs() < 5e-5);

    // 1. Through the closed-form orientation, started at (φ, θ, ψ) = (0, θ₀, 0).
    let theta_range = |theta0: f64| {
        let o0 = EulerAngles::new(0.0, theta0, 0.0).to_rotation();
        times(1000.0, 500)
            .into_iter()
            .map(|t| {
                EulerAngles::from_rotation(&truncated_orientation(&top, &omega0, &o0, t)).theta
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), th| {
                (lo.min(th), hi.max(th))
            })
    };
    let (lo, hi) = theta_range(corrected);
    assert!(
        hi - lo < 1e-12 && (lo - corrected).abs() < 1e-12,
        "corrected: θ in [{lo}, {hi}]"
    );
    let (lo, hi) = theta_range(printed);
    assert!(hi - lo > 0.3, "printed: θ only moved within [{lo}, {hi}]");

    // 2. By integrating the Poisson equations (4.10) in ϑ, independently of the closed form.
    let rhs =
        |_v: f64, y: &State<3>| -> State<3> { truncated_poisson_rhs(&top, omega0.y, omega0.z, y) };
    let theta_spread = |theta0: f64| {
        let opts = AdaptiveOptions::new(1e-12, 1e-14).unwrap();
        let mut stepper = Dop853::new(0.0, State::<3>::new(0.0, theta0, 0.0), opts).unwrap();
        let out = solve(&mut stepper, &rhs, &times(200.0, 400)).unwrap();
        out.iter()
            .map(|y| (y[1] - theta0).abs())
            .fold(0.0, f64::max)
    };
    assert!(theta_spread(corrected) < 1e-10);
    assert!(theta_spread(printed) > 0.1);

    // 3. (4.11)'s φ and ψ, with the corrected θ, are the Euler angles of the closed form.
    let o0 = EulerAngles::new(0.0, corrected, 0.0).to_rotation();
    for t in times(100.0, 20) {
        let e = EulerAngles::from_rotation(&truncated_orientation(&top, &omega0, &o0, t));
        let vt = truncated_clock(&top, 0.1, t).vartheta;
        let wrap = |a: f64| {
            (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        };
        assert!(
            wrap(e.psi - top.omega3_tilde(0.2) * vt).abs() < 1e-10,
            "psi at t = {t}"
        );
        assert!(
            wrap(e.phi - omega0.y * vt / corrected.sin()).abs() < 1e-10,
            "phi at t = {t}"
        );
    }
}

/// The truncated top keeps its tilt for ever (4.11); the reduced top's tilt
/// decays like e^{−t/σ} (4.18): it ends spinning about its symmetry axis along L.
#[test]
fn sec4_truncated_tilt_is_constant_and_reduced_top_ends_upright_at_rate_1_over_sigma() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let euler = EulerAngles::new(0.0, 0.0, 0.0);
    let mut trunc = simulation(
        Model::Truncated(top),
        MethodChoice::Auto,
        omega0,
        euler,
        3000.0,
    );
    let mut red = simulation(
        Model::Reduced(top),
        MethodChoice::Auto,
        omega0,
        euler,
        3000.0,
    );
    let tilt0 = precession_tilt(&top, &omega0);
    for s in trunc.run(&times(3000.0, 30)).unwrap() {
        assert!((s.tilt - tilt0).abs() < 1e-14);
    }
    let sigma = reduced_decay_time(&top, omega0.z);
    let s1 = *red.advance_to(1500.0).unwrap();
    let s2 = *red.advance_to(3000.0).unwrap();
    let rate = (s2.tilt / s1.tilt).ln() / 1500.0;
    assert!(
        (rate * sigma + 1.0).abs() < 1e-3,
        "tilt decays at {rate}, expected {}",
        -1.0 / sigma
    );
    assert!(s2.tilt < 1e-7);
}

/// Erratum 5: (4.18)'s θ → 0 holds only in a lab frame whose z axis is the final
/// direction of L. Started from the identity orientation, L is not along z,
/// and θ settles at the fixed angle between lab z and L∞, while φ̇ → 0 and ψ̇ → Ω₃.
#[test]
fn eq_4_18_erratum_theta_tends_to_the_angle_of_l_infinity_not_zero() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let mut red = simulation(
        Model::Reduced(top),
        MethodChoice::Auto,
        omega0,
        EulerAngles::new(0.0, 0.0, 0.0),
        4000.0,
    );
    let a = *red.advance_to(3000.0).unwrap();
    let b = *red.advance_to(4000.0).unwrap();
    let l_inf = Vec3::from(b.l_lab).normalize();
    let theta_inf = l_inf.z.acos();
    assert!(theta_inf > 0.1, "θ∞ = {theta_inf}");
    assert!(
        (b.euler[1] - theta_inf).abs() < 1e-6,
        "θ = {}, θ∞ = {theta_inf}",
        b.euler[1]
    );
    assert!((a.euler[1] - b.euler[1]).abs() < 1e-6);
    let rates = b.euler_rates.expect("not on a pole");
    assert!(rates[0].abs() < 1e-6, "φ̇ = {}", rates[0]);
    assert!((rates[2] - omega0.z).abs() < 1e-6, "ψ̇ = {}", rates[2]);
}

/// The reduced orientation (4.17) has no closed form. Two routes must agree:
/// Ω from (4.15)–(4.16) driving σ alone (what `auto` does), and Ω and σ
/// integrated together by DOP853, and by RK4 at a small step.
#[test]
fn eq_4_17_reduced_orientation_agrees_between_independent_routes() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.03, 0.1, 0.2);
    let euler = EulerAngles::new(0.4, 0.8, -1.0);
    let ts = times(600.0, 30);
    let mut auto = simulation(
        Model::Reduced(top),
        MethodChoice::Auto,
        omega0,
        euler,
        600.0,
    );
    let mut full = simulation(
        Model::Reduced(top),
        MethodChoice::Dop853,
        omega0,
        euler,
        600.0,
    );
    let a = auto.run(&ts).unwrap();
    let b = full.run(&ts).unwrap();
    for (x, y) in a.iter().zip(&b) {
        let err = (x.rotation_matrix() - y.rotation_matrix()).amax();
        assert!(err < 1e-8, "DOP853 routes differ by {err:e} at t = {}", x.t);
    }
    let options = MethodOptions::new(1e-12, 0.01).expect("valid options");
    let initial = InitialState::new(omega0, euler).unwrap();
    let mut rk4 = Simulation::new(
        Model::Reduced(top),
        MethodChoice::Rk4,
        options,
        initial,
        Some(600.0),
    )
    .unwrap();
    for (x, y) in a.iter().zip(&rk4.run(&ts).unwrap()) {
        let err = (x.rotation_matrix() - y.rotation_matrix()).amax();
        assert!(err < 1e-7, "RK4 differs by {err:e} at t = {}", x.t);
    }
}

/// An open-ended run (no horizon, as the TUI drives it) gives the same
/// numbers as a run told its last time in advance, to the tolerance.
#[test]
fn sim_open_ended_run_matches_a_run_with_a_horizon() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let initial = InitialState::new(omega0, EulerAngles::new(0.0, 0.3, 0.0)).unwrap();
    let options = MethodOptions::new(1e-12, 0.01).expect("valid options");
    for method in [MethodChoice::Auto, MethodChoice::Dopri5, MethodChoice::Rk4] {
        let mut open =
            Simulation::new(Model::Reduced(top), method, options, initial, None).unwrap();
        let mut closed =
            Simulation::new(Model::Reduced(top), method, options, initial, Some(100.0)).unwrap();
        for t in [1.0, 10.0, 55.5, 100.0] {
            let a = *open.advance_to(t).unwrap();
            let b = *closed.advance_to(t).unwrap();
            assert!(
                (a.rotation_matrix() - b.rotation_matrix()).amax() < 1e-8,
                "{method:?} at t = {t}"
            );
            assert!(
                (a.omega_vec() - b.omega_vec()).norm() < 1e-9,
                "{method:?} at t = {t}"
            );
        }
    }
}
