//! The catalogue of scenes (`crates/spintop/scenes/`): every scene runs, and each is
//! checked against what it claims — a closed form typed here from the paper,
//! an invariant, an independent method, or a hand calculation shown in the
//! book's "Real particles" chapter — never against its own earlier output.
//!
//! Also pinned down: `auto` takes the closed form wherever one exists and then
//! does less work (right-hand-side evaluations, not wall time) than a forced
//! integrator; the nanoparticle scenes are answered with no step at all.

use approx::assert_relative_eq;
use spintop::math::{Mat3, Vec3};
use spintop::output::simulate::SimulateOutput;
use spintop::physics::central::{ChargeInField, Potential, eq_2_9_rate};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::scene::answer::{
    Answer, OmegaOnlyOutput, PhysicalReport, Report, RigidReport, SecularOutput, TopRun, answer,
};
use spintop::scene::catalogue::{CATALOGUE, find};
use spintop::scene::{Body, Scene, parse};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
use std::collections::BTreeSet;
use std::f64::consts::PI;

fn scene(name: &str) -> Scene {
    find(name)
        .unwrap_or_else(|| panic!("{name} is in the catalogue"))
        .scene()
        .unwrap_or_else(|e| panic!("{e}"))
}

fn run(name: &str) -> Report {
    answer(&scene(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn full(r: &Report) -> &SimulateOutput {
    match &r.answer {
        Answer::Top(t) => match &t.run {
            TopRun::Full(o) => o,
            _ => panic!("{}: the orientation was skipped", r.scene.name),
        },
        _ => panic!("{} is not a top scene", r.scene.name),
    }
}

fn omega_only(r: &Report) -> (&OmegaOnlyOutput, &PhysicalReport) {
    match &r.answer {
        Answer::Top(t) => match (&t.run, &t.units) {
            (TopRun::OmegaOnly(o), Some(u)) => (o, u),
            _ => panic!(
                "{}: expected body-frame samples of a real particle",
                r.scene.name
            ),
        },
        _ => panic!("{} is not a top scene", r.scene.name),
    }
}

fn secular_run(r: &Report) -> (&SecularOutput, &RigidReport) {
    match &r.answer {
        Answer::Top(t) => match (&t.run, &t.rigid_units) {
            (TopRun::Secular(o), Some(u)) => (o, u),
            _ => panic!(
                "{}: expected the secular model of an asymmetric real particle",
                r.scene.name
            ),
        },
        _ => panic!("{} is not a top scene", r.scene.name),
    }
}

/// The angle between two vectors.
fn angle(a: &Vec3, b: &Vec3) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// The symmetry axis O·e₃ in the lab.
fn axis(rotation: &[[f64; 3]; 3]) -> Vec3 {
    Vec3::new(rotation[0][2], rotation[1][2], rotation[2][2])
}

/// Every scene file is in the compiled-in catalogue and the other way round,
/// each file's name is its scene's name, and each has a check in this file.
#[test]
fn catalogue_matches_lessons_scenes_and_every_scene_has_a_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../spintop/scenes");
    let files: BTreeSet<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".toml"))
        .map(|n| n.trim_end_matches(".toml").to_string())
        .collect();
    let listed: BTreeSet<String> = CATALOGUE.iter().map(|e| e.name.to_string()).collect();
    assert_eq!(files, listed);
    for entry in CATALOGUE {
        let on_disk = std::fs::read_to_string(dir.join(format!("{}.toml", entry.name))).unwrap();
        assert_eq!(
            on_disk, entry.text,
            "{} differs from the compiled copy",
            entry.name
        );
        assert_eq!(entry.scene().unwrap().name, entry.name);
    }
    let checked: BTreeSet<String> = CHECKED.iter().map(|s| s.to_string()).collect();
    assert_eq!(
        checked, listed,
        "a scene without a check below, or a check without a scene"
    );
}

/// The scenes checked below, one test each.
const CHECKED: [&str; 24] = [
    "figure-1",
    "figure-2",
    "erratum-1-instant-loss",
    "erratum-4-tilt",
    "erratum-5-generic-frame",
    "euler-pole",
    "reduced-strong-spin",
    "asymmetric-top",
    "full-ale-physical",
    "precessing-dipole",
    "coulomb-collapse",
    "appendix-convergence",
    "appendix-instability",
    "stability-row-1",
    "stability-row-2",
    "stability-row-3",
    "stability-row-4",
    "stability-row-5",
    "stability-row-6",
    "nanoparticle-1e3-debye",
    "nanoparticle-1e7-debye",
    "nanorod-cylinder",
    "formaldehyde-molecule",
    "nanoellipsoid-tumbling",
];

/// The method `chosen` reports is the method the output says it used.
#[test]
fn chosen_method_is_the_method_the_output_reports() {
    for entry in CATALOGUE {
        let r = run(entry.name);
        let used = match &r.answer {
            Answer::Top(t) => match &t.run {
                TopRun::Full(o) => Some(o.method.to_string()),
                TopRun::OmegaOnly(o) => Some(o.method.to_string()),
                TopRun::Secular(o) => Some(o.method.to_string()),
            },
            Answer::Orbit(o) => Some(o.method.to_string()),
            _ => None,
        };
        if let Some(used) = used {
            assert_eq!(r.chosen.method, used, "{}", entry.name);
        }
        assert!(!r.chosen.reason.is_empty());
    }
}

