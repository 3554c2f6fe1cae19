//! Issue 46, "estimates within 10× of the truth": the printed errors of the
//! secular model and of a general top's physical solution, each against a
//! reference that shares no code with what it checks: never below the real
//! error, and within 10× of it where the real error stands above rounding.

use crate::physics::invariance::{Manifold, Reference, angle_between};
use serde_json::Value;
use spintop::math::{Mat3, Real, Vec3};

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

/// E and |L| of a top of inertia `inertia` at Ω: ½Ω·IΩ and |IΩ|.
fn e_and_l(inertia: Vec3, w: Vec3) -> (Real, Real) {
    let l = inertia.component_mul(&w);
    (0.5 * w.dot(&l), l.norm())
}

/// E and |L| of the reference's Ω at each of `times`, and at the start.
fn e_and_l_along(
    inertia: Vec3,
    omega0: Vec3,
    times: &[Real],
    reference: &Reference,
) -> (Vec<(Real, Real)>, (Real, Real)) {
    let truth = times
        .iter()
        .map(|&t| e_and_l(inertia, reference.omega(t)))
        .collect();
    (truth, e_and_l(inertia, omega0))
}

/// A secular answer's largest error in E and in |L| (each relative to its
/// start) against the truth at its samples.
fn worst_e_and_l_error(v: &Value, truth: &[(Real, Real)], (e0, l0): (Real, Real)) -> Real {
    v["samples"]
        .as_array()
        .unwrap()
        .iter()
        .zip(truth)
        .map(|(s, (e, l))| {
            ((num(&s["energy"]) - e).abs() / e0).max((num(&s["l_norm"]) - l).abs() / l0)
        })
        .fold(0.0, Real::max)
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
    let (truth, start) = e_and_l_along(inertia, omega0, &times, &reference);
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
        let real = worst_e_and_l_error(&v, &truth, start);
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

/// Issue 46, the review after the secular fix: the same top at T = 3·10⁹
/// and rtol 1e-4 is answered by the secular model as a fallback (the
/// physical solution does not fit the step budget), and printed 3.78e-5
/// against a real 2.37e-7 (160×): the fallback's own error was `auto`'s Ω
/// estimate for stepping the tier, its phase error included, not its drift
/// in E and |L|. Now it is true and within 10× at each rtol of the fallback.
/// The truth as in the test above (the invariance equation of (3.4)'s slow
/// manifold).
#[test]
fn eq_3_4_the_secular_fallback_claims_its_own_drift_in_e_and_l() {
    let (inertia, dipole) = (Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0));
    let omega0 = Vec3::new(6e-5, 3e-5, 7.4e-5);
    let times = [0.0, 7.5e8, 1.5e9, 2.25e9, 3e9];
    let reference = Reference::new(Manifold::Physical, 0.4, 1.0, omega0, 3e9, 1.0);
    let (truth, start) = e_and_l_along(inertia, omega0, &times, &reference);
    let mut lines = Vec::new();
    let mut bad = Vec::new();
    let mut secular = 0;
    for rtol in [1e-3, 1e-4, 1e-5] {
        let v = answer(inertia, dipole, omega0, &times, rtol);
        if v["method"] != "secular" {
            lines.push(format!(
                "rtol {rtol:e}: {} (not the secular model)",
                v["method"]
            ));
            continue;
        }
        secular += 1;
        let error = &v["error"];
        let real = worst_e_and_l_error(&v, &truth, start);
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
    assert!(secular >= 1, "no secular answer: {}", lines.join("\n"));
    assert!(bad.is_empty(), "{}\n{}", bad.join("\n"), lines.join("\n"));
}

/// Issue 46, review F2: the asymmetric top of the catalogue's
/// `asymmetric-top` scene (I = (1, 1.5, 0.8), d = (0.2, 0, 1)) at
/// Ω₀ = 10⁻⁴·(0.6, 0.3, 0.74), rtol 1e-2, answered by the secular model of
/// the reduced ALE. Each sample printed the swing of E and |L| at the start
/// (8.2e-4) as its error, but the swing shrinks as the top slows down: at
/// t = 2.5·10¹⁰ the real error is 9.1e-6 (90× less). The error printed is
/// true and within 10×: for a run sampled from 10⁸ to 10¹¹, and for each
/// late sample alone (a run of [0, t, 10¹¹], whose claim is that of t; 10¹¹
/// makes `auto` choose the secular model outright, as a user's long run
/// does, where [0, t] alone is the slower fallback of a refused stepping).
/// (Early samples alone are left out: at 5·10⁸ the error gathered by the
/// drift changes sign and is 26× below its size before and after.)
///
/// The truth: E and |L| of the reduced ALE stepped directly (no averaging)
/// by `reduced_asymmetric_reference.c` beside this file: Gragg–Bulirsch–
/// Stoer of order 12 in long double, 0.15 rad per step up to 10⁹ and 0.3
/// rad beyond (`./red 1 6 0.3 1 1.5 0.8 0.2 0 1 6e-5 3e-5 7.4e-5 2e8 …`);
/// the two step sizes agree to 1e-16 of E₀ at 10⁹ and 2.5·10¹⁰. The
/// physical solution of (3.4) differs from the reduced ALE here by 4e-8 of
/// E₀ and |L₀| (the same program's second-order slow manifold, mode 2, at
/// 10⁸), far below the errors checked.
#[test]
fn eq_3_4_the_secular_claim_follows_the_swing_as_the_top_slows_down() {
    let (inertia, dipole) = (Vec3::new(1.0, 1.5, 0.8), Vec3::new(0.2, 0.0, 1.0));
    let omega0 = Vec3::new(6e-5, 3e-5, 7.4e-5);
    // (t, E, |L|) by the reference program.
    let reference = [
        (1e8, 2.382745376742122e-09, 6.721538600755413e-05),
        (2e8, 1.6986159626961254e-09, 5.612986124955476e-05),
        (5e8, 1.0179651992058841e-09, 4.2547737655654906e-05),
        (2e9, 4.853383218003773e-10, 2.8342645132108322e-05),
        (3.5e9, 3.7285943678611694e-10, 2.4603657301987637e-05),
        (5e9, 3.156321054363246e-10, 2.2553141341050377e-05),
        (7e9, 2.675811223496989e-10, 2.072414462001259e-05),
        (1e10, 2.2081933626792775e-10, 1.8807198559921023e-05),
        (1.3e10, 1.888780235899668e-10, 1.7388159032093697e-05),
        (1.6e10, 1.6525027339035126e-10, 1.6262205779726566e-05),
        (2e10, 1.4173177866431497e-10, 1.5059614535841047e-05),
        (2.5e10, 1.2037024795509485e-10, 1.3878021351080175e-05),
        (1e11, 3.6955558758521335e-11, 7.689531630746479e-06),
    ];
    let start = e_and_l(inertia, omega0);
    let last = reference.len() - 1;
    let mut runs: Vec<Vec<usize>> = vec![(0..=last).collect()];
    runs.extend((3..last).map(|k| vec![k, last]));
    let mut lines = Vec::new();
    let mut bad = Vec::new();
    for picked in runs {
        let mut times = vec![0.0];
        let mut truth = vec![start];
        for k in picked {
            times.push(reference[k].0);
            truth.push((reference[k].1, reference[k].2));
        }
        let v = answer(inertia, dipole, omega0, &times, 1e-2);
        assert_eq!(v["method"], "secular", "{}", v["chosen"]);
        let error = &v["error"];
        match true_within_ten(
            &format!("times {times:?}"),
            worst_e_and_l_error(&v, &truth, start),
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

/// Issue 46, review: a refusal of the asymmetric top of the F2 test above
/// (the reduced model, rtol 1e-4, up to 10¹¹, too many turns to step)
/// quoted the secular model as "good to about 8.2e-4", its swing at the
/// start, not what its run would meet. It now quotes the error the secular
/// run would print over five samples to the last time: true and within 10×
/// against the same reference (the reduced ALE stepped directly by
/// `reduced_asymmetric_reference.c`).
#[test]
fn eq_3_4_a_refusal_quotes_what_the_secular_model_would_meet() {
    let times = [0.0, 2.5e10, 5e10, 7.5e10, 1e11];
    // (E, |L|) at `times` by the reference program (turn 0.3 rad).
    let truth = [
        (4.6654e-9, 9.554914965608015e-5),
        (1.203702479550953e-10, 1.38780213510802e-05),
        (6.868413439687708e-11, 1.0483071196639507e-05),
        (4.8054949602699736e-11, 8.768576551656667e-06),
        (3.6955558758521335e-11, 7.689531630746479e-06),
    ];
    let text = "[scene]\nname = \"refused\"\nkind = \"top\"\ndescription = \"F2 refused.\"\n\n[top]\nmodel = \"reduced\"\ninertia = [1, 1.5, 0.8]\ndipole = [0.2, 0, 1]\nomega = [6e-5, 3e-5, 7.4e-5]\n\n[solve]\nrtol = 1e-4\ntimes = [0, 2.5e10, 5e10, 7.5e10, 1e11]\n";
    let refusal = match spintop::scene::parse(text, "refused.toml") {
        Ok(_) => panic!("answered at rtol 1e-4"),
        Err(e) => e.to_string(),
    };
    let quoted: Real = refusal
        .split("would print an error of ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no error quoted: {refusal}"));
    // The run the refusal speaks of, at the rtol it advises.
    let advised: Real = refusal
        .split("offered only at rtol >= ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no rtol advised: {refusal}"));
    let top = spintop::physics::general_top::GeneralTop::new(
        Vec3::new(1.0, 1.5, 0.8),
        Vec3::new(0.2, 0.0, 1.0),
    )
    .unwrap();
    let law = spintop::sim::secular::Law::Reduced;
    let run =
        spintop::sim::secular::secular(&top, law, &Vec3::new(6e-5, 3e-5, 7.4e-5), &times, advised)
            .unwrap();
    let (e0, l0) = truth[0];
    let real = run
        .samples
        .iter()
        .zip(&truth)
        .map(|(s, (e, l))| ((s.energy - e).abs() / e0).max((s.l_norm - l).abs() / l0))
        .fold(0.0, Real::max);
    let line = true_within_ten("refusal", real, quoted, 1e-14)
        .unwrap_or_else(|l| panic!("{l}: {refusal}"));
    println!("{line}\n{refusal}");
}

/// The reviewer's reference for the general top I = (0.5, 1, 1.2),
/// d = (0, 1, 0), Ω₀ = (0.05, 0.01, 0.1): the physical solution of (3.4)
/// by `gen34.c` (/work/review/ref46 in the review): backward
/// Gragg–Bulirsch–Stoer steps (H = 0.25, nine stages of Richardson
/// extrapolation) in quadruple precision (__float128) from T + 40, with
/// Newton's method on the three numbers Ω(T + 40) until Ω(0) matched Ω₀ to
/// a residual of 1e-31; the orientation U(t) = O(0)ᵀO(t) stepped with it.
/// Rerun from T + 60 (with the end guess from the full model at T + 60) it
/// agreed to 6e-17 of |Ω₀| at t = 300 and to all 32 printed digits before.
/// Each row: t, Ω (3), U row by row (9); rounded here to 19 digits.
const GENERAL_REFERENCE: [&str; 7] = [
    "0.0 0.05000000000000000000 0.01000000000000000000 0.1000000000000000000 1.000000000000000000 -1.0457318115536594e-30 2.6197462068527376e-31 -1.0457318115536594e-30 1.000000000000000000 5.151381118749759e-31 2.6197462068527376e-31 5.151381118749759e-31 1.000000000000000000",
    "50.0 -0.02667605699922227005 0.03928920321717115017 0.07145028731735792972 -0.1568875287869705473 0.9474897162490652259 -0.2786566721135227931 -0.9833797429223031089 -0.1759741790861956261 -0.04469194004520947836 -0.09138153271412411859 0.2670137185561921901 0.9593503476736807072",
    "100.0 -0.01828188553596245029 -0.03033773780907089811 0.05617957307740993710 -0.2617229858459822305 -0.9397622518627971468 -0.2198817606206308454 0.9598195056176417470 -0.2773302354266191782 0.04283056331781971543 -0.1012304070710454462 -0.1998370598562253705 0.9745858372622956553",
    "150.0 0.01762180663337848803 -0.02872392280226056266 0.05072487216470661063 0.2421520992829780286 0.7883145730388165716 0.5656169151886063287 -0.9572157122757806201 0.09891354694158838090 0.2719451974273569749 0.1584311869084389662 -0.6072694987944500122 0.7785392185681597073",
    "200.0 0.02154789111475220452 0.01182565216682663718 0.04702725778413981163 0.2761780998318086155 -0.9049921707023008123 0.3235967060104740639 0.9583098962804739746 0.2336306592760333543 -0.1644957681436006518 0.07326527051883973643 0.3555360544498738136 0.9317866247816704928",
    "250.0 -0.0002143487261548772036 0.02878531312632153836 0.03864491187156034136 -0.8157294333122319585 0.5597454444716036145 -0.1458441943355710974 -0.5551653537326783429 -0.6868272911123640882 0.4691052144222253294 0.1624097338307499435 0.4636305744626197417 0.8710165146427972110",
    "300.0 -0.01724093001580941390 0.01535132521978438538 0.04013694865119291072 0.9054965231268274987 0.3272177725722189918 0.2701935897057928376 -0.2434257142029409248 0.9220701900676482376 -0.3008828447309669702 -0.3475916688731403955 0.2066763022252106721 0.9145845711734363718",
];

/// Issue 46, 3: the general top above at rtol 1e-10 printed an Ω error of
/// 3.92e-14 where the real one was 5.23e-14: the backward passes were held
/// by their step cap (half an e-folding of the faster runaway), so the
/// second run at rtol 1e-12 took the same steps and agreed with the first
/// to 1e-14 while both were 5.2e-14 off. Now the second run halves that cap
/// too, and every printed error is true and within 10× of the real one, at
/// rtol 1e-8, 1e-10 and 1e-12.
#[test]
fn eq_3_4_general_physical_solution_prints_a_true_error() {
    let (inertia, dipole) = (Vec3::new(0.5, 1.0, 1.2), Vec3::new(0.0, 1.0, 0.0));
    let omega0 = Vec3::new(0.05, 0.01, 0.1);
    let reference: Vec<(Real, Vec3, Mat3)> = GENERAL_REFERENCE
        .iter()
        .map(|row| {
            let x: Vec<Real> = row.split(' ').map(|v| v.parse().unwrap()).collect();
            (
                x[0],
                Vec3::new(x[1], x[2], x[3]),
                Mat3::from_row_slice(&x[4..13]),
            )
        })
        .collect();
    let times: Vec<Real> = reference.iter().map(|r| r.0).collect();
    let (mut lines, mut bad) = (Vec::new(), Vec::new());
    for rtol in [1e-8, 1e-10, 1e-12] {
        let v = answer(inertia, dipole, omega0, &times, rtol);
        assert_eq!(v["model"], "general-full", "{}", v["chosen"]);
        let error = &v["error"];
        let (mut real_w, mut real_o) = (0.0 as Real, 0.0 as Real);
        for (s, (_, w, o)) in v["samples"].as_array().unwrap().iter().zip(&reference) {
            let got: Vec<Real> = s["omega"].as_array().unwrap().iter().map(num).collect();
            real_w = real_w.max((Vec3::new(got[0], got[1], got[2]) - w).norm() / omega0.norm());
            let r: Vec<Real> = s["rotation"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|row| row.as_array().unwrap().iter().map(num))
                .collect();
            real_o = real_o.max(angle_between(&Mat3::from_row_slice(&r), o));
        }
        for (what, real, claimed, rounding) in [
            (
                "Omega",
                real_w,
                num(&error["omega"]),
                num(&error["rounding"]),
            ),
            (
                "orientation",
                real_o,
                num(&error["orientation"]),
                num(&error["orientation_rounding"]),
            ),
        ] {
            match true_within_ten(&format!("rtol {rtol:e} {what}"), real, claimed, rounding) {
                Ok(line) => lines.push(line),
                Err(line) => bad.push(line),
            }
        }
    }
    println!("{}", lines.join("\n"));
    assert!(bad.is_empty(), "{}\n{}", bad.join("\n"), lines.join("\n"));
}

/// Issue 46, 4: Figure 2's top at [0, 1e6, 1e12] τ printed a rounding part
/// of 2e-4 (the whole turning's phase, 4ε per radian) inside a total error
/// of 1e-12: the part may not exceed the whole. No orientation is reported
/// there, so the rounding is Ω's own (the phase counts only while Ω⊥
/// turns, and it has decayed below 1e-300 by 10⁶ τ).
#[test]
fn eq_4_15_figure_2_at_long_times_prints_a_rounding_part_within_its_error() {
    let scene = crate::physics::errors_sweep::Scene::new(
        0.4,
        Vec3::new(0.0, 0.1, 0.2),
        vec![0.0, 1e6, 1e12],
        1e-10,
    );
    let parsed = spintop::scene::parse(&scene.text(), "fig2.toml").unwrap();
    let v = serde_json::to_value(spintop::scene::answer::answer(&parsed).unwrap()).unwrap();
    let error = &v["error"];
    assert!(error["orientation"].is_null(), "{error}");
    assert!(num(&error["rounding"]) <= num(&error["omega"]), "{error}");
}

/// Issue 46, review: Figure 2's catalogue scene (the reduced model, Ω by
/// its closed form and the orientation stepped) printed a rounding of
/// 2.1e-13, the orientation's floor, inside an Ω total of 1.3e-14. Each
/// part now lies within its own total: Ω's rounding within Ω's error, the
/// orientation's (4ε per radian over the whole turning, which the printed
/// samples' turning bounds) within the orientation's.
#[test]
fn eq_4_15_figure_2_prints_each_rounding_part_within_its_own_total() {
    let entry = spintop::scene::catalogue::find("figure-2").unwrap();
    let scene = entry.scene().unwrap();
    let v = serde_json::to_value(spintop::scene::answer::answer(&scene).unwrap()).unwrap();
    let error = &v["error"];
    assert!(num(&error["rounding"]) <= num(&error["omega"]), "{error}");
    let (floor, total) = (
        num(&error["orientation_rounding"]),
        num(&error["orientation"]),
    );
    assert!(floor <= total, "{error}");
    // The orientation's floor is 1e-14 + 4ε per radian: at least that of
    // the samples' own last turning (|Ω|·t bounds it from above, Ω₃·t
    // from below, Ω₃ being constant in the reduced model).
    let last = v["samples"].as_array().unwrap().last().unwrap();
    let w3 = num(&v["parameters"]["omega0"][2]);
    let turned = w3.abs() * num(&last["t"]);
    assert!(
        floor >= 4.0 * Real::EPSILON * turned,
        "{error}, turned {turned}"
    );
}

/// Issue 46, 4: an asymmetric top at T = 10⁹ that `auto` steps at rtol
/// 2e-12 (tighter than the scene's 1e-2, to hold the phase over 10⁵ rad)
/// warned "the error over the run, 3.9e-3, is above rtol = 2e-10": the
/// warning quoted the internal tolerance. The scene's own rtol is what the
/// error is held against: 3.9e-3 is within 1e-2, so no warning.
#[test]
#[ignore = "end-to-end: 10^9 tau stepped at rtol 2e-12 (seconds in release)"]
fn an_above_rtol_warning_quotes_the_scenes_rtol() {
    let v = answer(
        Vec3::new(1.0, 1.5, 0.8),
        Vec3::new(0.2, 0.0, 1.0),
        Vec3::new(0.6e-4, 0.3e-4, 0.74e-4),
        &[0.0, 1e6, 1e7, 1e8, 1e9],
        1e-2,
    );
    let error = &v["error"];
    let worst = num(&error["omega"]).max(num(&error["orientation"]));
    let warnings = v["warnings"].to_string();
    if worst <= 1e-2 {
        assert!(!warnings.contains("above rtol"), "{warnings}");
    } else {
        assert!(warnings.contains("above rtol = 1e-2"), "{warnings}");
    }
}

/// Issue 46, 3: no underflow for a slow top. At |Ω₀| ~ 1e-160 (2E = Ω·IΩ
/// is 1e-320, subnormal, and 0 below ~1e-162) the secular model took a
/// moving top for one at rest (|L| printed 0). Now it runs scale-free: |L|
/// is |IΩ₀| to 1e-13 (the radiation changes it by ~τ_f²|Ω₀|³t ~ 1e-119
/// over 1e200), and the printed error covers what a double drops of the
/// subnormal E (the truth, ½Ω₀·IΩ₀, computed in units of |Ω₀|).
#[test]
fn a_slow_top_is_not_a_top_at_rest_and_its_error_covers_the_subnormal_energy() {
    let (inertia, dipole) = (Vec3::new(0.5, 1.0, 1.2), Vec3::new(0.0, 1.0, 0.0));
    // NOTE: 1e-160 only: at 1e-170 `auto` steps the top (its turning is
    // too slow to change by a rounding), which is the refusals' business.
    for scale in [1e-160, 3e-161] {
        let unit = Vec3::new(1.0, 2.0, 3.0) / 14.0_f64.sqrt();
        let v = answer(inertia, dipole, unit * scale, &[0.0, 1e100, 1e200], 1e-8);
        assert_eq!(v["method"], "secular", "{}", v["chosen"]);
        let l_true = inertia.component_mul(&unit).norm();
        let e_true = 0.5 * unit.dot(&inertia.component_mul(&unit));
        let claimed = num(&v["error"]["omega"]);
        for s in v["samples"].as_array().unwrap() {
            let l = num(&s["l_norm"]) / scale;
            assert!((l / l_true - 1.0).abs() < 1e-13, "|L| {l} vs {l_true}");
            let e = num(&s["energy"]) / scale / scale;
            let real = (e / e_true - 1.0).abs();
            assert!(real <= claimed, "E real {real:e} printed {claimed:e}");
        }
    }
}
