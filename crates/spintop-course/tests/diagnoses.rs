//! The diagnoses of issue 45 (item 5): each is given a wrong answer as a
//! student writes it, and must fail with the words that name the mistake,
//! at every seed: which stage of RK4 or Dormand–Prince is wrong, which term
//! of a formula, degrees inside a trigonometric function, Newton's method
//! stopped early or given a wrong derivative.

use super::SEEDS;
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::balance::{self, DipoleTrajectory, Jet, PrecessingDipole};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use spintop_grading::{self as grading, DynField, Grade};

fn top(r: f64, tau: f64) -> SymmetricTop {
    SymmetricTop::new(r, tau).unwrap()
}

/// The diagnosis of a wrong answer, which must fail, checked for `words`.
#[track_caller]
fn says(grade: Grade, words: &[&str]) -> String {
    let failed = grade.expect_err("a wrong answer must fail");
    for w in words {
        assert!(failed.diagnosis.contains(w), "'{w}' not in:\n{failed}");
    }
    failed.diagnosis
}

/// An explicit Runge–Kutta step from its table: c, A by rows, b, and for an
/// embedded pair b̂ over the stages and f(t + h, y_new).
struct Table {
    c: Vec<f64>,
    a: Vec<Vec<f64>>,
    b: Vec<f64>,
    bhat: Vec<f64>,
}

impl Table {
    fn rk4() -> Self {
        Self {
            c: vec![0.0, 0.5, 0.5, 1.0],
            a: vec![vec![], vec![0.5], vec![0.0, 0.5], vec![0.0, 0.0, 1.0]],
            b: vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
            bhat: vec![],
        }
    }