/// Figure 1, (4.6)–(4.7) and (4.11) corrected: |Ω| = |Ω₀|/R(t) and Ω₃ = Ω₃₀/R
/// with R = √(1 + 2τΩ⊥₀²t); the tilt is arctan(1.25) = 0.8961 rad throughout,
/// and in the paper's frame θ equals it. All in closed form: no evaluation.
#[test]
fn figure_1_eq_4_7_rates_fall_as_one_over_r_at_the_corrected_tilt() {
    let r = run("figure-1");
    assert_eq!(r.chosen.method, "exact");
    let o = full(&r);
    assert_eq!(o.stats.rhs_evals, 0);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    let tilt = 1.25_f64.atan();
    assert_relative_eq!(tilt, 0.896_055_384_571_343_9, max_relative = 1e-15);
    for s in &o.samples {
        let big_r = (1.0 + 2.0 * 0.01 * s.t).sqrt();
        let w = Vec3::from(s.omega);
        assert_relative_eq!(w.norm(), 0.05_f64.sqrt() / big_r, max_relative = 1e-13);
        assert_relative_eq!(w.z, 0.2 / big_r, max_relative = 1e-13);
        assert_relative_eq!(s.tilt, tilt, max_relative = 1e-13);
        assert_relative_eq!(s.euler[1], tilt, max_relative = 1e-12);
    }
}

/// Figure 2, (4.14)–(4.16): Ω₃ stays 0.2, Ω⊥ = Ω⊥₀Φ(t) with Φ in the paper's
/// printed form (well conditioned up to t = 1000), the axis comes up to L —
/// and L turns away from lab z by about 0.0625 rad (erratum 5).
#[test]
fn figure_2_eq_4_16_omega_perp_decays_and_the_axis_comes_up_to_l() {
    let r = run("figure-2");
    assert_eq!(r.chosen.method, "exact+dop853");
    let o = full(&r);
    let (beta, sigma) = (1.0 + 0.08_f64.powi(2) / 0.01, 156.25);
    for s in &o.samples {
        assert_eq!(s.omega[2], 0.2);
        let phi = ((beta - 1.0) / (beta * (2.0 * s.t / sigma).exp() - 1.0)).sqrt();
        assert_relative_eq!(s.omega_perp, 0.1 * phi, max_relative = 1e-12);
    }
    let last = o.samples.last().unwrap();
    assert!(last.tilt < 2e-3, "{}", last.tilt);
    let l_end = Vec3::from(last.l_lab);
    let turned = angle(&l_end, &Vec3::z());
    assert!((turned - last.euler[1]).abs() < 2e-3);
    assert!(turned > 0.05 && turned < 0.08, "L turned by {turned}");
    // The orientation (only Q of O = Q·R_z(Ω̃₃t) is integrated) against an
    // independent run: Ω and O integrated together by DOP853 at rtol 1e-12.
    let top = spintop::physics::symmetric_top::SymmetricTop::figure();
    let initial = InitialState::new(
        Vec3::new(0.0, 0.1, 0.2),
        EulerAngles::new(0.0, 1.25_f64.atan(), 0.0),
    )
    .unwrap();
    let options = MethodOptions::default()
        .with_rtol(1e-12)
        .expect("a valid tolerance");
    let mut other = Simulation::new(
        Model::Reduced(top),
        MethodChoice::Dop853,
        options,
        initial,
        Some(1000.0),
    )
    .unwrap();
    for s in &o.samples {
        let reference = other.advance_to(s.t).unwrap().rotation_matrix();
        let m = Mat3::from_fn(|i, j| s.rotation[i][j]);
        assert!(
            (m - reference).norm() < 1e-8,
            "t = {}: {:e}",
            s.t,
            (m - reference).norm()
        );
    }
}

/// Erratum 4: in a generic orientation the angle between the axis O·e₃ and
/// L_lab, measured in the lab, is the corrected 0.8961 rad at every time, not
/// the printed arctan(Ω₂₀/Ω̃₃₀) = 0.6947 rad.
#[test]
fn erratum_4_eq_4_11_tilt_is_arctan_i1_omega20_over_i3_omega30() {
    let r = run("erratum-4-tilt");
    let o = full(&r);
    let printed = (0.1_f64 / (0.6 * 0.2)).atan();
    assert_relative_eq!(printed, 0.6947, epsilon = 1e-4);
    for s in &o.samples {
        let measured = angle(&axis(&s.rotation), &Vec3::from(s.l_lab));
        assert_relative_eq!(measured, 1.25_f64.atan(), epsilon = 1e-10);
        assert!((measured - printed).abs() > 0.2);
    }
}

