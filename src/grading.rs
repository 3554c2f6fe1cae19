//! Graders for the course assignments of the `spintop-lessons` package.
//!
//! Each grader takes a student's function, feeds it many random valid inputs
//! from a fixed seed (so every run and every student sees the same cases),
//! compares the answer with spintop's own implementation, and checks what
//! physics demands of it. On the first failing input it stops and returns a
//! [`Failed`] that names the input, the expected and the actual value, and the
//! equation to read again. A stub that panics (`todo!()`) fails the same way.
//!
//! | grader | equation | the student writes |
//! |---|---|---|
//! | [`larmor_rate`] | (2.1) | −ḋ × d̈ |
//! | [`torque_rate`] | (2.2) | d × d⃛ |
//! | [`schott_angular_momentum`] | (2.4) | d × d̈ |
//! | [`axial_schott_rate`] | (2.3)–(2.4) | n · dL_S/dt |
//! | [`truncated_ale_rhs`] | (3.3) | Ω̇ of a general top |
//! | [`reduced_closed_form`] | (4.15)–(4.16) | Ω(t) for any Ω₀ |
//! | [`precession_tilt`] | (4.11), corrected | the constant tilt θ |
//! | [`rk4_step`] | – | one classical RK4 step |
//! | [`dp5_step`] | – | one Dormand–Prince 5(4) step and its error estimate |
//! | [`euler_from_rotation`] | (3.5) | Euler angles of a rotation, pole included |
//! | [`shell_acceleration`] | (A.1) | the method-of-steps update Z'' |

use crate::integrate::{dopri5::dopri5_step, rk4::rk4_step as reference_rk4_step};
use crate::math::{Mat3, Real, State, Vec3};
use crate::physics::balance::{self, Jet};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::shell::{C, ShellModel};
use crate::physics::symmetric_top::{self, SymmetricTop};
use std::cell::Cell;
use std::fmt;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;

/// The seed of every grader's random cases.
pub const SEED: u64 = 2026;
/// Random cases per grader (plus its fixed special cases).
pub const CASES: usize = 200;

/// A passed assignment.
#[derive(Clone, Debug, PartialEq)]
pub struct Passed {
    /// The assignment.
    pub assignment: &'static str,
    /// How many inputs were checked.
    pub cases: usize,
}

/// A failed assignment, at its first failing input.
#[derive(Clone, Debug, PartialEq)]
pub struct Failed {
    /// The assignment.
    pub assignment: &'static str,
    /// The equation it implements.
    pub equation: &'static str,
    /// The input, readable.
    pub input: String,
    /// What the reference gives (or what physics requires).
    pub expected: String,
    /// What the student's function gave.
    pub actual: String,
    /// What to look at.
    pub hint: String,
}

impl fmt::Display for Failed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} ({}) is not right yet.",
            self.assignment, self.equation
        )?;
        writeln!(f, "  input:    {}", self.input)?;
        writeln!(f, "  expected: {}", self.expected)?;
        writeln!(f, "  got:      {}", self.actual)?;
        write!(f, "  hint:     {}", self.hint)
    }
}

/// The outcome of a grader.
/// (The failure is boxed: it carries four strings.)
pub type Grade = Result<Passed, Box<Failed>>;

/// Panic with a readable report unless `grade` passed (for `#[test]`s).
pub fn assert_passes(grade: Grade) {
    if let Err(failed) = grade {
        panic!("\n{failed}\n");
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): small, seedable, reproducible.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [a, b).
    pub fn uniform(&mut self, a: Real, b: Real) -> Real {
        let u = (self.next_u64() >> 11) as Real / (1u64 << 53) as Real;
        a + (b - a) * u
    }
    /// A vector with components uniform in [−r, r).
    pub fn vec3(&mut self, r: Real) -> Vec3 {
        Vec3::new(
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        )
    }
}

thread_local! {
    /// True while this thread runs a student's function inside a grader.
    static GRADING: Cell<bool> = const { Cell::new(false) };
}

