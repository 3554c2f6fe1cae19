//! The peers in one run: three compiled Rust crates measured beside spintop's
//! own integrators, on the same problems, against the same references, by the
//! same code (`spintop::workprecision`), in the same process:
//!
//! - `ode_solvers` 0.6.2: Dopri5 and Dop853 (Hairer's codes, ported);
//! - `differential-equations` 0.7.0: DOP853 and Verner's "most efficient"
//!   9(8) pair RKV988e with its 8th-order interpolant;
//! - `diffsol` 0.18.0: Tsit45 on its pure-Rust nalgebra back end.
//!
//! ```sh
//! cargo bench -p spintop-benches --bench peers -- --out peers.csv            # a few minutes
//! cargo bench -p spintop-benches --bench peers -- --quick --out peers.csv    # under a minute
//! cargo run --release -- bench --join peers.csv scipy.csv
//! ```
//!
//! Every peer gets what spintop's product path gets: Ω̇ = F(Ω) as one concrete
//! closure, chosen once per solve (never a `match` per evaluation), the same
//! rtol, the same atol = 1e-6·rtol·|Ω₀|, and the output times 1, 2, …, 200.
//! Before anything is timed, each peer solves each problem at rtol 1e-8 and
//! its answer is compared with the problem's 40-digit reference; a method
//! whose answer is wrong there (or that fails) is left out of the timings,
//! and the bench prints why.
//!
//! The sweep's times are then taken again as the head-to-head takes them
//! (`retime`: five interleaved rounds, each sample the fastest of 5
//! back-to-back solves, the median over the rounds): a batched median is cut
//! by other processes on a shared machine, a single short solve mostly is
//! not. The table, the join and `--out` carry those times.
//!
//! After the sweep, a head-to-head round times every method at the two
//! tolerances that bracket each matched error (1e-8, 1e-10, 1e-12, 1e-14),
//! interleaved (one sample of each method in turn, rotating the order, 15
//! rounds; a sample is the fastest of 5 back-to-back solves), and prints each
//! peer's time over spintop's best at matched error as the median over the
//! rounds with its spread (smallest and largest), then the best Runge–Kutta
//! method of any crate (spintop's DOP853 included) over spintop's Taylor
//! method, the same way. `--h2h-out FILE.csv` keeps every round's times;
//! `--spread A.csv B.csv …` reads several such files (runs on other days or
//! loads) and reports each ratio's spread across the runs:
//!
//! ```sh
//! cargo bench -p spintop-benches --bench peers -- --out peers.csv --h2h-out h2h-1.csv
//! cargo bench -p spintop-benches --bench peers -- --spread h2h-1.csv h2h-2.csv h2h-3.csv
//! ```
//!
//! Only the first-order problems (truncated, reduced, general) run: the full
//! ALE's physical solution needs a backward shoot that no peer offers.
//!
//! `ode_solvers` is asked for dense output every 1τ from 0 to 200, the
//! natural call for 200 output points. Its dense output at the final time is
//! extrapolated: when an output time lands within rounding of `x_end` before
//! the last step is taken, it pushes the value at `x_end` from the current
//! step's interpolant evaluated beyond the step (θ > 1), and never replaces it.
//! The rows keep what the crate hands back (that is what its users get), and
//! the bench prints, for every run, the error at t = 200 beside the error over
//! t < 200, and whether the t = 200 value was extrapolated.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use diffsol::{NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod, Op};
use ode_solvers::{OutputType, SVector, System};
use spintop::integrate::Stats;
use spintop::math::{Real, Vec3};
use spintop::numbers;
use spintop::physics::symmetric_top::{reduced_ale_rhs, truncated_ale_rhs};
use spintop::workprecision::report;
use spintop::workprecision::{
    KnobKind, OmegaRhs, Plan, Problem, ProblemKind, Row, Solution, Solver, Spintop, Stopwatch,
    Target, omega_error,
};
use std::time::Instant;

#[path = "peers/spread.rs"]
mod spread;
use spread::spread_of_runs;

type V3 = SVector<f64, 3>;

/// Something to do with Ω̇ = F(Ω) once F is a concrete closure.
trait WithRhs {
    type Out;
    fn run<F: Fn(&Vec3) -> Vec3>(self, f: F) -> Self::Out;
}