/// Erratum 5, (4.18): started in a generic orientation, the tilt goes to 0 but
/// θ tends to the angle between lab z and the final L (here about 0.48 rad),
/// while φ̇ → 0 and ψ̇ → Ω₃.
#[test]
fn erratum_5_eq_4_18_theta_tends_to_the_angle_between_z_and_final_l() {
    let r = run("erratum-5-generic-frame");
    let o = full(&r);
    let n = o.samples.len();
    let (before, last) = (&o.samples[n - 2], &o.samples[n - 1]);
    assert!(last.tilt < 1e-5);
    let l = Vec3::from(last.l_lab);
    assert!(angle(&l, &Vec3::from(before.l_lab)) < 1e-5, "L has settled");
    let theta_inf = angle(&l, &Vec3::z());
    assert!((last.euler[1] - theta_inf).abs() < 1e-5);
    assert!(theta_inf > 0.3, "theta tends to {theta_inf}, not 0");
    let [phi_dot, _, psi_dot] = last.euler_rates.expect("off the pole");
    assert!(phi_dot.abs() < 1e-5, "{phi_dot}");
    assert!((psi_dot - 0.2).abs() < 1e-5, "{psi_dot}");
}

/// The pole of the Euler angles: the scene starts there, so spintop warns; the
/// orientation itself (a closed-form rotation) stays exact, the axis on its
/// cone of half-angle 0.8961 rad about L.
#[test]
fn euler_pole_is_reported_while_the_rotation_stays_exact() {
    let r = run("euler-pole");
    assert_eq!(r.warnings.len(), 1);
    assert!(
        r.warnings[0].contains("near their pole"),
        "{}",
        r.warnings[0]
    );
    let o = full(&r);
    assert_eq!(o.samples[0].euler[1], 0.0);
    for s in &o.samples {
        let m = Mat3::from_fn(|i, j| s.rotation[i][j]);
        assert!((m.transpose() * m - Mat3::identity()).norm() < 1e-14);
        let cone = angle(&axis(&s.rotation), &Vec3::from(s.l_lab));
        assert_relative_eq!(cone, 1.25_f64.atan(), epsilon = 1e-12);
    }
}

/// τk = 0.5: the reduced model still follows its own closed form (late decay
/// rate τk² = 0.25), but the full ALE's physical solution decays with
/// σ_phys = 7.35τ, not 4τ; the warning says so before anything runs.
#[test]
fn reduced_strong_spin_warns_that_tau_k_is_not_small() {
    let r = run("reduced-strong-spin");
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    assert!(r.warnings[0].contains("tau k = 0.500"), "{}", r.warnings[0]);
    let o = full(&r);
    let n = o.samples.len();
    let (a, b) = (&o.samples[n - 2], &o.samples[n - 1]);
    let rate = (b.omega_perp / a.omega_perp).ln() / (b.t - a.t);
    assert!((rate + 0.25).abs() < 1e-4, "{rate}");
    let top = spintop::physics::symmetric_top::SymmetricTop::new(1.0, 1.0).unwrap();
    let sigma_phys = spintop::sim::physical::late_time_decay_time(&top, 0.5);
    // σ_phys = 2/(√((1 + √5)/2) − 1), from the physics notes.
    let expected = 2.0 / (((1.0 + 5.0_f64.sqrt()) / 2.0).sqrt() - 1.0);
    assert_relative_eq!(sigma_phys, expected, max_relative = 1e-14);
    assert!((sigma_phys - 7.35).abs() < 0.01 && sigma_phys / 4.0 > 1.8);
}

/// The asymmetric top has no closed form: the scene's answer (the Taylor
/// method, which `auto` takes at the default rtol 1e-10) agrees with an
/// independent method (fixed-step RK4, h = 0.005, error ~h⁴) on Ω and
/// O, and |L| has fallen by t = 200.
#[test]
fn asymmetric_top_eq_3_3_agrees_with_an_independent_rk4_run() {
    let r = run("asymmetric-top");
    assert_eq!(r.chosen.method, "taylor");
    let o = full(&r);
    assert!(o.stats.rhs_evals > 0);
    let top = GeneralTop::new(Vec3::new(1.0, 1.5, 0.8), Vec3::new(0.2, 0.0, 1.0)).unwrap();
    let initial =
        InitialState::new(Vec3::new(0.1, 0.05, 0.2), EulerAngles::new(0.2, 0.9, 0.1)).unwrap();
    let options = MethodOptions::default()
        .with_step(0.005)
        .expect("a valid step");
    let mut rk4 = Simulation::new(
        Model::General(top),
        MethodChoice::Rk4,
        options,
        initial,
        Some(200.0),
    )
    .unwrap();
    for s in &o.samples {
        let other = *rk4.advance_to(s.t).unwrap();
        assert!(
            (Vec3::from(s.omega) - other.omega_vec()).norm() < 1e-8,
            "t = {}",
            s.t
        );
        let m = Mat3::from_fn(|i, j| s.rotation[i][j]);
        assert!((m - other.rotation_matrix()).norm() < 1e-7, "t = {}", s.t);
    }
    let l = |s: &spintop::sim::Sample| Vec3::from(s.l_lab).norm();
    assert!(l(o.samples.last().unwrap()) < 0.5 * l(&o.samples[0]));
}

