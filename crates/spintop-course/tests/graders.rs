//! The graders really grade. For every assignment of the course, at several
//! seeds: spintop's own implementation passes; a `todo!()` stub fails and
//! says it is a stub; at least two plausible wrong answers fail, each with its
//! own diagnosis; the failure never prints the formula (the last hint rung
//! does) and always prints its seed.

use super::SEEDS;
use super::wrong_answers::{Wrong, wrong_answers};
use spintop::integrate::dopri5::dopri5_step;
use spintop::integrate::rk4::rk4_step;
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet, PrecessingDipole};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use spintop_course::COURSE;
use spintop_grading::{self as grading, DynField, Failed, Grade, shape_diagnosis};
use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap};

fn top(r: f64, tau: f64) -> SymmetricTop {
    SymmetricTop::new(r, tau).unwrap()
}

/// spintop's own answer to every assignment, graded, by function name.
pub(crate) fn references(seed: u64) -> Vec<(&'static str, Grade)> {
    let mut all = references_to_section_3(seed);
    all.extend(references_from_section_4(seed));
    all
}

fn top_rhs(i: Vec3, d: Vec3, w: Vec3) -> Vec3 {
    GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w)
}

fn reduced_rhs(r: f64, tau: f64, w: Vec3) -> Vec3 {
    sym::reduced_ale_rhs(&top(r, tau), &w)
}

/// spintop's own answers of Sections 2 and 3, graded.
fn references_to_section_3(seed: u64) -> Vec<(&'static str, Grade)> {
    vec![
        (
            "larmor_rate",
            grading::larmor_rate(seed, balance::larmor_rate),
        ),
        (
            "schott_angular_momentum",
            grading::schott_angular_momentum(seed, balance::schott_angular_momentum),
        ),
        (
            "torque_rate",
            grading::torque_rate(seed, balance::torque_rate),
        ),
        (
            "schott_rate",
            grading::schott_rate(seed, balance::schott_rate),
        ),
        (
            "axial_schott_rate",
            grading::axial_schott_rate(seed, |j: &Jet| {
                balance::axial(&j[0], &balance::schott_rate(j))
            }),
        ),
        (
            "precessing_dipole_jet",
            grading::precessing_dipole_jet(seed, |th, w, t| {
                PrecessingDipole::new(th, w).unwrap().jet(t)
            }),
        ),
        (
            "truncated_ale_rhs",
            grading::truncated_ale_rhs(seed, top_rhs),
        ),
        (
            "energy_rate",
            grading::energy_rate(seed, move |i, d, w| {
                w.dot(&i.component_mul(&top_rhs(i, d, w)))
            }),
        ),
        (
            "euler_from_rotation",
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.phi, a.theta, a.psi)
            }),
        ),
    ]
}

/// spintop's own answers of Section 4, the appendix and the step methods,
/// graded.
fn references_from_section_4(seed: u64) -> Vec<(&'static str, Grade)> {
    vec![
        (
            "truncated_omega_perp",
            grading::truncated_omega_perp(seed, |r, tau, w, t| {
                sym::truncated_omega_perp(&top(r, tau), w, t)
            }),
        ),
        (
            "truncated_closed_form",
            grading::truncated_closed_form(seed, |r, tau, w0, t| {
                sym::truncated_closed_form(&top(r, tau), &w0, t)
            }),
        ),
        (
            "truncated_time_to_factor",
            grading::truncated_time_to_factor(seed, |r, tau, w, p| {
                sym::truncated_time_to_factor(&top(r, tau), w, p)
            }),
        ),
        (
            "precession_tilt",
            grading::precession_tilt(seed, |r, w0| sym::precession_tilt(&top(r, 1.0), &w0)),
        ),
        (
            "reduced_ale_rhs",
            grading::reduced_ale_rhs(seed, reduced_rhs),
        ),
        (
            "reduced_decay_time",
            grading::reduced_decay_time(seed, |r, tau, w3| {
                sym::reduced_decay_time(&top(r, tau), w3)
            }),
        ),
        (
            "reduced_closed_form",
            grading::reduced_closed_form(seed, |r, tau, w0, t| {
                sym::reduced_closed_form(&top(r, tau), &w0, t)
            }),
        ),
        (
            "shell_masses",
            grading::shell_masses(seed, |tau0, delta| {
                let m = ShellModel::new(tau0, delta).unwrap();
                (m.m0(), m.m_em())
            }),
        ),
        (
            "shell_acceleration",
            grading::shell_acceleration(seed, |tau0, delta, z, zr| {
                ShellModel::new(tau0, delta).unwrap().acceleration(z, zr)
            }),
        ),
        (
            "characteristic_root",
            grading::characteristic_root(seed, |tau0, delta| {
                ShellModel::new(tau0, delta)
                    .unwrap()
                    .root_near_al()
                    .unwrap()
            }),
        ),
        (
            "rk4_step",
            grading::rk4_step(seed, |f: DynField, t, y: &State<3>, h| {
                rk4_step(&f, t, y, h)
            }),
        ),
        (
            "dp5_step",
            grading::dp5_step(seed, |f: DynField, t, y: &State<3>, h| {
                dopri5_step(&f, t, y, h)
            }),
        ),
        (
            "reduced_rk4",
            grading::reduced_rk4(seed, move |r, tau, w0, t_end, n| {
                let h = t_end / n as f64;
                let f = |_t: f64, y: &State<3>| reduced_rhs(r, tau, *y);
                (0..n).fold(w0, |y, i| rk4_step(&f, i as f64 * h, &y, h))
            }),
        ),
    ]
}

