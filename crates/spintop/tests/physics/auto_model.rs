//! `model = "auto"` chooses the lightest model whose estimated error over the
//! run is within rtol (`spintop::sim::accuracy`). Each estimate is checked
//! here against the real error, the largest distance of the model from the
//! physical solution of (3.4) (backward shooting at rtol 1e-12), relative to
//! |Ω₀|: real ≤ claimed everywhere, and claimed ≤ 10 × real wherever the real
//! error stands above the reference's own (1e-9 here), over a grid of
//! I₃/I₁ from 0.05 (prolate) to 2 (the flattest oblate), directions of Ω₀
//! from near the axis to across it, strengths up to the validity line
//! τ√(Ω⊥² + k²) = 0.3 (so τk ≤ 0.3), and horizons from a tenth to several
//! decay times; then asymmetric tops, the secular model's two estimates, the
//! axial case that radiates nothing, and the scenes of the issue that found
//! the old estimate wrong.
//!
//! The coarse grids run in `cargo test`; the finer ones are `#[ignore]`d
//! (`cargo test -p spintop-tests --test core auto_ -- --ignored`).

use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::{Real, State, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::full_ale::{slow_manifold_second_order, slow_manifold_third_order};
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::{SymmetricTop, reduced_closed_form, truncated_closed_form};
use spintop::sim::accuracy::{general_errors, secular_errors, symmetric_errors};
use spintop::sim::physical::general::general_physical_solution;
use spintop::sim::physical::physical_solution;
use spintop::sim::secular::{Law, averaging_error, secular};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

/// Below this the real error is the reference's own (rtol 1e-12 over a run).
const ROUNDING: Real = 1e-9;

/// Checks real ≤ claimed and claimed ≤ 10 × real, with a line for the report.
fn check(what: &str, real: Real, claimed: Real, report: &mut Vec<String>, bad: &mut Vec<String>) {
    check_within(10.0, what, real, claimed, report, bad);
}

/// Checks real ≤ claimed and claimed ≤ `factor` × real.
fn check_within(
    factor: Real,
    what: &str,
    real: Real,
    claimed: Real,
    report: &mut Vec<String>,
    bad: &mut Vec<String>,
) {
    let line = format!("{what}: real {real:.2e} claimed {claimed:.2e}");
    if real > claimed + 1e-11 || (real > ROUNDING && claimed > factor * real) {
        bad.push(line.clone());
    }
    report.push(line);
}

/// The top of a grid point: I₃/I₁ = `ratio`, Ω₀ at angle `theta` from the
/// axis with τ√(Ω⊥₀² + k²) = `strength`, and the end of a run of `decays`
/// decay times 1/(τs₀).
fn symmetric_setup(
    ratio: Real,
    theta: Real,
    strength: Real,
    decays: Real,
) -> (SymmetricTop, Vec3, Real) {
    let top = SymmetricTop::new(ratio, 1.0).unwrap();
    let (sin, cos) = if theta == std::f64::consts::FRAC_PI_2 {
        (1.0, 0.0)
    } else {
        theta.sin_cos()
    };
    let size = strength / (sin * sin + (ratio * cos).powi(2)).sqrt();
    // A phase χ₀ off the axes (the physics does not depend on it).
    let omega0 = Vec3::new(0.6 * size * sin, 0.8 * size * sin, size * cos);
    (top, omega0, decays / (strength * strength))
}

/// One symmetric top: I₃/I₁ = `ratio`, Ω₀ at angle `theta` from the axis
/// with τ√(Ω⊥₀² + k²) = `strength`, over `decays` decay times 1/(τs₀).
fn symmetric_case(point: [Real; 4], report: &mut Vec<String>, bad: &mut Vec<String>) {
    let [ratio, theta, strength, decays] = point;
    let (top, omega0, t_end) = symmetric_setup(ratio, theta, strength, decays);
    let times: Vec<Real> = (0..=400).map(|j| j as Real * t_end / 400.0).collect();
    let phys = physical_solution(&top, &omega0, &times, 1e-12).unwrap();
    let (mut real_t, mut real_r): (Real, Real) = (0.0, 0.0);
    for (j, &t) in times.iter().enumerate() {
        let p = Vec3::new(phys.z[j].re, phys.z[j].im, omega0.z);
        real_t = real_t.max((truncated_closed_form(&top, &omega0, t) - p).norm());
        real_r = real_r.max((reduced_closed_form(&top, &omega0, t) - p).norm());
    }
    let claimed = symmetric_errors(&top, &omega0, t_end);
    assert!(!claimed.exact);
    let what = format!("I3/I1 {ratio} theta {theta:.2} strength {strength} decays {decays}");
    let scale = omega0.norm();
    check(
        &format!("{what} truncated"),
        real_t / scale,
        claimed.truncated,
        report,
        bad,
    );
    check(
        &format!("{what} reduced"),
        real_r / scale,
        claimed.reduced,
        report,
        bad,
    );
}

/// The grid of tops: I₃/I₁ × direction × strength × horizon, each case
/// checked by `case`; fails with every case outside real ≤ claimed ≤
/// `factor` × real.
type Case<'a> = &'a dyn Fn([Real; 4], &mut Vec<String>, &mut Vec<String>);

fn symmetric_grid_of(factor: Real, case: Case, grid: [&[Real]; 4]) {
    let [ratios, thetas, strengths, decays] = grid;
    let (mut report, mut bad) = (Vec::new(), Vec::new());
    for &r in ratios {
        for &th in thetas {
            for &s in strengths {
                for &d in decays {
                    let seen = report.len();
                    case([r, th, s, d], &mut report, &mut bad);
                    if std::env::var_os("SPINTOP_REPORT").is_some() {
                        eprintln!("{}", report[seen..].join("\n"));
                    }
                }
            }
        }
    }
    assert!(
        bad.is_empty(),
        "outside real <= claimed <= {factor} real:\n{}\n(all: {} cases)",
        bad.join("\n"),
        report.len()
    );
}

fn symmetric_grid(ratios: &[Real], thetas: &[Real], strengths: &[Real], decays: &[Real]) {
    symmetric_grid_of(10.0, &symmetric_case, [ratios, thetas, strengths, decays]);
}

/// The coarse grid: prolate, near spherical and oblate tops, Ω₀ near the
/// axis, across it and in between, weak and at the validity line, a short
/// run and one of three decay times.
const COARSE: [&[Real]; 4] = [
    &[0.05, 0.4, 1.0, 2.0],
    &[0.3, 1.0, std::f64::consts::FRAC_PI_2],
    &[0.03, 0.3],
    &[0.1, 3.0],
];

/// The symmetric top's closed-form estimates, coarse grid: prolate, near
/// spherical and oblate tops, Ω₀ near the axis, across it and in between,
/// weak and at the validity line, a short run and one of three decay times.
#[test]
fn auto_estimates_bound_the_symmetric_models_errors_within_a_factor_10() {
    let [ratios, thetas, strengths, decays] = COARSE;
    symmetric_grid(ratios, thetas, strengths, decays);
}

/// The same, on a finer grid (about 1900 cases; the largest claimed/real
/// ratio found is 5.3, at the validity line over 20 decay times).
#[test]
#[ignore = "a finer grid: cargo test -p spintop-tests --test core auto_ -- --ignored"]
fn auto_estimates_bound_the_symmetric_models_errors_on_a_fine_grid() {
    symmetric_grid(
        &[0.05, 0.1, 0.2, 0.4, 0.7, 1.0, 1.3, 1.6, 2.0],
        &[0.02, 0.3, 0.7, 1.0, 1.3, std::f64::consts::FRAC_PI_2],
        &[0.003, 0.01, 0.03, 0.1, 0.2, 0.3],
        &[0.01, 0.1, 1.0, 5.0, 20.0],
    );
}

/// The angle of the rotation between two orientations, in radians:
/// ‖O₁ − O₂‖_F = 2√2 sin(angle/2), without the acos of a trace near 1.
fn rotation_angle(a: &spintop::math::Mat3, b: &spintop::math::Mat3) -> Real {
    2.0 * ((a - b).norm() / (2.0 * std::f64::consts::SQRT_2))
        .min(1.0)
        .asin()
}

/// O(t) of `model` run by `choice` at rtol 1e-12 from Ω₀ and the Euler
/// angles `euler`, at `n` + 1 even times over [0, `t_end`].
fn rotations(
    model: Model,
    choice: MethodChoice,
    omega0: Vec3,
    euler: [Real; 3],
    t_end: Real,
    n: usize,
) -> Vec<spintop::math::Mat3> {
    let [phi, theta, psi] = euler;
    let initial = InitialState::new(omega0, EulerAngles::new(phi, theta, psi)).unwrap();
    let options = MethodOptions::new(1e-12, 0.01).unwrap();
    let times: Vec<Real> = (0..=n).map(|j| t_end * (j as Real / n as Real)).collect();
    Simulation::new(model, choice, options, initial, Some(t_end))
        .unwrap()
        .run(&times)
        .unwrap()
        .iter()
        .map(|s| s.rotation_matrix())
        .collect()
}

/// The largest angle between two runs' orientations, sample by sample.
fn largest_angle(a: &[spintop::math::Mat3], b: &[spintop::math::Mat3]) -> Real {
    a.iter()
        .zip(b)
        .map(|(x, y)| rotation_angle(x, y))
        .fold(0.0, Real::max)
}

/// One symmetric top's orientation errors, as [`symmetric_case`] sets it up:
/// each model's orientation (the truncated one by its closed form (4.9),
/// the reduced one integrated on SO(3) at rtol 1e-12) against the physical
/// solution's (backward shooting, its orientation integrated at 1e-12).
fn orientation_case(
    factor: Real,
    point: [Real; 4],
    report: &mut Vec<String>,
    bad: &mut Vec<String>,
) {
    let [ratio, theta, strength, decays] = point;
    let (top, omega0, t_end) = symmetric_setup(ratio, theta, strength, decays);
    let run = |model: Model, choice: MethodChoice| {
        rotations(model, choice, omega0, [0.3, 0.7, -0.2], t_end, 200)
    };
    let phys = run(Model::Full(top), MethodChoice::Auto);
    let real_t = largest_angle(&run(Model::Truncated(top), MethodChoice::Exact), &phys);
    let real_r = largest_angle(&run(Model::Reduced(top), MethodChoice::Exact), &phys);
    let claimed = symmetric_errors(&top, &omega0, t_end);
    let what = format!("I3/I1 {ratio} theta {theta:.2} strength {strength} decays {decays}");
    check_within(
        factor,
        &format!("{what} truncated orientation"),
        real_t,
        claimed.truncated_orientation,
        report,
        bad,
    );
    check_within(
        factor,
        &format!("{what} reduced orientation"),
        real_r,
        claimed.reduced_orientation,
        report,
        bad,
    );
}

fn orientation_grid(factor: Real, grid: [&[Real]; 4]) {
    symmetric_grid_of(
        factor,
        &|point, report, bad| orientation_case(factor, point, report, bad),
        grid,
    );
}

/// The orientation estimates (in radians), coarse grid: the same tops as
/// the estimates of Ω, each model's orientation against the physical
/// solution's, over a tenth of a decay time and three.
#[test]
fn auto_orientation_estimates_bound_the_symmetric_models_orientation_errors() {
    orientation_grid(10.0, COARSE);
}

/// The same, on a finer grid (450 tops, runs up to twenty decay times):
/// never below the real error; the reduced model's estimate within 1.5 to
/// 8.9 times it, the truncated model's up to 76 times for nearly axial tops
/// over 5 to 20 decay times, where the real error is itself 0.01 to 0.2 rad
/// (there the truncated Ω⊥, which hardly decays, is compared with a reduced
/// one that has, and its turning part is bounded by its integral).
#[test]
#[ignore = "a finer grid: cargo test -p spintop-tests --test core auto_ -- --ignored"]
fn auto_orientation_estimates_bound_the_symmetric_models_orientation_errors_on_a_fine_grid() {
    orientation_grid(
        80.0,
        [
            &[0.05, 0.2, 0.7, 1.0, 1.5, 2.0],
            &[0.02, 0.3, 0.7, 1.3, std::f64::consts::FRAC_PI_2],
            &[0.01, 0.1, 0.3],
            &[0.01, 0.3, 1.0, 5.0, 20.0],
        ],
    );
}

/// Ω₀ along the axis of a symmetric top: the dipole does not move, nothing
/// radiates, and every model keeps Ω₀; the estimate says so exactly.
#[test]
fn auto_recognises_an_axial_spin_as_exact() {
    for ratio in [0.1, 1.0, 2.0] {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let omega0 = Vec3::new(0.0, 0.0, 0.7);
        let e = symmetric_errors(&top, &omega0, 1e6);
        assert!(e.exact && e.truncated == 0.0 && e.reduced == 0.0, "{e:?}");
        let phys = physical_solution(&top, &omega0, &[0.0, 10.0, 1e3], 1e-12).unwrap();
        assert!(phys.z.iter().all(|z| z.norm() == 0.0));
        for t in [10.0, 1e3] {
            assert_eq!(truncated_closed_form(&top, &omega0, t), omega0);
            assert_eq!(reduced_closed_form(&top, &omega0, t), omega0);
        }
    }
    // A general top spinning about a principal axis along its dipole.
    let top = GeneralTop::new(Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.0, 0.3, 0.0)).unwrap();
    let e = general_errors(&top, &Vec3::new(0.0, 0.8, 0.0), 1e4);
    assert!(e.exact, "{e:?}");
    // Off the dipole it radiates, and is not exact.
    let e = general_errors(&top, &Vec3::new(0.0, 0.8, 0.01), 1e2);
    assert!(!e.exact && e.reduced > 0.0, "{e:?}");
}