/// The full ALE (3.4) has no closed form and runs away forward: `auto` takes
/// its physical solution (backward shooting). Ω₃ stays constant (d ∥ e₃), and
/// against the reduced closed form (4.16) Ω⊥ is larger by the physics notes'
/// 1.007 at t = 10 and 1.22 at t = 1000.
#[test]
fn full_ale_physical_solution_drifts_from_the_reduced_model_as_the_notes_say() {
    let r = run("full-ale-physical");
    assert_eq!(r.chosen.method, "physical");
    let o = full(&r);
    let top = spintop::physics::symmetric_top::SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let ratio = |t: f64| {
        let s = o.samples.iter().find(|s| s.t == t).unwrap();
        assert_relative_eq!(s.omega[2], 0.2, max_relative = 1e-12);
        s.omega_perp / (0.1 * spintop::physics::symmetric_top::reduced_amplitude(&top, &omega0, t))
    };
    assert!((ratio(10.0) - 1.007).abs() < 1e-3, "{}", ratio(10.0));
    assert!((ratio(1000.0) - 1.22).abs() < 1e-2, "{}", ratio(1000.0));
}

/// Section 2's precessing dipole (physics notes): (2.1) is the constant
/// −ω³sin²θ ẑ; dL_S/dt averages to zero over a period, yet its component along
/// the dipole is the constant ω³sin²θ cos θ; (2.3) holds at every sample.
#[test]
fn precessing_dipole_eq_2_1_and_eq_2_4_schott_axial_part_survives_the_average() {
    let r = run("precessing-dipole");
    let Answer::Balance(o) = &r.answer else {
        panic!()
    };
    let (st, ct) = 0.5_f64.sin_cos();
    for s in &o.samples {
        assert!((Vec3::from(s.larmor) - Vec3::new(0.0, 0.0, -st * st)).norm() < 1e-13);
        assert_relative_eq!(s.schott_rate_axial, st * st * ct, max_relative = 1e-12);
        let sum = Vec3::from(s.larmor) + Vec3::from(s.schott_rate);
        assert!((Vec3::from(s.torque) - sum).norm() < 1e-13);
    }
    let avg = &o.period_average;
    assert!(Vec3::from(avg.schott_rate).norm() < 1e-12);
    assert_relative_eq!(avg.schott_rate_axial, st * st * ct, max_relative = 1e-12);
}

/// Section 2: the circular Coulomb orbit under Landau–Lifshitz follows the
/// balance law's r³ = r₀³ − 6τ₀t and collapses at t_c = r₀³/(6τ₀). The start at
/// circular speed, without the inward drift ṙ = −2τ₀/r², excites an
/// eccentricity of about ṙ/v = 2τ₀r^{−3/2}: r wobbles about the law by that much.
#[test]
fn coulomb_collapse_eq_2_9_r_cubed_falls_linearly() {
    let r = run("coulomb-collapse");
    let Answer::Orbit(o) = &r.answer else {
        panic!()
    };
    assert_relative_eq!(o.collapse_time.unwrap(), 1.0 / 6e-3, max_relative = 1e-14);
    for s in &o.samples {
        let expected = (1.0 - 6e-3 * s.t).cbrt();
        let wobble = 2.0 * 1e-3 * s.r.powf(-1.5);
        assert!(
            (s.r / expected - 1.0).abs() < wobble,
            "t = {}: r = {}, law {expected}",
            s.t,
            s.r
        );
    }
}

/// Erratum 1, (2.9) with dV/dr: under Landau–Lifshitz, dL/dt = −τ₀ g(r) L at
/// every instant (differences of the integrated L at close triples of times);
/// at the pericentre the printed dV/dt version would give 0.
#[test]
fn erratum_1_eq_2_9_holds_at_every_instant_with_dv_dr() {
    let r = run("erratum-1-instant-loss");
    let Answer::Orbit(o) = &r.answer else {
        panic!()
    };
    let q = ChargeInField::new(Potential::Coulomb, 1e-3).unwrap();
    let h = 1e-3;
    let s = &o.samples;
    let pos = |i: usize| nalgebra::Vector2::new(s[i].position[0], s[i].position[1]);
    // At t = 0, a one-sided second-order difference.
    let l_dot0 = (-3.0 * s[0].l + 4.0 * s[1].l - s[2].l) / (2.0 * h);
    let law0 = eq_2_9_rate(&q, &pos(0), s[0].l);
    assert_relative_eq!(l_dot0, law0, max_relative = 1e-5);
    let radial_speed =
        (s[0].position[0] * s[0].velocity[0] + s[0].position[1] * s[0].velocity[1]) / s[0].r;
    assert_eq!(
        radial_speed, 0.0,
        "the orbit starts at its pericentre, where dV/dt = 0"
    );
    assert!(law0.abs() > 1e-3);
    for c in [3, 6] {
        let l_dot = (s[c + 2].l - s[c].l) / (2.0 * h);
        assert_relative_eq!(
            l_dot,
            eq_2_9_rate(&q, &pos(c + 1), s[c + 1].l),
            max_relative = 1e-5
        );
    }
}