/// Every todo!() stub, graded, by function name.
fn stubs(seed: u64) -> Vec<(&'static str, Grade)> {
    let v = |_: &Jet| -> Vec3 { todo!("stub") };
    vec![
        ("larmor_rate", grading::larmor_rate(seed, v)),
        (
            "schott_angular_momentum",
            grading::schott_angular_momentum(seed, v),
        ),
        ("torque_rate", grading::torque_rate(seed, v)),
        ("schott_rate", grading::schott_rate(seed, v)),
        (
            "axial_schott_rate",
            grading::axial_schott_rate(seed, |_: &Jet| -> f64 { todo!() }),
        ),
        (
            "precessing_dipole_jet",
            grading::precessing_dipole_jet(seed, |_, _, _| -> Jet { todo!() }),
        ),
        (
            "truncated_ale_rhs",
            grading::truncated_ale_rhs(seed, |_, _, _| -> Vec3 { todo!() }),
        ),
        (
            "energy_rate",
            grading::energy_rate(seed, |_, _, _| -> f64 { todo!() }),
        ),
        (
            "euler_from_rotation",
            grading::euler_from_rotation(seed, |_: &Mat3| -> (f64, f64, f64) { todo!() }),
        ),
        (
            "truncated_omega_perp",
            grading::truncated_omega_perp(seed, |_, _, _, _| -> f64 { todo!() }),
        ),
        (
            "truncated_closed_form",
            grading::truncated_closed_form(seed, |_, _, _, _| -> Vec3 { todo!() }),
        ),
        (
            "truncated_time_to_factor",
            grading::truncated_time_to_factor(seed, |_, _, _, _| -> f64 { todo!() }),
        ),
        (
            "precession_tilt",
            grading::precession_tilt(seed, |_, _| -> f64 { todo!() }),
        ),
        (
            "reduced_ale_rhs",
            grading::reduced_ale_rhs(seed, |_, _, _| -> Vec3 { todo!() }),
        ),
        (
            "reduced_decay_time",
            grading::reduced_decay_time(seed, |_, _, _| -> f64 { todo!() }),
        ),
        (
            "reduced_closed_form",
            grading::reduced_closed_form(seed, |_, _, _, _| -> Vec3 { todo!() }),
        ),
        (
            "shell_masses",
            grading::shell_masses(seed, |_, _| -> (f64, f64) { todo!() }),
        ),
        (
            "shell_acceleration",
            grading::shell_acceleration(seed, |_, _, _, _| -> C { todo!() }),
        ),
        (
            "characteristic_root",
            grading::characteristic_root(seed, |_, _| -> C { todo!() }),
        ),
        (
            "rk4_step",
            grading::rk4_step(seed, |_: DynField, _, _: &State<3>, _| -> State<3> {
                todo!()
            }),
        ),
        (
            "dp5_step",
            grading::dp5_step(
                seed,
                |_: DynField, _, _: &State<3>, _| -> (State<3>, State<3>) { todo!() },
            ),
        ),
        (
            "reduced_rk4",
            grading::reduced_rk4(seed, |_, _, _, _, _| -> Vec3 { todo!() }),
        ),
    ]
}