/// DOP853 on Ω̇ = f(Ω), tight, sampled at `times`.
fn stepped(f: &dyn Fn(&Vec3) -> Vec3, omega0: Vec3, times: &[Real]) -> Vec<Vec3> {
    let rhs = |_t: Real, y: &State<3>| f(y);
    let mut s = Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-12, 1e-16).unwrap()).unwrap();
    solve(&mut s, &rhs, times).unwrap()
}

/// Tops with three different moments (and one symmetric top written as a
/// general one), with Ω₀ and d in general directions.
fn general_tops() -> Vec<(Vec3, Vec3, Vec3)> {
    vec![
        // the asymmetric-top scene's shape
        (
            Vec3::new(1.0, 1.5, 0.8),
            Vec3::new(0.2, 0.0, 1.0),
            Vec3::new(0.1, 0.05, 0.2),
        ),
        // the book's asymmetric top
        (
            Vec3::new(1.0, 2.0, 2.5),
            Vec3::new(1.0, 0.5, 0.2),
            Vec3::new(0.2, 0.5, -0.4),
        ),
        // spinning near the intermediate axis
        (
            Vec3::new(1.0, 2.0, 2.9),
            Vec3::new(0.0, 0.6, 0.8),
            Vec3::new(0.05, 1.0, 0.05),
        ),
        // the oblate symmetric top, as a general one
        (
            Vec3::new(1.0, 1.0, 2.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.6, 0.8),
        ),
    ]
}