/// Appendix, stable shell (δ = 0.03 > 2τ₀): the motion stays on the
/// Abraham–Lorentz physical solution with the phase slip τ₀δt/4 (the
/// appendix's convergence, tests/physics/shell_model.rs).
#[test]
fn appendix_convergence_phase_slips_by_tau0_delta_t_over_4() {
    let r = run("appendix-convergence");
    assert!(r.warnings.is_empty());
    let Answer::Shell(o) = &r.answer else {
        panic!()
    };
    assert!(o.stable);
    let last = o.samples.last().unwrap();
    let dz = nalgebra::Vector2::from(last.z_minus_z_al).norm();
    assert!(
        (dz / (1e-3 * 0.03 * 20.0 / 4.0) - 1.0).abs() < 0.05,
        "{dz:e}"
    );
}

/// Appendix, unstable shell (m_em = 0.6 > m₀ = 0.4): warned before the run, and
/// the deviation from Abraham–Lorentz grows at ln(m_em/m₀)/δ = 4.05 (peaks over
/// [2, 3] and [6, 7], within 5%).
#[test]
fn appendix_instability_grows_at_ln_m_em_over_m0_over_delta() {
    let r = run("appendix-instability");
    assert_eq!(r.warnings.len(), 1);
    assert!(r.warnings[0].contains("unstable"));
    let Answer::Shell(o) = &r.answer else {
        panic!()
    };
    assert_eq!(o.regime, "growing-oscillation");
    let predicted = 1.5_f64.ln() / 0.1;
    let peak = |a: f64| {
        o.samples
            .iter()
            .filter(|s| s.t >= a && s.t <= a + 1.0)
            .map(|s| nalgebra::Vector2::from(s.z_minus_z_al).norm())
            .fold(0.0, f64::max)
    };
    let measured = (peak(6.0) / peak(2.0)).ln() / 4.0;
    assert!(
        (measured / predicted - 1.0).abs() < 0.05,
        "{measured} vs {predicted}"
    );
}

fn stability_row(n: u8) {
    let r = run(&format!("stability-row-{n}"));
    let Answer::Stability(a) = &r.answer else {
        panic!()
    };
    assert_eq!(a.rows.len(), 1);
    assert_eq!(a.rows[0].number, n);
    assert!(a.rows[0].holds(), "{}", a.rows[0]);
}

/// Each stability row shows what it claims: the naive methods fail, spintop's succeed
/// (the numbers themselves are pinned in tests/numerics/stability.rs).
#[test]
fn stability_rows_hold_as_scenes() {
    for n in 1..=6 {
        stability_row(n);
    }
}

/// The hand calculation of the book's "Real particles" chapter, for a silica
/// sphere of radius 50 nm (ρ = 2.2 g/cm³) spun to 1 GHz at 45° from its dipole.
struct Hand {
    tau_s: f64,
    half_spin_s: f64,
    sigma_s: f64,
    upright_s: f64,
}

fn hand(debye: f64) -> Hand {
    let a: f64 = 5e-6; // cm
    let mass = 4.0 / 3.0 * PI * a.powi(3) * 2.2; // g
    let i = 0.4 * mass * a * a; // g cm²
    let d = debye * 1e-18; // statC cm
    let c: f64 = 2.997_924_58e10; // cm/s
    let tau_s = 2.0 * d * d / (3.0 * i * c.powi(3));
    let w = 2.0 * PI * 1e9; // rad/s
    let (w_perp, w3) = (w * (PI / 4.0).sin(), w * (PI / 4.0).cos());
    // Truncated: R = 2 at 2τΩ⊥²t = 3.
    let half_spin_s = 3.0 / (2.0 * tau_s * w_perp * w_perp);
    // Reduced, (4.16) as printed: σ = 1/(τΩ₃²) for a sphere, β = 1 + Ω₃²/Ω⊥²,
    // and the tilt is 1° when Φ = (Ω₃/Ω⊥) tan 1°.
    let sigma_s = 1.0 / (tau_s * w3 * w3);
    let beta = 1.0 + (w3 / w_perp).powi(2);
    let phi = (w3 / w_perp) * 1.0_f64.to_radians().tan();
    let upright_s = sigma_s / 2.0 * ((1.0 + (beta - 1.0) / (phi * phi)) / beta).ln();
    Hand {
        tau_s,
        half_spin_s,
        sigma_s,
        upright_s,
    }
}

const YEAR: f64 = 365.25 * 86400.0;

