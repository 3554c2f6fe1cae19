//! The graders of the course assignments really grade: spintop's own
//! implementations pass every one, a `todo!()` stub fails every one, and for
//! each assignment at least one plausible wrong answer (a sign flip, a missing
//! Schott term, I₁ and I₃ swapped, the printed (4.11) θ, a wrong RK
//! coefficient, …) fails with a report that names the equation.

use spintop::grading::{self, DynField, Failed, Grade};
use spintop::integrate::dopri5::dopri5_step;
use spintop::integrate::rk4::rk4_step;
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::balance::{self, Jet};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::shell::{C, ShellModel};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};

fn fails(grade: Grade, equation: &str) -> Box<Failed> {
    let failed = grade.expect_err("a wrong answer must fail its grader");
    assert!(
        failed.equation.contains(equation),
        "the report names {}, not {equation}",
        failed.equation
    );
    let text = failed.to_string();
    for part in ["input:", "expected:", "got:", "hint:"] {
        assert!(text.contains(part), "{text}");
    }
    failed
}

// ---- spintop's own implementations pass ----

#[test]
fn graders_pass_the_reference_implementations() {
    let top_rhs = |i: Vec3, d: Vec3, w: Vec3| GeneralTop::new(i, d).unwrap().truncated_ale_rhs(&w);
    let reduced = |r: f64, tau: f64, w0: Vec3, t: f64| {
        sym::reduced_closed_form(&SymmetricTop::new(r, tau).unwrap(), &w0, t)
    };
    let tilt = |r: f64, w0: Vec3| sym::precession_tilt(&SymmetricTop::new(r, 1.0).unwrap(), &w0);
    let grades = [
        grading::larmor_rate(balance::larmor_rate),
        grading::torque_rate(balance::torque_rate),
        grading::schott_angular_momentum(balance::schott_angular_momentum),
        grading::axial_schott_rate(|j: &Jet| balance::axial(&j[0], &balance::schott_rate(j))),
        grading::truncated_ale_rhs(top_rhs),
        grading::reduced_closed_form(reduced),
        grading::precession_tilt(tilt),
        grading::rk4_step(|f: DynField, t, y: &State<3>, h| rk4_step(&f, t, y, h)),
        grading::dp5_step(|f: DynField, t, y: &State<3>, h| dopri5_step(&f, t, y, h)),
        grading::euler_from_rotation(|m: &Mat3| {
            let a = EulerAngles::from_rotation(m);
            (a.phi, a.theta, a.psi)
        }),
        grading::shell_acceleration(|tau0, delta, z, zr| {
            ShellModel::new(tau0, delta).unwrap().acceleration(z, zr)
        }),
    ];
    for grade in grades {
        let passed = grade.unwrap_or_else(|f| panic!("{f}"));
        assert!(passed.cases >= grading::CASES, "{passed:?}");
    }
}

// ---- a stub fails, and says it is a stub ----

#[test]
fn graders_fail_a_todo_stub_with_a_pointer() {
    let failed = fails(
        grading::larmor_rate(|_: &Jet| -> Vec3 { todo!("Eq. (2.1): see the book") }),
        "(2.1)",
    );
    assert!(failed.actual.contains("not yet implemented: Eq. (2.1)"));
    assert!(failed.hint.starts_with("the stub is still a todo!()"));
}

// ---- plausible wrong answers fail ----

#[test]
fn eq_2_1_wrong_sign_fails() {
    fails(grading::larmor_rate(|j: &Jet| j[1].cross(&j[2])), "(2.1)");
}

#[test]
fn eq_2_2_missing_schott_term_fails() {
    // The Larmor-like law (2.1) handed in for the torque (2.2).
    let failed = fails(grading::torque_rate(balance::larmor_rate), "(2.2)");
    assert!(failed.hint.contains("Schott"));
}

#[test]
fn eq_2_4_wrong_derivative_fails() {
    fails(
        grading::schott_angular_momentum(|j: &Jet| j[0].cross(&j[1])),
        "(2.4)",
    );
}

#[test]
fn eq_2_3_unnormalised_projection_fails() {
    fails(
        grading::axial_schott_rate(|j: &Jet| j[0].dot(&balance::schott_rate(j))),
        "(2.3)",
    );
    // Projecting only d x d''' (always 0 along d) is also wrong.
    fails(
        grading::axial_schott_rate(|j: &Jet| balance::axial(&j[0], &j[0].cross(&j[3]))),
        "(2.3)",
    );
}

#[test]
fn eq_3_3_swapped_moments_fail() {
    let swapped = |i: Vec3, d: Vec3, w: Vec3| {
        GeneralTop::new(Vec3::new(i.z, i.y, i.x), d)
            .unwrap()
            .truncated_ale_rhs(&w)
    };
    fails(grading::truncated_ale_rhs(swapped), "(3.3)");
    // Dropping the Omega' term on the right (Omega' only on the left) is wrong too.
    let explicit = |i: Vec3, d: Vec3, w: Vec3| {
        let b = -w.cross(&i.component_mul(&w)) - d.cross(&w).norm_squared() * w;
        b.component_div(&i)
    };
    fails(grading::truncated_ale_rhs(explicit), "(3.3)");
}