/// Hand `w` the problem's right-hand side as a closure of its own type: the
/// model is matched here, once per solve, as spintop's product path does.
fn dispatch<W: WithRhs>(rhs: OmegaRhs, w: W) -> W::Out {
    match rhs {
        OmegaRhs::Truncated(top) => w.run(move |o: &Vec3| truncated_ale_rhs(&top, o)),
        OmegaRhs::Reduced(top) => w.run(move |o: &Vec3| reduced_ale_rhs(&top, o)),
        OmegaRhs::General(top) => w.run(move |o: &Vec3| top.truncated_ale_rhs(o)),
    }
}

/// A peer crate's method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Method {
    /// `ode_solvers::Dopri5`.
    OsDopri5,
    /// `ode_solvers::Dop853`.
    OsDop853,
    /// `differential_equations`' `ExplicitRungeKutta::dop853()`.
    DeDop853,
    /// `differential_equations`' `ExplicitRungeKutta::rkv988e()`: Verner's
    /// efficient 9(8) pair, 16 stages, 8th-order interpolant.
    DeVern98,
    /// `diffsol`'s `tsit45()` on `NalgebraMat<f64>`.
    DiffsolTsit45,
}

impl Method {
    fn source(self) -> &'static str {
        match self {
            Method::OsDopri5 | Method::OsDop853 => "ode_solvers",
            Method::DeDop853 | Method::DeVern98 => "differential-equations",
            Method::DiffsolTsit45 => "diffsol",
        }
    }
}

/// What one peer run gave: the output points and the work.
struct Run {
    times: Vec<f64>,
    omega: Vec<Vec3>,
    stats: Stats,
}

/// One call of a peer: everything but the right-hand side.
struct Call<'a> {
    method: Method,
    y0: Vec3,
    t_end: f64,
    times: &'a [f64],
    rtol: f64,
    atol: f64,
    /// `ode_solvers` only: its step ends instead of the dense output.
    sparse: bool,
}

/// Ω̇ = F(Ω) in `ode_solvers`' vector type (its nalgebra is another version
/// than spintop's, so the three components are copied across).
struct OsSystem<F>(F);

impl<F: Fn(&Vec3) -> Vec3> System<f64, V3> for OsSystem<F> {
    fn system(&self, _t: f64, y: &V3, dy: &mut V3) {
        let f = (self.0)(&Vec3::new(y[0], y[1], y[2]));
        dy[0] = f.x;
        dy[1] = f.y;
        dy[2] = f.z;
    }
}

/// Ω̇ = F(Ω) for `differential_equations`, on its `[f64; 3]` state.
struct DeSystem<F>(F);

impl<F: Fn(&Vec3) -> Vec3> ODE<f64, [f64; 3]> for DeSystem<F> {
    fn diff(&self, _t: f64, y: &[f64; 3], dydt: &mut [f64; 3]) {
        let f = (self.0)(&Vec3::new(y[0], y[1], y[2]));
        *dydt = [f.x, f.y, f.z];
    }
}