/// 10³ D: τ = 2.148e-36 s, |Ω| halves after 1.12e9 yr (truncated); the
/// reduced tilt e-folds in 7.47e8 yr and is below 1° after 2.77e9 yr. The
/// samples follow 1/R(t); nothing is stepped.
#[test]
fn nanoparticle_1e3_debye_matches_the_hand_calculation() {
    let r = run("nanoparticle-1e3-debye");
    let (o, u) = omega_only(&r);
    let h = hand(1e3);
    // The numbers the book's chapter prints, to four digits.
    assert_relative_eq!(h.tau_s, 2.148e-36, max_relative = 5e-4);
    assert_relative_eq!(h.half_spin_s / YEAR, 1.121e9, max_relative = 5e-4);
    assert_relative_eq!(h.sigma_s / YEAR, 7.474e8, max_relative = 5e-4);
    assert_relative_eq!(h.upright_s / YEAR, 2.767e9, max_relative = 5e-4);
    assert_relative_eq!(u.tau_s, h.tau_s, max_relative = 1e-12);
    let m = &u.milestones;
    assert_relative_eq!(
        m.truncated_half_spin.unwrap().seconds,
        h.half_spin_s,
        max_relative = 1e-12
    );
    assert_relative_eq!(
        m.reduced_tilt_decay.unwrap().seconds,
        h.sigma_s,
        max_relative = 1e-12
    );
    assert_relative_eq!(
        m.reduced_upright.unwrap().seconds,
        h.upright_s,
        max_relative = 1e-9
    );
    assert_relative_eq!(
        m.reduced_upright.unwrap().unit,
        h.upright_s / YEAR,
        max_relative = 1e-9
    );
    assert!(m.reduced_half_spin.is_none(), "Ω₃ = 0.707|Ω₀| is kept");
    assert_eq!(o.stats.rhs_evals, 0);
    assert_eq!(o.stats.steps, 0);
    // Samples in years: f = 1 GHz / R(t), R² = 1 + 2τΩ⊥²t.
    let w = 2.0 * PI * 1e9;
    for s in &o.samples {
        let t_s = s.t_unit.unwrap() * YEAR;
        let big_r = (1.0 + 2.0 * h.tau_s * w * w * 0.5 * t_s).sqrt();
        let f = Vec3::from(s.omega).norm() / h.tau_s / (2.0 * PI);
        assert_relative_eq!(f, 1e9 / big_r, max_relative = 1e-12);
        assert_relative_eq!(s.tilt, PI / 4.0, max_relative = 1e-12);
    }
}

/// 10⁷ D: τ grows by 10⁸, every time shrinks by 10⁸: |Ω| would halve after
/// 11.2 yr without the Schott term; with it (reduced) the tilt is below 1°
/// after 27.7 yr, which the sample at 27.7 yr confirms.
#[test]
fn nanoparticle_1e7_debye_stands_upright_within_decades() {
    let r = run("nanoparticle-1e7-debye");
    let (o, u) = omega_only(&r);
    let h = hand(1e7);
    assert_relative_eq!(h.tau_s, 2.148e-28, max_relative = 5e-4);
    assert_relative_eq!(h.half_spin_s / YEAR, 11.21, max_relative = 5e-4);
    assert_relative_eq!(h.upright_s / YEAR, 27.67, max_relative = 5e-4);
    let m = &u.milestones;
    assert_relative_eq!(
        m.truncated_half_spin.unwrap().unit,
        h.half_spin_s / YEAR,
        max_relative = 1e-12
    );
    assert_relative_eq!(
        m.reduced_upright.unwrap().unit,
        h.upright_s / YEAR,
        max_relative = 1e-9
    );
    let at = o.samples.iter().find(|s| s.t_unit == Some(27.7)).unwrap();
    assert!(
        at.tilt.to_degrees() < 1.0 && at.tilt.to_degrees() > 0.98,
        "{}",
        at.tilt.to_degrees()
    );
    assert_eq!(o.stats.rhs_evals, 0);
    assert!(r.chosen.reason.contains("skipped"));
}

/// The rod's moments follow from its shape: I₃/I₁ = 6a²/(3a² + h²); τ from its
/// own I₁; the tilt reaches 1° when (4.16), as printed, says; the body-frame
/// phase is beyond a double, and spintop says so.
#[test]
fn nanorod_cylinder_moments_follow_from_its_shape() {
    let r = run("nanorod-cylinder");
    let (o, u) = omega_only(&r);
    let (a, l) = (2.5e-6, 2e-5); // cm
    assert_relative_eq!(
        u.ratio,
        6.0 * a * a / (3.0 * a * a + l * l),
        max_relative = 1e-14
    );
    let mass = PI * a * a * l * 2.2;
    let i1 = mass * (3.0 * a * a + l * l) / 12.0;
    let tau_s = 2.0 * 1e-26 / (3.0 * i1 * 2.997_924_58e10_f64.powi(3));
    assert_relative_eq!(u.tau_s, tau_s, max_relative = 1e-12);
    let w = 2.0 * PI * 1e9;
    let (w_perp, w3) = (w * 0.5, w * 3.0_f64.sqrt() / 2.0);
    let k = u.ratio * w3;
    let sigma = 1.0 / (tau_s * k * k);
    let beta = 1.0 + (k / w_perp).powi(2);
    let phi = k * 1.0_f64.to_radians().tan() / w_perp;
    let upright = sigma / 2.0 * ((1.0 + (beta - 1.0) / (phi * phi)) / beta).ln();
    assert_relative_eq!(
        u.milestones.reduced_upright.unwrap().seconds,
        upright,
        max_relative = 1e-9
    );
    assert!(
        r.warnings.iter().any(|w| w.contains("phase")),
        "{:?}",
        r.warnings
    );
    assert_eq!(o.stats.rhs_evals, 0);
}

