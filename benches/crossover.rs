//! `auto`'s crossover between DOP853 and the Taylor method, measured where
//! `auto` uses it: Ω and the orientation of an asymmetric top together, as a
//! simulation computes them (`Simulation::with_method`), at the same rtol.
//!
//! ```sh
//! cargo bench -p spintop-benches --bench crossover                       # about half a minute
//! cargo bench -p spintop-benches --bench crossover -- --out crossover.csv
//! ```
//!
//! Three tops (the asymmetric tops of `crates/spintop/tests/numerics/cost.rs`: three
//! different sets of moments, weakly radiating), each under the truncated
//! ALE (3.3) and the reduced ALE, over 300 rad of turning with 5 and with
//! 1000 output times, at rtol 1e-4 to 1e-14. Each case is timed in
//! interleaved rounds (a sample is the fastest of 3 back-to-back solves, the
//! two methods one after the other), and reported as DOP853's time over the
//! Taylor method's: the median over the rounds, with the smallest and
//! largest. `spintop::sim::auto_integrator` takes the Taylor method at an
//! rtol only where it was the faster in every case here; a test
//! (`crates/spintop/tests/numerics/taylor.rs`) holds the rule to the committed
//! `benches/results/crossover-*.csv`.

use spintop::math::{Real, Vec3};
use spintop::numbers;
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::sim::{InitialState, Method, MethodOptions, Model, Simulation};
use std::time::Instant;

/// The tolerances measured.
const RTOLS: [Real; 8] = [1e-4, 1e-6, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-14];

/// Interleaved rounds per case.
const ROUNDS: usize = 11;

/// Back-to-back solves per sample; a sample is the fastest of them (the
/// least disturbed on a shared machine; the work of a solve does not vary).
const SOLVES_PER_SAMPLE: usize = 3;

/// Moments, dipole direction and Ω₀ of the three tops; the dipole is scaled
/// so that τ_f|Ω₀| = 1e-8 (weak radiation, as a real particle's).
const TOPS: [([Real; 3], [Real; 3], [Real; 3]); 3] = [
    ([1.0, 1.5, 0.8], [0.2, 0.0, 1.0], [0.1, 0.05, 0.2]),
    ([1.0, 2.0, 2.5], [1.0, 0.5, 0.2], [0.2, 0.5, -0.4]),
    ([1.0, 5.0, 5.5], [0.3, 1.0, 0.6], [0.9, 0.2, 0.1]),
];

/// One solve of `times`; returns the steps taken.
fn solve(model: Model, method: Method, rtol: Real, initial: InitialState, times: &[Real]) -> u64 {
    let options = MethodOptions::default()
        .with_rtol(rtol)
        .expect("a valid rtol");
    let horizon = times.last().copied();
    let mut sim =
        Simulation::with_method(model, method, options, initial, horizon).expect("a simulation");
    std::hint::black_box(sim.run(std::hint::black_box(times)).expect("a run"));
    sim.stats().steps
}

