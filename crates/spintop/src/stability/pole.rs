//! Row 2: the orientation integrated through Euler angles, (4.8), breaks at the
//! pole θ = 0, where (4.8) divides by sin θ; integrated on SO(3) it does not.
//!
//! The experiment: the truncated top of the paper's figure (I₃/I₁ = 2/5, τ = 1,
//! Ω₀ = (0, 0.1, 0.2)) with Ω(t) from its closed form (4.7), and the exact
//! orientation from the closed form Rot(n_L, |L₀|ϑ)·O₀·R_z(Ω̃₃₀ϑ) as the
//! reference. (4.8) is integrated by DOP853 at rtol 1e-10:
//!
//! - from θ₀ = 0 it cannot take a single step: (4.8) is undefined there;
//! - from θ₀ = ε it runs, but φ̇ and ψ̇ start near Ω⊥/ε, so the step size
//!   shrinks with ε, the work grows like ln(1/ε), and the accuracy of φ and ψ
//!   (whose sum alone is defined at the pole) degrades as ε shrinks.
//!
//! spintop's orientation is a rotation matrix advanced on SO(3) (Runge–Kutta–
//! Munthe-Kaas, [`crate::sim`]); the pole is not special there.

use super::{Outcome, Row, RowError};
use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Rk4, Stats, Stepper, solve};
use crate::math::{Mat3, Real, State, Vec3};
use crate::physics::euler_angles::{EulerAngles, euler_rates};
use crate::physics::symmetric_top::{SymmetricTop, truncated_closed_form, truncated_orientation};
use crate::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

/// One start of (4.8) near (or at) the pole.
#[derive(Clone, Debug, PartialEq)]
pub struct EulerRun {
    /// The integrator: DOP853 at rtol 1e-10, or RK4 with h = 0.01.
    pub method: &'static str,
    /// θ₀.
    pub theta0: Real,
    /// `Err` when the integration stopped (with the time), else the error of
    /// the final orientation in the Frobenius norm against the closed form.
    pub result: Result<Real, IntegrateError>,
    /// RHS evaluations spent.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub steps: u64,
}

/// The measurement of row 2.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The end of the runs.
    pub t_end: Real,
    /// (4.8) from θ₀ = 0, 1e-2, 1e-5, 1e-8.
    pub euler: Vec<EulerRun>,
    /// spintop on SO(3) from θ₀ = 0, by DOP853 at rtol 1e-10 and by RK4 with
    /// h = 0.01: (method, orientation error against the closed form, RHS
    /// evaluations).
    pub so3: Vec<(&'static str, Real, u64)>,
}

/// The starts of (4.8).
pub const THETA0: [Real; 4] = [0.0, 1e-2, 1e-5, 1e-8];

const RTOL: Real = 1e-10;
/// The fixed step of the RK4 runs, the crate's default.
const STEP: Real = 0.01;
/// An orientation error below this counts as a usable answer.
pub const ACCURATE: Real = 1e-6;

/// (4.8) from Euler angles (0, θ₀, 0) to `t_end`, by DOP853 (`fixed_step`
/// `None`) or RK4.
fn euler_run(
    top: &SymmetricTop,
    omega0: &Vec3,
    theta0: Real,
    t_end: Real,
    fixed_step: Option<Real>,
) -> EulerRun {
    // ANCHOR: euler_rhs
    let rhs = |t: Real, y: &State<3>| {
        let omega = truncated_closed_form(top, omega0, t);
        match euler_rates(&EulerAngles::new(y[0], y[1], y[2]), &omega) {
            Some(r) => State::<3>::new(r.phi_dot, r.theta_dot, r.psi_dot),
            // (4.8) is undefined on the pole; the integrator reports the NaN.
            None => State::<3>::repeat(Real::NAN),
        }
    };
    // ANCHOR_END: euler_rhs
    let start = EulerAngles::new(0.0, theta0, 0.0);
    let reference = truncated_orientation(top, omega0, &start.to_rotation(), t_end);
    let y0 = State::<3>::new(0.0, theta0, 0.0);
    let run = match fixed_step {
        None => AdaptiveOptions::new(RTOL, RTOL * 1e-3)
            .and_then(|opts| Dop853::new(0.0, y0, opts))
            .map_err(|e| (e, Stats::default()))
            .and_then(|mut stepper| finish(&mut stepper, &rhs, t_end)),
        Some(h) => Rk4::new(0.0, y0, h)
            .map_err(|e| (e, Stats::default()))
            .and_then(|mut stepper| finish(&mut stepper, &rhs, t_end)),
    };
    let method = if fixed_step.is_some() {
        "RK4, h = 0.01"
    } else {
        "DOP853"
    };
    match run {
        Ok((y, stats)) => {
            let got = EulerAngles::new(y[0], y[1], y[2]).to_rotation();
            EulerRun {
                method,
                theta0,
                result: Ok((got - reference).norm()),
                rhs_evals: stats.rhs_evals,
                steps: stats.steps,
            }
        }
        Err((e, stats)) => EulerRun {
            method,
            theta0,
            result: Err(e),
            rhs_evals: stats.rhs_evals,
            steps: stats.steps,
        },
    }
}