/// Install (once) a panic hook that stays quiet for panics inside a grader,
/// whose message the grader reports itself, and defers to the previous hook
/// for every other panic.
fn quiet_panics_while_grading() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !GRADING.with(Cell::get) {
                previous(info);
            }
        }));
    });
}

/// Call the student's code; a panic (a `todo!()` stub, say) becomes its message.
fn call<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    quiet_panics_while_grading();
    GRADING.with(|g| g.set(true));
    let result = catch_unwind(AssertUnwindSafe(f));
    GRADING.with(|g| g.set(false));
    result.map_err(|payload| {
        let msg = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".to_string());
        format!("panicked: {msg}")
    })
}

/// The context of one grader, to build its [`Failed`].
struct Assignment {
    name: &'static str,
    equation: &'static str,
    hint: &'static str,
}

impl Assignment {
    fn fail(&self, input: String, expected: String, actual: String) -> Box<Failed> {
        let hint = if actual.starts_with("panicked: not yet implemented")
            || actual.starts_with("panicked: not implemented")
        {
            format!("the stub is still a todo!(): fill it in. {}", self.hint)
        } else {
            self.hint.to_string()
        };
        Box::new(Failed {
            assignment: self.name,
            equation: self.equation,
            input,
            expected,
            actual,
            hint,
        })
    }

    /// Compare the student's answer with the reference on every input.
    fn compare<I: fmt::Debug, T: Show>(
        &self,
        inputs: &[I],
        student: impl Fn(&I) -> T,
        reference: impl Fn(&I) -> T,
        close: impl Fn(&T, &T) -> bool,
    ) -> Grade {
        for input in inputs {
            let expected = reference(input);
            match call(|| student(input)) {
                Ok(actual) if close(&actual, &expected) => {}
                Ok(actual) => {
                    return Err(self.fail(format!("{input:?}"), expected.show(), actual.show()));
                }
                Err(msg) => {
                    return Err(self.fail(format!("{input:?}"), expected.show(), msg));
                }
            }
        }
        Ok(Passed {
            assignment: self.name,
            cases: inputs.len(),
        })
    }
}

/// A value as a grader prints it: plain numbers, vectors as (x, y, z).
trait Show {
    fn show(&self) -> String;
}

impl Show for Real {
    fn show(&self) -> String {
        format!("{self:e}")
    }
}

impl Show for Vec3 {
    fn show(&self) -> String {
        format!("({:e}, {:e}, {:e})", self.x, self.y, self.z)
    }
}

impl Show for (State<3>, State<3>) {
    fn show(&self) -> String {
        format!(
            "step ({:e}, {:e}, {:e}), error estimate ({:e}, {:e}, {:e})",
            self.0[0], self.0[1], self.0[2], self.1[0], self.1[1], self.1[2]
        )
    }
}

impl Show for C {
    fn show(&self) -> String {
        format!("{:e} + {:e}i", self.re, self.im)
    }
}

/// |a − b| ≤ tol·(1 + |b|), componentwise through the norm.
fn close_vec(a: &Vec3, b: &Vec3, tol: Real) -> bool {
    a.iter().all(|x| x.is_finite()) && (a - b).norm() <= tol * (1.0 + b.norm())
}

fn close_real(a: Real, b: Real, tol: Real) -> bool {
    a.is_finite() && (a - b).abs() <= tol * (1.0 + b.abs())
}

/// A readable jet for reports.
#[derive(Clone, Copy)]
struct JetInput(Jet);

impl fmt::Debug for JetInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [d, d1, d2, d3] = self.0;
        write!(
            f,
            "d = {:?}, d' = {:?}, d'' = {:?}, d''' = {:?}",
            d.as_slice(),
            d1.as_slice(),
            d2.as_slice(),
            d3.as_slice()
        )
    }
}

