//! Euler angles (3.5)/(4.8) as an input and output format: the round trip
//! angles → O → angles is exact away from the poles, and on the poles the
//! conversion stays finite and still reproduces O.

use proptest::prelude::*;
use spintop::math::Vec3;
use spintop::physics::euler_angles::{EulerAngles, body_rate_from_euler, euler_rates};
use std::f64::consts::{PI, TAU};

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

proptest! {
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