/// Replace the method of a catalogue scene's `[solve]`.
fn forced(name: &str, method: &str) -> Result<Scene, spintop::scene::SceneError> {
    let text = find(name)
        .unwrap()
        .text
        .replace("[solve]\n", &format!("[solve]\nmethod = \"{method}\"\n"));
    parse(&text, name)
}

fn evals(r: &Report) -> u64 {
    full(r).stats.rhs_evals
}

/// `auto` takes the closed form wherever one exists: for every catalogue top
/// scene of a symmetric model it reports an `exact` method.
#[test]
fn auto_picks_the_closed_form_for_every_symmetric_scene() {
    for entry in CATALOGUE {
        let s = entry.scene().unwrap();
        if let Body::Top(top) = &s.body
            && top.model.has_closed_form()
        {
            assert!(
                s.chosen.method.starts_with("exact"),
                "{}: {}",
                entry.name,
                s.chosen.method
            );
        }
    }
}

/// And it is cheaper there than forcing an integrator on the same question,
/// counted in right-hand-side evaluations.
#[test]
fn auto_does_less_work_than_a_forced_integrator() {
    for name in ["figure-1", "figure-2", "erratum-5-generic-frame"] {
        let auto = evals(&run(name));
        for method in ["dop853", "dopri5"] {
            let other = answer(&forced(name, method).unwrap()).unwrap();
            assert_eq!(other.chosen.method, method);
            assert!(
                evals(&other) > auto,
                "{name}: auto {auto}, {method} {}",
                evals(&other)
            );
        }
    }
    assert_eq!(evals(&run("figure-1")), 0);
}

/// The nanoparticle asks for 10⁵² τ: auto answers from the closed forms with no
/// step (the plain work count standing in for a benchmark), while a forced
/// integrator is refused before it starts, with the number of steps it would need.
#[test]
fn nanoparticle_is_answered_without_a_step_and_integrators_are_refused() {
    for name in ["nanoparticle-1e3-debye", "nanoparticle-1e7-debye"] {
        let r = run(name);
        let (o, _) = omega_only(&r);
        assert_eq!(
            (o.stats.rhs_evals, o.stats.steps, o.stats.rejected),
            (0, 0, 0)
        );
        for method in ["dop853", "rk4"] {
            let e = forced(name, method).unwrap_err();
            assert!(e.message.contains("steps"), "{e}");
            assert!(e.message.contains("auto"), "{e}");
        }
    }
}

/// The book's reference page names every catalogue scene and every key the
/// parser accepts; the keys are read from the parser's own refusal of an
/// unknown key in each section, so a new key without documentation fails here.
#[test]
fn scene_reference_page_lists_every_key_and_every_scene() {
    let page = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../book/src/scene-reference.md"
    ))
    .unwrap();
    let keys_of = |text: &str| -> Vec<String> {
        let e = parse(text, "probe.toml").unwrap_err();
        let list = e
            .message
            .split("expected")
            .nth(1)
            .unwrap_or_else(|| panic!("{e}"));
        list.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    };
    let sections = keys_of("[zzz]\n");
    assert!(sections.len() >= 8, "{sections:?}");
    for section in &sections {
        assert!(
            page.contains(&format!("`[{section}]`")),
            "section [{section}] is not documented"
        );
        for key in keys_of(&format!("[{section}]\nzzz = 1\n")) {
            assert!(
                page.contains(&format!("`{key}`")),
                "[{section}] {key} is not documented"
            );
        }
    }
    for entry in CATALOGUE {
        let short = entry.name.trim_start_matches("stability-row-");
        assert!(
            page.contains(&format!("`{}`", entry.name)) || page.contains(&format!("`-{short}`")),
            "{} is not in the catalogue table",
            entry.name
        );
    }
}

/// Gaussian κ|D|²/min I, written out here from the constants (c exact,
/// 1 D = 1e-18 statC cm, 1 amu A^2 = 1.66053906660e-40 g cm^2, CODATA 2018).
fn fast_time_s(inertia_g_cm2: Vec3, dipole_debye: Vec3) -> f64 {
    let c = 2.997_924_58e10_f64;
    2.0 * (dipole_debye * 1e-18).norm_squared() / (3.0 * c.powi(3) * inertia_g_cm2.min())
}