impl WithRhs for Call<'_> {
    type Out = Result<Run, String>;
    fn run<F: Fn(&Vec3) -> Vec3>(self, f: F) -> Self::Out {
        let (y0, t_end, rtol, atol) = (self.y0, self.t_end, self.rtol, self.atol);
        match self.method {
            Method::OsDopri5 | Method::OsDop853 => {
                let y0 = V3::new(y0.x, y0.y, y0.z);
                let output = if self.sparse {
                    OutputType::Sparse
                } else {
                    OutputType::Dense
                };
                // NOTE: dx = 1 is exact in binary, so the crate's running sum of
                // output times hits 1, 2, …, 200 exactly, the problem's times.
                let (stats, times, ys) = if self.method == Method::OsDopri5 {
                    let mut s =
                        ode_solvers::Dopri5::new(OsSystem(f), 0.0, t_end, 1.0, y0, rtol, atol);
                    s.set_output(output);
                    let stats = s.integrate().map_err(|e| e.to_string())?;
                    (stats, s.x_out().clone(), s.y_out().clone())
                } else {
                    let mut s =
                        ode_solvers::Dop853::new(OsSystem(f), 0.0, t_end, 1.0, y0, rtol, atol);
                    s.set_output(output);
                    let stats = s.integrate().map_err(|e| e.to_string())?;
                    (stats, s.x_out().clone(), s.y_out().clone())
                };
                Ok(Run {
                    times,
                    omega: ys.iter().map(|y| Vec3::new(y[0], y[1], y[2])).collect(),
                    stats: Stats {
                        rhs_evals: stats.num_eval as u64,
                        steps: stats.accepted_steps as u64,
                        rejected: stats.rejected_steps as u64,
                    },
                })
            }
            Method::DeDop853 | Method::DeVern98 => {
                let system = DeSystem(f);
                let ivp = IVP::ode(&system, 0.0, t_end, [y0.x, y0.y, y0.z]).t_eval(self.times);
                let solution = if self.method == Method::DeDop853 {
                    ivp.method(ExplicitRungeKutta::dop853().rtol(rtol).atol(atol))
                        .solve()
                } else {
                    ivp.method(ExplicitRungeKutta::rkv988e().rtol(rtol).atol(atol))
                        .solve()
                }
                .map_err(|e| format!("{e:?}"))?;
                Ok(Run {
                    omega: solution
                        .y
                        .iter()
                        .map(|y| Vec3::new(y[0], y[1], y[2]))
                        .collect(),
                    times: solution.t,
                    stats: Stats {
                        rhs_evals: solution.evals.function as u64,
                        steps: solution.steps.accepted as u64,
                        rejected: solution.steps.rejected as u64,
                    },
                })
            }
            Method::DiffsolTsit45 => {
                let problem = OdeBuilder::<NalgebraMat<f64>>::new()
                    .rtol(rtol)
                    .atol([atol])
                    .rhs(move |x, _p, _t, y| {
                        let w = f(&Vec3::new(x[0], x[1], x[2]));
                        y[0] = w.x;
                        y[1] = w.y;
                        y[2] = w.z;
                    })
                    .init(
                        move |_p, _t, y| {
                            y[0] = y0.x;
                            y[1] = y0.y;
                            y[2] = y0.z;
                        },
                        3,
                    )
                    .build()
                    .map_err(|e| e.to_string())?;
                let mut solver = problem.tsit45().map_err(|e| e.to_string())?;
                let (ys, _) = solver.solve_dense(self.times).map_err(|e| e.to_string())?;
                let stats = solver.get_statistics().clone();
                let evals = problem.eqn.rhs().statistics().number_of_calls;
                Ok(Run {
                    times: self.times.to_vec(),
                    omega: (0..self.times.len())
                        .map(|j| Vec3::new(ys[(0, j)], ys[(1, j)], ys[(2, j)]))
                        .collect(),
                    stats: Stats {
                        rhs_evals: evals as u64,
                        steps: stats.number_of_steps as u64,
                        rejected: stats.number_of_error_test_failures as u64,
                    },
                })
            }
        }
    }
}

/// One peer method as a sweep entry. With `interior`, the value at t = 200
/// (which `ode_solvers` may extrapolate) is replaced by the reference, so the
/// row's error is that of t = 1..199 only: the method's own accuracy, at the
/// same cost.
struct Peer {
    method: Method,
    interior: bool,
}

impl Peer {
    fn run(&self, problem: &Problem, rtol: Real, sparse: bool) -> Result<Run, String> {
        let rhs = problem.omega_rhs().ok_or("no first-order form")?;
        let call = Call {
            method: self.method,
            y0: problem.initial().omega,
            t_end: problem.t_end(),
            times: problem.times(),
            rtol,
            atol: problem.atol(rtol),
            sparse,
        };
        dispatch(rhs, call)
    }
}

impl Solver for Peer {
    fn source(&self) -> &str {
        self.method.source()
    }
    fn method(&self) -> &str {
        match (self.method, self.interior) {
            (Method::OsDopri5, false) => "Dopri5",
            (Method::OsDop853, false) => "Dop853",
            (Method::OsDopri5, true) => "Dopri5 (t<200)",
            (Method::OsDop853, true) => "Dop853 (t<200)",
            (Method::DeDop853, _) => "dop853",
            (Method::DeVern98, _) => "rkv988e",
            (Method::DiffsolTsit45, _) => "tsit45",
        }
    }
    fn target(&self) -> Target {
        Target::Omega
    }
    fn knob(&self) -> KnobKind {
        KnobKind::Rtol
    }
    fn applies_to(&self, problem: &Problem) -> bool {
        problem.omega_rhs().is_some()
    }
    fn solve(&self, problem: &Problem, knob: Option<Real>) -> Result<Solution, String> {
        let rtol = knob.ok_or("needs rtol")?;
        let run = self.run(problem, rtol, false)?;
        // Some peers report t = 0 too; the problem's times are 1..=200.
        let skip = usize::from(run.times.first() == Some(&0.0));
        let (times, omega) = (&run.times[skip..], &run.omega[skip..]);
        if times != problem.times() {
            return Err(format!(
                "output times differ from 1..=200 ({} points, last {:?})",
                times.len(),
                times.last()
            ));
        }
        let mut omega = omega.to_vec();
        if self.interior {
            omega[problem.times().len() - 1] = problem.reference().omega[problem.times().len() - 1];
        }
        Ok(Solution {
            omega,
            rotation: None,
            stats: Some(run.stats),
        })
    }
}

