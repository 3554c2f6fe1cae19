//! The work-precision sweep measures what it says it measures.
//!
//! Its references are right (the stored mpmath runs are the problems spintop
//! solves, the full ALE's shoot converges), its errors behave as the methods'
//! orders say they must (they shrink with the tolerance, RK4's by 2⁴ per
//! halving of the step), the closed forms sit at rounding level against an
//! independent 40-digit reference, the reported time is the time of one
//! solve whatever the batching, and the CSV a run writes reads back to the
//! same rows. The cost of every method on fixed problems is snapshot-tested,
//! so a change that makes a method silently take more steps fails here.

use spintop::integrate::Stats;
use spintop::math::{Real, Vec3};
use spintop::physics::symmetric_top::{SymmetricTop, reduced_closed_form};
use spintop::sim::physical::physical_solution;
use spintop::workprecision::report::{self, cost_at};
use spintop::workprecision::{
    KnobKind, Method, Plan, Problem, ProblemKind, Row, Solution, Solver, Spintop, Stopwatch,
    Target, Timing, measure, omega_error, sweep,
};
use std::cell::Cell;

fn entry(method: Method, target: Target) -> Spintop {
    Spintop { method, target }
}

fn untimed(problem: &Problem, method: Method, target: Target, knob: Option<Real>) -> Row {
    let row = measure(problem, &entry(method, target), knob, None);
    assert!(
        row.ok(),
        "{} {}: {}",
        problem.name(),
        row.method,
        row.status
    );
    row
}

#[test]
fn every_problem_builds_with_a_reference_at_all_200_output_times() {
    for problem in Problem::all().expect("the problems") {
        let times = problem.times();
        assert_eq!(times.len(), 200);
        assert_eq!((times[0], times[199]), (1.0, 200.0));
        let reference = problem.reference();
        assert_eq!(reference.omega.len(), 200, "{}", problem.name());
        let has_orientation = problem.kind() != ProblemKind::Full;
        assert_eq!(reference.rotation.is_some(), has_orientation);
        assert!(!reference.provenance.is_empty());
    }
}

/// The stored references are the problems spintop solves (same start, same
/// parameters, same equations): DOP853 at rtol 1e-13, Ω and the orientation
/// together, lands within 1e-11 of each.
#[test]
fn stored_references_are_the_problems_spintop_solves() {
    for kind in [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ] {
        let problem = Problem::new(kind).unwrap();
        let row = untimed(
            &problem,
            Method::Dop853,
            Target::OmegaOrientation,
            Some(1e-13),
        );
        assert!(row.omega_error.unwrap() < 1e-11, "{kind:?}: {row:?}");
        assert!(row.orientation_error.unwrap() < 1e-11, "{kind:?}: {row:?}");
    }
}

/// Eq. (4.7) and Eqs. (4.15)–(4.16) in double precision against the 40-digit
/// reference: the closed-form rows are at rounding level. The bound is the
/// one of `tests/physics/closed_forms.rs`: a few ulps plus the rounding of the phase
/// α = Ω̃₃ϑ (up to about 24 rad here), 4ε(1 + |α|).
#[test]
fn eq_4_7_and_eq_4_16_closed_form_rows_are_at_rounding_level() {
    let bound = 8.0 * Real::EPSILON + 4.0 * Real::EPSILON * 25.0;
    for kind in [ProblemKind::Truncated, ProblemKind::Reduced] {
        let problem = Problem::new(kind).unwrap();
        let row = untimed(&problem, Method::ClosedForm, Target::Omega, None);
        let err = row.omega_error.unwrap();
        assert!(
            err > 0.0 && err < bound,
            "{kind:?}: {err:e} (bound {bound:e})"
        );
        assert_eq!(row.rhs_evals, Some(0));
    }
    // The truncated orientation (4.9)-(4.11) too.
    let problem = Problem::new(ProblemKind::Truncated).unwrap();
    let row = untimed(&problem, Method::ClosedForm, Target::OmegaOrientation, None);
    assert!(row.orientation_error.unwrap() < bound, "{row:?}");
}

#[test]
fn adaptive_errors_shrink_with_the_tolerance() {
    for kind in [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ] {
        let problem = Problem::new(kind).unwrap();
        for method in [Method::Dopri5, Method::Dop853] {
            let errors: Vec<Real> = [1e-5, 1e-8, 1e-11]
                .iter()
                .map(|&rtol| {
                    untimed(&problem, method, Target::Omega, Some(rtol))
                        .omega_error
                        .unwrap()
                })
                .collect();
            for pair in errors.windows(2) {
                assert!(
                    pair[1] < pair[0] / 30.0,
                    "{kind:?} {method:?}: {errors:?} should fall about 1000x per step"
                );
            }
        }
    }
}

