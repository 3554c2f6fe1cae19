//! Issue 46, "estimates within 10× of the truth": the printed errors of the
//! secular model and of a general top's physical solution, each against a
//! reference that shares no code with what it checks: never below the real
//! error, and within 10× of it where the real error stands above rounding.

use crate::physics::invariance::{Manifold, Reference};
use serde_json::Value;
use spintop::math::{Real, Vec3};

/// The answer of a general top's scene, as JSON.
fn answer(inertia: Vec3, dipole: Vec3, omega0: Vec3, times: &[Real], rtol: Real) -> Value {
    let v = |x: Vec3| format!("[{:e}, {:e}, {:e}]", x.x, x.y, x.z);
    let times: Vec<String> = times.iter().map(|t| format!("{t:e}")).collect();
    let text = format!(
        "[scene]\nname = \"claims\"\nkind = \"top\"\ndescription = \"Issue 46 claims.\"\n\n[top]\nmodel = \"auto\"\ninertia = {}\ndipole = {}\nomega = {}\n\n[solve]\ntimes = [{}]\nrtol = {rtol:e}\n",
        v(inertia),
        v(dipole),
        v(omega0),
        times.join(", ")
    );
    let scene = spintop::scene::parse(&text, "claims.toml").unwrap();
    let report = spintop::scene::answer::answer(&scene).unwrap();
    serde_json::to_value(&report).unwrap()
}

fn num(v: &Value) -> Real {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

/// real ≤ claimed, and claimed ≤ 10 real where real is above `floor`.
fn true_within_ten(tag: &str, real: Real, claimed: Real, floor: Real) -> Result<String, String> {
    let line = format!("{tag}: real {real:.2e} printed {claimed:.2e}");
    if real > claimed || (real > floor && claimed > 10.0 * real) || claimed.is_nan() {
        Err(line)
    } else {
        Ok(line)
    }
}

/// Issue 46, 3: the secular model of a symmetric top entered as general
/// (I = (1, 1, 0.4), d = (0, 0, 1), Ω₀ = (6, 3, 7.4)·10⁻⁵, T = 10¹¹) printed
/// "good to about 1.2e-17" at rtol 1e-2, and no `error`; the real |ΔE|/E₀
/// was 6.7e-6 (the slow integration's own error: the averaging loses
/// nothing for this top, whose E and |L| drain at the same rate all round
/// its circular polhode). Now the answer prints its error in E and |L|,
/// true and within 10×, at rtol 1e-2 (the integration's error dominates)
/// down to 1e-8 (the reduced model's own error against (3.4), some 4e-10,
/// dominates: with the second-order manifold standing in for (3.4) it was
/// claimed 4.6e-14).
///
/// The truth: the physical solution of (3.4) for the same top as a
/// symmetric one (I₃/I₁ = 0.4, τ = d²/I₁ = 1) by the invariance equation
/// of its slow manifold ([`crate::physics::invariance`]), E and |L| from its
/// Ω. (The reviewer's mpmath series of the same equation, integrated by
/// SciPy's DOP853 at 1e-13 in ln u, gave E(10⁹) = 1.1695642198266244e-9 and
/// |L|(10⁹) = 3.201387885985153e-5; the reference here agrees with them,
/// checked first.)
#[test]
fn secular_error_of_e_and_l_is_true_for_a_symmetric_top_entered_as_general() {
    let (inertia, dipole) = (Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0));
    let omega0 = Vec3::new(6e-5, 3e-5, 7.4e-5);
    let times = [0.0, 1e9, 1e10, 3e10, 1e11];
    let reference = Reference::new(Manifold::Physical, 0.4, 1.0, omega0, 1e11, 1.0);
    let invariants = |w: Vec3| {
        let l = inertia.component_mul(&w);
        (0.5 * w.dot(&l), l.norm())
    };
    let (e0, l0) = invariants(omega0);
    let truth: Vec<(Real, Real)> = times
        .iter()
        .map(|&t| invariants(reference.omega(t)))
        .collect();
    // The reviewer's independent values at t = 10⁹ (see above).
    assert!((truth[1].0 / 1.1695642198266244e-9 - 1.0).abs() < 1e-11);
    assert!((truth[1].1 / 3.201387885985153e-5 - 1.0).abs() < 1e-11);
    let mut lines = Vec::new();
    let mut bad = Vec::new();
    for rtol in [1e-2, 1e-4, 1e-6, 1e-8] {
        let v = answer(inertia, dipole, omega0, &times, rtol);
        assert_eq!(v["method"], "secular", "{}", v["chosen"]);
        let error = &v["error"];
        assert_eq!(error["measured"], "E and |L|", "{error}");
        assert!(
            error["against"]
                .as_str()
                .unwrap()
                .contains("physical solution"),
            "{error}"
        );
        let real = v["samples"]
            .as_array()
            .unwrap()
            .iter()
            .zip(&truth)
            .map(|(s, (e, l))| {
                ((num(&s["energy"]) - e).abs() / e0).max((num(&s["l_norm"]) - l).abs() / l0)
            })
            .fold(0.0, Real::max);
        match true_within_ten(
            &format!("rtol {rtol:e}"),
            real,
            num(&error["omega"]),
            num(&error["rounding"]),
        ) {
            Ok(line) => lines.push(line),
            Err(line) => bad.push(line),
        }
    }
    println!("{}", lines.join("\n"));
    assert!(bad.is_empty(), "{}\n{}", bad.join("\n"), lines.join("\n"));
}