/// Each general top's estimates against the real errors: of Ω, or (with
/// `orientation`) of the orientation.
fn general_grid(
    tops: &[(Vec3, Vec3, Vec3)],
    shares: &[Real],
    decays: &[Real],
    orientation: bool,
) -> Vec<String> {
    let (mut report, mut bad) = (Vec::new(), Vec::new());
    for &(inertia, direction, omega0) in tops {
        for &eps in shares {
            for &d in decays {
                // τ_f|Ω₀| = eps.
                let dipole = direction.normalize() * (eps * inertia.min() / omega0.norm()).sqrt();
                let top = GeneralTop::new(inertia, dipole).unwrap();
                let t_end = d / (eps * omega0.norm());
                let claimed = general_errors(&top, &omega0, t_end);
                let what = format!("I {:?} eps {eps} decays {d}", inertia.as_slice());
                if orientation {
                    general_orientation_case(
                        &top,
                        omega0,
                        t_end,
                        &claimed,
                        &what,
                        &mut report,
                        &mut bad,
                    );
                    continue;
                }
                let times: Vec<Real> = (0..=200).map(|j| j as Real * t_end / 200.0).collect();
                let phys = general_physical_solution(&top, &omega0, &times, 1e-11).unwrap();
                let red = stepped(&|w| top.reduced_ale_rhs(w), omega0, &times);
                let trunc = stepped(&|w| top.truncated_ale_rhs(w), omega0, &times);
                let worst = |m: &[Vec3]| {
                    m.iter()
                        .zip(&phys.omega)
                        .map(|(a, b)| (a - b).norm() / omega0.norm())
                        .fold(0.0, Real::max)
                };
                check(
                    &format!("{what} truncated"),
                    worst(&trunc),
                    claimed.truncated,
                    &mut report,
                    &mut bad,
                );
                check(
                    &format!("{what} reduced"),
                    worst(&red),
                    claimed.reduced,
                    &mut report,
                    &mut bad,
                );
            }
        }
    }
    if std::env::var_os("SPINTOP_REPORT").is_some() {
        eprintln!("{}", report.join("\n"));
    }
    assert!(
        bad.is_empty(),
        "outside real <= claimed <= 10 real:\n{}",
        bad.join("\n")
    );
    report
}