struct WallClock;

impl Stopwatch for WallClock {
    fn seconds(&mut self, work: &mut dyn FnMut()) -> Real {
        let start = Instant::now();
        work();
        start.elapsed().as_secs_f64()
    }
}

/// The final-time behaviour of one `ode_solvers` run, in one line.
fn final_point_note(peer: &Peer, problem: &Problem, rtol: Real) -> Option<String> {
    let dense = peer.solve(problem, Some(rtol)).ok()?;
    let reference = &problem.reference().omega;
    let n = reference.len();
    let inner = omega_error(&reference[..n - 1], &dense.omega[..n - 1]);
    let last = omega_error(&reference[n - 1..], &dense.omega[n - 1..]);
    // The step ends: the t = 200 value is extrapolated when the step before
    // the last one already ended within 1 of t = 200.
    let sparse = peer.run(problem, rtol, true).ok()?;
    let before_last = sparse.times.iter().rev().nth(1).copied().unwrap_or(0.0);
    let extrapolated = before_last > problem.t_end() - 1.0 && before_last < problem.t_end();
    Some(format!(
        "{:<9} {:<6} rtol={rtol}: error at t = 200 {:>9}, over t < 200 {:>9}; last step {} -> 200{}",
        problem.name(),
        peer.method(),
        report::sci(Some(last)),
        report::sci(Some(inner)),
        numbers::fixed(before_last, 3),
        if extrapolated {
            ": t = 200 extrapolated from the step before"
        } else {
            ""
        },
        rtol = numbers::exponent(rtol, 0)
    ))
}

/// The tolerance of the correctness check, and the largest error it accepts
/// there: a hundred times the tolerance. spintop's integrators stay within 10
/// times it on these problems; `differential-equations`' DOP853 is a
/// thousand times off (its steps are right, its dense output is not: the
/// factors θ and 1 − θ of the interpolant's higher terms are exchanged in its
/// `dormandprince/ordinary.rs`; on y'' = −y at rtol 1e-12 its step ends are
/// within 1.3e-12 and its interpolated values 2.5e-8 off).
const CHECK_RTOL: Real = 1e-8;
const CHECK_LIMIT: Real = 1e-6;

/// Why `peer` is left out on `problem`, or `None` when its answer at
/// [`CHECK_RTOL`] is right.
fn wrong_answer(peer: &Peer, problem: &Problem) -> Option<String> {
    match peer.solve(problem, Some(CHECK_RTOL)) {
        Err(e) => Some(format!(
            "failed at rtol {CHECK_RTOL}: {e}",
            CHECK_RTOL = numbers::exponent(CHECK_RTOL, 0)
        )),
        Ok(s) => {
            let error = omega_error(&problem.reference().omega, &s.omega);
            (error.is_nan() || error > CHECK_LIMIT).then(|| {
                format!(
                    "at rtol {CHECK_RTOL} its largest relative error of Ω is {} (the check accepts up to {CHECK_LIMIT})",
                    report::sci(Some(error))
                , CHECK_RTOL = numbers::exponent(CHECK_RTOL, 0), CHECK_LIMIT = numbers::exponent(CHECK_LIMIT, 0))
            })
        }
    }
}

/// A sweep entry restricted to the problems its answers were checked on.
struct Checked<'a> {
    solver: &'a dyn Solver,
    excluded: Vec<String>,
}

impl Solver for Checked<'_> {
    fn source(&self) -> &str {
        self.solver.source()
    }
    fn method(&self) -> &str {
        self.solver.method()
    }
    fn target(&self) -> Target {
        self.solver.target()
    }
    fn knob(&self) -> KnobKind {
        self.solver.knob()
    }
    fn applies_to(&self, problem: &Problem) -> bool {
        self.solver.applies_to(problem) && !self.excluded.iter().any(|p| p == problem.name())
    }
    fn solve(&self, problem: &Problem, knob: Option<Real>) -> Result<Solution, String> {
        self.solver.solve(problem, knob)
    }
}

