//! The peers in one run: the `ode_solvers` crate's Dopri5 and Dop853 measured
//! beside spintop's own integrators, on the same problems, against the same
//! references, by the same code (`spintop::workprecision`), in the same process.
//!
//! ```sh
//! cargo bench -p spintop-benches --bench peers -- --out peers.csv            # about a minute
//! cargo bench -p spintop-benches --bench peers -- --quick --out peers.csv    # a few seconds
//! cargo run --release -- bench --join peers.csv scipy.csv
//! ```
//!
//! Only the first-order problems (truncated, reduced, general) run: the full
//! ALE's physical solution needs a backward shoot that neither peer offers.
//!
//! `ode_solvers` is asked for dense output every 1τ from 0 to 200, the
//! natural call for 200 output points. Its dense output at the final time is
//! extrapolated: when an output time lands within rounding of `x_end` before
//! the last step is taken, it pushes the value at `x_end` from the current
//! step's interpolant evaluated beyond the step (θ > 1), and never replaces it.
//! The rows keep what the crate hands back (that is what its users get), and
//! the bench prints, for every run, the error at t = 200 beside the error over
//! t < 200, and whether the t = 200 value was extrapolated.

use ode_solvers::{OutputType, SVector, System};
use spintop::math::{Real, Vec3};
use spintop::workprecision::report;
use spintop::workprecision::{
    KnobKind, OmegaRhs, Plan, Problem, ProblemKind, Solution, Solver, Spintop, Stopwatch, Target,
    omega_error,
};
use std::time::Instant;

type V3 = SVector<f64, 3>;

/// Ω̇ = F(Ω) in `ode_solvers`' vector type (its nalgebra is another version
/// than spintop's, so the three components are copied across).
struct OmegaSystem(OmegaRhs);