/// One general top's orientation errors: each model stepped at rtol 1e-12
/// on SO(3), against the physical solution's.
fn general_orientation_case(
    top: &GeneralTop,
    omega0: Vec3,
    t_end: Real,
    claimed: &spintop::sim::accuracy::ModelErrors,
    what: &str,
    report: &mut Vec<String>,
    bad: &mut Vec<String>,
) {
    let top = *top;
    let run = |model: Model, choice: MethodChoice| {
        rotations(model, choice, omega0, [0.3, 0.7, -0.2], t_end, 200)
    };
    let phys = run(Model::GeneralFull(top), MethodChoice::Auto);
    let apart = |m: Vec<spintop::math::Mat3>| largest_angle(&m, &phys);
    check(
        &format!("{what} truncated orientation"),
        apart(run(Model::General(top), MethodChoice::Dop853)),
        claimed.truncated_orientation,
        report,
        bad,
    );
    check(
        &format!("{what} reduced orientation"),
        apart(run(Model::GeneralReduced(top), MethodChoice::Dop853)),
        claimed.reduced_orientation,
        report,
        bad,
    );
}

/// Asymmetric tops: the leading errors integrated along the run (with the
/// slow manifold to second order) against the physical solution of (3.4)
/// by its three-dimensional shoot.
#[test]
fn auto_estimates_bound_the_general_models_errors_within_a_factor_10() {
    general_grid(&general_tops(), &[0.03], &[0.1, 1.0], false);
    // The weak dipole over a whole decay time (about 330 radians, the
    // slowest case) is the fine grid's, in the end-to-end tier.
    general_grid(&general_tops(), &[0.003], &[0.1], false);
}

/// The same tops' orientation estimates (the body-frame orientation error
/// integrated with the run) against each model's orientation stepped on
/// SO(3) and the physical solution's.
#[test]
fn auto_orientation_estimates_bound_the_general_models_orientation_errors() {
    general_grid(&general_tops(), &[0.03], &[0.1, 1.0], true);
    general_grid(&general_tops(), &[0.003], &[0.1], true);
}

/// More shares and horizons, and an elongated top (moments 1, 5, 5.5) over
/// a tenth of a decay time.
#[test]
#[ignore = "a finer grid: cargo test -p spintop-tests --test core auto_ -- --ignored"]
fn auto_estimates_bound_the_general_models_errors_on_a_fine_grid() {
    let elongated = [(
        Vec3::new(1.0, 5.0, 5.5),
        Vec3::new(0.3, 1.0, 0.6),
        Vec3::new(0.9, 0.2, 0.1),
    )];
    general_grid(
        &general_tops(),
        &[0.003, 0.01, 0.03],
        &[0.1, 1.0, 5.0],
        false,
    );
    general_grid(&elongated, &[0.003, 0.01, 0.03], &[0.1, 0.3], false);
    // The orientation's reference is the simulation of the physical
    // solution, which refuses 5 decay times at τ_f|Ω₀| = 0.003 (4e7 steps).
    general_grid(&general_tops(), &[0.003, 0.01, 0.03], &[0.1, 1.0], true);
    general_grid(&elongated, &[0.003, 0.01, 0.03], &[0.1, 0.3], true);
}

/// Where the estimate is loose: the elongated top (1, 5, 5.5) spun near its
/// axis of least inertia loses energy across the separatrix of the
/// intermediate axis within a decay time, where a small difference in the
/// invariants becomes a large one in the phase, and the third-order term
/// partly cancels the second: the estimate still bounds the real error, by
/// up to 16 times.
#[test]
fn auto_estimate_still_bounds_the_error_across_a_separatrix() {
    let (inertia, direction, omega0) = (
        Vec3::new(1.0, 5.0, 5.5),
        Vec3::new(0.3, 1.0, 0.6),
        Vec3::new(0.9, 0.2, 0.1),
    );
    let eps = 0.01;
    let top = GeneralTop::new(
        inertia,
        direction.normalize() * (eps * inertia.min() / omega0.norm()).sqrt(),
    )
    .unwrap();
    let t_end = 1.0 / (eps * omega0.norm());
    let times: Vec<Real> = (0..=200).map(|j| j as Real * t_end / 200.0).collect();
    let phys = general_physical_solution(&top, &omega0, &times, 1e-11).unwrap();
    let red = stepped(&|w| top.reduced_ale_rhs(w), omega0, &times);
    let real = red
        .iter()
        .zip(&phys.omega)
        .map(|(a, b)| (a - b).norm() / omega0.norm())
        .fold(0.0, Real::max);
    let claimed = general_errors(&top, &omega0, t_end).reduced;
    assert!(
        real <= claimed && claimed <= 20.0 * real,
        "real {real:e}, claimed {claimed:e}"
    );
}