fn jets() -> Vec<JetInput> {
    let mut rng = Rng::new(SEED);
    let mut out: Vec<JetInput> = (0..CASES)
        .map(|_| JetInput([rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0), rng.vec3(2.0)]))
        .collect();
    // A precessing dipole, the Section 2 example, at a few times.
    if let Ok(p) = balance::PrecessingDipole::new(0.7, 1.3) {
        use balance::DipoleTrajectory;
        out.extend([0.0, 0.4, 2.0].map(|t| JetInput(p.jet(t))));
    }
    out
}

/// Grade the Larmor-like loss rate.
///
/// Paper: Eq. (2.1).
pub fn larmor_rate(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Assignment {
        name: "larmor_rate",
        equation: "Eq. (2.1)",
        hint: "(2.1) with kappa = 1 is dL/dt = -d' x d''. Check the sign and the order of the cross product.",
    }
    .compare(
        &jets(),
        |j| student(&j.0),
        |j| balance::larmor_rate(&j.0),
        |a, b| close_vec(a, b, 1e-12),
    )
}

/// Grade the Abraham–Lorentz torque.
///
/// Paper: Eq. (2.2).
pub fn torque_rate(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Assignment {
        name: "torque_rate",
        equation: "Eq. (2.2)",
        hint: "(2.2) with kappa = 1 is dL/dt = d x d'''. If you got -d' x d'', that is the Larmor-like law (2.1): the Schott term (2.3) is missing.",
    }
    .compare(
        &jets(),
        |j| student(&j.0),
        |j| balance::torque_rate(&j.0),
        |a, b| close_vec(a, b, 1e-12),
    )
}

/// Grade the Schott angular momentum.
///
/// Paper: Eq. (2.4).
pub fn schott_angular_momentum(student: impl Fn(&Jet) -> Vec3) -> Grade {
    Assignment {
        name: "schott_angular_momentum",
        equation: "Eq. (2.4)",
        hint: "(2.4) with kappa = 1 is L_S = d x d'', the time derivative of d x d'.",
    }
    .compare(
        &jets(),
        |j| student(&j.0),
        |j| balance::schott_angular_momentum(&j.0),
        |a, b| close_vec(a, b, 1e-12),
    )
}

/// Grade the axial projection n·dL_S/dt, n = d/|d|.
///
/// Paper: Eq. (2.3), Eq. (2.4).
pub fn axial_schott_rate(student: impl Fn(&Jet) -> Real) -> Grade {
    Assignment {
        name: "axial_schott_rate",
        equation: "Eqs. (2.3)-(2.4)",
        hint: "dL_S/dt = d' x d'' + d x d''' (differentiate (2.4)); project on the unit vector n = d/|d| (divide by |d|). The d x d''' part has no axial component.",
    }
    .compare(
        &jets(),
        |j| student(&j.0),
        |j| balance::axial(&j.0[0], &balance::schott_rate(&j.0)),
        |a, b| close_real(*a, *b, 1e-12),
    )
}

/// A general top and a rate, for (3.3).
#[derive(Clone, Copy)]
struct TopInput {
    inertia: Vec3,
    dipole: Vec3,
    omega: Vec3,
}

impl fmt::Debug for TopInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "inertia = {:?}, dipole = {:?}, omega = {:?}",
            self.inertia.as_slice(),
            self.dipole.as_slice(),
            self.omega.as_slice()
        )
    }
}

/// Grade the body-frame right-hand side of the truncated ALE of a general top.
///
/// Paper: Eq. (3.3).
pub fn truncated_ale_rhs(student: impl Fn(Vec3, Vec3, Vec3) -> Vec3) -> Grade {
    let mut rng = Rng::new(SEED);
    let mut inputs = Vec::new();
    while inputs.len() < CASES {
        let inertia = Vec3::new(
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
            rng.uniform(0.3, 2.0),
        );
        // Small dipoles keep I + d(d x Omega)^T far from singular; every tenth
        // case is nearly free (Euler's equations).
        let dipole = if inputs.len() % 10 == 0 {
            rng.vec3(1e-6)
        } else {
            rng.vec3(0.6)
        };
        let input = TopInput {
            inertia,
            dipole,
            omega: rng.vec3(1.0),
        };
        if GeneralTop::new(inertia, dipole).is_ok() {
            inputs.push(input);
        }
    }
    Assignment {
        name: "truncated_ale_rhs",
        equation: "Eq. (3.3)",
        hint: "(3.3): I Omega' + Omega x I Omega = -{ |d x Omega|^2 Omega + (d.(Omega x Omega')) d }. Omega' is on both sides: solve the 3x3 linear system. With d = 0 it must reduce to Euler's equations; check that I1, I2, I3 multiply the right components.",
    }
    .compare(
        &inputs,
        |x| student(x.inertia, x.dipole, x.omega),
        |x| match GeneralTop::new(x.inertia, x.dipole) {
            Ok(top) => top.truncated_ale_rhs(&x.omega),
            Err(_) => Vec3::repeat(Real::NAN),
        },
        |a, b| close_vec(a, b, 1e-10),
    )
}