/// The two tolerances of the sweep whose errors bracket `error` for one
/// method, as `report::cost_at` reads them: the first that reaches `error`
/// walking from the loosest, and the one before it (the same one twice when
/// the loosest already does).
fn bracket(
    rows: &[Row],
    model: &str,
    source: &str,
    method: &str,
    error: Real,
) -> Option<[Real; 2]> {
    let runs: Vec<&Row> = rows
        .iter()
        .filter(|r| r.ok() && r.model == model && r.source == source && r.method == method)
        .filter(|r| r.target == Target::Omega && r.knob == KnobKind::Rtol)
        .collect();
    let i = runs
        .iter()
        .position(|r| r.omega_error.is_some_and(|e| e <= error))?;
    let at = |k: usize| runs[k].value;
    Some([at(i.saturating_sub(1))?, at(i)?])
}

/// One method at one matched error in the head-to-head.
struct Entry<'a> {
    solver: &'a dyn Solver,
    problem: &'a Problem,
    error_index: usize,
    /// The two tolerances that bracket the matched error, with their errors
    /// (deterministic: computed once).
    rtols: [(Real, Real); 2],
    /// The time at matched error in each round.
    times: Vec<Real>,
}

/// Back-to-back solves per sample: a sample is the fastest of them.
///
/// NOTE: the least disturbed of a few single solves, not the mean of a long
/// batch: on a shared machine a batch of milliseconds is cut by other
/// processes' time slices, while a single solve of tens of microseconds
/// mostly runs whole; its fastest repetition is the solve's own cost. The
/// work of a solve does not vary, so this favours no method.
const SOLVES_PER_SAMPLE: usize = 5;

/// The time of one solve at `knob`: the fastest of [`SOLVES_PER_SAMPLE`].
fn sample(solver: &dyn Solver, problem: &Problem, knob: Option<Real>) -> Real {
    (0..SOLVES_PER_SAMPLE)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(solver.solve(std::hint::black_box(problem), knob)).ok();
            start.elapsed().as_secs_f64()
        })
        .fold(Real::INFINITY, Real::min)
}

/// Rounds of [`retime`].
const RETIME_ROUNDS: usize = 5;

/// The sweep's times again, the way the head-to-head takes them: every row
/// that ran is timed in [`RETIME_ROUNDS`] interleaved rounds, a sample the
/// fastest of [`SOLVES_PER_SAMPLE`] back-to-back solves, and its time is the
/// median over the rounds (`repeats` says how many).
///
/// NOTE: the sweep's own time is the median of batches of at least 2 ms; on
/// a shared machine such a batch is cut by other processes' time slices,
/// and under a load of 10 or more a curve of the sweep jumps by 10× from one
/// tolerance to the next. A single solve of tens of microseconds mostly runs
/// whole, and the work of a solve does not vary, so its fastest repetition
/// is its own cost. The rows written with `--out` (and the book's figure)
/// carry these times.
fn retime(rows: &mut [Row], problems: &[Problem], solvers: &[&dyn Solver]) {
    let mut jobs: Vec<(usize, &dyn Solver, &Problem, Vec<Real>)> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        if !row.ok() || row.time_s.is_none() {
            continue;
        }
        let solver = solvers.iter().find(|s| {
            s.source() == row.source
                && s.method() == row.method
                && s.target() == row.target
                && s.knob() == row.knob
        });
        let problem = problems.iter().find(|p| p.name() == row.model);
        if let (Some(&solver), Some(problem)) = (solver, problem) {
            jobs.push((i, solver, problem, Vec::new()));
        }
    }
    let n = jobs.len();
    for round in 0..RETIME_ROUNDS {
        for k in 0..n {
            let (i, solver, problem, times) = &mut jobs[(k + round * 7) % n];
            times.push(sample(*solver, problem, rows[*i].value));
        }
    }
    for (i, _, _, times) in jobs {
        rows[i].time_s = median(times);
        rows[i].repeats = RETIME_ROUNDS as u32;
    }
}

const ROUNDS: usize = 15;

/// True for the Taylor method (spintop's), which the goal compares with
/// every Runge–Kutta method of every crate.
fn is_taylor(e: &Entry) -> bool {
    e.solver.source() == "spintop" && e.solver.method() == "taylor"
}