/// The secular model answers E and |L| alone. Its own error, the swing of
/// the invariants within a turn that averaging leaves out
/// (`averaging_error`), against the secular model run beside DOP853 stepping
/// each law: real ≤ claimed ≤ 10 × real; and the models' errors in E and |L|
/// (`secular_errors`) against the stepped models, with the slow manifold to
/// third order stepped as the physical solution (the shoot over thousands of
/// turns is too costly) and the secular model's own swing allowed on top.
#[test]
fn auto_secular_estimates_bound_the_errors_of_e_and_l() {
    let (mut report, mut bad) = (Vec::new(), Vec::new());
    let tops = [general_tops()[0], general_tops()[1], general_tops()[2]];
    let invariants =
        |i: &Vec3, w: &Vec3| (0.5 * w.dot(&i.component_mul(w)), i.component_mul(w).norm());
    for (inertia, direction, omega0) in tops {
        for eps in [1e-3, 1e-2] {
            let dipole = direction.normalize() * (eps * inertia.min() / omega0.norm()).sqrt();
            let top = GeneralTop::new(inertia, dipole).unwrap();
            for decays in [0.3, 3.0] {
                let t_end = decays / (eps * omega0.norm());
                let times: Vec<Real> = (0..=200).map(|j| j as Real * t_end / 200.0).collect();
                let second = stepped(
                    &|w| {
                        top.reduced_ale_rhs(w)
                            + slow_manifold_second_order(&top, w)
                            + slow_manifold_third_order(&top, w)
                    },
                    omega0,
                    &times,
                );
                let what = format!("I {:?} eps {eps} decays {decays}", inertia.as_slice());
                for law in [Law::Truncated, Law::Reduced] {
                    let f = |w: &Vec3| match law {
                        Law::Truncated => top.truncated_ale_rhs(w),
                        _ => top.reduced_ale_rhs(w),
                    };
                    let path = stepped(&f, omega0, &times);
                    let run = secular(&top, law, &omega0, &times, 1e-10).unwrap();
                    let (mut averaging, mut model): (Real, Real) = (0.0, 0.0);
                    // The models' errors in E and |L|, each relative to its
                    // start, as the estimate states them.
                    let (e0, l0) = invariants(&inertia, &omega0);
                    for ((s, w), p) in run.samples.iter().zip(&path).zip(&second) {
                        let (e, l) = invariants(&inertia, w);
                        let (e2, l2) = invariants(&inertia, p);
                        averaging = averaging
                            .max((s.energy / e - 1.0).abs())
                            .max((s.l_norm / l - 1.0).abs());
                        model = model.max((e - e2).abs() / e0).max((l - l2).abs() / l0);
                    }
                    let swing = averaging_error(&top, law, &omega0);
                    check(
                        &format!("{what} {law:?} averaging"),
                        averaging,
                        swing,
                        &mut report,
                        &mut bad,
                    );
                    let claimed = secular_errors(&top, &omega0, &times, 1e-10).unwrap();
                    let c = if law == Law::Truncated {
                        claimed.truncated
                    } else {
                        claimed.reduced
                    };
                    // The stepped models' invariants swing within a turn
                    // about the drift the estimate follows.
                    let allowed = c + swing + averaging_error(&top, Law::Manifold, &omega0);
                    report.push(format!(
                        "{what} {law:?} model: real {model:.2e} claimed {allowed:.2e}"
                    ));
                    if model > allowed {
                        bad.push(format!(
                            "{what} {law:?} model: real {model:.2e} claimed {allowed:.2e}"
                        ));
                    }
                }
            }
        }
    }
    println!("{}", report.join("\n"));
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The scenes that found the old estimate wrong: the oblate top of the
/// issue, where the reduced model's real error (3.8e-3) exceeds rtol = 1e-3
/// although the old estimate claimed 9.0e-4, now goes to the physical
/// solution; a prolate top whose reduced model is within rtol (the old
/// estimate sent it to the full model) now takes the reduced model; an axial
/// spin takes the truncated model, exactly.
#[test]
fn auto_picks_a_model_really_within_rtol_for_the_issues_scenes() {
    let scene = |ratio: Real, omega: &str| {
        spintop::scene::parse(
            &format!(
                "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"auto\"\nratio = {ratio}\nomega = {omega}\n[solve]\nt_end = 900.0\nrtol = 1e-3\n"
            ),
            "s.toml",
        )
        .unwrap()
    };
    let times: Vec<Real> = (0..=400).map(|j| j as Real * 900.0 / 400.0).collect();
    let real_reduced = |ratio: Real, omega0: Vec3| {
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let phys = physical_solution(&top, &omega0, &times, 1e-12).unwrap();
        times
            .iter()
            .zip(&phys.z)
            .map(|(&t, z)| {
                (reduced_closed_form(&top, &omega0, t) - Vec3::new(z.re, z.im, omega0.z)).norm()
                    / omega0.norm()
            })
            .fold(0.0, Real::max)
    };
    let oblate = scene(2.0, "[0.0, 0.006, 0.008]");
    assert_eq!(oblate.chosen.method, "physical", "{}", oblate.chosen.reason);
    let real = real_reduced(2.0, Vec3::new(0.0, 0.006, 0.008));
    assert!(
        (3.5e-3..4.1e-3).contains(&real),
        "the issue measured 3.8e-3: {real:e}"
    );

    let prolate = scene(0.1, "[0.0, 0.006, 0.008]");
    assert_eq!(
        prolate.chosen.method, "exact+dop853",
        "{}",
        prolate.chosen.reason
    );
    assert!(
        prolate
            .chosen
            .reason
            .contains("the lightest within rtol = 1e-3 is the reduced ALE")
    );
    let real = real_reduced(0.1, Vec3::new(0.0, 0.006, 0.008));
    assert!(
        real < 1e-3,
        "the reduced model really is within rtol: {real:e}"
    );

    let axial = scene(0.4, "[0.0, 0.0, 0.3]");
    assert_eq!(axial.chosen.method, "exact", "{}", axial.chosen.reason);
    assert!(
        axial.chosen.reason.contains("nothing radiates"),
        "{}",
        axial.chosen.reason
    );
}

/// Times that end at t = 0 (or within rounding of it) lose nothing, and
/// both estimates are +0: the reason said "by -0.0e0" (expm1 of −0).
#[test]
fn auto_estimates_of_a_run_that_ends_at_zero_are_zero_not_minus_zero() {
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    for t in [0.0, 1e-300] {
        let e = symmetric_errors(&top, &Vec3::new(0.0, 0.1, -0.2), t);
        assert!(
            e.reduced == 0.0 && e.reduced.is_sign_positive(),
            "{t}: {e:?}"
        );
    }
    let text = "[scene]\nname = \"x\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"auto\"\nomega = [0.0, 0.1, -0.2]\n[solve]\ntimes = [0.0, 1e-300]\n";
    let scene = spintop::scene::parse(text, "zero.toml").unwrap();
    assert!(
        !scene.chosen.reason.contains("-0."),
        "{}",
        scene.chosen.reason
    );
}

/// The orientation counts as well as Ω: this prolate top's truncated model
/// stays within 0.1 of Ω₀ in Ω over t = 2000, while its orientation ends
/// 1.9 rad off the physical solution's (the precession's phase error adds
/// up). `auto` at rtol 0.1 once took the truncated model on Ω alone; now it
/// takes a model whose orientation really is within rtol, and says both.
#[test]
fn auto_holds_the_orientation_to_rtol_as_well_as_omega() {
    let omega0 = Vec3::new(0.0, 0.0062068, 0.124033);
    let t_end = 2000.0;
    let scene = spintop::scene::parse(
        "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"auto\"\nratio = 0.4\nomega = [0.0, 0.0062068, 0.124033]\n[solve]\nt_end = 2000.0\nrtol = 0.1\n",
        "s.toml",
    )
    .unwrap();
    let reason = &scene.chosen.reason;
    assert!(reason.contains("rad in the orientation"), "{reason}");
    assert!(
        !reason.contains("the lightest within rtol = 1e-1 is the truncated ALE"),
        "{reason}"
    );
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let run =
        |model: Model, choice: MethodChoice| rotations(model, choice, omega0, [0.0; 3], t_end, 200);
    let phys = run(Model::Full(top), MethodChoice::Auto);
    let worst = |m: Vec<spintop::math::Mat3>| largest_angle(&m, &phys);
    let truncated = worst(run(Model::Truncated(top), MethodChoice::Exact));
    assert!(truncated > 1.5, "the truncated orientation: {truncated}");
    let e = symmetric_errors(&top, &omega0, t_end);
    assert!(
        e.truncated < 0.1 && e.truncated_orientation >= truncated,
        "{e:?}"
    );
    // The chosen model (the reduced one, or the physical solution itself).
    if reason.contains("is the reduced ALE") {
        let reduced = worst(run(Model::Reduced(top), MethodChoice::Exact));
        assert!(reduced <= 0.1, "the reduced orientation: {reduced}");
    } else {
        assert!(reason.contains("is the physical solution"), "{reason}");
    }
}

/// A general top (no closed form) over 10⁷ τ, Ω₀ across its axis: Ω is held
/// by the lighter models (the reduced ALE by 1e-4 at 10⁵ τ already), the
/// orientation only by the physical solution, which would take 3e8 steps.
/// The refusal says so and names the model that answers Ω, instead of only
/// "ask for shorter times"; where no lighter model holds Ω (an asymmetric top
/// over 10⁶ τ at rtol 1e-3, off by 0.6) it gives their errors.
#[test]
fn auto_refusing_the_physical_solution_says_why_and_which_model_holds_omega() {
    let refusal = |inertia: &str, dipole: &str, omega: &str, t_end: &str, rtol: &str| {
        spintop::scene::parse(
            &format!(
                "[scene]\nname = \"g\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"auto\"\ninertia = {inertia}\ndipole = {dipole}\nomega = {omega}\n[solve]\nt_end = {t_end}\nrtol = {rtol}\n"
            ),
            "g.toml",
        )
        .map_or_else(|e| e.message, |_| panic!("the physical solution is refused"))
    };
    let orientation = refusal(
        "[1.0, 1.0, 0.4]",
        "[0.0, 0.0, 1.0]",
        "[0.0, 0.01, 0.0]",
        "1e7",
        "1e-2",
    );
    assert!(
        orientation.contains("for the orientation alone")
            && (orientation.contains("(model = \"reduced\")")
                || orientation.contains("(model = \"truncated\")")),
        "{orientation}"
    );
    let omega = refusal(
        "[1.0, 1.5, 0.8]",
        "[0.2, 0.0, 1.0]",
        "[0.0, 0.01, 0.02]",
        "1e6",
        "1e-3",
    );
    assert!(
        omega.contains("chose it: the truncated and the reduced ALE may be off by")
            && omega.contains("in Omega, more than rtol = 1e-3"),
        "{omega}"
    );
}

/// Ω₀ across the axis of a weak top: Ω stays within rtol in every model,
/// but the orientation's lab phase about L grows like √t (1 rad by 10⁷ τ),
/// so only the physical solution holds it. Over 10⁷ τ it runs (its cost is
/// counted until Ω⊥ settles: about 5e3 steps; the old estimate said 4e7
/// and the closed form answered Ω alone); over 10⁹ τ it would take more
/// than the budget, and `auto` answers Ω by the closed form and leaves the
/// orientation out, saying why, instead of refusing the scene (or
/// reporting an orientation radians off).
#[test]
fn auto_answers_omega_alone_when_only_the_physical_solution_holds_the_orientation() {
    let scene = |t_end: &str| {
        spintop::scene::parse(
            &format!(
                "[scene]\nname = \"s\"\nkind = \"top\"\ndescription = \"d\"\n[top]\nmodel = \"auto\"\nratio = 0.4\nomega = [0.0, 0.01, 0.0]\n[solve]\nt_end = {t_end}\nrtol = 1e-2\n"
            ),
            "s.toml",
        )
        .unwrap()
    };
    let long = scene("1e9");
    assert_eq!(long.chosen.method, "exact", "{}", long.chosen.reason);
    assert!(
        long.chosen.reason.contains("so it is skipped")
            || long
                .chosen
                .reason
                .contains("the orientation is not computed"),
        "{}",
        long.chosen.reason
    );
    let top = SymmetricTop::new(0.4, 1.0).unwrap();
    let e = symmetric_errors(&top, &Vec3::new(0.0, 0.01, 0.0), 1e7);
    assert!(
        e.truncated <= 1e-2 && e.truncated_orientation > 1e-2,
        "{e:?}"
    );
    let shorter = scene("1e7");
    assert_eq!(
        shorter.chosen.method, "physical",
        "{}",
        shorter.chosen.reason
    );
}

/// A general top's reduced model against the physical solution of (3.4), in
/// Ω and in the orientation (and the truncated model's orientation), both integrated at rtol 1e-12 on SO(3) from the
/// same start, and the estimate [`general_errors`] over the run.
fn general_model_errors(inertia: Vec3, dipole: Vec3, omega0: Vec3, t_end: Real) -> [Real; 6] {
    let top = GeneralTop::new(inertia, dipole).unwrap();
    let times: Vec<Real> = (0..=400).map(|j| j as Real * t_end / 400.0).collect();
    let initial = InitialState::new(omega0, EulerAngles::new(0.3, 0.7, -0.2)).unwrap();
    let options = MethodOptions::new(1e-12, 0.01).unwrap();
    let run = |model: Model| {
        Simulation::new(model, MethodChoice::Auto, options, initial, Some(t_end))
            .unwrap()
            .run(&times)
            .unwrap()
    };
    let (phys, red) = (
        run(Model::GeneralFull(top)),
        run(Model::GeneralReduced(top)),
    );
    let pairs = || red.iter().zip(&phys);
    let omega = pairs()
        .map(|(a, b)| (Vec3::from(a.omega) - Vec3::from(b.omega)).norm() / omega0.norm())
        .fold(0.0, Real::max);
    let turn = pairs()
        .map(|(a, b)| rotation_angle(&a.rotation_matrix(), &b.rotation_matrix()))
        .fold(0.0, Real::max);
    let truncated = run(Model::General(top));
    let turn_t = truncated
        .iter()
        .zip(&phys)
        .map(|(a, b)| rotation_angle(&a.rotation_matrix(), &b.rotation_matrix()))
        .fold(0.0, Real::max);
    let claimed = general_errors(&top, &omega0, t_end);
    [
        omega,
        claimed.reduced,
        turn,
        claimed.reduced_orientation,
        turn_t,
        claimed.truncated_orientation,
    ]
}

/// Ω₀ across the dipole (no spin term, so G₂ nearly vanishes): the reduced
/// ALE's error is its wrong drift of the invariants, third order in Ω
/// (G₃), and over a long run it adds up along L into the orientation's
/// phase, first order in τ_f. With G₂ alone the estimate claimed 4.8e-3 rad
/// where the orientation was 9.4e-3 rad off (so auto at rtol 5e-3 took the
/// reduced model), 4.0e-4 where it was 2.3e-3 with τ_f/4, and 3.7e-6 in Ω
/// where it was 1.4e-5. The truncated model's orientation follows its
/// error of Ω past the linearisation's reach (the last top: it claimed
/// 0.31 rad where the orientation was 0.41 off).
#[test]
fn auto_general_estimates_bound_the_models_orientation_through_the_third_order() {
    let (mut report, mut bad) = (Vec::new(), Vec::new());
    let across = Vec3::new(0.02, 0.001, 0.0);
    for (inertia, dipole, omega0, t_end) in [
        (
            Vec3::new(1.0, 1.05, 1.8),
            Vec3::new(0.3, 0.0, 1.0),
            across,
            3000.0,
        ),
        (
            Vec3::new(1.0, 1.05, 1.8),
            Vec3::new(0.15, 0.0, 0.5),
            across,
            12000.0,
        ),
        (
            Vec3::new(1.0, 1.3, 0.6),
            Vec3::new(0.0, 0.0, 1.0),
            across,
            30.0,
        ),
        (
            Vec3::new(1.0, 1.05, 1.8),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.002, 0.03),
            3000.0,
        ),
    ] {
        let [omega, claimed, turn, claimed_turn, turn_t, claimed_turn_t] =
            general_model_errors(inertia, dipole, omega0, t_end);
        let what = format!(
            "I {:?} d {:?} T {t_end}",
            inertia.as_slice(),
            dipole.as_slice()
        );
        check(
            &format!("{what} reduced Omega"),
            omega,
            claimed,
            &mut report,
            &mut bad,
        );
        check(
            &format!("{what} reduced orientation"),
            turn,
            claimed_turn,
            &mut report,
            &mut bad,
        );
        check(
            &format!("{what} truncated orientation"),
            turn_t,
            claimed_turn_t,
            &mut report,
            &mut bad,
        );
    }
    assert!(bad.is_empty(), "{bad:#?}\n{report:#?}");
}

