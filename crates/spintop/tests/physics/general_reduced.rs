//! The reduced ALE for any top, `GeneralTop::reduced_ale_rhs`: (3.4) with the
//! free motion's Ω̇ and Ω̈ in its small terms. Checked against the symmetric
//! top's (4.12)–(4.14) (an independent implementation), against the free Euler
//! motion as d → 0 (the correction quadratic in d), and against (3.3) for the
//! paper's top: the spin that (3.3) damps, the Schott term keeps.

use proptest::prelude::*;
use spintop::math::Vec3;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};

proptest! {
    #[test]
    fn eq_3_4_reduced_for_a_symmetric_top_is_eq_4_12_to_4_14(
        i1 in 0.3f64..3.0,
        ratio in 0.1f64..2.0,
        d in 0.05f64..1.5,
        w in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let general = GeneralTop::new(Vec3::new(i1, i1, ratio * i1), Vec3::new(0.0, 0.0, d)).unwrap();
        // kappa = 1: tau = d^2 / I1.
        let symmetric = SymmetricTop::new(ratio, d * d / i1).unwrap();
        let omega = Vec3::from(w);
        let a = general.reduced_ale_rhs(&omega);
        let b = sym::reduced_ale_rhs(&symmetric, &omega);
        prop_assert!((a - b).norm() <= 1e-13 * (1.0 + b.norm()), "{a:?} vs {b:?}");
    }

    #[test]
    fn eq_3_4_reduced_tends_to_the_free_euler_motion_as_the_dipole_vanishes(
        inertia in prop::array::uniform3(0.3f64..3.0),
        dir in prop::array::uniform3(-1.0f64..1.0),
        w in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let inertia = Vec3::from(inertia);
        let omega = Vec3::from(w);
        let free = -(omega.cross(&inertia.component_mul(&omega))).component_div(&inertia);
        let dir = Vec3::from(dir);
        prop_assume!(dir.norm() > 0.1);
        prop_assume!(GeneralTop::new(inertia, dir).is_ok()); // a rigid body: triangle inequality
        // The correction is quadratic in the dipole: halving d quarters it.
        let correction = |scale: f64| {
            let top = GeneralTop::new(inertia, dir * scale).unwrap();
            (top.reduced_ale_rhs(&omega) - free).norm()
        };
        let (c1, c2) = (correction(1e-2), correction(5e-3));
        if c1 > 1e-14 {
            prop_assert!((c1 / c2 - 4.0).abs() < 1e-6, "ratio {}", c1 / c2);
        }
    }
}

#[test]
fn eq_3_4_reduced_differs_from_the_truncated_model_by_the_schott_term() {
    // The paper's top: the two reduced forms differ from (3.3) in the spin,
    // which (3.3) damps and the Schott term protects.
    let top = GeneralTop::new(Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0)).unwrap();
    let omega = Vec3::new(0.0, 0.1, 0.2);
    let reduced = top.reduced_ale_rhs(&omega);
    let truncated = top.truncated_ale_rhs(&omega);
    assert_eq!(reduced.z, 0.0);
    assert!((truncated.z - (-0.01 * 0.2)).abs() < 1e-15);
}
