//! `spintop bench`: the work-precision sweep of [`spintop::workprecision`], with
//! the clock, the charts and the files that the pure core leaves out.
//!
//! `spintop bench --join A.csv B.csv …` reads runs written by `--out`, by the
//! peers bench (`cargo bench -p spintop-benches --bench peers`) or by SciPy's script
//! (`benches/scipy_work_precision.py`) and prints each method's cost at
//! matched error, side by side.

use super::gate::Gate;
use super::{CliError, bad};
use clap::{Args, ValueEnum};
use spintop::math::Real;
use spintop::workprecision::report::{self, CostAxis};
use spintop::workprecision::{
    self, Plan, Problem, ProblemKind, Row, Solver, Spintop, Stopwatch, Target,
};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum BenchModel {
    /// Every problem.
    All,
    /// Eqs. (4.2)-(4.4).
    Truncated,
    /// Eqs. (4.12)-(4.14).
    Reduced,
    /// Eq. (3.3), an asymmetric top.
    General,
    /// Eq. (3.4), its physical solution.
    Full,
}

impl BenchModel {
    fn kind(self) -> Option<ProblemKind> {
        match self {
            BenchModel::All => None,
            BenchModel::Truncated => Some(ProblemKind::Truncated),
            BenchModel::Reduced => Some(ProblemKind::Reduced),
            BenchModel::General => Some(ProblemKind::General),
            BenchModel::Full => Some(ProblemKind::Full),
        }
    }
}

/// One problem, for `--chart`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ChartModel {
    /// Eqs. (4.2)-(4.4).
    Truncated,
    /// Eqs. (4.12)-(4.14).
    Reduced,
    /// Eq. (3.3), an asymmetric top.
    General,
    /// Eq. (3.4), its physical solution.
    Full,
}

impl ChartModel {
    fn kind(self) -> ProblemKind {
        match self {
            ChartModel::Truncated => ProblemKind::Truncated,
            ChartModel::Reduced => ProblemKind::Reduced,
            ChartModel::General => ProblemKind::General,
            ChartModel::Full => ProblemKind::Full,
        }
    }
}

/// The raw arguments of `bench`, before validation.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    spintop bench --quick                            every problem and method in about a second\n  \
    spintop bench --model reduced --out spintop.csv\n  \
    spintop bench --join benches/results/peers-2026-11-26.csv benches/results/scipy-2026-11-25.csv")]
pub struct BenchArgs {
    /// A short sweep: 4 tolerances, 3 RK4 steps, 3 timed samples (about a second in a release build).
    #[arg(long)]
    quick: bool,
    /// Which problems to sweep.
    #[arg(long, value_enum, default_value = "all")]
    model: BenchModel,
    /// The problem whose two charts are drawn [default: reduced, or the one --model names]
    #[arg(long, value_enum)]
    chart: Option<ChartModel>,
    /// Timed samples per run, 1 to 1000; the median is reported [default: 7, 3 with --quick]
    #[arg(long, value_parser = spintop::numbers::parse_count::<u32>, allow_hyphen_values = true)]
    repeats: Option<u32>,
    /// Also write the rows to this file: FILE.csv or FILE.json.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Width of each chart, in characters (16 to 250).
    #[arg(long, default_value_t = 60, value_parser = spintop::numbers::parse_count::<u32>, allow_hyphen_values = true)]
    width: u32,
    /// Height of each chart, in lines (4 to 100).
    #[arg(long, default_value_t = 18, value_parser = spintop::numbers::parse_count::<u32>, allow_hyphen_values = true)]
    height: u32,
    /// Instead of a sweep: join CSV files of earlier runs, chart every source's methods for one problem (--chart), and print each method's time at matched error 1e-8, 1e-10, 1e-12 and 1e-14, with ratios.
    #[arg(long, value_name = "CSV", num_args = 1..,
          conflicts_with_all = ["quick", "repeats", "out"])]
    join: Option<Vec<PathBuf>>,
}

/// The output file's format, from its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum OutFormat {
    Csv,
    Json,
}

/// A validated sweep.
struct BenchConfig {
    kinds: Vec<ProblemKind>,
    chart: ProblemKind,
    plan: Plan,
    quick: bool,
    /// The file, opened before the sweep (a path that cannot be written is
    /// refused before minutes of timing, not after), its name and format.
    out: Option<(std::fs::File, PathBuf, OutFormat)>,
    /// Whether `out` was created by this run (and is removed if the run fails).
    created: bool,
    width: u32,
    height: u32,
}

/// A validated join.
struct JoinConfig {
    files: Vec<PathBuf>,
    /// The problem charted; `None`: reduced if the files have it, else the first.
    chart: Option<ProblemKind>,
    width: u32,
    height: u32,
}