    fn dp5() -> Self {
        Self {
            c: vec![0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0],
            a: vec![
                vec![],
                vec![0.2],
                vec![3.0 / 40.0, 9.0 / 40.0],
                vec![44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
                vec![
                    19372.0 / 6561.0,
                    -25360.0 / 2187.0,
                    64448.0 / 6561.0,
                    -212.0 / 729.0,
                ],
                vec![
                    9017.0 / 3168.0,
                    -355.0 / 33.0,
                    46732.0 / 5247.0,
                    49.0 / 176.0,
                    -5103.0 / 18656.0,
                ],
            ],
            b: vec![
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
            bhat: vec![
                5179.0 / 57600.0,
                0.0,
                7571.0 / 16695.0,
                393.0 / 640.0,
                -92097.0 / 339200.0,
                187.0 / 2100.0,
                1.0 / 40.0,
            ],
        }
    }

    fn step(&self, f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
        let mut k: Vec<State<3>> = Vec::new();
        for (i, c) in self.c.iter().enumerate() {
            let yi = k
                .iter()
                .zip(&self.a[i])
                .fold(*y, |s, (kj, a)| s + kj * (a * h));
            k.push(f(t + c * h, &yi));
        }
        let next = k
            .iter()
            .zip(&self.b)
            .fold(*y, |s, (kj, b)| s + kj * (b * h));
        if self.bhat.is_empty() {
            return (next, State::<3>::zeros());
        }
        k.push(f(t + h, &next));
        let low = k
            .iter()
            .zip(&self.bhat)
            .fold(*y, |s, (kj, b)| s + kj * (b * h));
        (next, next - low)
    }
}

#[test]
fn a_wrong_stage_of_rk4_is_named_with_its_time() {
    for seed in SEEDS {
        let mut k2_at_t = Table::rk4();
        k2_at_t.c[1] = 0.0;
        says(
            grading::rk4_step(seed, |f, t, y, h| k2_at_t.step(f, t, y, h).0),
            &["stage 2 (k2)", "wrong time", "start of the step"],
        );
        let mut k4_at_half = Table::rk4();
        k4_at_half.c[3] = 0.5;
        says(
            grading::rk4_step(seed, |f, t, y, h| k4_at_half.step(f, t, y, h).0),
            &["stage 4 (k4)", "wrong time", "midpoint"],
        );
        // A coefficient no plausible slip of the list predicts: found by the fit.
        let mut odd = Table::rk4();
        odd.a[2] = vec![0.1, 0.4];
        says(
            grading::rk4_step(seed, |f, t, y, h| odd.step(f, t, y, h).0),
            &["stage 3 (k3)", "coefficient on k1", "coefficient on k2"],
        );
    }
}

/// A slip written into a Butcher table.
type Slip = Box<dyn Fn(&mut Table)>;

#[test]
fn a_wrong_coefficient_of_dormand_prince_is_named_with_its_stage() {
    let cases: Vec<(Slip, &[&str])> = vec![
        (
            Box::new(|t: &mut Table| t.b[4] = -t.b[4]),
            &["weight of stage 5 (k5)", "wrong sign"],
        ),
        (
            Box::new(|t: &mut Table| t.a[3][1] = -t.a[3][1]),
            &["stage 4 (k4)", "coefficient on k2", "wrong sign"],
        ),
        (
            Box::new(|t: &mut Table| t.c[5] = 8.0 / 9.0),
            &["stage 6 (k6)", "wrong time", "time of stage 5"],
        ),
        (
            Box::new(|t: &mut Table| t.a[2] = vec![9.0 / 40.0, 3.0 / 40.0]),
            &["stage 3 (k3)", "k1 and k2 are swapped"],
        ),
        (
            Box::new(|t: &mut Table| t.bhat[6] = 0.0),
            &["error estimate", "stage 7 (k7)", "missing"],
        ),
    ];
    for seed in SEEDS {
        for (change, words) in &cases {
            let mut table = Table::dp5();
            change(&mut table);
            says(
                grading::dp5_step(seed, |f, t, y, h| table.step(f, t, y, h)),
                words,
            );
        }
    }
}

/// Newton's method on P(s) of (A.1) from s = i, with the right derivative
/// or the one without its product-rule term, at most `steps` iterations,
/// stopping once a step is below `stop` (and then, if `discard`, without
/// taking it).
fn newton(tau0: f64, delta: f64, steps: usize, product_rule: bool, stop: f64, discard: bool) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..steps {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let mut dp = s * 2.0 * (e + m0);
        if product_rule {
            dp -= s * s * e * delta;
        }
        let step = p / dp;
        if discard && step.norm() < stop {
            break;
        }
        s -= step;
        if step.norm() <= stop * s.norm().max(1.0) {
            break;
        }
    }
    s
}

#[test]
fn newton_stopped_early_or_with_a_wrong_derivative_fails_and_is_named() {
    for seed in SEEDS {
        // Both converge on small shells; the hard shells show them.
        says(
            grading::characteristic_root(seed, |tau0, delta| {
                newton(tau0, delta, 3, true, 1e-15, false)
            }),
            &[
                "Newton's method after 3 steps",
                "not converged",
                "3 iterations are not enough",
            ],
        );
        says(
            grading::characteristic_root(seed, |tau0, delta| {
                newton(tau0, delta, 20, false, 1e-15, false)
            }),
            &["wrong derivative", "product rule", "after 20 iterations"],
        );
        says(
            grading::characteristic_root(seed, |tau0, delta| {
                newton(tau0, delta, 100, true, 1e-3, true)
            }),
            &["stopping test", "tolerance is far above rounding"],
        );
        // The right method with a wrong derivative, iterated to the end,
        // finds the same root (more slowly): not a wrong answer.
        grading::characteristic_root(seed, |tau0, delta| {
            newton(tau0, delta, 400, false, 1e-15, false)
        })
        .expect("a slow Newton iteration that converges is right");
    }
}

#[test]
fn the_wrong_term_of_the_shell_update_is_found_by_zeroing_the_other() {
    for seed in SEEDS {
        says(
            grading::shell_acceleration(seed, |tau0, delta, z: C, zr: C| {
                let m0 = ShellModel::new(tau0, delta).unwrap().m0();
                (-z - zr) / m0
            }),
            &["with Z = 0", "the retarded term", "a factor m_em missing"],
        );
        // The same slip in the restoring term: its factor 1/m0 missing.
        says(
            grading::shell_acceleration(seed, |tau0, delta, z: C, zr: C| {
                let m = ShellModel::new(tau0, delta).unwrap();
                -z - zr * m.m_em() / m.m0()
            }),
            &[
                "with Z''(t - delta) = 0",
                "restoring force",
                "a factor m0 too many",
            ],
        );
    }
}

#[test]
fn the_terms_of_a_law_of_section_2_are_read_one_pair_of_derivatives_at_a_time() {
    for seed in SEEDS {
        // The torque built as (2.1) plus half of dL_S/dt.
        says(
            grading::torque_rate(seed, |j: &Jet| -j[1].cross(&j[2]) + j[0].cross(&j[3])),
            &["Larmor-like law (2.1)", "product rule", "d' × d''"],
        );
        // A factor 3 on one term of the product rule: no listed slip.
        says(
            grading::schott_rate(seed, |j: &Jet| 3.0 * j[1].cross(&j[2]) + j[0].cross(&j[3])),
            &[
                "sum of cross products",
                "first term",
                "3 times the right one",
            ],
        );
        // A term too many, named for the law it belongs to.
        says(
            grading::larmor_rate(seed, |j: &Jet| -j[1].cross(&j[2]) + j[0].cross(&j[2])),
            &["a term too many", "d × d''", "L_S"],
        );
        // A wrong pair: which factor is wrong, by how many derivatives.
        says(
            grading::larmor_rate(seed, |j: &Jet| j[0].cross(&j[1])),
            &[
                "you crossed d with d'",
                "d is the wrong factor",
                "2 derivatives too few",
            ],
        );

        says(
            grading::schott_angular_momentum(seed, |j: &Jet| j[2].cross(&j[0])),
            &["sign flip", "wrong order"],
        );
    }
}

#[test]
fn degrees_inside_sin_and_cos_are_named() {
    let cone = |th: f64, w: f64, t: f64| PrecessingDipole::new(th, w).unwrap().jet(t);
    for seed in SEEDS {
        says(
            grading::precessing_dipole_jet(seed, move |th, w, t| cone(th.to_radians(), w, t)),
            &["theta", "degrees", "radians"],
        );
        says(
            grading::precessing_dipole_jet(seed, move |th, w, t| cone(th, w, t.to_radians())),
            &["omega t", "degrees", "radians"],
        );
        // The precession angle of (4.7) and of (4.15) through to_radians.
        let trunc = |r: f64, tau: f64, w0: Vec3, t: f64, turn: f64| {
            let u0 = w0.x.hypot(w0.y);
            let big_r = (1.0 + 2.0 * tau * u0 * u0 * t).sqrt();
            let a = turn * (1.0 - r) * w0.z * 2.0 * t / (1.0 + big_r);
            let (s, c) = a.sin_cos();
            Vec3::new(w0.x * c + w0.y * s, w0.y * c - w0.x * s, w0.z) / big_r
        };
        says(
            grading::truncated_closed_form(seed, move |r, tau, w0, t| {
                trunc(r, tau, w0, t, 1f64.to_radians())
            }),
            &["phase", "degrees to radians"],
        );
        // Half the clock: the phase at half speed, a factor 2.
        says(
            grading::truncated_closed_form(seed, move |r, tau, w0, t| trunc(r, tau, w0, t, 0.5)),
            &["phase runs at half speed", "factor 2", "clock"],
        );
        // Another factor on the rate: the precession rate, not degrees.
        says(
            grading::truncated_closed_form(seed, move |r, tau, w0, t| trunc(r, tau, w0, t, 1.3)),
            &["phase is off", "1.300 times", "precession rate"],
        );
    }
}

#[test]
fn the_general_top_s_terms_are_checked_one_condition_at_a_time() {
    let rhs = |i: Vec3, d: Vec3, w: Vec3| GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w);
    for seed in SEEDS {
        // The damping not squared.
        says(
            grading::truncated_ale_rhs(seed, |i: Vec3, d: Vec3, w: Vec3| {
                let dw = d.cross(&w);
                let a = Mat3::from_diagonal(&i) + d * dw.transpose();
                let b = -w.cross(&i.component_mul(&w)) - dw.norm() * w;
                a.lu().solve(&b).unwrap()
            }),
            &["damping is not squared"],
        );
        // The damping three times too strong: right without a dipole, wrong
        // with equal moments (no listed slip).
        says(
            grading::truncated_ale_rhs(seed, |i: Vec3, d: Vec3, w: Vec3| {
                let dw = d.cross(&w);
                let a = Mat3::from_diagonal(&i) + d * dw.transpose();
                let b = -w.cross(&i.component_mul(&w)) - 3.0 * dw.norm_squared() * w;
                a.lu().solve(&b).unwrap()
            }),
            &["with equal moments of inertia", "radiation's terms"],
        );
        // The energy's rate with the inertia twice, and with half the product rule.
        says(
            grading::energy_rate(seed, move |i, d, w| {
                i.component_mul(&w).dot(&i.component_mul(&rhs(i, d, w)))
            }),
            &["inertia is applied twice", "angular momentum"],
        );
        says(
            grading::energy_rate(seed, move |i, d, w| {
                0.5 * w.dot(&i.component_mul(&rhs(i, d, w)))
            }),
            &["half of the product rule", "factor 2"],
        );
    }
}