/// A symmetric top, a start and a time, for (4.15)–(4.16).
#[derive(Clone, Copy)]
struct ReducedInput {
    ratio: Real,
    tau: Real,
    omega0: Vec3,
    t: Real,
}

impl fmt::Debug for ReducedInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega0 = {:?}, t = {}",
            self.ratio,
            self.tau,
            self.omega0.as_slice(),
            self.t
        )
    }
}

/// Grade the reduced model's closed form, with Ω₁₀ ≠ 0.
///
/// Paper: Eq. (4.15), Eq. (4.16).
pub fn reduced_closed_form(student: impl Fn(Real, Real, Vec3, Real) -> Vec3) -> Grade {
    let mut rng = Rng::new(SEED);
    let inputs: Vec<ReducedInput> = (0..CASES)
        .map(|_| ReducedInput {
            ratio: rng.uniform(0.1, 2.0),
            tau: rng.uniform(0.2, 2.0),
            omega0: rng.vec3(0.5),
            t: rng.uniform(0.0, 40.0),
        })
        .collect();
    Assignment {
        name: "reduced_closed_form",
        equation: "Eqs. (4.15)-(4.16)",
        hint: "Omega_perp(t) = Phi(t) Omega_perp0 with Phi of (4.16), turning clockwise at (1 - I3/I1) Omega3 as in (4.15), and Omega3 constant. The paper sets Omega_10 = 0: keep both Omega_10 and Omega_20.",
    }
    .compare(
        &inputs,
        |x| student(x.ratio, x.tau, x.omega0, x.t),
        |x| match SymmetricTop::new(x.ratio, x.tau) {
            Ok(top) => symmetric_top::reduced_closed_form(&top, &x.omega0, x.t),
            Err(_) => Vec3::repeat(Real::NAN),
        },
        |a, b| close_vec(a, b, 1e-10),
    )
}

/// Grade the constant tilt between the symmetry axis and L.
///
/// Paper: Eq. (4.11) (corrected: erratum 4).
pub fn precession_tilt(student: impl Fn(Real, Vec3) -> Real) -> Grade {
    let mut rng = Rng::new(SEED);
    let mut inputs: Vec<(Real, Vec3)> = (0..CASES)
        .map(|_| {
            let ratio = rng.uniform(0.1, 2.0);
            let w = rng.vec3(0.5);
            (ratio, Vec3::new(w.x, w.y, w.z.abs() + 0.05))
        })
        .collect();
    inputs.push((0.4, Vec3::new(0.0, 0.1, 0.2)));
    Assignment {
        name: "precession_tilt",
        equation: "Eq. (4.11), corrected",
        hint: "The axis keeps a constant angle to L: tan(theta) = I1 Omega_perp0 / (I3 Omega_30). The printed arctan(Omega_20 / Omega~_30) is erratum 4 (see the Errata page).",
    }
    .compare(
        &inputs,
        |(ratio, w)| student(*ratio, *w),
        |(ratio, w)| match SymmetricTop::new(*ratio, 1.0) {
            Ok(top) => symmetric_top::precession_tilt(&top, w),
            Err(_) => Real::NAN,
        },
        |a, b| close_real(*a, *b, 1e-12),
    )
}