#[test]
fn every_reference_implementation_passes_its_grader() {
    for seed in SEEDS {
        let refs = references(seed);
        let names: BTreeSet<_> = refs.iter().map(|(n, _)| *n).collect();
        let course: BTreeSet<_> = COURSE.iter().map(|a| a.function).collect();
        assert_eq!(names, course, "one reference per assignment of the course");
        for (name, grade) in refs {
            let passed = grade.unwrap_or_else(|f| panic!("{name}, seed {seed}: {f}"));
            assert!(passed.cases >= 20, "{passed:?}");
        }
    }
}

#[test]
fn every_stub_fails_and_says_it_is_a_stub() {
    let stubs = stubs(2026);
    assert_eq!(stubs.len(), COURSE.len());
    for (name, grade) in stubs {
        let failed = grade.expect_err(name);
        assert_eq!(failed.assignment, name);
        assert!(failed.is_stub(), "{failed}");
        let text = failed.to_string();
        assert!(
            text.contains(&format!("spintop course hint {name}")),
            "{text}"
        );
        assert!(text.contains("SPINTOP_SEED=2026"), "{text}");
    }
}

fn report(failed: &Failed) -> String {
    let text = failed.to_string();
    for part in ["input:", "expected:", "got:", "diagnosis:", "seed:"] {
        assert!(text.contains(part), "{text}");
    }
    text
}

#[test]
fn every_plausible_wrong_answer_fails_with_its_own_diagnosis() {
    for seed in SEEDS {
        let wrong = wrong_answers(seed);
        for a in COURSE {
            let mine: Vec<&Wrong> = wrong
                .iter()
                .filter(|x| x.assignment == a.function)
                .collect();
            assert!(
                mine.len() >= 2,
                "{}: fewer than two wrong answers",
                a.function
            );
            let diagnoses: BTreeSet<String> = mine
                .iter()
                .map(|x| match &x.grade {
                    Ok(p) => panic!("{} ({}) passed at seed {seed}: {p:?}", a.function, x.what),
                    Err(f) => {
                        assert_eq!(f.assignment, a.function);
                        report(f);
                        assert!(
                            f.diagnosis.contains(x.says),
                            "{} ({}), seed {seed}: the diagnosis should say '{}':\n{f}",
                            a.function,
                            x.what,
                            x.says
                        );
                        f.diagnosis.clone()
                    }
                })
                .collect();
            assert!(
                diagnoses.len() >= 2,
                "{}: the wrong answers share one diagnosis: {diagnoses:?}",
                a.function
            );
        }
    }
}

/// The pieces of a formula rung worth looking for in a report.
fn formula_pieces(formula: &str) -> Vec<&str> {
    let mut pieces: Vec<&str> = formula
        .split([';', ','])
        .map(str::trim)
        .filter(|p| p.len() >= 12)
        .collect();
    pieces.push(formula);
    pieces
}

#[test]
fn no_failure_prints_the_formula_and_the_last_hint_does() {
    let mut failures: Vec<(&str, String)> = Vec::new();
    for (name, grade) in stubs(2026) {
        failures.push((name, grade.unwrap_err().to_string()));
    }
    for seed in SEEDS {
        for x in wrong_answers(seed) {
            failures.push((x.assignment, x.grade.unwrap_err().to_string()));
        }
    }
    for a in COURSE {
        let formula = a.hints[2];
        assert!(
            formula.contains('='),
            "{}: the last rung is a formula",
            a.function
        );
        for rung in &a.hints[..2] {
            for piece in formula_pieces(formula) {
                assert!(
                    !rung.contains(piece),
                    "{}: an early rung gives the formula: {rung}",
                    a.function
                );
            }
        }
        for (name, text) in failures.iter().filter(|(n, _)| *n == a.function) {
            for piece in formula_pieces(formula) {
                assert!(
                    !text.contains(piece),
                    "{name}: the report prints the formula '{piece}':\n{text}"
                );
            }
        }
    }
}