/// What `bench` was asked to do.
enum Job {
    Sweep(BenchConfig),
    Join(JoinConfig),
}

impl BenchArgs {
    fn validate(self) -> Result<Job, CliError> {
        check_chart_size(self.width, self.height)?;
        if let Some(files) = self.join {
            return Ok(Job::Join(JoinConfig {
                files,
                chart: self.chart.map(ChartModel::kind),
                width: self.width,
                height: self.height,
            }));
        }
        let kinds = match self.model.kind() {
            Some(k) => vec![k],
            None => ProblemKind::ALL.to_vec(),
        };
        let chart = match self.chart {
            None => self.model.kind().unwrap_or(ProblemKind::Reduced),
            Some(m) => m.kind(),
        };
        if !kinds.contains(&chart) {
            return Err(bad(format!(
                "--chart {} is not among the problems swept (--model {})",
                chart.name(),
                kinds[0].name()
            )));
        }
        let mut plan = if self.quick {
            Plan::quick()
        } else {
            Plan::full()
        };
        if let Some(n) = self.repeats {
            if !(1..=1000).contains(&n) {
                return Err(bad(format!("--repeats must be 1 to 1000, got {n}")));
            }
            if let Some(t) = plan.timing.as_mut() {
                t.repeats = n;
            }
        }
        let mut created = false;
        let out = match self.out {
            None => None,
            Some(path) => {
                let format = match path.extension().and_then(|e| e.to_str()) {
                    Some("csv") => OutFormat::Csv,
                    Some("json") => OutFormat::Json,
                    _ => {
                        return Err(bad(format!(
                            "--out must name a .csv or .json file, got '{}'",
                            path.display()
                        )));
                    }
                };
                // NOTE: a FIFO would block the open, a device take the rows
                // nowhere: only a regular file (or a new one) is written.
                if path.exists() && !path.is_file() {
                    return Err(bad(format!(
                        "cannot write --out '{}': not a regular file",
                        path.display()
                    )));
                }
                created = !path.exists();
                // NOTE: opened now, not truncated until the rows are there.
                let file = std::fs::OpenOptions::new()
                    .write(true)
                    .create(true)
                    .truncate(false)
                    .open(&path)
                    .map_err(|e| bad(format!("cannot write --out '{}': {e}", path.display())))?;
                Some((file, path, format))
            }
        };
        Ok(Job::Sweep(BenchConfig {
            kinds,
            chart,
            plan,
            quick: self.quick,
            out,
            created,
            width: self.width,
            height: self.height,
        }))
    }
}

/// The charts' size, in characters and lines.
fn check_chart_size(width: u32, height: u32) -> Result<(), CliError> {
    if !(16..=250).contains(&width) {
        return Err(bad(format!(
            "--width must be 16 to 250 characters, got {width}"
        )));
    }
    if !(4..=100).contains(&height) {
        return Err(bad(format!(
            "--height must be 4 to 100 lines, got {height}"
        )));
    }
    Ok(())
}

/// The wall clock, for the sweep.
struct WallClock;

impl Stopwatch for WallClock {
    fn seconds(&mut self, work: &mut dyn FnMut()) -> Real {
        let start = Instant::now();
        work();
        start.elapsed().as_secs_f64()
    }
}

/// Validate, run and print `bench`.
pub(crate) fn execute(args: BenchArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    match args.validate()? {
        Job::Join(config) => join(&config, out),
        Job::Sweep(config) => {
            let result = sweep(&config, out);
            // NOTE: a file this run created is not left empty by a failure.
            if let (Err(_), true, Some((_, path, _))) = (&result, config.created, &config.out) {
                let _ = std::fs::remove_file(path);
            }
            result
        }
    }
}