/// The test problems of the step graders: a non-autonomous linear system and
/// the reduced ALE (4.12), as `(name, f)`.
type Field = fn(Real, &State<3>) -> State<3>;

fn fields() -> [(&'static str, Field); 2] {
    fn linear(t: Real, y: &State<3>) -> State<3> {
        State::<3>::new(
            -0.5 * y[0] + 2.0 * y[1] + t.sin(),
            -2.0 * y[0] - 0.5 * y[1],
            -y[2] + t * t,
        )
    }
    fn reduced(_t: Real, y: &State<3>) -> State<3> {
        let top = SymmetricTop::figure();
        symmetric_top::reduced_ale_rhs(&top, &Vec3::new(y[0], y[1], y[2]))
    }
    [("linear", linear), ("reduced ALE (4.12), tau = 1", reduced)]
}

#[derive(Clone, Copy)]
struct StepInput {
    field: usize,
    t: Real,
    y: State<3>,
    h: Real,
}

impl fmt::Debug for StepInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "f = {}, t = {}, y = {:?}, h = {}",
            fields()[self.field].0,
            self.t,
            self.y.as_slice(),
            self.h
        )
    }
}

fn step_inputs() -> Vec<StepInput> {
    let mut rng = Rng::new(SEED);
    (0..CASES)
        .map(|i| StepInput {
            field: i % 2,
            t: rng.uniform(-1.0, 3.0),
            y: State::<3>::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            ),
            h: rng.uniform(0.01, 0.4),
        })
        .collect()
}

/// A right-hand side as the assignments take it.
pub type DynField<'a> = &'a dyn Fn(Real, &State<3>) -> State<3>;

/// Grade one classical RK4 step.
pub fn rk4_step(student: impl Fn(DynField, Real, &State<3>, Real) -> State<3>) -> Grade {
    Assignment {
        name: "rk4_step",
        equation: "classical RK4, Hairer-Norsett-Wanner I, Table II.1.2",
        hint: "k1 = f(t, y), k2 = f(t + h/2, y + h k1/2), k3 = f(t + h/2, y + h k2/2), k4 = f(t + h, y + h k3); y_new = y + h (k1 + 2 k2 + 2 k3 + k4)/6.",
    }
    .compare(
        &step_inputs(),
        |x| student(&fields()[x.field].1, x.t, &x.y, x.h),
        |x| reference_rk4_step(&fields()[x.field].1, x.t, &x.y, x.h),
        |a, b| close_state(a, b, 1e-13),
    )
}

fn close_state(a: &State<3>, b: &State<3>, tol: Real) -> bool {
    a.iter().all(|x| x.is_finite()) && (a - b).norm() <= tol * (1.0 + b.norm())
}

/// Grade one Dormand–Prince 5(4) step: (y₅, y₅ − ŷ₄).
pub fn dp5_step(
    student: impl Fn(DynField, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    Assignment {
        name: "dp5_step",
        equation: "Dormand-Prince 5(4), Hairer-Norsett-Wanner I, Table II.5.2",
        hint: "Seven stages with the Dormand-Prince tableau; the step is the fifth-order b, the error estimate is y5 - y4_hat = h sum (b_i - b_hat_i) k_i, with k7 = f(t + h, y5).",
    }
    .compare(
        &step_inputs(),
        |x| student(&fields()[x.field].1, x.t, &x.y, x.h),
        |x| dopri5_step(&fields()[x.field].1, x.t, &x.y, x.h),
        |a, b| close_state(&a.0, &b.0, 1e-13) && (a.1 - b.1).norm() <= 1e-13 + 1e-9 * b.1.norm(),
    )
}

#[derive(Clone, Copy)]
struct RotationInput(Mat3);

impl fmt::Debug for RotationInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = EulerAngles::from_rotation(&self.0);
        write!(
            f,
            "the rotation with (phi, theta, psi) = ({}, {:e}, {})",
            a.phi, a.theta, a.psi
        )
    }
}