#[test]
fn the_shape_of_a_wrong_answer_is_named() {
    let e = [1.0, -2.0, 0.5];
    assert!(shape_diagnosis(&[-1.0, 2.0, -0.5], &e).contains("sign flip"));
    assert!(shape_diagnosis(&[2.0, -4.0, 1.0], &e).contains("factor 2"));
    assert!(shape_diagnosis(&[0.5, -1.0, 0.25], &e).contains("factor 1/2"));
    assert!(shape_diagnosis(&[0.0, 0.0, 0.0], &e).contains("zero"));
    assert!(shape_diagnosis(&[f64::NAN, 0.0, 0.0], &e).contains("not finite"));
    assert!(
        shape_diagnosis(&[-2.0, 1.0, 0.5], &e).contains("component 1 and component 2 are swapped")
    );
    assert!(shape_diagnosis(&[2.0, -1.0, -0.5], &e).contains("right size in the wrong direction"));
    assert!(shape_diagnosis(&[1.7, -3.4, 0.85], &e).contains("1.700 times"));
    assert!(shape_diagnosis(&[5.0, 1.0, 0.0], &e).contains("wrong in size and direction"));
    // One part right, one with its sign flipped, one missing: each is named.
    let d = shape_diagnosis(&[1.0, 2.0, 0.0], &e);
    assert!(
        d.contains("component 1 is right")
            && d.contains("component 2 has the wrong sign")
            && d.contains("component 3 is zero"),
        "{d}"
    );
}

// ------------------------------------------------- the diagnoses that misled

/// `steps` RK4 steps of size `h` of the reduced model.
fn rk4_run(r: f64, tau: f64, w0: Vec3, steps: usize, h: f64) -> Vec3 {
    let f = |_t: f64, y: &State<3>| sym::reduced_ale_rhs(&top(r, tau), y);
    (0..steps).fold(w0, |y, i| rk4_step(&f, i as f64 * h, &y, h))
}

fn diagnosis(grade: Grade) -> String {
    let failed = grade.expect_err("a wrong answer must fail");
    report(&failed);
    failed.diagnosis
}

#[test]
fn reduced_rk4_tells_a_wrong_step_count_and_end_time_from_a_wrong_stage() {
    for seed in SEEDS {
        let d = diagnosis(grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            rk4_run(r, tau, w0, n + 1, t_end / n as f64)
        }));
        assert!(d.contains("one step too many"), "{d}");
        let d = diagnosis(grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            rk4_run(r, tau, w0, n - 1, t_end / n as f64)
        }));
        assert!(d.contains("one step too few"), "{d}");
        let d = diagnosis(grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            rk4_run(r, tau, w0, n, t_end / (n + 1) as f64)
        }));
        assert!(d.contains("t_end/(steps + 1)"), "{d}");
        // A wrong stage: k3 from k1.
        let d = diagnosis(grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            let h = t_end / n as f64;
            let f = |y: &Vec3| sym::reduced_ale_rhs(&top(r, tau), y);
            (0..n).fold(w0, |y, _| {
                let k1 = f(&y);
                let k2 = f(&(y + k1 * (h / 2.0)));
                let k3 = f(&(y + k1 * (h / 2.0)));
                let k4 = f(&(y + k3 * h));
                y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
            })
        }));
        assert!(d.contains("third stage steps from the wrong slope"), "{d}");
        assert!(!d.contains("step too"), "{d}");
    }
}

#[test]
fn reduced_rk4_checks_the_value_not_only_the_order() {
    // The closed form plus a term of order h^4 converges at order 4 but is
    // not N classical RK4 steps.
    for seed in SEEDS {
        let failed = grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            let h = t_end / n as f64;
            sym::reduced_closed_form(&top(r, tau), &w0, t_end) + Vec3::repeat(0.3 * h.powi(4))
        })
        .expect_err("the closed form plus 0.3 h^4 is not an RK4 run");
        assert_eq!(failed.assignment, "reduced_rk4");
        // The closed form itself is named (its error is zero, so its
        // order of convergence is no number at all).
        let d = diagnosis(grading::reduced_rk4(seed, |r, tau, w0, t_end, _n| {
            sym::reduced_closed_form(&top(r, tau), &w0, t_end)
        }));
        assert!(d.contains("closed form"), "{d}");
        // A real RK4 run passes to rounding, whatever its step count.
        grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
            rk4_run(r, tau, w0, n, t_end / n as f64)
        })
        .expect("N classical steps pass");
    }
}

