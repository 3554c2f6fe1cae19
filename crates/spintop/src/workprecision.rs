//! Work against precision: how much computing each method spends for the
//! accuracy it delivers, on the problems of the paper.
//!
//! The sweep runs every [`Solver`] on every [`Problem`] it applies to, over a
//! ladder of tolerances or step sizes ([`Plan`]), and makes one [`Row`] per
//! run: the largest relative error of Ω over the 200 output points against the
//! problem's reference, the orientation error where there is one, the
//! right-hand-side evaluations and accepted and rejected steps, and the median
//! wall time of repeated solves.
//!
//! Pure like the rest of the core: no clock, no files. The time is measured
//! through a [`Stopwatch`] that the caller supplies (the CLI and the peers
//! bench wrap `std::time::Instant`); without one, a sweep is deterministic to
//! the bit, which is what the tests and the book use.
//!
//! | module | what |
//! |---|---|
//! | [`problem`] | the four problems and their references |
//! | [`method`] | spintop's methods as [`Solver`]s |
//! | [`report`] | the table, the charts, CSV and JSON, and the join of two runs |
//!
//! Other implementations (the `ode_solvers` crate in `benches/peers.rs`) are
//! [`Solver`]s too, so they are measured by the same code against the same
//! references; SciPy (`benches/scipy_work_precision.py`) writes the same CSV
//! columns.

use crate::integrate::Stats;
use crate::math::{Mat3, Real, Vec3};
use serde::Serialize;
use std::fmt;

pub mod method;
pub mod problem;
pub mod report;

pub use crate::sim::Method;
pub use method::{SWEPT, Spintop};
pub use problem::{OmegaRhs, Problem, ProblemKind};

/// What a run solves for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum Target {
    /// Ω alone: Ω̇ = F(Ω), the equations a reader would give any ODE solver.
    #[serde(rename = "omega")]
    Omega,
    /// Ω and the orientation O(t) together, as `spintop simulate` computes them.
    #[serde(rename = "omega+orientation")]
    OmegaOrientation,
}

impl Target {
    /// The name in tables and CSV files.
    pub fn name(self) -> &'static str {
        match self {
            Target::Omega => "omega",
            Target::OmegaOrientation => "omega+orientation",
        }
    }

    /// The target of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        [Target::Omega, Target::OmegaOrientation]
            .into_iter()
            .find(|t| t.name() == name)
    }
}

/// The knob a sweep turns for a method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum KnobKind {
    /// Relative tolerance of an adaptive method.
    #[serde(rename = "rtol")]
    Rtol,
    /// Fixed step size, in τ.
    #[serde(rename = "h")]
    Step,
    /// Nothing to turn (a closed form).
    #[serde(rename = "")]
    None,
}

impl KnobKind {
    /// The name in tables and CSV files (`rtol`, `h`, or empty).
    pub fn name(self) -> &'static str {
        match self {
            KnobKind::Rtol => "rtol",
            KnobKind::Step => "h",
            KnobKind::None => "",
        }
    }

    /// The knob of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        [KnobKind::Rtol, KnobKind::Step, KnobKind::None]
            .into_iter()
            .find(|k| k.name() == name)
    }
}

/// What a solver hands back: Ω (and O, if it computes it) at the problem's
/// output times, and its work.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Ω at each output time.
    pub omega: Vec<Vec3>,
    /// O(t) at each output time, for the [`Target::OmegaOrientation`] runs.
    pub rotation: Option<Vec<Mat3>>,
    /// Evaluations and steps, when the solver counts them.
    pub stats: Option<Stats>,
}

/// A way to solve the problems: spintop's [`Method`]s, and other crates.
pub trait Solver {
    /// Whose implementation: `spintop`, `ode_solvers`, …
    fn source(&self) -> &str;
    /// The method's name within its source.
    fn method(&self) -> &str;
    /// What it solves for.
    fn target(&self) -> Target;
    /// The knob a sweep turns.
    fn knob(&self) -> KnobKind;
    /// True when it can solve `problem`.
    fn applies_to(&self, problem: &Problem) -> bool;
    /// Solve `problem` with the knob at `knob` (`None` for [`KnobKind::None`]),
    /// at exactly the problem's output times. A failure is reported in one line.
    fn solve(&self, problem: &Problem, knob: Option<Real>) -> Result<Solution, String>;
    /// False for a knob value that cannot be measured on `problem` (the sweep
    /// skips it); every value by default.
    fn accepts(&self, _problem: &Problem, _knob: Option<Real>) -> bool {
        true
    }
}

/// Measures the wall time of a piece of work. The core never reads a clock;
/// the command line implements this with `std::time::Instant`.
pub trait Stopwatch {
    /// Run `work` once and return the seconds it took.
    fn seconds(&mut self, work: &mut dyn FnMut()) -> Real;
}

