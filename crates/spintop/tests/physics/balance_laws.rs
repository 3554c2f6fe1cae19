//! Section 2's two balance laws for a system of charges, (2.1)–(2.4).
//!
//! Pins down: identity (2.3) — the torque (2.2) equals the Larmor-like rate
//! (2.1) plus dL_S/dt — with dL_S/dt obtained *independently* by spectral
//! differentiation of L_S (exact for trigonometric polynomials up to
//! rounding); the torque never has a component along the dipole; the closed
//! forms of the three built-in trajectories (derived by hand, and their jets
//! checked against finite differences); and the period averages.

use approx::assert_relative_eq;
use proptest::prelude::*;
use spintop::math::Vec3;
use spintop::physics::balance::{
    ClosureDipole, DipoleTrajectory, Dumbbell, Jet, PlanarLoop, PrecessingDipole, axial,
    balance_at, larmor_rate, period_average, schott_angular_momentum, schott_rate, torque_rate,
};
use std::f64::consts::{PI, TAU};

/// A random trigonometric polynomial 𝔡(t) = Σₖ₌₀³ (aₖ cos kt + bₖ sin kt), period 2π,
/// with its exact derivatives.
fn trig_dipole(coeffs: Vec<f64>) -> impl DipoleTrajectory {
    assert_eq!(coeffs.len(), 24);
    let c = move |k: usize, j: usize| {
        Vec3::new(
            coeffs[k * 6 + j * 3],
            coeffs[k * 6 + j * 3 + 1],
            coeffs[k * 6 + j * 3 + 2],
        )
    };
    ClosureDipole::new(
        move |t: f64| {
            let mut jet: Jet = [Vec3::zeros(); 4];
            for k in 0..4 {
                let kf = k as f64;
                let (s, co) = (kf * t).sin_cos();
                let (a, b) = (c(k, 0), c(k, 1));
                // d^n/dt^n of a cos kt + b sin kt.
                jet[0] += a * co + b * s;
                jet[1] += kf * (-a * s + b * co);
                jet[2] += -kf * kf * (a * co + b * s);
                jet[3] += kf.powi(3) * (a * s - b * co);
            }
            jet
        },
        Some(TAU),
    )
}

/// The derivative at the nodes of a 2π-periodic sampled function, by the
/// discrete Fourier transform (exact for degree < N/2, up to rounding).
fn spectral_derivative(f: &[Vec3]) -> Vec<Vec3> {
    let n = f.len();
    let mut out = vec![Vec3::zeros(); n];
    let nodes: Vec<f64> = (0..n).map(|j| TAU * j as f64 / n as f64).collect();
    for k in 1..(n / 2) {
        // c_k and c_{-k} combine into a cos + b sin; its derivative is k(b cos − a sin).
        let mut a = Vec3::zeros();
        let mut b = Vec3::zeros();
        for (fj, &t) in f.iter().zip(&nodes) {
            a += fj * (k as f64 * t).cos();
            b += fj * (k as f64 * t).sin();
        }
        a *= 2.0 / n as f64;
        b *= 2.0 / n as f64;
        for (o, &t) in out.iter_mut().zip(&nodes) {
            let (s, c) = (k as f64 * t).sin_cos();
            *o += k as f64 * (b * c - a * s);
        }
    }
    out
}