/// Formaldehyde: the moments convert from amu A^2, τ_f from Gaussian
/// units; `auto` refuses (3.3) (its error over 10¹⁷ rad is of order 1) and
/// takes the reduced ALE by the secular model; the loss at the start is
/// Larmor's power averaged over the free motion (both laws lose energy at
/// that rate on average; computed here by DOP853 on Euler's equations, in
/// SI), and the spin drains towards rotation about the dipole's axis.
#[test]
fn formaldehyde_molecule_auto_picks_the_reduced_ale_and_loses_larmor_power() {
    use spintop::integrate::{AdaptiveOptions, Dop853, solve};
    use spintop::math::State;
    let r = run("formaldehyde-molecule");
    assert_eq!(r.chosen.method, "secular");
    assert!(
        r.chosen
            .reason
            .contains("the lightest within rtol = 1e-10 is the reduced ALE"),
        "{}",
        r.chosen.reason
    );
    let (o, u) = secular_run(&r);
    assert_eq!(o.model, "general-reduced");
    let moments = Vec3::new(1.7923, 13.014, 14.8063) * 1.660_539_066_60e-40;
    for k in 0..3 {
        assert_relative_eq!(u.inertia_kg_m2[k], moments[k] * 1e-7, max_relative = 1e-14);
    }
    let tau_f = fast_time_s(moments, Vec3::new(2.33, 0.0, 0.0));
    assert_relative_eq!(u.fast_time_s, tau_f, max_relative = 1e-13);
    // Larmor: P = (2/3c³)|d̈|², d̈ = Ω̇ × D + Ω × (Ω × D) in the body frame,
    // averaged over 200 periods of the free motion (Gaussian units).
    let omega0 = Vec3::new(1.9e12, 7.0e11, 6.5e11) * (2.0 * PI);
    let d = Vec3::new(2.33e-18, 0.0, 0.0);
    let i = moments;
    let free = |w: &Vec3| -(w.cross(&i.component_mul(w))).component_div(&i);
    let period = o.samples[0].sample.period.expect("a period") * tau_f;
    let n = 400_000;
    let t_end = 200.0 * period;
    let times: Vec<f64> = (0..=n).map(|k| t_end * k as f64 / n as f64).collect();
    let rhs = |_t: f64, y: &State<3>| -> State<3> { free(&Vec3::new(y[0], y[1], y[2])) };
    let mut s = Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-12, 1.0).unwrap()).unwrap();
    let ys = solve(&mut s, &rhs, &times).unwrap();
    let c = 2.997_924_58e10_f64;
    let mut power = 0.0;
    for (k, y) in ys.iter().enumerate() {
        let w = Vec3::new(y[0], y[1], y[2]);
        let dd = free(&w).cross(&d) + w.cross(&w.cross(&d));
        let weight = if k == 0 || k == n { 0.5 } else { 1.0 };
        power += weight * 2.0 / (3.0 * c.powi(3)) * dd.norm_squared() / n as f64;
    }
    // The secular model's loss over a short first step, in erg/s.
    let e0 = 0.5 * omega0.dot(&i.component_mul(&omega0));
    let top = spintop::physics::general_top::GeneralTop::new(i / i.min(), d / d.norm()).unwrap();
    let w0 = omega0 * tau_f;
    let h = 1e-4 / (tau_f * power / e0); // 1e-4 of the loss time, in u
    let short = spintop::sim::secular::secular(
        &top,
        spintop::sim::secular::Law::Reduced,
        &w0,
        &[0.0, h],
        1e-12,
    )
    .unwrap();
    let loss = (1.0 - short.samples[1].energy / short.samples[0].energy) * e0 / (h * tau_f);
    assert_relative_eq!(loss, power, max_relative = 1e-3);
    // It drains, and the polhode circles the dipole's (smallest) axis.
    let last = o.samples.last().unwrap();
    assert!(last.sample.energy < 0.3 * o.samples[0].sample.energy);
    assert!(o.samples.iter().all(|s| s.sample.axis == 1));
}

/// The ellipsoid: the moments of a homogeneous ellipsoid, τ_f, `auto`'s
/// choice of the reduced ALE, and the drain of E and |L|, with |L| falling
/// more slowly than √E would if it kept its polhode (the top settles
/// towards rotation about its axis of largest moment, axis 3).
#[test]
fn nanoellipsoid_moments_follow_from_its_shape_and_it_drains() {
    let r = run("nanoellipsoid-tumbling");
    assert_eq!(r.chosen.method, "secular");
    let (o, u) = secular_run(&r);
    assert_eq!(o.model, "general-reduced");
    let (a1, a2, a3) = (1.5e-5, 6e-6, 4e-6); // cm
    let mass = 4.0 / 3.0 * PI * a1 * a2 * a3 * 2.2;
    let i = Vec3::new(a2 * a2 + a3 * a3, a3 * a3 + a1 * a1, a1 * a1 + a2 * a2) * (mass / 5.0);
    for k in 0..3 {
        assert_relative_eq!(u.inertia_kg_m2[k], i[k] * 1e-7, max_relative = 1e-14);
    }
    assert_relative_eq!(
        u.fast_time_s,
        fast_time_s(i, Vec3::new(0.0, 3e4, 4e4)),
        max_relative = 1e-13
    );
    let e: Vec<f64> = o.samples.iter().map(|s| s.sample.energy).collect();
    assert!(e.windows(2).all(|w| w[1] < w[0]), "{e:?}");
    assert!(e.last().unwrap() / e[0] < 0.05);
    assert_eq!(o.samples.last().unwrap().sample.axis, 3);
}