/// G₃ where τ|Ω| is a molecule's (10⁻¹⁶ … 10⁻¹³): G₁ is then below 10⁻¹⁶ of
/// the free Euler term G₀ (I₃ ≠ I₁), so a derivative of G₁ taken as one of
/// (G₀ + G₁) − G₀ is lost to rounding (G₃ came out 0.025 and 0.74 of the
/// series' τ³s(3u + 5k²)z at I₃/I₁ = 0.1 and 2). Prolate and oblate, d
/// from 10⁻⁸ to 10⁻⁵, |Ω| from 10⁻³ to 10³.
#[test]
fn eq_3_4_slow_manifold_third_order_of_the_symmetric_top_holds_at_a_molecules_tau_omega() {
    for ratio in [0.1, 2.0] {
        for (d, scale) in [(1e-8, 1e-3), (1e-8, 1.0), (1e-8, 1e3), (1e-5, 1e-3)] {
            let top = GeneralTop::new(Vec3::new(1.0, 1.0, ratio), Vec3::new(0.0, 0.0, d)).unwrap();
            let omega = Vec3::new(0.3, -0.4, 0.7) * scale;
            let tau: Real = d * d;
            let (u, k) = (omega.x * omega.x + omega.y * omega.y, ratio * omega.z);
            let s = u + k * k;
            let z = Vec3::new(omega.x, omega.y, 0.0);
            let g3 = z * (tau.powi(3) * s * (3.0 * u + 5.0 * k * k));
            let got = slow_manifold_third_order(&top, &omega);
            let along = got.dot(&z) / u;
            assert!(
                (along / (g3.norm() / u.sqrt()) - 1.0).abs() < 1e-6,
                "I3/I1 {ratio}, d {d:e}, Omega {omega:?}: {got:?} against {g3:?}"
            );
        }
    }
}