/// How to time a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Timed samples; the row reports their median.
    pub repeats: u32,
    /// Shortest duration of one sample, in seconds: a fast solve is repeated
    /// inside a sample until it lasts this long, so the clock's resolution
    /// and the cost of reading it do not count.
    pub min_sample: Real,
}

/// One run of one solver on one problem at one knob value: one line of the
/// table, one row of the CSV file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// Whose implementation (`spintop`, `ode_solvers`, `scipy`).
    pub source: String,
    /// The problem (`truncated`, `reduced`, `general`, `full`).
    pub model: String,
    /// The method.
    pub method: String,
    /// Ω alone, or Ω with the orientation.
    pub target: Target,
    /// The knob.
    pub knob: KnobKind,
    /// Its value (`None` for a closed form).
    pub value: Option<Real>,
    /// max over the output points of |Ω − Ω_ref| / |Ω_ref|.
    pub omega_error: Option<Real>,
    /// max over the output points of the angle of O_refᵀO, in radians.
    pub orientation_error: Option<Real>,
    /// Right-hand-side evaluations of one solve.
    pub rhs_evals: Option<u64>,
    /// Accepted steps.
    pub steps: Option<u64>,
    /// Rejected step attempts.
    pub rejected: Option<u64>,
    /// Median wall time of one solve, in seconds.
    pub time_s: Option<Real>,
    /// Timed samples behind the median (0 when not timed).
    pub repeats: u32,
    /// `ok`, or why the run failed.
    pub status: String,
}

impl Row {
    /// True when the run succeeded.
    pub fn ok(&self) -> bool {
        self.status == "ok"
    }
}

/// Why a sweep could not start.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// A reference could not be read or computed.
    #[error("reference: {0}")]
    Reference(String),
    /// A parameter was refused.
    #[error("{0}")]
    Invalid(String),
}

impl SweepError {
    pub(crate) fn from_display(e: impl fmt::Display) -> Self {
        SweepError::Invalid(e.to_string())
    }
}

// ANCHOR: errors
/// The largest relative error of Ω over the output points.
///
/// A non-finite value anywhere makes the error infinite.
pub fn omega_error(reference: &[Vec3], got: &[Vec3]) -> Real {
    if reference.len() != got.len() {
        return Real::INFINITY;
    }
    reference
        .iter()
        .zip(got)
        .map(|(r, g)| {
            let e = (g - r).norm() / r.norm();
            if e.is_finite() { e } else { Real::INFINITY }
        })
        .fold(0.0, Real::max)
}

/// The angle of the rotation that takes `a` to `b`, in radians.
///
/// NOTE: from atan2(sin, cos) of the relative rotation, not from acos of its
/// trace, which loses half the digits near 0 (an error of 1e-12 rad would
/// read as about 1e-8).
pub fn rotation_angle(a: &Mat3, b: &Mat3) -> Real {
    let r = a.transpose() * b;
    let sin = crate::math::vee(&r).norm();
    let cos = 0.5 * (r.trace() - 1.0);
    sin.atan2(cos)
}

/// The largest orientation error over the output points, in radians.
pub fn orientation_error(reference: &[Mat3], got: &[Mat3]) -> Real {
    if reference.len() != got.len() {
        return Real::INFINITY;
    }
    reference
        .iter()
        .zip(got)
        .map(|(r, g)| {
            let e = rotation_angle(r, g);
            if e.is_finite() { e } else { Real::INFINITY }
        })
        .fold(0.0, Real::max)
}
// ANCHOR_END: errors

/// The median of `xs` (the mean of the middle two for an even count).
pub fn median(xs: &mut [Real]) -> Option<Real> {
    if xs.is_empty() {
        return None;
    }
    xs.sort_by(Real::total_cmp);
    let n = xs.len();
    Some(if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    })
}