/// Every method at every matched error, one sample each per round, the
/// order rotating from round to round; prints each peer's time over
/// spintop's best adaptive integrator's in the same round, and the best
/// Runge–Kutta method's (any crate's) over the Taylor method's. Returns the
/// per-round rows `model,error,source,method,round,time_s` for `--h2h-out`.
fn head_to_head(
    rows: &[Row],
    problems: &[Problem],
    solvers: &[&dyn Solver],
    rounds: usize,
) -> String {
    let mut entries = h2h_entries(rows, problems, solvers);
    time_rounds(&mut entries, rounds);
    print_h2h(&entries, problems, rounds);
    h2h_csv(&entries)
}

/// Every (problem, matched error, method) the sweep brackets: the two
/// tolerances round the matched error, each with its error.
fn h2h_entries<'a>(
    rows: &[Row],
    problems: &'a [Problem],
    solvers: &[&'a dyn Solver],
) -> Vec<Entry<'a>> {
    let mut entries: Vec<Entry> = Vec::new();
    for problem in problems {
        for (error_index, &error) in report::MATCHED_ERRORS.iter().enumerate() {
            for &solver in solvers {
                if solver.target() != Target::Omega
                    || solver.knob() != KnobKind::Rtol
                    || !solver.applies_to(problem)
                {
                    continue;
                }
                if let Some(rtols) = bracket(
                    rows,
                    problem.name(),
                    solver.source(),
                    solver.method(),
                    error,
                ) {
                    let with_error = |rtol: Real| {
                        let row =
                            spintop::workprecision::measure(problem, solver, Some(rtol), None);
                        (rtol, row.omega_error.unwrap_or(Real::NAN))
                    };
                    entries.push(Entry {
                        solver,
                        problem,
                        error_index,
                        rtols: [with_error(rtols[0]), with_error(rtols[1])],
                        times: Vec::new(),
                    });
                }
            }
        }
    }
    entries
}

/// One sample of every entry per round, the order rotating from round to
/// round: each entry's time at its matched error.
fn time_rounds(entries: &mut [Entry], rounds: usize) {
    let n = entries.len();
    for round in 0..rounds {
        for k in 0..n {
            let entry = &mut entries[(k + round * 7) % n];
            let error = report::MATCHED_ERRORS[entry.error_index];
            let mut points: Vec<(Real, Real)> = entry
                .rtols
                .iter()
                .map(|&(rtol, err)| (sample(entry.solver, entry.problem, Some(rtol)), err))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            entry
                .times
                .push(report::cost_at(&points, error).unwrap_or(Real::NAN));
        }
    }
}

/// Each peer's time over spintop's best adaptive integrator, and the best
/// Runge–Kutta method's over the Taylor method's, round by round.
fn print_h2h(entries: &[Entry], problems: &[Problem], rounds: usize) {
    println!(
        "\n# head to head at matched error: {rounds} interleaved rounds (a sample is the fastest of {SOLVES_PER_SAMPLE} back-to-back solves); each peer's time over spintop's best adaptive integrator in the same round, median [smallest, largest]"
    );
    println!(
        "{:<9} {:>5}  {:<34} {:>10}  {:<18} {:>10}  ratio",
        "model", "error", "peer", "time", "spintop best", "time"
    );
    let mut goal_lines = Vec::new();
    for problem in problems {
        for (i, &error) in report::MATCHED_ERRORS.iter().enumerate() {
            let here = |e: &&Entry| e.problem.name() == problem.name() && e.error_index == i;
            let ours: Vec<&Entry> = entries
                .iter()
                .filter(here)
                .filter(|e| e.solver.source() == "spintop")
                .collect();
            // spintop's best in each round, and which method it was most often.
            let best: Vec<(Real, &str)> = (0..rounds)
                .map(|r| fastest(ours.iter().copied(), r))
                .collect();
            let Some(best_median) = median(best.iter().map(|b| b.0).collect()) else {
                continue;
            };
            let best_name = most_often(&best);
            for peer in entries
                .iter()
                .filter(here)
                .filter(|e| e.solver.source() != "spintop")
            {
                let ratios: Vec<Real> = (0..rounds).map(|r| peer.times[r] / best[r].0).collect();
                let Some(time) = median(peer.times.clone()) else {
                    continue;
                };
                println!(
                    "{:<9} {:>5}  {:<34} {:>10}  {:<18} {:>10}  {}",
                    problem.name(),
                    numbers::exponent(error, 0),
                    format!("{} {}", peer.solver.source(), peer.solver.method()),
                    report::duration(Some(time)),
                    best_name,
                    report::duration(Some(best_median)),
                    spread(&ratios)
                );
            }
            // The goal: the best Runge–Kutta method of any crate over the
            // Taylor method, round by round.
            let taylor: Vec<&Entry> = entries
                .iter()
                .filter(here)
                .filter(|e| is_taylor(e))
                .collect();
            let rk: Vec<&Entry> = entries
                .iter()
                .filter(here)
                .filter(|e| !is_taylor(e))
                .collect();
            if let (Some(t), false) = (taylor.first(), rk.is_empty()) {
                let best_rk: Vec<(Real, &str)> = (0..rounds)
                    .map(|r| fastest(rk.iter().copied(), r))
                    .collect();
                let ratios: Vec<Real> = (0..rounds).map(|r| best_rk[r].0 / t.times[r]).collect();
                goal_lines.push(format!(
                    "{:<9} {:>5}  taylor {:>10}  best Runge-Kutta {:<34} {:>10}  {}",
                    problem.name(),
                    numbers::exponent(error, 0),
                    report::duration(median(t.times.clone())),
                    most_often(&best_rk),
                    report::duration(median(best_rk.iter().map(|b| b.0).collect())),
                    spread(&ratios)
                ));
            }
        }
    }
    println!(
        "\n# the Taylor method against the best Runge-Kutta method of any crate (spintop's included), same rounds: the best RK time over Taylor's, median [smallest, largest]"
    );
    for line in goal_lines {
        println!("{line}");
    }
}