/// RK4 is of order 4: quartering the step divides the error by about 4⁴ = 256.
#[test]
fn rk4_error_falls_as_h_to_the_fourth() {
    let problem = Problem::new(ProblemKind::Reduced).unwrap();
    let err = |h: Real| {
        untimed(&problem, Method::Rk4, Target::Omega, Some(h))
            .omega_error
            .unwrap()
    };
    let ratio = err(0.5) / err(0.125);
    assert!((180.0..360.0).contains(&ratio), "ratio {ratio}");
}

/// The full ALE's reference (spintop's own shoot at rtol 1e-13) agrees with
/// the physical solution found an independent way, the invariance equation of
/// its slow manifold integrated in ln|z|² (tests/support), to 1e-6 at all 200
/// times, and with a looser shoot to 1e-11. Its gap to the reduced model
/// (4.15)–(4.16) is pinned to its O(τ²) prediction: the reduced model
/// precesses 2τ²ks too fast and decays τ³s(3u + 5k²) too fast (s = u + k²),
/// so the physical z is the reduced one times e^{δ − iΔθ} with
/// Δθ = 2τk ln(A₀/A) and δ = τ²[(3/2)(u₀ − u) + 5k² ln(A₀/A)]; the next
/// terms are 7τ²s ≈ 11 % of these here, so within 20 %.
#[test]
fn eq_3_4_full_reference_is_the_physical_solution_and_its_gap_the_predicted_one() {
    let problem = Problem::new(ProblemKind::Full).unwrap();
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let omega0 = problem.initial().omega;
    let reference = &problem.reference().omega;
    let independent: Vec<Vec3> =
        crate::support::physical_by_invariance_equation(&top, &omega0, problem.times())
            .iter()
            .map(|z| Vec3::new(z.re, z.im, omega0.z))
            .collect();
    let diff = omega_error(reference, &independent);
    assert!(
        diff < 1e-6,
        "reference vs the invariance equation: {diff:e}"
    );
    let looser = physical_solution(&top, &omega0, problem.times(), 1e-12).unwrap();
    let looser: Vec<Vec3> = looser
        .z
        .iter()
        .map(|z| Vec3::new(z.re, z.im, omega0.z))
        .collect();
    let diff = omega_error(reference, &looser);
    assert!(diff < 1e-11, "rtol 1e-12 vs 1e-13: {diff:e}");
    let reduced: Vec<Vec3> = problem
        .times()
        .iter()
        .map(|&t| reduced_closed_form(&top, &omega0, t))
        .collect();
    let (tau, k) = (top.tau(), top.ratio() * omega0.z);
    let (a0, u0) = (
        omega0.x.hypot(omega0.y),
        omega0.x.powi(2) + omega0.y.powi(2),
    );
    let predicted: Vec<Vec3> = reduced
        .iter()
        .map(|w| {
            let a = w.x.hypot(w.y);
            let lost = (a0 / a).ln();
            let dtheta = 2.0 * tau * k * lost;
            let delta = tau * tau * (1.5 * (u0 - a * a) + 5.0 * k * k * lost);
            let z = nalgebra::Complex::new(w.x, w.y) * nalgebra::Complex::new(delta, -dtheta).exp();
            Vec3::new(z.re, z.im, w.z)
        })
        .collect();
    let gap = omega_error(reference, &reduced);
    let predicted_gap = omega_error(&predicted, &reduced);
    assert!(
        (gap / predicted_gap - 1.0).abs() < 0.2,
        "full vs reduced: {gap:e}, predicted {predicted_gap:e}"
    );
}

#[test]
fn the_physical_method_is_not_measured_at_or_below_its_reference_tolerance() {
    let problem = Problem::new(ProblemKind::Full).unwrap();
    let physical = entry(Method::Physical, Target::Omega);
    assert!(physical.accepts(&problem, Some(1e-12)));
    assert!(!physical.accepts(&problem, Some(1e-13)));
    let plan = Plan {
        rtols: vec![1e-6, 1e-13],
        steps: vec![],
        timing: None,
    };
    let rows = sweep(&[problem], &[&physical], &plan, None);
    assert_eq!(rows.len(), 1);
    assert!(rows[0].omega_error.unwrap() < 1e-5, "{:?}", rows[0]);
}

#[test]
fn an_untimed_sweep_is_deterministic_to_the_bit() {
    let problems = vec![Problem::new(ProblemKind::General).unwrap()];
    let entries = Spintop::all();
    let solvers: Vec<&dyn Solver> = entries.iter().map(|s| s as &dyn Solver).collect();
    let plan = Plan::quick().untimed();
    let a = sweep(&problems, &solvers, &plan, None);
    let b = sweep(&problems, &solvers, &plan, None);
    assert_eq!(a, b);
    assert!(a.iter().all(|r| r.time_s.is_none() && r.repeats == 0));
}

