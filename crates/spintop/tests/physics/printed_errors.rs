//! The scenes issue 46 quoted, each against the invariance-equation
//! reference ([`crate::physics::invariance`]): the physical solution within
//! the rtol it is run at, and every printed error true and within 10× of
//! the real one ([`crate::physics::errors_sweep::run_scene`]).

use crate::physics::errors_sweep::{Scene, run_scene};
use crate::physics::invariance::{Manifold, Reference, angle_between};
use serde_json::Value;
use spintop::math::{Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

/// `n` even steps from 0 to `t`.
fn even(t: Real, n: usize) -> Vec<Real> {
    (0..=n).map(|j| t * j as Real / n as Real).collect()
}

/// The physical solution of (3.4) by `Simulation` at `rtol`, its largest
/// errors over `times` against the reference: Ω relative to |Ω₀|, and the
/// orientation in radians.
fn physical_errors(ratio: Real, omega0: Vec3, times: &[Real], rtol: Real) -> (Real, Real) {
    let t_max = *times.last().unwrap();
    let reference = Reference::new(Manifold::Physical, ratio, 1.0, omega0, t_max, 1.0);
    let euler = EulerAngles::new(0.3, 0.7, 0.1);
    let truth = reference.orientations(&euler.to_rotation(), times);
    let top = SymmetricTop::new(ratio, 1.0).unwrap();
    let initial = InitialState::new(omega0, euler).unwrap();
    let options = MethodOptions::default().with_rtol(rtol).unwrap();
    let mut sim = Simulation::new(
        Model::Full(top),
        MethodChoice::Auto,
        options,
        initial,
        Some(t_max),
    )
    .unwrap();
    let (mut omega, mut turn) = (0.0 as Real, 0.0 as Real);
    for (&t, o) in times.iter().zip(&truth) {
        let s = *sim.advance_to(t).unwrap();
        omega = omega.max((s.omega_vec() - reference.omega(t)).norm() / omega0.norm());
        turn = turn.max(angle_between(&s.rotation_matrix(), o));
    }
    (omega, turn)
}

/// Every printed error of the scene holds; the answer's JSON.
fn holds(tag: &str, scene: &Scene) -> Value {
    let o = run_scene(tag, scene);
    assert!(o.bad.is_empty(), "{tag}: {}", o.bad.join("\n"));
    o.json
        .unwrap_or_else(|| panic!("{tag}: refused: {:?}", o.lines))
}

/// Issue 46, 1: a floor of 3.0e-9 at rtol 1e-12 (ratio 0.4, Ω₀ = (0, 0.3, 0))
/// and of 4.2e-9 at every rtol (ratio 0.05, Ω₀ = (0.212, 0.212, 0)): now
/// within rtol in Ω and in the orientation.
#[test]
fn eq_3_4_physical_solution_within_rtol_where_issue_46_found_floors() {
    let times = [0.0, 2.22, 6.67, 8.89, 11.1];
    for rtol in [1e-8, 1e-10, 1e-12] {
        let (omega, turn) = physical_errors(0.4, Vec3::new(0.0, 0.3, 0.0), &times, rtol);
        assert!(
            omega <= rtol && turn <= rtol,
            "rtol {rtol:e}: {omega:e} {turn:e}"
        );
    }
    for rtol in [1e-8, 1e-12, 1e-14] {
        let w = Vec3::new(0.212, 0.212, 0.0);
        let (omega, turn) = physical_errors(0.05, w, &even(0.222, 10), rtol);
        let floor = rtol.max(1e-14);
        assert!(
            omega <= floor && turn <= floor,
            "rtol {rtol:e}: {omega:e} {turn:e}"
        );
    }
}

/// Issue 46, 1: the orientation drifted 3.0e-8 rad at every rtol over
/// 1.33·10⁵ τ (ratio 0.05, Ω₀ = (0, 0.0003, 0.3)); now within rtol.
#[test]
fn eq_3_4_physical_orientation_within_rtol_over_a_long_turning_run() {
    for rtol in [1e-6, 1e-8, 1e-10] {
        let w = Vec3::new(0.0, 0.0003, 0.3);
        let (omega, turn) = physical_errors(0.05, w, &even(1.33e5, 10), rtol);
        assert!(
            omega <= rtol && turn <= rtol,
            "rtol {rtol:e}: {omega:e} {turn:e}"
        );
    }
}

/// The scene at rtol 0.5 answers, its first sample is the input, and what
/// it prints holds.
fn loose(ratio: Real, w: Vec3, t_end: Real) {
    let scene = Scene {
        model: "full",
        ..Scene::new(ratio, w, even(t_end, 4), 0.5)
    };
    let v = holds(&format!("ratio {ratio} {w:?}"), &scene);
    let first: Vec<Real> = v["samples"][0]["omega"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(first, [w.x, w.y, w.z], "ratio {ratio}");
}

/// Issue 46, 4: at rtol 0.5 the first sample was |Ω⊥| = 0.452, not 0.6.
#[test]
fn eq_3_4_loose_rtol_starts_from_the_input_and_its_error_holds() {
    loose(1.0, Vec3::new(0.0, 0.6, 0.29), 20.0);
}

/// Issue 46, 5: the shoots that failed with exit 3 at rtol 0.5 are answered,
/// and what they print holds.
#[test]
#[ignore = "end-to-end: three physical solutions at rtol 0.5 and their references (a minute in debug)"]
fn eq_3_4_loose_rtol_shoots_are_answered_and_hold() {
    loose(0.4, Vec3::new(0.0, 0.5, 0.0), 100.0);
    loose(1.0, Vec3::new(0.0, 1.0, 0.0), 10.0);
    loose(0.5, Vec3::new(0.0, 2.0, 0.0), 1.0);
}

/// Issue 46, 3 and 4: the truncated orientation near the axis (claimed
/// 0.021 rad, real 2.15e-4) within 10× of the truth, and a top that does
/// not move (|Ω₀| ~ 1e-170: the estimates underflowed to 2.0 and the
/// physical tier was chosen) answered by the lightest model, exactly.
#[test]
fn eq_4_7_estimates_near_the_axis_and_for_a_still_top_hold() {
    let scene = Scene::new(
        0.665,
        Vec3::new(4.3e-6, -9.2e-6, 0.0745),
        even(2337.0, 10),
        0.03,
    );
    let v = holds("near the axis", &scene);
    assert_eq!(v["model"], "truncated");
    let still = Scene::new(0.4, Vec3::new(1e-170, 2e-170, 1e-170), even(10.0, 2), 1e-10);
    let v = holds("still", &still);
    assert_eq!(v["model"], "truncated", "{}", v["chosen"]);
    assert!(
        v["error"]["omega"].as_f64().unwrap() <= 1e-13,
        "{}",
        v["error"]
    );
}

/// Issue 46, 4: Figure 2's top at [0, 1e6, 1e12] τ is answered, and
/// without a warning that its error is above rtol: Ω⊥ has decayed below
/// 1e-300 long before its phase (1.2e11 rad) could matter.
#[test]
fn eq_4_15_figure_2_at_long_times_is_answered_within_rtol() {
    let text = Scene::new(0.4, Vec3::new(0.0, 0.1, 0.2), vec![0.0, 1e6, 1e12], 1e-10).text();
    let scene = spintop::scene::parse(&text, "x.toml").unwrap();
    let v = serde_json::to_value(spintop::scene::answer::answer(&scene).unwrap()).unwrap();
    let warnings = v["warnings"].to_string();
    assert!(!warnings.contains("above rtol"), "{warnings}");
    assert!(
        v["error"]["omega"].as_f64().unwrap() <= 1e-10,
        "{}",
        v["error"]
    );
    let last = &v["samples"][2]["omega"];
    assert!(last[0].as_f64().unwrap().abs() < 1e-300, "{last}");
    assert!(last[1].as_f64().unwrap().abs() < 1e-300, "{last}");
    // Ω₃ is conserved by every model of the symmetric top, (4.14).
    assert_eq!(last[2].as_f64().unwrap(), 0.2);
}

/// A nearly free asymmetric top (tiny dipole) by `simulate` with `method`
/// at `rtol`: the largest real errors over the samples (Ω relative to |Ω₀|,
/// the orientation in radians) against `truth` (another method, at 1e-14)
/// and the printed estimate.
fn general_run(
    method: MethodChoice,
    rtol: Real,
    truth: MethodChoice,
    t_end: Real,
) -> (Real, Real, spintop::sim::claim::ErrorEstimate) {
    use spintop::output::simulate::{SimulateConfig, simulate};
    use spintop::physics::general_top::GeneralTop;
    let top = GeneralTop::new(Vec3::new(1.0, 1.5, 0.8), Vec3::new(1e-4, 0.0, 1e-4)).unwrap();
    let omega0 = Vec3::new(0.1, 0.05, 0.2);
    let euler = EulerAngles::new(0.2, 0.9, 0.1);
    let initial = InitialState::new(omega0, euler).unwrap();
    let times = even(t_end, 8);
    let config = SimulateConfig {
        model: Model::General(top),
        method,
        options: MethodOptions::default().with_rtol(rtol).unwrap(),
        initial,
        euler0: [0.2, 0.9, 0.1],
        times: times.clone(),
        format: spintop::output::Format::Json,
        entry: spintop::output::Entry::CommandLine,
    };
    let out = simulate(&config).unwrap();
    let options = MethodOptions::default().with_rtol(1e-14).unwrap();
    let mut reference =
        Simulation::new(Model::General(top), truth, options, initial, Some(t_end)).unwrap();
    let (mut omega, mut turn) = (0.0 as Real, 0.0 as Real);
    for (s, &t) in out.samples.iter().zip(&times) {
        let r = *reference.advance_to(t).unwrap();
        omega = omega.max((s.omega_vec() - r.omega_vec()).norm() / omega0.norm());
        turn = turn.max(angle_between(&s.rotation_matrix(), &r.rotation_matrix()));
    }
    (omega, turn, out.error.expect("an error estimate"))
}

/// Issue 46, 2: `simulate --method dop853|taylor` over 2.3·10⁴ rad printed
/// nothing (2,000–5,000× its rtol); now its printed error over the run is
/// never below the real one and within 10× of it. The truth is the other
/// method at rtol 1e-14 (its own error ~1e-11, far below these).
#[test]
#[ignore = "end-to-end: 2.3e4 rad by two methods and their checks (a minute in debug)"]
fn eq_3_3_an_explicit_methods_error_over_the_run_is_true() {
    for (method, truth, rtol) in [
        (MethodChoice::Dop853, MethodChoice::Taylor, 1e-6),
        (MethodChoice::Dop853, MethodChoice::Taylor, 1e-8),
        (MethodChoice::Taylor, MethodChoice::Dop853, 1e-8),
    ] {
        let (omega, turn, e) = general_run(method, rtol, truth, 1e5);
        let claimed_o = e.orientation.unwrap();
        let tag = format!(
            "{method:?} rtol {rtol:e}: real {omega:.2e} {turn:.2e}, printed {:.2e} {claimed_o:.2e}",
            e.omega
        );
        println!("{tag}");
        assert!(
            omega <= e.omega && e.omega <= 10.0 * omega.max(e.rounding),
            "{tag}"
        );
        assert!(
            turn <= claimed_o && claimed_o <= 10.0 * turn.max(e.orientation_rounding.unwrap()),
            "{tag}"
        );
    }
}
