//! `spintop simulate`: one model of the top, sampled at given times, as a
//! table, CSV or the JSON contract.

use super::gate::Gate;
use super::values::{self, help, value_name};
use super::{CliError, Format, TimeList, bad};
use clap::Args;
use spintop::math::Real;
use spintop::output::simulate::{SimulateConfig, simulate};
use spintop::scene::request::{self, Given, RawSolve, RawTop};
use spintop::scene::table::{self, Command::Simulate as S, MODELS};

/// The examples and the ranges of `simulate --help`, the ranges from the
/// core's table.
pub(crate) fn after_help() -> String {
    format!(
        "Examples:\n  \
        spintop simulate --model reduced --t-end 1000 --samples 11\n  \
        spintop simulate --model truncated --omega 0,0.1,0.2 --times 0,10,100 --format json\n  \
        spintop simulate --model general --inertia 1,1.5,0.8 --dipole 0.2,0,1 --t-end 100\n  \
        spintop simulate --model full --method forward --times 0,1,2,5,10   (runs away at t = 3: exit 3)\n\n\
        Ranges: {}. {}.",
        table::ranges_help(S),
        spintop::sim::cost::budget_rule()
    )
}

/// The raw arguments of `simulate`, before validation: the keys of a top
/// scene's `[top]` and `[solve]` (help, ranges and defaults from the table).
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[arg(long, value_parser = values::names(&MODELS, |c| c.value.tier.is_some()),
          help = help(S, "top", "model"))]
    model: String,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(S, "top", "ratio"), help = help(S, "top", "ratio"))]
    ratio: Option<Real>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = value_name(S, "top", "inertia"), help = help(S, "top", "inertia"))]
    inertia: Option<[Real; 3]>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = value_name(S, "top", "dipole"), help = help(S, "top", "dipole"))]
    dipole: Option<[Real; 3]>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = value_name(S, "top", "omega"), help = help(S, "top", "omega"))]
    omega: Option<[Real; 3]>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = value_name(S, "top", "euler"), help = help(S, "top", "euler"))]
    euler: Option<[Real; 3]>,
    #[arg(long, value_parser = super::parse_times, allow_hyphen_values = true,
          value_name = value_name(S, "solve", "times"), help = help(S, "solve", "times"))]
    times: Option<TimeList>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(S, "solve", "t_end"), help = help(S, "solve", "t_end"))]
    t_end: Option<Real>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(S, "solve", "samples"), help = help(S, "solve", "samples"))]
    samples: Option<i64>,
    #[arg(long, value_parser = values::method_name_of(S, "solve", "method"),
          help = help(S, "solve", "method"))]
    method: Option<String>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(S, "solve", "rtol"), help = help(S, "solve", "rtol"))]
    rtol: Option<Real>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(S, "solve", "step"), help = help(S, "solve", "step"))]
    step: Option<Real>,
    /// Output format.
    #[arg(long, value_parser = values::format(), default_value = "table")]
    format: Format,
}

impl SimulateArgs {
    /// The keys of `[top]` and `[solve]` the flags fill.
    fn keys(self) -> (RawTop, RawSolve, Format) {
        let top = RawTop {
            model: Some(Given::flag(self.model)),
            ratio: self.ratio.map(Given::flag),
            inertia: self.inertia.map(Given::flag),
            dipole: self.dipole.map(Given::flag),
            omega: self.omega.map(Given::flag),
            euler: self.euler.map(Given::flag),
            frame: None,
        };
        let solve = RawSolve {
            method: self.method.map(Given::flag),
            rtol: self.rtol.map(Given::flag),
            step: self.step.map(Given::flag),
            times: self.times.map(|t| Given::flag(t.0)),
            t_end: self.t_end.map(Given::flag),
            samples: self.samples.map(Given::flag),
        };
        (top, solve, self.format)
    }

    /// Turn raw arguments into a validated configuration: the same
    /// validation as a top scene's.
    fn validate(self) -> Result<SimulateConfig, CliError> {
        let (top, solve, format) = self.keys();
        let request = request::top(&top, &solve)?;
        // NOTE: `auto` is a scene's (it plans before running); the flag's
        // names leave it out.
        let model = request.model().ok_or_else(|| {
            bad("--model auto chooses for a scene (spintop run); simulate runs the model named")
        })?;
        Ok(SimulateConfig {
            model,
            method: request.method,
            options: request.options,
            initial: request.initial,
            euler0: request.euler0,
            times: request.times,
            format,
            entry: spintop::output::Entry::CommandLine,
        })
    }
}

/// Validate, run and print `simulate`.
pub(crate) fn execute(
    args: SimulateArgs,
    out: &mut Gate<'_>,
    err: &mut impl std::io::Write,
) -> Result<(), CliError> {
    let config = args.validate()?;
    let output = simulate(&config)?;
    // The notes go to stderr before the answer (JSON carries them too), as
    // `shell` prints its warning.
    for note in &output.warnings {
        writeln!(err, "spintop: warning: {note}")?;
    }
    err.flush()?;
    // The samples before a runaway are written (CSV and JSON stay whole and
    // parseable, with their `stopped` line); the run still failed to give
    // what was asked: the gate exits 3.
    out.emit(&output, config.format)
}