/// Check a jet's derivatives against central finite differences of the jet.
fn assert_jet_consistent(traj: &impl DipoleTrajectory, t: f64) {
    let h = 1e-5;
    let (jp, jm, j) = (traj.jet(t + h), traj.jet(t - h), traj.jet(t));
    for n in 0..3 {
        let fd = (jp[n] - jm[n]) / (2.0 * h);
        assert_relative_eq!(fd, j[n + 1], epsilon = 1e-7 * (1.0 + j[n + 1].norm()));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// (2.3): 𝔡 × 𝔡⃛ = d(𝔡 × 𝔡̈)/dt − 𝔡̇ × 𝔡̈, with d/dt taken spectrally from samples of L_S.
    #[test]
    fn eq_2_3_identity_holds_for_random_trajectories(coeffs in prop::collection::vec(-1.0f64..1.0, 24)) {
        let traj = trig_dipole(coeffs);
        let n = 32; // L_S has degree ≤ 6 < n/2
        let nodes: Vec<f64> = (0..n).map(|j| TAU * j as f64 / n as f64).collect();
        let ls: Vec<Vec3> = nodes.iter().map(|&t| schott_angular_momentum(&traj.jet(t))).collect();
        let dls = spectral_derivative(&ls);
        let scale = ls.iter().map(|v| v.norm()).fold(1.0, f64::max) * 27.0;
        for (j, &t) in nodes.iter().enumerate() {
            let jet = traj.jet(t);
            let lhs = torque_rate(&jet);
            let rhs = dls[j] + larmor_rate(&jet);
            prop_assert!((lhs - rhs).norm() <= 1e-12 * scale, "t = {t}: {lhs} vs {rhs}");
            // And the crate's own dL_S/dt is the same to rounding.
            prop_assert!((lhs - larmor_rate(&jet) - schott_rate(&jet)).norm() <= 1e-14 * scale);
        }
    }

    /// 𝔡 · (𝔡 × 𝔡⃛) = 0 for any jet: (2.2) cannot change the spin along the dipole.
    #[test]
    fn eq_2_2_torque_has_no_component_along_the_dipole(
        v in prop::collection::vec(-10.0f64..10.0, 12)
    ) {
        let jet: Jet = [
            Vec3::new(v[0], v[1], v[2]),
            Vec3::new(v[3], v[4], v[5]),
            Vec3::new(v[6], v[7], v[8]),
            Vec3::new(v[9], v[10], v[11]),
        ];
        let d = jet[0];
        let bound = 8.0 * f64::EPSILON * d.norm() * jet[3].norm();
        prop_assert!(axial(&d, &torque_rate(&jet)).abs() <= bound);
    }

    #[test]
    fn eq_2_1_2_4_precessing_dipole_matches_its_closed_forms(
        theta in 0.0f64..PI, omega in -3.0f64..3.0, t in -20.0f64..20.0
    ) {
        prop_assume!(omega.abs() > 1e-3);
        let p = PrecessingDipole::new(theta, omega).unwrap();
        let b = balance_at(&p, t);
        let [larmor, torque, schott, rate] = p.closed_forms(t);
        let tol = 1e-14 * (1.0 + omega.abs().powi(3));
        prop_assert!((b.larmor - larmor).norm() <= tol);
        prop_assert!((b.torque - torque).norm() <= tol);
        prop_assert!((b.schott - schott).norm() <= tol);
        prop_assert!((b.schott_rate - rate).norm() <= tol);
        let w3 = omega.powi(3);
        prop_assert!((b.schott_rate_axial - w3 * theta.sin().powi(2) * theta.cos()).abs() <= tol);
        prop_assert!((b.larmor_axial + w3 * theta.sin().powi(2) * theta.cos()).abs() <= tol);
        prop_assert!(b.torque_axial.abs() <= tol);
    }

    #[test]
    fn eq_2_1_2_4_loop_matches_its_closed_forms(
        b in -2.0f64..2.0, eps in -1.0f64..1.0, t in -20.0f64..20.0
    ) {
        let lp = PlanarLoop::new(b, eps).unwrap();
        let bal = balance_at(&lp, t);
        let [larmor, torque, schott, rate] = lp.closed_forms(t);
        let tol = 1e-13;
        for (v, z) in [(bal.larmor, larmor), (bal.torque, torque), (bal.schott, schott), (bal.schott_rate, rate)] {
            prop_assert!((v - Vec3::new(0.0, 0.0, z)).norm() <= tol, "{v} vs {z}");
        }
    }
}

#[test]
fn builtin_jets_are_the_derivatives_of_the_dipole() {
    for t in [-3.0, 0.0, 0.4, 2.5, 11.0] {
        assert_jet_consistent(&PrecessingDipole::new(0.7, 1.3).unwrap(), t);
        assert_jet_consistent(&PlanarLoop::new(0.6, 0.3).unwrap(), t);
        assert_jet_consistent(
            &Dumbbell::new([1.0, -0.5], [2.0, 1.0], 1.5, -0.8).unwrap(),
            t,
        );
    }
}

/// The precessing dipole: in the lab the Schott rate averages to zero, yet its
/// projection on the dipole is the constant ω³ sin²θ cos θ — the difference
/// between (4.4) and (4.14).
#[test]
fn sec2_precessing_dipole_schott_rate_averages_out_in_the_lab_but_not_along_the_axis() {
    let (theta, omega) = (0.6, 1.7);
    let avg = period_average(&PrecessingDipole::new(theta, omega).unwrap()).unwrap();
    let w3s2 = omega.powi(3) * theta.sin().powi(2);
    assert_relative_eq!(avg.t, TAU / omega, epsilon = 1e-15);
    assert_relative_eq!(avg.larmor, Vec3::new(0.0, 0.0, -w3s2), epsilon = 1e-14);
    assert_relative_eq!(avg.torque, Vec3::new(0.0, 0.0, -w3s2), epsilon = 1e-14);
    assert!(avg.schott_rate.norm() < 1e-14);
    assert_relative_eq!(avg.schott_rate_axial, w3s2 * theta.cos(), epsilon = 1e-14);
    assert_relative_eq!(avg.larmor_axial, -w3s2 * theta.cos(), epsilon = 1e-14);
    assert!(avg.torque_axial.abs() < 1e-15);
}

/// The loop: both laws give −b ẑ on average, but differ at an instant by
/// dL_S/dt, e.g. by −6ε at t = 0.
#[test]
fn sec2_loop_laws_agree_on_average_not_at_an_instant() {
    let (b, eps) = (0.5, 0.2);
    let lp = PlanarLoop::new(b, eps).unwrap();
    let avg = period_average(&lp).unwrap();
    assert_relative_eq!(avg.larmor, Vec3::new(0.0, 0.0, -b), epsilon = 1e-15);
    assert_relative_eq!(avg.torque, Vec3::new(0.0, 0.0, -b), epsilon = 1e-15);
    assert!(avg.schott_rate.norm() < 1e-15 && avg.schott.norm() < 1e-15);
    let at0 = balance_at(&lp, 0.0);
    assert_relative_eq!(at0.torque.z - at0.larmor.z, -6.0 * eps, epsilon = 1e-15);
    // The planar dipole has no component along any vector of the balance laws.
    assert_eq!(at0.larmor_axial, 0.0);
    // ε = 0 (an ellipse): L_S vanishes and the laws agree at every instant.
    let ellipse = PlanarLoop::new(b, 0.0).unwrap();
    for t in [0.0, 1.0, 2.0] {
        assert!(balance_at(&ellipse, t).schott.norm() < 1e-16);
    }
}

/// The trapezoid rule on 256 nodes is exact for trigonometric polynomials of
/// degree < 256 (the NOTE in `period_average`), and visibly not beyond: a
/// component with harmonic 256 aliases to its value at t = 0.
#[test]
fn period_average_is_exact_below_the_node_count_and_aliases_at_it() {
    let harmonic = |k: f64| {
        ClosureDipole::new(
            move |t: f64| {
                let c = (k * t).cos();
                [
                    Vec3::new(1.0 + c, 1.0, 0.0),
                    Vec3::zeros(),
                    Vec3::zeros(),
                    Vec3::zeros(),
                ]
            },
            Some(TAU),
        )
    };
    assert_relative_eq!(
        period_average(&harmonic(255.0)).unwrap().dipole.x,
        1.0,
        epsilon = 1e-13
    );
    assert_relative_eq!(
        period_average(&harmonic(256.0)).unwrap().dipole.x,
        2.0,
        epsilon = 1e-13
    );
}

/// The dumbbell, a planar rigid rotor: L_S ≡ 0 and both laws give −d₀²ω³ ẑ;
/// equal charge-to-mass ratios give no dipole at all.
#[test]
fn sec2_rigid_dumbbell_has_no_schott_term() {
    let (q, m, l, w) = ([1.0, -1.0], [1.0, 3.0], 2.0, 0.9);
    let db = Dumbbell::new(q, m, l, w).unwrap();
    let d0 = l * (q[0] * m[1] - q[1] * m[0]) / (m[0] + m[1]);
    assert_relative_eq!(db.amplitude(), d0, epsilon = 1e-15);
    for t in [0.0, 0.3, 5.0] {
        let b = balance_at(&db, t);
        assert!(b.schott.norm() < 1e-15 && b.schott_rate.norm() < 1e-14);
        assert_relative_eq!(
            b.larmor,
            Vec3::new(0.0, 0.0, -d0 * d0 * w.powi(3)),
            epsilon = 1e-14
        );
        assert_relative_eq!(b.torque, b.larmor, epsilon = 1e-14);
    }
    let same_ratio = Dumbbell::new([1.0, 2.0], [1.0, 2.0], 1.0, 1.0).unwrap();
    assert_eq!(same_ratio.amplitude(), 0.0);
    assert_eq!(balance_at(&same_ratio, 1.0).larmor_axial, 0.0);
}

#[test]
fn sec2_builtins_refuse_unphysical_parameters() {
    assert!(PrecessingDipole::new(-0.1, 1.0).is_err());
    assert!(PrecessingDipole::new(0.5, 0.0).is_err());
    assert!(PrecessingDipole::new(f64::NAN, 1.0).is_err());
    assert!(PlanarLoop::new(f64::INFINITY, 0.0).is_err());
    assert!(Dumbbell::new([1.0, -1.0], [0.0, 1.0], 1.0, 1.0).is_err());
    assert!(Dumbbell::new([1.0, -1.0], [1.0, 1.0], -1.0, 1.0).is_err());
    assert!(Dumbbell::new([1.0, -1.0], [1.0, 1.0], 1.0, 0.0).is_err());
}