/// The time of one solve: the fastest of [`SOLVES_PER_SAMPLE`].
fn sample(model: Model, method: Method, rtol: Real, initial: InitialState, times: &[Real]) -> Real {
    (0..SOLVES_PER_SAMPLE)
        .map(|_| {
            let start = Instant::now();
            solve(model, method, rtol, initial, times);
            start.elapsed().as_secs_f64()
        })
        .fold(Real::INFINITY, Real::min)
}

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1));
    if let Some(bad) = args
        .iter()
        .find(|a| a.starts_with("--") && !["--bench", "--out"].contains(&a.as_str()))
    {
        eprintln!("crossover: unknown option {bad} (use --out FILE.csv)");
        std::process::exit(2);
    }
    let start_load = load();
    println!(
        "# auto's crossover: Omega and the orientation, DOP853's time over the Taylor method's at the same rtol, {ROUNDS} interleaved rounds, median [smallest, largest]"
    );
    println!("# load average at the start (1, 5, 15 min): {start_load}");
    let mut csv = String::from(
        "top,model,outputs,rtol,dop853_steps,taylor_steps,ratio_median,ratio_min,ratio_max\n",
    );
    for (k, (i, d, w)) in TOPS.iter().enumerate() {
        let (i, d, w) = (Vec3::from(*i), Vec3::from(*d), Vec3::from(*w));
        let dipole = d.normalize() * (1e-8 * i.min() / w.norm()).sqrt();
        let top = GeneralTop::new(i, dipole).expect("a top");
        let initial = InitialState::new(w, EulerAngles::new(0.2, 0.9, 0.1)).expect("a start");
        // The turning rate bound of `sim::cost::turning_angle`.
        let rate = (w.dot(&i.component_mul(&w)) / i.min()).sqrt();
        let t_end = 300.0 / rate;
        for outputs in [5usize, 1000] {
            let times: Vec<Real> = (1..=outputs)
                .map(|j| t_end * j as Real / outputs as Real)
                .collect();
            for model in [Model::General(top), Model::GeneralReduced(top)] {
                for rtol in RTOLS {
                    let steps = [Method::Dop853, Method::Taylor]
                        .map(|m| solve(model, m, rtol, initial, &times));
                    let mut ratios: Vec<Real> = (0..ROUNDS)
                        .map(|round| {
                            // Alternate which method goes first.
                            let order = if round % 2 == 0 { [0, 1] } else { [1, 0] };
                            let mut t = [0.0; 2];
                            for j in order {
                                let m = [Method::Dop853, Method::Taylor][j];
                                t[j] = sample(model, m, rtol, initial, &times);
                            }
                            t[0] / t[1]
                        })
                        .collect();
                    ratios.sort_by(|a, b| a.total_cmp(b));
                    let (median, lo, hi) = (ratios[ROUNDS / 2], ratios[0], ratios[ROUNDS - 1]);
                    println!(
                        "top {k} {:<16} {outputs:>4} outputs  rtol {rtol:>5}  steps {:>5} / {:>4}  dop853/taylor {median} [{lo}, {hi}]",
                        model.name(),
                        steps[0],
                        steps[1],
                        rtol = numbers::exponent(rtol, 0),
                        median = numbers::fixed(median, 2),
                        lo = numbers::fixed(lo, 2),
                        hi = numbers::fixed(hi, 2)
                    );
                    csv.push_str(&format!(
                        "{k},{},{outputs},{rtol:e},{},{},{median},{lo},{hi}\n",
                        model.name(),
                        steps[0],
                        steps[1],
                        median = numbers::fixed(median, 3),
                        lo = numbers::fixed(lo, 3),
                        hi = numbers::fixed(hi, 3)
                    ));
                }
            }
        }
    }
    let end_load = load();
    println!("# load average at the end (1, 5, 15 min): {end_load}");
    println!("# where the Taylor method was the faster in every case:");
    for rtol in RTOLS {
        let key = format!(",{rtol:e},");
        let all = csv
            .lines()
            .filter(|l| l.contains(&key))
            .filter_map(|l| l.split(',').nth(6)?.parse::<Real>().ok())
            .collect::<Vec<_>>();
        let lo = all.iter().copied().fold(Real::INFINITY, Real::min);
        let hi = all.iter().copied().fold(0.0, Real::max);
        println!(
            "#   rtol {rtol}: medians {lo} to {hi}: {}",
            if lo > 1.0 {
                "Taylor in every case"
            } else {
                "DOP853 in some"
            },
            rtol = numbers::exponent(rtol, 0),
            lo = numbers::fixed(lo, 2),
            hi = numbers::fixed(hi, 2)
        );
    }
    if let Some(path) = out {
        let text = format!(
            "# cargo bench -p spintop-benches --bench crossover; load average {start_load} at the start, {end_load} at the end\n{csv}"
        );
        if let Err(e) = std::fs::write(path, text) {
            eprintln!("crossover: cannot write {path}: {e}");
            std::process::exit(1);
        }
        println!("wrote {path}");
    }
}