impl System<f64, V3> for OmegaSystem {
    fn system(&self, _t: f64, y: &V3, dy: &mut V3) {
        let f = self.0.omega_dot(&Vec3::new(y[0], y[1], y[2]));
        dy[0] = f.x;
        dy[1] = f.y;
        dy[2] = f.z;
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Which {
    Dopri5,
    Dop853,
}

/// One of `ode_solvers`' methods as a sweep entry. With `interior`, the value
/// at t = 200 (which the crate may extrapolate) is replaced by the reference,
/// so the row's error is that of t = 1..199 only: the method's own accuracy,
/// at the same cost.
struct OdeSolvers {
    which: Which,
    interior: bool,
}

/// What one `ode_solvers` run gave: the output points and the work.
struct Run {
    times: Vec<f64>,
    omega: Vec<Vec3>,
    stats: ode_solvers::dop_shared::Stats,
}

impl OdeSolvers {
    fn run(&self, problem: &Problem, rtol: Real, output: OutputType) -> Result<Run, String> {
        let rhs = problem.omega_rhs().ok_or("no first-order form")?;
        let w0 = problem.initial().omega;
        let y0 = V3::new(w0.x, w0.y, w0.z);
        let (t_end, atol) = (problem.t_end(), problem.atol(rtol));
        // NOTE: dx = 1 is exact in binary, so the crate's running sum of output
        // times hits 1, 2, …, 200 exactly, the problem's output times.
        let (stats, times, ys) = match self.which {
            Which::Dopri5 => {
                let mut s =
                    ode_solvers::Dopri5::new(OmegaSystem(rhs), 0.0, t_end, 1.0, y0, rtol, atol);
                s.set_output(output);
                let stats = s.integrate().map_err(|e| e.to_string())?;
                (stats, s.x_out().clone(), s.y_out().clone())
            }
            Which::Dop853 => {
                let mut s =
                    ode_solvers::Dop853::new(OmegaSystem(rhs), 0.0, t_end, 1.0, y0, rtol, atol);
                s.set_output(output);
                let stats = s.integrate().map_err(|e| e.to_string())?;
                (stats, s.x_out().clone(), s.y_out().clone())
            }
        };
        Ok(Run {
            times,
            omega: ys.iter().map(|y| Vec3::new(y[0], y[1], y[2])).collect(),
            stats,
        })
    }
}

impl Solver for OdeSolvers {
    fn source(&self) -> &str {
        "ode_solvers"
    }
    fn method(&self) -> &str {
        match (self.which, self.interior) {
            (Which::Dopri5, false) => "Dopri5",
            (Which::Dop853, false) => "Dop853",
            (Which::Dopri5, true) => "Dopri5 (t<200)",
            (Which::Dop853, true) => "Dop853 (t<200)",
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
        let run = self.run(problem, rtol, OutputType::Dense)?;
        // The dense output starts with t = 0; the problem's times are 1..=200.
        let (times, omega) = (&run.times[1..], &run.omega[1..]);
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
            stats: Some(spintop::integrate::Stats {
                rhs_evals: run.stats.num_eval as u64,
                steps: run.stats.accepted_steps as u64,
                rejected: run.stats.rejected_steps as u64,
            }),
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

/// The final-time behaviour of one run, in one line.
fn final_point_note(peer: &OdeSolvers, problem: &Problem, rtol: Real) -> Option<String> {
    let dense = peer.solve(problem, Some(rtol)).ok()?;
    let reference = &problem.reference().omega;
    let n = reference.len();
    let inner = omega_error(&reference[..n - 1], &dense.omega[..n - 1]);
    let last = omega_error(&reference[n - 1..], &dense.omega[n - 1..]);
    // The step ends: the t = 200 value is extrapolated when the step before
    // the last one already ended within 1 of t = 200.
    let sparse = peer.run(problem, rtol, OutputType::Sparse).ok()?;
    let before_last = sparse.times.iter().rev().nth(1).copied().unwrap_or(0.0);
    let extrapolated = before_last > problem.t_end() - 1.0 && before_last < problem.t_end();
    Some(format!(
        "{:<9} {:<6} rtol={rtol:.0e}: error at t = 200 {:>9}, over t < 200 {:>9}; last step {:.3} -> 200{}",
        problem.name(),
        peer.method(),
        report::sci(Some(last)),
        report::sci(Some(inner)),
        before_last,
        if extrapolated {
            ": t = 200 extrapolated from the step before"
        } else {
            ""
        }
    ))
}

fn main() {
    // `cargo bench` passes `--bench`; everything else is ours.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .cloned();
    if let Some(bad) = args
        .iter()
        .find(|a| a.starts_with("--") && !["--bench", "--quick", "--out"].contains(&a.as_str()))
    {
        eprintln!("peers: unknown option {bad} (use --quick, --out FILE.csv)");
        std::process::exit(2);
    }
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
    let peer = |which, interior| OdeSolvers { which, interior };
    let peers = [
        peer(Which::Dopri5, false),
        peer(Which::Dop853, false),
        peer(Which::Dop853, true),
    ];
    let mut solvers: Vec<&dyn Solver> = ours.iter().map(|s| s as &dyn Solver).collect();
    solvers.extend(peers.iter().map(|p| p as &dyn Solver));
    let rows = spintop::workprecision::sweep(&problems, &solvers, &plan, Some(&mut WallClock));

    println!(
        "# peers: spintop and ode_solvers 0.6.2 on the same problems, same references, one process"
    );
    print!("{}", report::table(&rows));
    print!("{}", report::join_table(&rows));
    println!("\n# ode_solvers' value at the final time (dense output every 1 tau to x_end = 200):");
    for problem in &problems {
        for peer in peers.iter().filter(|p| !p.interior) {
            for &rtol in &plan.rtols {
                if let Some(line) = final_point_note(peer, problem, rtol) {
                    println!("{line}");
                }
            }
        }
    }
    if let Some(path) = out {
        if let Err(e) = std::fs::write(&path, report::to_csv(&rows)) {
            eprintln!("peers: cannot write {path}: {e}");
            std::process::exit(1);
        }
        println!("wrote {} rows to {path}", rows.len());
    }
}