#[test]
fn eq_4_15_dropping_omega_10_fails() {
    // The paper's (4.15) with Omega_10 = 0, applied to a start with Omega_10 != 0.
    let printed = |r: f64, tau: f64, w0: Vec3, t: f64| {
        let start = Vec3::new(0.0, w0.x.hypot(w0.y), w0.z);
        sym::reduced_closed_form(&SymmetricTop::new(r, tau).unwrap(), &start, t)
    };
    fails(grading::reduced_closed_form(printed), "(4.15)");
    // Precession turning the wrong way.
    let backwards = |r: f64, tau: f64, w0: Vec3, t: f64| {
        let top = SymmetricTop::new(r, tau).unwrap();
        let w = sym::reduced_closed_form(&top, &w0, t);
        let a = top.omega3_tilde(w0.z) * t;
        let amp = sym::reduced_amplitude(&top, &w0, t);
        let (s, c) = a.sin_cos();
        Vec3::new(
            amp * (w0.x * c - w0.y * s),
            amp * (w0.y * c + w0.x * s),
            w.z,
        )
    };
    fails(grading::reduced_closed_form(backwards), "(4.15)");
}

#[test]
fn eq_4_11_printed_tilt_fails() {
    let printed =
        |r: f64, w0: Vec3| sym::printed_tilt_4_11(&SymmetricTop::new(r, 1.0).unwrap(), &w0);
    let failed = fails(grading::precession_tilt(printed), "(4.11)");
    assert!(failed.hint.contains("erratum"));
}

#[test]
fn rk4_wrong_coefficient_fails() {
    let wrong = |f: DynField, t: f64, y: &State<3>, h: f64| {
        let k1 = f(t, y);
        let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
        let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
        let k4 = f(t + h, &(y + k3 * h));
        // Weights (1, 1, 2, 2)/6 instead of (1, 2, 2, 1)/6.
        y + (k1 + k2 + k3 * 2.0 + k4 * 2.0) * (h / 6.0)
    };
    fails(grading::rk4_step(wrong), "RK4");
    // k4 evaluated at the old time.
    let stale = |f: DynField, t: f64, y: &State<3>, h: f64| {
        let k1 = f(t, y);
        let k2 = f(t + h / 2.0, &(y + k1 * (h / 2.0)));
        let k3 = f(t + h / 2.0, &(y + k2 * (h / 2.0)));
        let k4 = f(t, &(y + k3 * h));
        y + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    };
    fails(grading::rk4_step(stale), "RK4");
}

#[test]
fn dp5_wrong_error_estimate_or_coefficient_fails() {
    // The right step with the error estimate's sign flipped (y4 - y5).
    let flipped = |f: DynField, t: f64, y: &State<3>, h: f64| {
        let (y5, e) = dopri5_step(&f, t, y, h);
        (y5, -e)
    };
    fails(grading::dp5_step(flipped), "Dormand-Prince");
    // The fourth-order solution returned as the step.
    let lower = |f: DynField, t: f64, y: &State<3>, h: f64| {
        let (y5, e) = dopri5_step(&f, t, y, h);
        (y5 - e, e)
    };
    fails(grading::dp5_step(lower), "Dormand-Prince");
}

#[test]
fn eq_3_5_euler_without_pole_handling_or_with_acos_fails() {
    let no_pole = |m: &Mat3| {
        let theta = m[(0, 2)].hypot(m[(1, 2)]).atan2(m[(2, 2)]);
        (
            m[(0, 2)].atan2(-m[(1, 2)]),
            theta,
            m[(2, 0)].atan2(m[(2, 1)]),
        )
    };
    fails(grading::euler_from_rotation(no_pole), "(3.5)");
    let acos = |m: &Mat3| {
        let a = EulerAngles::from_rotation(m);
        (a.phi, m[(2, 2)].clamp(-1.0, 1.0).acos(), a.psi)
    };
    fails(grading::euler_from_rotation(acos), "(3.5)");
}

#[test]
fn eq_a_1_wrong_sign_or_mass_fails() {
    let sign = |tau0: f64, delta: f64, z: C, zr: C| {
        let m_em = tau0 / delta;
        (-z + zr * m_em) / (1.0 - m_em)
    };
    fails(grading::shell_acceleration(sign), "(A.1)");
    // The bare mass taken as the whole mass, m0 = 1.
    let whole = |tau0: f64, delta: f64, z: C, zr: C| -z - zr * (tau0 / delta);
    fails(grading::shell_acceleration(whole), "(A.1)");
}