#[test]
fn euler_angles_tell_a_pole_test_too_wide_from_an_inverse_cosine() {
    for seed in SEEDS {
        // The reference solution's algorithm with its pole test 10^6 times too wide.
        let d = diagnosis(grading::euler_from_rotation(seed, |m: &Mat3| {
            let s = m[(0, 2)].hypot(m[(1, 2)]);
            let theta = s.atan2(m[(2, 2)]);
            if s < 1e-6 {
                return (m[(1, 0)].atan2(m[(0, 0)]), theta, 0.0);
            }
            (
                m[(0, 2)].atan2(-m[(1, 2)]),
                theta,
                m[(2, 0)].atan2(m[(2, 1)]),
            )
        }));
        assert!(d.contains("pole test is too wide"), "{d}");
        assert!(!d.contains("cosine"), "no acos was used: {d}");
        let d = diagnosis(grading::euler_from_rotation(seed, |m: &Mat3| {
            let a = EulerAngles::from_rotation(m);
            (a.phi, m[(2, 2)].clamp(-1.0, 1.0).acos(), a.psi)
        }));
        assert!(d.contains("inverse cosine"), "{d}");
    }
}

/// Newton's method on P(s) of (A.1) from s = i, `steps` iterations.
fn newton_steps(tau0: f64, delta: f64, steps: usize) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..steps {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        s -= p / dp;
    }
    s
}

#[test]
fn characteristic_root_says_newton_stopped_early_not_a_factor_one() {
    for seed in SEEDS {
        for steps in [1, 2] {
            let d = diagnosis(grading::characteristic_root(seed, move |tau0, delta| {
                newton_steps(tau0, delta, steps)
            }));
            let plural = if steps == 1 { "" } else { "s" };
            assert!(
                d.contains(&format!("after {steps} step{plural}")),
                "{steps} steps: {d}"
            );
            assert!(
                !d.contains("1.0000 times") && !d.contains("direction"),
                "{d}"
            );
        }
    }
}

#[test]
fn a_sign_in_one_component_of_the_truncated_closed_form_is_named() {
    for seed in SEEDS {
        // (4.7) with the sign of the sine term of Omega_1 flipped: right at
        // t = 0, a mirror image later.
        let d = diagnosis(grading::truncated_closed_form(
            seed,
            |r, tau, w0: Vec3, t| {
                let u0 = w0.x.hypot(w0.y);
                let big_r = (1.0 + 2.0 * tau * u0 * u0 * t).sqrt();
                let vartheta = 2.0 * t / (1.0 + big_r);
                let (s, c) = ((1.0 - r) * w0.z * vartheta).sin_cos();
                Vec3::new(w0.x * c - w0.y * s, w0.y * c - w0.x * s, w0.z) / big_r
            },
        ));
        assert!(d.contains("sign wrong in one of its terms"), "{d}");
        assert!(!d.contains("a rate"), "{d}");
    }
}

#[test]
fn the_wrong_way_diagnosis_has_the_physics_right() {
    // Omega_perp' = -i Omega~_3 Omega_perp with Omega~_3 = (1 - I3/I1) Omega_3:
    // for a prolate top (I3 < I1) with Omega_3 > 0, Omega_perp turns clockwise
    // seen from +z (from Omega_1 toward -Omega_2).
    let top = top(0.4, 1.0);
    let w = sym::truncated_closed_form(&top, &Vec3::new(1.0, 0.0, 1.0), 0.1);
    assert!(w.y < 0.0, "clockwise: {w:?}");
    for seed in SEEDS {
        let d = diagnosis(grading::truncated_closed_form(
            seed,
            |r, tau, w0: Vec3, t| {
                let m =
                    sym::truncated_closed_form(&top_of(r, tau), &Vec3::new(w0.x, -w0.y, w0.z), t);
                Vec3::new(m.x, -m.y, m.z)
            },
        ));
        assert!(
            d.contains("clockwise (seen from the tip of the symmetry axis) when the top is prolate and Omega_3 > 0"),
            "{d}"
        );
        assert!(!d.contains("clockwise when the top is oblate"), "{d}");
    }
}

fn top_of(r: f64, tau: f64) -> SymmetricTop {
    top(r, tau)
}