/// The per-round rows `model,error,source,method,round,time_s`.
fn h2h_csv(entries: &[Entry]) -> String {
    let mut csv = String::from("model,error,source,method,round,time_s\n");
    for e in entries {
        for (r, t) in e.times.iter().enumerate() {
            csv.push_str(&format!(
                "{},{:e},{},{},{r},{t:e}\n",
                e.problem.name(),
                report::MATCHED_ERRORS[e.error_index],
                e.solver.source(),
                e.solver.method()
            ));
        }
    }
    csv
}

/// The fastest entry in round `r`, and its name (`source method`, or the
/// method alone for spintop's).
fn fastest<'a>(entries: impl Iterator<Item = &'a Entry<'a>>, r: usize) -> (Real, &'a str) {
    entries
        .map(|e| (e.times[r], e.solver.method()))
        .filter(|(t, _)| t.is_finite())
        .fold((Real::INFINITY, ""), |a, b| if b.0 < a.0 { b } else { a })
}

/// The name that is fastest in most rounds.
fn most_often<'a>(best: &[(Real, &'a str)]) -> &'a str {
    let mut names: Vec<&str> = best.iter().map(|b| b.1).collect();
    names.sort_unstable();
    names
        .iter()
        .max_by_key(|m| names.iter().filter(|x| x == m).count())
        .copied()
        .unwrap_or("")
}

/// `median [smallest, largest]` of the finite values.
fn spread(xs: &[Real]) -> String {
    let finite: Vec<Real> = xs.iter().copied().filter(|x| x.is_finite()).collect();
    let lo = finite.iter().copied().fold(Real::INFINITY, Real::min);
    let hi = finite.iter().copied().fold(0.0, Real::max);
    match median(finite) {
        Some(m) => format!(
            "{m} [{lo}, {hi}]",
            m = numbers::fixed(m, 2),
            lo = numbers::fixed(lo, 2),
            hi = numbers::fixed(hi, 2)
        ),
        None => "-".into(),
    }
}

/// The median of the finite values, `None` when there are none.
fn median(mut xs: Vec<Real>) -> Option<Real> {
    xs.retain(|x| x.is_finite());
    spintop::workprecision::median(&mut xs)
}

/// The machine's load averages (1, 5, 15 minutes), for the record.
fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// Correctness first: every peer at [`CHECK_RTOL`] against each problem's
/// reference; a problem it answers wrongly (or fails) is left out of its
/// timings, and the bench says why.
fn check_peers<'a>(peers: &'a [Peer], problems: &[Problem]) -> Vec<Checked<'a>> {
    println!(
        "# correctness first: every peer at rtol {CHECK_RTOL} against each problem's reference",
        CHECK_RTOL = numbers::exponent(CHECK_RTOL, 0)
    );
    let mut checked: Vec<Checked> = Vec::new();
    for p in peers {
        let mut excluded = Vec::new();
        for problem in problems {
            if let Some(why) = wrong_answer(p, problem) {
                println!(
                    "#   left out: {} {} on {}: {why}",
                    p.source(),
                    p.method(),
                    problem.name()
                );
                excluded.push(problem.name().to_string());
            }
        }
        checked.push(Checked {
            solver: p,
            excluded,
        });
    }
    checked
}

