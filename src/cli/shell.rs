//! `spintop shell`: the charge as a small shell (Appendix, (A.1)–(A.3)), a
//! neutral delay equation solved by the method of steps and sampled at given
//! times.

use super::gate::Gate;
use super::{CliError, Format, TimeList, bad, check_output_times, parse_number, parse_times};
use clap::Args;
use spintop::math::Real;
use spintop::output::shell::{ShellRequest, instability_warning, shell, steps_per_delay};
use spintop::physics::shell::ShellModel;
use std::io::Write;

/// The raw arguments of `shell`, before validation.
#[derive(Debug, Args)]
#[command(
    after_help = "Units: m = m0 + m_em = 1, k = 1 (the isotropic oscillator), Z = x + iy. The shell of \
                  radius r0 has delay = r0/c and electromagnetic mass m_em = tau0/delay; the history on \
                  [-delay, 0] is the Abraham-Lorentz physical circular mode Z = exp(s_AL t).\n\
                  (A.1) is stable only for m0 > m_em, i.e. delay > 2 tau0 (exactly: m0 - m_em > delay^2/pi^2).\n\
                  Example: spintop shell --tau0 1e-3 --delay 0.03 --times 0,5,10,20"
)]
pub struct ShellArgs {
    /// tau0 = 2q^2/(3mc^3), positive.
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    tau0: Real,
    /// The delay r0/c, positive and different from tau0.
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    delay: Real,
    /// Output times, comma-separated, >= 0 and non-decreasing.
    #[arg(long, value_name = "T1,T2,...", value_parser = parse_times, allow_hyphen_values = true)]
    times: TimeList,
    /// Output format.
    #[arg(long, value_parser = super::values::format(), default_value = "table")]
    format: Format,
}

impl ShellArgs {
    fn validate(self) -> Result<ShellRequest, CliError> {
        let model = ShellModel::new(self.tau0, self.delay).map_err(|e| bad(e.to_string()))?;
        let times = self.times.0;
        check_output_times(&times)?;
        let t_last = *times.last().expect("non-empty");
        let steps = steps_per_delay(&model, t_last).map_err(|e| {
            bad(format!(
                "{e}: {}",
                if e.delay_too_long {
                    "the delay is longer than the run itself; choose a shorter --delay"
                } else {
                    "ask for shorter --times or a longer --delay"
                }
            ))
        })?;
        Ok(ShellRequest {
            model,
            steps,
            times,
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
        writeln!(err, "{}", instability_warning(&model, rate))?;
        err.flush()?;
    }
    out.emit(&output, request.format)
}