#[test]
fn euler_angles_name_an_atan2_slip_and_the_transpose() {
    for seed in SEEDS {
        says(
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let a = EulerAngles::from_rotation(m);
                (a.phi, a.theta, m[(2, 1)].atan2(m[(2, 0)]))
            }),
            &[
                "psi is wrong",
                "phi and theta are right",
                "arguments of its atan2 are swapped",
            ],
        );
        says(
            grading::euler_from_rotation(seed, |m: &Mat3| {
                let a = EulerAngles::from_rotation(&m.transpose());
                (a.phi, a.theta, a.psi)
            }),
            &["transpose", "rows and columns", "inverse rotation"],
        );
    }
}

#[test]
fn the_reduced_model_s_terms_decay_and_phase_are_named() {
    for seed in SEEDS {
        // A precession rate no listed slip predicts: tau = 0 isolates it.
        says(
            grading::reduced_ale_rhs(seed, |r, tau, w: Vec3| {
                let (wt, damp) = (
                    (1.0 + r) * w.z,
                    tau * (w.x * w.x + w.y * w.y + (r * w.z).powi(2)),
                );
                Vec3::new(wt * w.y - damp * w.x, -wt * w.x - damp * w.y, 0.0)
            }),
            &["with tau = 0", "free precession", "precession rate"],
        );
        says(
            grading::reduced_decay_time(seed, |r, tau, w3| 0.5 / (tau * (r * w3).powi(2))),
            &["half the decay time", "factor 1/2"],
        );
        // Phi without its exponential, and with s at half its rate.
        let reduced = |r: f64, tau: f64, w0: Vec3, t: f64, f: f64, exp: bool| {
            let u0 = w0.x * w0.x + w0.y * w0.y;
            let s = f * 2.0 * tau * (r * w0.z).powi(2) * t;
            let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
            let decay = if exp { (-0.5 * s).exp() } else { 1.0 };
            let phi = decay / (1.0 + 2.0 * tau * u0 * t * g).sqrt();
            let (sa, ca) = ((1.0 - r) * w0.z * t).sin_cos();
            Vec3::new(
                phi * (w0.x * ca + w0.y * sa),
                phi * (w0.y * ca - w0.x * sa),
                w0.z,
            )
        };
        says(
            grading::reduced_closed_form(seed, move |r, tau, w0, t| {
                reduced(r, tau, w0, t, 1.0, false)
            }),
            &["exponential factor of Phi is missing", "does not decay"],
        );
        says(
            grading::reduced_closed_form(seed, move |r, tau, w0, t| {
                reduced(r, tau, w0, t, 0.5, true)
            }),
            &[
                "decays at half the rate",
                "factor 2 missing in its exponent",
            ],
        );
        grading::reduced_closed_form(seed, move |r, tau, w0, t| reduced(r, tau, w0, t, 1.0, true))
            .expect("the closed form written out passes");
    }
}