/// The symmetric top as a general one (I = (1, 1, 2), d on the axis, so
/// τ = |d|²): the slow manifold's series ż = f(u)z of the notes,
/// Re f = −τs + τ³s(3u + 5k²), Im f = −Ω̃₃ − 2τ²ks + O(τ⁴), gives
/// G₂ = −2iτ²ksz and G₃ = τ³s(3u + 5k²)z.
#[test]
fn eq_3_4_slow_manifold_third_order_of_the_symmetric_top_is_tau3_s_3u_5k2_z() {
    let tau: Real = 0.01;
    let top = GeneralTop::new(Vec3::new(1.0, 1.0, 2.0), Vec3::new(0.0, 0.0, tau.sqrt())).unwrap();
    for omega in [
        Vec3::new(0.3, -0.4, 0.7),
        Vec3::new(0.05, 0.02, -1.1),
        Vec3::new(0.9, 0.1, 0.0),
    ] {
        let (u, k) = (omega.x * omega.x + omega.y * omega.y, 2.0 * omega.z);
        let s = u + k * k;
        let iz = Vec3::new(-omega.y, omega.x, 0.0);
        let z = Vec3::new(omega.x, omega.y, 0.0);
        let g2 = iz * (-2.0 * tau * tau * k * s);
        let g3 = z * (tau.powi(3) * s * (3.0 * u + 5.0 * k * k));
        let (got2, got3) = (
            slow_manifold_second_order(&top, &omega),
            slow_manifold_third_order(&top, &omega),
        );
        assert!(
            (got2 - g2).norm() <= 1e-9 * g2.norm().max(1e-12),
            "{got2:?} {g2:?}"
        );
        // Along z, G₃ exactly; across it only the fourth order that the
        // recursion's DG₁[G₂] brings along (below 20τ⁴s²(|k| + √u)|z|).
        let along = got3.dot(&z) / u;
        let across = (got3 - z * along).norm();
        assert!(
            (along / (g3.norm() / u.sqrt()) - 1.0).abs() < 1e-6,
            "{omega:?}: {got3:?} against {g3:?}"
        );
        assert!(
            across <= 20.0 * tau.powi(4) * s * s * (k.abs() + u.sqrt()) * u.sqrt(),
            "{omega:?}: {got3:?} against {g3:?}"
        );
    }
}