fn sweep(config: &BenchConfig, out: &mut Gate<'_>) -> Result<(), CliError> {
    let problems: Vec<Problem> = config
        .kinds
        .iter()
        .map(|k| Problem::new(*k))
        .collect::<Result<_, _>>()
        .map_err(|e| CliError::Stopped(e.to_string()))?;
    let entries = Spintop::all();
    let solvers: Vec<&dyn Solver> = entries.iter().map(|s| s as &dyn Solver).collect();
    let rows = workprecision::sweep(&problems, &solvers, &config.plan, Some(&mut WallClock));
    out.check(
        &rows,
        "a method's error or time overflowed; run a single --model to see which",
    )?;

    let build = if cfg!(debug_assertions) {
        "debug build: the times are not representative, use cargo run --release"
    } else {
        "release build"
    };
    writeln!(
        out,
        "# spintop bench{}: error of Ω over t = 1..200 (200 points) against cost; {build}",
        if config.quick { " --quick" } else { "" }
    )?;
    if let Some(t) = config.plan.timing {
        writeln!(
            out,
            "# time: median of {} samples of at least {} ms each (a fast solve is repeated within a sample)",
            t.repeats,
            t.min_sample * 1e3
        )?;
    }
    for p in &problems {
        writeln!(
            out,
            "# {} reference: {}",
            p.name(),
            p.reference().provenance
        )?;
    }
    let chart = config.chart.name();
    for axis in [CostAxis::Time, CostAxis::Evals] {
        if let Some(text) = report::chart(&rows, chart, axis, 2 * config.width, 4 * config.height) {
            writeln!(out)?;
            write!(out, "{text}")?;
        }
    }
    write!(out, "{}", report::table(&rows))?;
    writeln!(out)?;
    for line in summary(&rows) {
        writeln!(out, "{line}")?;
    }
    if let Some((file, path, format)) = &config.out {
        let text = match format {
            OutFormat::Csv => report::to_csv(&rows),
            OutFormat::Json => report::to_json(&rows) + "\n",
        };
        let mut file = file;
        file.set_len(0)
            .and_then(|()| file.write_all(text.as_bytes()))
            .map_err(|e| {
                CliError::BadInput(format!("cannot write --out '{}': {e}", path.display()))
            })?;
        writeln!(out, "wrote {} rows to {}", rows.len(), path.display())?;
    }
    Ok(())
}

/// Per problem: the fastest integrator at matched error, and the closed form
/// against it.
fn summary(rows: &[Row]) -> Vec<String> {
    let matched = report::matched(rows);
    let mut lines = Vec::new();
    let mut models: Vec<&str> = Vec::new();
    for r in rows {
        if !models.contains(&r.model.as_str()) {
            models.push(&r.model);
        }
    }
    for model in models {
        let mut parts = Vec::new();
        for (i, e) in report::MATCHED_ERRORS.iter().enumerate() {
            if let Some(b) = report::best(&matched, model, "spintop", i) {
                parts.push(format!(
                    "at {e:.0e} {} in {}",
                    b.method,
                    report::duration(b.time[i])
                ));
            }
        }
        let closed = rows.iter().find(|r| {
            r.model == model && r.method == "closed-form" && r.target == Target::Omega && r.ok()
        });
        if let Some(c) = closed {
            let at_12 = report::matched_index(1e-12)
                .and_then(|i| report::best(&matched, model, "spintop", i).and_then(|b| b.time[i]));
            if let (Some(tc), Some(ti)) = (c.time_s, at_12) {
                parts.push(format!(
                    "closed form {} (error {}), {:.0}x faster than the best integrator at 1e-12",
                    report::duration(Some(tc)),
                    report::sci(c.omega_error),
                    ti / tc
                ));
            }
        }
        if !parts.is_empty() {
            lines.push(format!("{model}: fastest: {}", parts.join("; ")));
        }
    }
    lines
}

fn join(config: &JoinConfig, out: &mut Gate<'_>) -> Result<(), CliError> {
    let files = &config.files;
    let mut rows = Vec::new();
    for path in files {
        rows.extend(read_rows(path)?);
    }
    out.check(&rows, "the files hold a number that is not finite")?;
    if rows.is_empty() {
        return Err(bad(format!(
            "{} hold no row to chart, only a header",
            files
                .iter()
                .map(|p| format!("'{}'", p.display()))
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let has = |name: &str| rows.iter().any(|r| r.model == name);
    let model = match config.chart {
        Some(kind) if has(kind.name()) => Some(kind.name().to_string()),
        Some(kind) => {
            return Err(bad(format!(
                "--chart {}: the files hold no row of that problem",
                kind.name()
            )));
        }
        None if has(ProblemKind::Reduced.name()) => Some(ProblemKind::Reduced.name().to_string()),
        None => rows.first().map(|r| r.model.clone()),
    };
    writeln!(
        out,
        "# spintop bench --join: {} rows from {}",
        rows.len(),
        files
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )?;
    if let Some(model) = model {
        for axis in [CostAxis::Time, CostAxis::Evals] {
            if let Some(text) =
                report::chart(&rows, &model, axis, 2 * config.width, 4 * config.height)
            {
                writeln!(out)?;
                write!(out, "{text}")?;
            }
        }
    }
    write!(out, "{}", report::join_table(&rows))?;
    Ok(())
}

fn read_rows(path: &Path) -> Result<Vec<Row>, CliError> {
    // A sweep's CSV is a few hundred kB; 64 MB is generous and bounded.
    let text = super::read_text_file(path, "CSV file", 64 << 20)?;
    report::parse_csv(&text).map_err(|e| bad(format!("'{}': {e}", path.display())))
}