/// A solver that counts its solves, and a clock that advances 1 ms per solve:
/// whatever the batching, a row reports 1 ms.
struct Counting<'a>(&'a Cell<u64>);

impl Solver for Counting<'_> {
    fn source(&self) -> &str {
        "test"
    }
    fn method(&self) -> &str {
        "counting"
    }
    fn target(&self) -> Target {
        Target::Omega
    }
    fn knob(&self) -> KnobKind {
        KnobKind::None
    }
    fn applies_to(&self, _problem: &Problem) -> bool {
        true
    }
    fn solve(&self, problem: &Problem, _knob: Option<Real>) -> Result<Solution, String> {
        self.0.set(self.0.get() + 1);
        Ok(Solution {
            omega: problem.reference().omega.clone(),
            rotation: None,
            stats: Some(Stats::default()),
        })
    }
}

struct VirtualClock<'a>(&'a Cell<u64>);

impl Stopwatch for VirtualClock<'_> {
    fn seconds(&mut self, work: &mut dyn FnMut()) -> Real {
        let before = self.0.get();
        work();
        (self.0.get() - before) as Real * 1e-3
    }
}

#[test]
fn the_reported_time_is_one_solve_and_the_median_of_the_repeats() {
    let solves = Cell::new(0);
    let problem = Problem::new(ProblemKind::Reduced).unwrap();
    let solver = Counting(&solves);
    let mut clock = VirtualClock(&solves);
    let timing = Timing {
        repeats: 5,
        min_sample: 4.5e-3,
    };
    let row = measure(&problem, &solver, None, Some((&mut clock, timing)));
    assert_eq!(row.time_s, Some(1e-3));
    assert_eq!(row.repeats, 5);
    assert_eq!(row.omega_error, Some(0.0));
    // One first solve, then 5 samples of ceil(4.5 ms / 1 ms) = 5 solves.
    assert_eq!(solves.get(), 1 + 5 * 5);
}

#[test]
fn csv_rows_read_back_identically() {
    let problems = vec![Problem::new(ProblemKind::Reduced).unwrap()];
    let entries = Spintop::all();
    let solvers: Vec<&dyn Solver> = entries.iter().map(|s| s as &dyn Solver).collect();
    let mut rows = sweep(&problems, &solvers, &Plan::quick().untimed(), None);
    rows[0].time_s = Some(1.234_567_890_123e-5);
    rows[0].repeats = 7;
    rows[1].status = "failed, twice\nreally".into();
    let text = report::to_csv(&rows);
    assert!(text.starts_with(&report::CSV_COLUMNS.join(",")));
    let back = report::parse_csv(&text).expect("our own CSV");
    rows[1].status = "failed; twice really".into();
    assert_eq!(back, rows);
    let json: serde_json::Value = serde_json::from_str(&report::to_json(&rows)).unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), rows.len());
    assert_eq!(json["rows"][0]["target"], "omega");
}

#[test]
fn cost_at_interpolates_in_log_log_and_never_extrapolates() {
    // error = cost⁻², from cost 10 (1e-2) to 1000 (1e-6).
    let pts = [(10.0, 1e-2), (100.0, 1e-4), (1000.0, 1e-6)];
    let c = cost_at(&pts, 1e-5).unwrap();
    assert!((c - 10f64.powf(2.5)).abs() < 1e-9 * c, "{c}");
    assert_eq!(cost_at(&pts, 1e-2), Some(10.0));
    assert_eq!(cost_at(&pts, 1e-1), Some(10.0));
    assert_eq!(cost_at(&pts, 1e-8), None);
    // A lucky loose point does not count once the curve is past it.
    let bumpy = [(10.0, 1e-3), (20.0, 1e-9), (30.0, 1e-7), (40.0, 1e-10)];
    let c = cost_at(&bumpy, 1e-8).unwrap();
    assert!(c > 10.0 && c < 20.0, "{c}");
}

/// A successful Ω row of the reduced problem with the given error and time
/// (one evaluation per nanosecond), as a joined CSV file would hold it.
fn row(source: &str, method: &str, err: Real, time: Real) -> Row {
    Row {
        source: source.into(),
        model: "reduced".into(),
        method: method.into(),
        target: Target::Omega,
        knob: KnobKind::Rtol,
        value: Some(1e-6),
        omega_error: Some(err),
        orientation_error: None,
        rhs_evals: Some((time * 1e9) as u64),
        steps: Some(1),
        rejected: Some(0),
        time_s: Some(time),
        repeats: 3,
        status: "ok".into(),
    }
}