/// ode_solvers' value at the final time, for every run of its methods.
fn print_final_points(peers: &[Peer], problems: &[Problem], plan: &Plan) {
    println!("\n# ode_solvers' value at the final time (dense output every 1 tau to x_end = 200):");
    for problem in problems {
        for peer in peers
            .iter()
            .filter(|p| p.method.source() == "ode_solvers" && !p.interior)
        {
            for &rtol in &plan.rtols {
                if let Some(line) = final_point_note(peer, problem, rtol) {
                    println!("{line}");
                }
            }
        }
    }
}

/// The sweep of spintop and the peers, retimed; the table, the join, the
/// head-to-head; the rows to `out` and the head-to-head's rounds to `h2h_out`.
fn sweep_and_report(quick: bool, out: Option<String>, h2h_out: Option<String>) {
    let problems: Vec<Problem> = [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
    ]
    .into_iter()
    .map(Problem::new)
    .collect::<Result<_, _>>()
    .unwrap_or_else(|e| {
        eprintln!("peers: {e}");
        std::process::exit(3);
    });
    let plan = if quick { Plan::quick() } else { Plan::full() };
    let ours: Vec<Spintop> = Spintop::all()
        .into_iter()
        .filter(|s| s.target == Target::Omega)
        .collect();
    let peer = |method, interior| Peer { method, interior };
    let peers = [
        peer(Method::OsDopri5, false),
        peer(Method::OsDop853, false),
        peer(Method::OsDop853, true),
        peer(Method::DeDop853, false),
        peer(Method::DeVern98, false),
        peer(Method::DiffsolTsit45, false),
    ];
    println!(
        "# peers: spintop, ode_solvers 0.6.2, differential-equations 0.7.0 and diffsol 0.18.0 on the same problems, same references, one process"
    );
    println!("# load average at the start (1, 5, 15 min): {}", load());
    let checked = check_peers(&peers, &problems);
    let mut solvers: Vec<&dyn Solver> = ours.iter().map(|s| s as &dyn Solver).collect();
    solvers.extend(checked.iter().map(|p| p as &dyn Solver));
    let mut rows = spintop::workprecision::sweep(&problems, &solvers, &plan, Some(&mut WallClock));
    retime(&mut rows, &problems, &solvers);

    print!("{}", report::table(&rows));
    print!("{}", report::join_table(&rows));
    let per_round = head_to_head(&rows, &problems, &solvers, if quick { 5 } else { ROUNDS });
    println!("# load average at the end (1, 5, 15 min): {}", load());
    if let Some(path) = &h2h_out
        && let Err(e) = std::fs::write(path, per_round)
    {
        eprintln!("peers: cannot write {path}: {e}");
        std::process::exit(1);
    }
    print_final_points(&peers, &problems, &plan);
    if let Some(path) = out {
        if let Err(e) = std::fs::write(&path, report::to_csv(&rows)) {
            eprintln!("peers: cannot write {path}: {e}");
            std::process::exit(1);
        }
        println!("wrote {} rows to {path}", rows.len());
    }
}

fn main() {
    // `cargo bench` passes `--bench`; everything else is ours.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let value = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let out = value("--out");
    let h2h_out = value("--h2h-out");
    if let Some(bad) = args.iter().find(|a| {
        a.starts_with("--")
            && !["--bench", "--quick", "--out", "--h2h-out", "--spread"].contains(&a.as_str())
    }) {
        eprintln!(
            "peers: unknown option {bad} (use --quick, --out FILE.csv, --h2h-out FILE.csv, --spread FILE.csv...)"
        );
        std::process::exit(2);
    }
    if let Some(i) = args.iter().position(|a| a == "--spread") {
        let files: Vec<String> = args[i + 1..]
            .iter()
            .filter(|a| !a.starts_with("--"))
            .cloned()
            .collect();
        if let Err(e) = spread_of_runs(&files) {
            eprintln!("peers: {e}");
            std::process::exit(2);
        }
        return;
    }
    sweep_and_report(quick, out, h2h_out);
}
