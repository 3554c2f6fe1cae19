//! `spintop shell`: the charge as a small shell (Appendix, (A.1)–(A.3)), a
//! neutral delay equation solved by the method of steps and sampled at given
//! times.

use super::gate::Gate;
use super::values::{self, help, value_name};
use super::{CliError, Format, TimeList, parse_times};
use clap::Args;
use spintop::math::Real;
use spintop::output::shell::{ShellRequest, instability_warning, shell};
use spintop::scene::request::{self, Given, RawShell, RawSolve};
use spintop::scene::table::Command::Shell as H;
use std::io::Write;

/// The raw arguments of `shell`, before validation: the keys of a shell
/// scene's `[shell]` and `[solve]` (help, ranges and defaults from the table).
#[derive(Debug, Args)]
#[command(
    after_help = "Units: m = m0 + m_em = 1, k = 1 (the isotropic oscillator), Z = x + iy. The shell of \
                  radius r0 has delay = r0/c and electromagnetic mass m_em = tau0/delay; the history on \
                  [-delay, 0] is the Abraham-Lorentz physical circular mode Z = exp(s_AL t).\n\
                  (A.1) is stable only for m0 > m_em, i.e. delay > 2 tau0 (exactly: m0 - m_em > delay^2/pi^2).\n\
                  Example: spintop shell --tau0 1e-3 --delay 0.03 --times 0,5,10,20"
)]
pub struct ShellArgs {
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(H, "shell", "tau0"), help = help(H, "shell", "tau0"))]
    tau0: Real,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(H, "shell", "delay"), help = help(H, "shell", "delay"))]
    delay: Real,
    #[arg(long, value_parser = parse_times, allow_hyphen_values = true,
          value_name = value_name(H, "solve", "times"), help = help(H, "solve", "times"))]
    times: Option<TimeList>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(H, "solve", "t_end"), help = help(H, "solve", "t_end"))]
    t_end: Option<Real>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(H, "solve", "samples"), help = help(H, "solve", "samples"))]
    samples: Option<i64>,
    /// Output format.
    #[arg(long, value_parser = values::format(), default_value = "table")]
    format: Format,
}

impl ShellArgs {
    /// The same validation as a shell scene's.
    fn validate(self) -> Result<ShellRequest, CliError> {
        let raw = RawShell {
            tau0: Some(Given::flag(self.tau0)),
            delay: Some(Given::flag(self.delay)),
        };
        let solve = RawSolve {
            times: self.times.map(|t| Given::flag(t.0)),
            t_end: self.t_end.map(Given::flag),
            samples: self.samples.map(Given::flag),
            ..RawSolve::default()
        };
        let scene = request::shell(&raw, &solve)?;
        Ok(ShellRequest {
            model: scene.model,
            steps: scene.steps,
            times: scene.times,
            format: self.format,
            entry: spintop::output::Entry::CommandLine,
        })
    }
}

/// Validate, warn when unstable, run and print `shell`.
pub(crate) fn execute(
    args: ShellArgs,
    out: &mut Gate<'_>,
    err: &mut impl Write,
) -> Result<(), CliError> {
    let request = args.validate()?;
    let model = request.model;
    let output = shell(&request)?;
    // The warning comes before any output, so a reader piping stdout still
    // sees it first; a run that failed says so in its one error line instead.
    if let Some(rate) = model.growth_rate() {
        writeln!(
            err,
            "spintop: warning: {}",
            instability_warning(&model, rate)
        )?;
        err.flush()?;
    }
    out.emit(&output, request.format)
}