#[test]
fn the_join_reports_time_ratios_at_matched_error() {
    // spintop reaches 1e-8 at 10 µs and 1e-12 at 100 µs; scipy 300x slower.
    let rows = vec![
        row("spintop", "dop853", 1e-6, 1e-6),
        row("spintop", "dop853", 1e-10, 1e-5),
        row("spintop", "dop853", 1e-14, 1e-4),
        row("scipy", "DOP853", 1e-6, 3e-4),
        row("scipy", "DOP853", 1e-10, 3e-3),
        row("scipy", "DOP853", 1e-14, 3e-2),
    ];
    let m = report::matched(&rows);
    assert_eq!(m.len(), 2);
    let t = m[0].time[0].unwrap();
    assert!((t - 10f64.powf(-5.5)).abs() < 1e-12, "{t}");
    let text = report::join_table(&rows);
    assert!(text.contains("(300.0x)"), "{text}");
    assert!(
        text.contains("best integrator at 1e-8") && text.contains("best integrator at 1e-12"),
        "{text}"
    );
}

#[test]
fn every_curve_of_a_joined_chart_has_its_own_marker() {
    // Two unknown sources with one initial, and a known peer's marker ('D').
    let rows = vec![
        row("spintop", "dop853", 1e-6, 1e-5),
        row("alpha", "m", 1e-7, 2e-5),
        row("another", "m", 1e-8, 3e-5),
        row("ode_solvers", "Dop853", 1e-9, 4e-5),
    ];
    let text = report::chart(&rows, "reduced", report::CostAxis::Time, 60, 20).unwrap();
    let legend = text.lines().nth(1).unwrap();
    assert!(
        legend.contains("8 dop853")
            && legend.contains("a alpha m")
            && legend.contains("D ode_solvers Dop853"),
        "{legend}"
    );
    // "another m" gets a marker of its own, and each marker is drawn once.
    let marks: Vec<char> = legend
        .split(", ")
        .map(|item| item.trim().chars().next().unwrap())
        .collect();
    assert_eq!(marks.len(), 4, "{legend}");
    let mut unique = marks.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), 4, "{legend}");
    for m in marks {
        assert_eq!(
            text.lines().skip(2).filter(|l| l.contains(m)).count(),
            1,
            "{m}\n{text}"
        );
    }
}

/// The cost of every spintop method on the reduced, general and full
/// problems, at the quick plan's knobs. A change in any count (a method that takes more
/// steps or evaluations for the same answer) fails here; review it with
/// `cargo insta review`.
#[test]
fn cost_counts_of_every_method_on_fixed_problems() {
    let problems = vec![
        Problem::new(ProblemKind::Reduced).unwrap(),
        Problem::new(ProblemKind::General).unwrap(),
        Problem::new(ProblemKind::Full).unwrap(),
    ];
    let entries = Spintop::all();
    let solvers: Vec<&dyn Solver> = entries.iter().map(|s| s as &dyn Solver).collect();
    let rows = sweep(&problems, &solvers, &Plan::quick().untimed(), None);
    // The fixed-step methods' counts follow from their step alone: T/h steps,
    // 4 evaluations each for RK4 (the end slope is reused as the next first
    // stage; src/integrate/rk4.rs) and 2 sub-flows each for the exact
    // rotation-damping splitting of the reduced model (Lie-Trotter with two
    // parts; src/integrate/splitting.rs), none rejected. They are derived
    // here; only the adaptive methods' counts are snapshotted.
    let mut fixed = 0;
    for r in rows.iter().filter(|r| r.knob.name() == "h") {
        let h = r.value.unwrap();
        let steps = (spintop::workprecision::problem::T_END / h).round() as u64;
        let per_step = match r.method.as_str() {
            "rk4" => 4,
            "rotation-damping" => 2,
            other => panic!("a fixed-step method without a derived count: {other}"),
        };
        assert_eq!(
            (r.steps.unwrap(), r.rhs_evals.unwrap(), r.rejected.unwrap()),
            (steps, per_step * steps, 0),
            "{} {} h = {h}",
            r.model,
            r.method
        );
        fixed += 1;
    }
    assert_eq!(
        fixed, 15,
        "rk4 on the reduced and general problems, both targets, and rotation-damping, each at 3 steps"
    );
    let mut text = String::from(
        "model     method              target             knob         evals  steps  rejected\n",
    );
    for r in rows.iter().filter(|r| r.knob.name() != "h") {
        let knob = match r.value {
            Some(v) => format!("{}={v:e}", r.knob.name()),
            None => "-".into(),
        };
        text.push_str(&format!(
            "{:<9} {:<19} {:<18} {:<11} {:>6} {:>6} {:>9}\n",
            r.model,
            r.method,
            r.target.name(),
            knob,
            r.rhs_evals.unwrap(),
            r.steps.unwrap(),
            r.rejected.unwrap()
        ));
    }
    insta::assert_snapshot!(text);
}