type Finished = Result<(State<3>, Stats), (IntegrateError, Stats)>;

/// Step to `t_end`, keeping the work done even when the run fails.
fn finish<S: Stepper<3>, R: crate::integrate::Rhs<3>>(
    stepper: &mut S,
    rhs: &R,
    t_end: Real,
) -> Finished {
    let out = solve(stepper, rhs, &[t_end]);
    let stats = stepper.stats();
    out.map(|y| (y[0], stats)).map_err(|e| (e, stats))
}

/// Run the experiment of row 2.
pub fn measure() -> Result<Measurement, RowError> {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let t_end = 50.0;
    let mut euler = vec![euler_run(&top, &omega0, 0.0, t_end, None)];
    for &theta0 in &THETA0[1..] {
        euler.push(euler_run(&top, &omega0, theta0, t_end, Some(STEP)));
    }
    for &theta0 in &THETA0[1..] {
        euler.push(euler_run(&top, &omega0, theta0, t_end, None));
    }
    let reference = truncated_orientation(&top, &omega0, &Mat3::identity(), t_end);
    let so3 = [
        ("DOP853", MethodChoice::Dop853),
        ("RK4, h = 0.01", MethodChoice::Rk4),
    ]
    .into_iter()
    .map(|(name, choice)| {
        let (error, evals) = so3_run(&top, &omega0, choice, t_end, &reference)?;
        Ok((name, error, evals))
    })
    .collect::<Result<Vec<_>, RowError>>()?;
    Ok(Measurement { t_end, euler, so3 })
}

/// spintop's orientation on SO(3) from θ₀ = 0: error and RHS evaluations.
fn so3_run(
    top: &SymmetricTop,
    omega0: &Vec3,
    choice: MethodChoice,
    t_end: Real,
    reference: &Mat3,
) -> Result<(Real, u64), RowError> {
    let err = |e: crate::sim::SimError| RowError::new(2, e);
    let initial = InitialState::new(*omega0, EulerAngles::new(0.0, 0.0, 0.0)).map_err(err)?;
    let options = MethodOptions::new(RTOL, STEP).map_err(|e| RowError::new(2, e))?;
    let mut sim = Simulation::new(
        Model::Truncated(*top),
        choice,
        options,
        initial,
        Some(t_end),
    )
    .map_err(err)?;
    let sample = sim.run(&[t_end]).map_err(err)?[0];
    Ok((
        (sample.rotation_matrix() - reference).norm(),
        sim.stats().rhs_evals,
    ))
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        // NOTE: the naive methods are (4.8) at the pole and RK4 near it; the
        // runs that cope (RK4 a little away, DOP853 paying extra steps) are
        // shown as notes, so the reader sees where the failure sets in.
        let describe = |r: &EulerRun| match &r.result {
            Ok(e) => format!(
                "orientation error {e:.1e} at t = {}; {} steps, {} evals",
                self.t_end, r.steps, r.rhs_evals
            ),
            Err(e) => format!("stopped: {e}"),
        };
        let fails = |r: &EulerRun| !matches!(r.result, Ok(e) if e < ACCURATE);
        let naive = self
            .euler
            .iter()
            .filter(|r| fails(r))
            .map(|r| Outcome {
                method: format!("(4.8), {}, from theta0 = {:e}", r.method, r.theta0),
                ok: false,
                result: describe(r),
            })
            .collect();
        let mut notes: Vec<String> = self
            .euler
            .iter()
            .filter(|r| !fails(r))
            .map(|r| {
                format!(
                    "(4.8), {}, from theta0 = {:e} copes: {}",
                    r.method,
                    r.theta0,
                    describe(r)
                )
            })
            .collect();
        notes.push(format!(
            "rtol {RTOL:e}; reference: the closed-form orientation of the truncated model"
        ));
        Row {
            number: 2,
            problem: "Euler angles (4.8) at the pole theta = 0".into(),
            naive,
            fix: self
                .so3
                .iter()
                .map(|(name, error, evals)| Outcome {
                    method: format!("rotation matrix on SO(3), {name}, from theta0 = 0"),
                    ok: *error < ACCURATE,
                    result: format!(
                        "orientation error {error:.1e} at t = {}; {evals} evals",
                        self.t_end
                    ),
                })
                .collect(),
            notes,
        }
    }
}