/// Run `solver` on `problem` at `knob`, compare with the reference, and time
/// it if a stopwatch is given.
pub fn measure(
    problem: &Problem,
    solver: &dyn Solver,
    knob: Option<Real>,
    clock: Option<(&mut dyn Stopwatch, Timing)>,
) -> Row {
    let mut row = Row {
        source: solver.source().to_string(),
        model: problem.name().to_string(),
        method: solver.method().to_string(),
        target: solver.target(),
        knob: solver.knob(),
        value: knob,
        omega_error: None,
        orientation_error: None,
        rhs_evals: None,
        steps: None,
        rejected: None,
        time_s: None,
        repeats: 0,
        status: "ok".to_string(),
    };
    // With a clock, the first solve is also the first timing (it sizes the
    // batches); without one, it is the only solve.
    let mut result = None;
    let mut first = || result = Some(solver.solve(problem, knob));
    let mut clock = clock;
    let first_time = match clock.as_mut() {
        Some((stopwatch, _)) => Some(stopwatch.seconds(&mut first)),
        None => {
            first();
            None
        }
    };
    let solution = match result.expect("the solve ran") {
        Ok(s) => s,
        Err(e) => {
            row.status = e;
            return row;
        }
    };
    let reference = problem.reference();
    row.omega_error = Some(omega_error(&reference.omega, &solution.omega));
    if let (Some(r), Some(g)) = (&reference.rotation, &solution.rotation) {
        row.orientation_error = Some(orientation_error(r, g));
    }
    if let Some(stats) = solution.stats {
        row.rhs_evals = Some(stats.rhs_evals);
        row.steps = Some(stats.steps);
        row.rejected = Some(stats.rejected);
    }
    if let (Some((stopwatch, timing)), Some(first)) = (clock, first_time) {
        row.time_s = Some(time_solve(problem, solver, knob, stopwatch, timing, first));
        row.repeats = timing.repeats;
    }
    row
}

/// The median over `timing.repeats` samples of the time of one solve, in
/// batches sized by the time of the first solve.
fn time_solve(
    problem: &Problem,
    solver: &dyn Solver,
    knob: Option<Real>,
    stopwatch: &mut dyn Stopwatch,
    timing: Timing,
    first: Real,
) -> Real {
    let once = || {
        std::hint::black_box(solver.solve(std::hint::black_box(problem), knob)).ok();
    };
    let first = first.max(1e-9);
    let batch = (timing.min_sample / first).ceil().clamp(1.0, 1e6) as u64;
    let mut samples: Vec<Real> = (0..timing.repeats.max(1))
        .map(|_| {
            stopwatch.seconds(&mut || {
                for _ in 0..batch {
                    once();
                }
            }) / batch as Real
        })
        .collect();
    median(&mut samples).unwrap_or(first)
}

/// The knobs of a sweep and how to time it.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Relative tolerances of the adaptive methods.
    pub rtols: Vec<Real>,
    /// Step sizes of the fixed-step methods, in τ.
    pub steps: Vec<Real>,
    /// The timing, or `None` for an untimed (deterministic) sweep.
    pub timing: Option<Timing>,
}

impl Plan {
    /// Thirteen tolerances from 1e-3 to 1e-15 and seven steps from 1 to
    /// 1/64, each run timed over 7 samples of at least 2 ms.
    ///
    /// NOTE: down to 1e-15, a few units of rounding of a double, because the
    /// last digits are where the methods part ways: a Runge–Kutta method pays
    /// ever more steps for them, the Taylor method one more order.
    pub fn full() -> Self {
        Self {
            rtols: (3..=15).map(|k| (10.0 as Real).powi(-k)).collect(),
            // NOTE: powers of two that divide 1, so every output time (a whole
            // number) is a step point of RK4, not an interpolated value.
            steps: (0..=6).map(|k| (0.5 as Real).powi(k)).collect(),
            timing: Some(Timing {
                repeats: 7,
                min_sample: 2e-3,
            }),
        }
    }

    /// Four tolerances and three steps, 3 samples of at least 0.2 ms: the
    /// whole sweep takes about a second in a release build.
    pub fn quick() -> Self {
        Self {
            rtols: vec![1e-4, 1e-7, 1e-10, 1e-13],
            steps: vec![1.0, 0.25, 0.0625],
            timing: Some(Timing {
                repeats: 3,
                min_sample: 2e-4,
            }),
        }
    }

    /// The same plan without timing.
    pub fn untimed(mut self) -> Self {
        self.timing = None;
        self
    }

    /// The knob values for a kind of knob.
    pub fn knobs(&self, kind: KnobKind) -> Vec<Option<Real>> {
        match kind {
            KnobKind::Rtol => self.rtols.iter().map(|&r| Some(r)).collect(),
            KnobKind::Step => self.steps.iter().map(|&h| Some(h)).collect(),
            KnobKind::None => vec![None],
        }
    }
}

/// Run every solver on every problem it applies to, at every knob of the plan.
///
/// Rows come out grouped by problem, then solver, then knob (loosest first).
pub fn sweep(
    problems: &[Problem],
    solvers: &[&dyn Solver],
    plan: &Plan,
    mut stopwatch: Option<&mut dyn Stopwatch>,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for problem in problems {
        for solver in solvers {
            if !solver.applies_to(problem) {
                continue;
            }
            for knob in plan.knobs(solver.knob()) {
                if !solver.accepts(problem, knob) {
                    continue;
                }
                let clock = match (&mut stopwatch, plan.timing) {
                    (Some(s), Some(t)) => Some((&mut **s as &mut dyn Stopwatch, t)),
                    _ => None,
                };
                rows.push(measure(problem, *solver, knob, clock));
            }
        }
    }
    rows
}