/// `steps` classical RK4 steps of size `h` of `f` from `w0`.
fn run(f: impl Fn(&Vec3) -> Vec3, w0: Vec3, steps: usize, h: f64) -> Vec3 {
    (0..steps).fold(w0, |y, _| {
        let k1 = f(&y);
        let k2 = f(&(y + k1 * (h / 2.0)));
        let k3 = f(&(y + k2 * (h / 2.0)));
        let k4 = f(&(y + k3 * h));
        y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    })
}

#[test]
fn a_wrong_run_names_its_step_size_and_its_model() {
    for seed in SEEDS {
        let right = |r: f64, tau: f64| move |y: &Vec3| sym::reduced_ale_rhs(&top(r, tau), y);
        says(
            grading::reduced_rk4(seed, move |r, tau, w0, t_end, n| {
                run(right(r, tau), w0, n, t_end)
            }),
            &["step size is wrong", "each of your steps is t_end long"],
        );
        says(
            grading::reduced_rk4(seed, |r, tau, w0, t_end, n| {
                let f = |w: &Vec3| {
                    let (wt, damp) = (
                        (1.0 - r) * w.z,
                        tau * (w.x * w.x + w.y * w.y + r * w.z * w.z),
                    );
                    Vec3::new(wt * w.y - damp * w.x, -wt * w.x - damp * w.y, 0.0)
                };
                run(f, w0, n, t_end / n as f64)
            }),
            &[
                "wrong model",
                "moment ratio enters the damping once, not squared",
            ],
        );
    }
}

#[test]
fn the_reworded_diagnoses_say_what_is_wrong() {
    let jet = |j: &Jet| balance::schott_rate(j);
    for seed in SEEDS {
        says(
            grading::axial_schott_rate(seed, move |j: &Jet| jet(j).norm()),
            &["size of dL_S/dt", "magnitude", "projection"],
        );
        says(
            grading::shell_masses(seed, |tau0, delta| (1.0 - delta / tau0, delta / tau0)),
            &["m_em is inverted"],
        );
        says(
            grading::precession_tilt(seed, |r, w: Vec3| (r * w.x.hypot(w.y)).atan2(w.z)),
            &["ratio of the moments is inverted"],
        );
        says(
            grading::truncated_time_to_factor(seed, |_r, tau, w, p| {
                (1.0 - p * p) / (2.0 * tau * w * w)
            }),
            &["upside down (inverted)"],
        );
    }
}