/// Grade Euler angles from a rotation matrix, z-x-z, pole included.
///
/// Paper: Eq. (3.5) (its angle convention).
pub fn euler_from_rotation(student: impl Fn(&Mat3) -> (Real, Real, Real)) -> Grade {
    let mut rng = Rng::new(SEED);
    let pi = std::f64::consts::PI;
    let mut inputs: Vec<RotationInput> = (0..CASES)
        .map(|_| {
            let e = EulerAngles::new(
                rng.uniform(-pi, pi),
                rng.uniform(0.0, pi),
                rng.uniform(-pi, pi),
            );
            RotationInput(e.to_rotation())
        })
        .collect();
    for theta in [0.0, pi, 1e-9, 1e-13, pi - 1e-9] {
        let e = EulerAngles::new(rng.uniform(-pi, pi), theta, rng.uniform(-pi, pi));
        inputs.push(RotationInput(e.to_rotation()));
    }
    let a = Assignment {
        name: "euler_from_rotation",
        equation: "Eq. (3.5), z-x-z angles",
        hint: "theta = atan2(sqrt(O13^2 + O23^2), O33) (acos loses digits near the poles); phi = atan2(O13, -O23), psi = atan2(O31, O32); on a pole only phi + psi (or phi - psi) is defined: set psi = 0 and read phi from the first column.",
    };
    for input in &inputs {
        let m = input.0;
        match call(|| student(&m)) {
            Ok((phi, theta, psi)) => {
                let finite = phi.is_finite() && theta.is_finite() && psi.is_finite();
                let rebuilt = EulerAngles::new(phi, theta, psi).to_rotation();
                let err = (rebuilt - m).norm();
                if !finite || !(0.0..=pi).contains(&theta) || err > 1e-12 {
                    return Err(a.fail(
                        format!("{input:?}"),
                        "finite angles, theta in [0, pi], rebuilding the matrix to 1e-12".into(),
                        format!("({phi}, {theta:e}, {psi}), rebuilding it to {err:.1e}"),
                    ));
                }
            }
            Err(msg) => {
                return Err(a.fail(format!("{input:?}"), "three angles".into(), msg));
            }
        }
    }
    Ok(Passed {
        assignment: a.name,
        cases: inputs.len(),
    })
}

#[derive(Clone, Copy)]
struct ShellInput {
    tau0: Real,
    delta: Real,
    z: C,
    z_ddot_ret: C,
}

impl fmt::Debug for ShellInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "tau0 = {}, delta = {}, Z = {}, Z''(t - delta) = {}",
            self.tau0, self.delta, self.z, self.z_ddot_ret
        )
    }
}

/// Grade the method-of-steps update of the shell model: Z''(t) from Z(t) and
/// the retarded Z''(t − δ).
///
/// Paper: Eq. (A.1).
pub fn shell_acceleration(student: impl Fn(Real, Real, C, C) -> C) -> Grade {
    let mut rng = Rng::new(SEED);
    let inputs: Vec<ShellInput> = (0..CASES)
        .map(|_| {
            let tau0 = rng.uniform(1e-3, 0.05);
            ShellInput {
                tau0,
                delta: rng.uniform(2.5 * tau0, 1.0),
                z: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
                z_ddot_ret: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
            }
        })
        .collect();
    Assignment {
        name: "shell_acceleration",
        equation: "Eq. (A.1)",
        hint: "(A.1) with m = k = 1: m0 Z''(t) + Z(t) = -m_em Z''(t - delta), where m_em = tau0/delta and m0 = 1 - m_em. Solve for Z''(t).",
    }
    .compare(
        &inputs,
        |x| student(x.tau0, x.delta, x.z, x.z_ddot_ret),
        |x| match ShellModel::new(x.tau0, x.delta) {
            Ok(m) => m.acceleration(x.z, x.z_ddot_ret),
            Err(_) => C::new(Real::NAN, Real::NAN),
        },
        |a, b| a.re.is_finite() && a.im.is_finite() && (a - b).norm() <= 1e-12 * (1.0 + b.norm()),
    )
}
