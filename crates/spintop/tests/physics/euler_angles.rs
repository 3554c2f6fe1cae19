//! Euler angles (3.5)/(4.8) as an input and output format: (3.5) is the
//! kinematics (3.2), Ω̂ = Oᵀ dO/dt, written in the angles (checked at many
//! points against O(t) built by hand and differentiated numerically); the
//! round trip angles → O → angles is exact away from the poles, and on the
//! poles the conversion stays finite and still reproduces O.

use nalgebra::Matrix3;
use proptest::prelude::*;
use spintop::math::Vec3;
use spintop::physics::euler_angles::{EulerAngles, EulerRates, body_rate_from_euler, euler_rates};
use std::f64::consts::{PI, TAU};

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// O = R_z(φ) R_x(θ) R_z(ψ), built here from its three factors (z-x-z,
/// active; the physics notes' convention), not by the crate.
fn o_by_hand(phi: f64, theta: f64, psi: f64) -> Matrix3<f64> {
    let rz = |a: f64| {
        let (s, c) = a.sin_cos();
        Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
    };
    let (s, c) = theta.sin_cos();
    let rx = Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c);
    rz(phi) * rx * rz(psi)
}

proptest! {
    /// (3.5) against the kinematics (3.2): along angles moving at constant
    /// rates, O(t) built by hand and differentiated by a central difference
    /// (error ~h² ≈ 1e-10) gives Ω̂ = Oᵀ dO/dt, whose axial vector must be
    /// (3.5)'s Ω. A sign or a swapped sin/cos in (3.5), or the lab-frame rate
    /// O dO/dtᵀ in place of the body-frame one, fails at almost every point.
    #[test]
    fn eq_3_5_is_the_kinematics_3_2_in_euler_angles(
        phi in -PI..PI, theta in 1e-2..(PI - 1e-2), psi in -PI..PI,
        rates in prop::array::uniform3(-3.0..3.0f64),
    ) {
        let [phi_dot, theta_dot, psi_dot] = rates;
        let h = 1e-5;
        let at = |t: f64| o_by_hand(phi + phi_dot * t, theta + theta_dot * t, psi + psi_dot * t);
        let o = at(0.0);
        prop_assert!((EulerAngles::new(phi, theta, psi).to_rotation() - o).amax() < 1e-14);
        let o_dot = (at(h) - at(-h)) / (2.0 * h);
        let hat = o.transpose() * o_dot;
        // Ω̂ is antisymmetric: its axial vector is (Ω̂₃₂, Ω̂₁₃, Ω̂₂₁).
        prop_assert!((hat + hat.transpose()).amax() < 1e-8, "not antisymmetric: {}", hat);
        let kinematics = Vec3::new(hat[(2, 1)], hat[(0, 2)], hat[(1, 0)]);
        let angles = EulerAngles::new(phi, theta, psi);
        let rates = EulerRates { phi_dot, theta_dot, psi_dot };
        let omega = body_rate_from_euler(&angles, &rates);
        prop_assert!(
            (omega - kinematics).norm() < 1e-8,
            "(3.5) {} vs (3.2) {}", omega, kinematics
        );
    }

    #[test]
    fn eq_3_5_euler_round_trip_away_from_the_poles(
        phi in -PI..PI, theta in 1e-3..(PI - 1e-3), psi in -PI..PI,
    ) {
        let back = EulerAngles::from_rotation(&EulerAngles::new(phi, theta, psi).to_rotation());
        prop_assert!((back.theta - theta).abs() < 1e-12);
        // φ and ψ are defined to within rounding divided by sin θ.
        let tol = 1e-13 / theta.sin();
        prop_assert!(wrap(back.phi - phi).abs() < tol, "phi {} vs {}", back.phi, phi);
        prop_assert!(wrap(back.psi - psi).abs() < tol, "psi {} vs {}", back.psi, psi);
    }

    #[test]
    fn eq_3_5_pole_gives_finite_angles_that_reproduce_the_rotation(
        phi in -PI..PI, psi in -PI..PI, south in any::<bool>(), tiny in 0.0..1e-13f64,
    ) {
        let theta = if south { PI - tiny } else { tiny };
        let o = EulerAngles::new(phi, theta, psi).to_rotation();
        let back = EulerAngles::from_rotation(&o);
        prop_assert!(back.phi.is_finite() && back.theta.is_finite() && back.psi.is_finite());
        prop_assert!((back.to_rotation() - o).amax() < 1e-12);
        prop_assert!(euler_rates(&back, &Vec3::new(0.1, 0.2, 0.3)).is_none());
    }

    #[test]
    fn eq_4_8_and_eq_3_5_are_inverse(
        phi in -PI..PI, theta in 1e-2..(PI - 1e-2), psi in -PI..PI,
        w in prop::array::uniform3(-5.0..5.0f64),
    ) {
        let angles = EulerAngles::new(phi, theta, psi);
        let omega = Vec3::from(w);
        let rates = euler_rates(&angles, &omega).unwrap();
        let back = body_rate_from_euler(&angles, &rates);
        prop_assert!((back - omega).norm() < 1e-12 * (1.0 + omega.norm()) / theta.sin());
    }
}