#[test]
fn a_scalar_never_hears_direction_and_a_factor_shows_its_digits() {
    for seed in SEEDS {
        let d = diagnosis(grading::truncated_time_to_factor(seed, |r, tau, w, p| {
            1.7 * sym::truncated_time_to_factor(&top(r, tau), w, p)
        }));
        assert!(d.contains("1.700 times") && !d.contains("direction"), "{d}");
        // A constant rounded: 1.0000003 times, never 1.0000.
        let d = diagnosis(grading::reduced_decay_time(seed, |r, tau, w3| {
            1.000_000_3 * sym::reduced_decay_time(&top(r, tau), w3)
        }));
        assert!(d.contains("1.0000003") && !d.contains("direction"), "{d}");
        let d = diagnosis(grading::axial_schott_rate(seed, |j: &Jet| {
            -2.5 * balance::axial(&j[0], &balance::schott_rate(j))
        }));
        assert!(!d.contains("direction") && d.contains("−2.500"), "{d}");
    }
}

#[test]
fn precession_tilt_is_tried_with_a_negative_spin() {
    for seed in SEEDS {
        // atan in place of atan2: right for Omega_3 > 0 only.
        let d = diagnosis(grading::precession_tilt(seed, |r: f64, w0: Vec3| {
            (w0.x.hypot(w0.y) / (r * w0.z)).atan()
        }));
        assert!(d.contains("Omega_3 < 0"), "{d}");
    }
}

#[test]
fn inputs_change_between_gradings_and_a_table_of_one_fails_the_next() {
    // A "student" that answers right and writes down every input and answer.
    let table: RefCell<HashMap<[u64; 4], f64>> = RefCell::new(HashMap::new());
    let key = |r: f64, tau: f64, w: f64, p: f64| [r, tau, w, p].map(f64::to_bits);
    let first = grading::truncated_time_to_factor(11, |r, tau, w, p| {
        let t = sym::truncated_time_to_factor(&top(r, tau), w, p);
        table.borrow_mut().insert(key(r, tau, w, p), t);
        t
    });
    assert!(first.is_ok());
    assert!(table.borrow().len() >= grading::CASES);
    let lookup = |r, tau, w, p| {
        table
            .borrow()
            .get(&key(r, tau, w, p))
            .copied()
            .unwrap_or(1.0)
    };
    // The same seed again: the table passes (replay works)...
    assert!(grading::truncated_time_to_factor(11, lookup).is_ok());
    // ...another seed: the table is worth nothing.
    let failed = grading::truncated_time_to_factor(12, lookup).expect_err("a table of seed 11");
    assert_eq!(failed.seed, 12);
    assert!(failed.to_string().contains("SPINTOP_SEED=12"));
    // Every grader's inputs move with the seed: the reference records them.
    for (seed_a, seed_b) in [(1, 2), (2026, 2027)] {
        let seen = |seed: u64| {
            let inputs: RefCell<Vec<u64>> = RefCell::new(Vec::new());
            let _ = grading::larmor_rate(seed, |j: &Jet| {
                inputs.borrow_mut().push(j[0].x.to_bits());
                balance::larmor_rate(j)
            });
            inputs.into_inner()
        };
        assert_ne!(seen(seed_a), seen(seed_b));
        assert_eq!(seen(seed_a), seen(seed_a));
    }
}

/// An answer that is not finite (0/0 somewhere) is a common first attempt:
/// its report names it in words, so that the CLI, which prints no bare
/// `NaN`, shows the whole report instead of stopping at the line `got:`.
#[test]
fn a_non_finite_answer_is_reported_in_words_that_the_cli_prints() {
    for seed in SEEDS {
        let grade = grading::rk4_step(seed, |_f: DynField, _t, _y: &State<3>, _h| {
            State::<3>::repeat(f64::NAN)
        });
        let failed = grade.expect_err("a NaN answer fails");
        let text = failed.to_string();
        assert_eq!(spintop::numbers::non_finite_word(&text), None, "{text}");
        assert!(text.contains("got:       (not-a-number"), "{text}");
        assert!(failed.diagnosis.contains("not finite"), "{text}");
        let grade = grading::reduced_decay_time(seed, |_r, _tau, _w3| f64::INFINITY);
        let text = grade.expect_err("an infinite answer fails").to_string();
        assert_eq!(spintop::numbers::non_finite_word(&text), None, "{text}");
        assert!(text.contains("infinity"), "{text}");
    }
}
