//! `spintop shell`: the charge as a small shell (Appendix, (A.1)–(A.3)), a
//! neutral delay equation solved by the method of steps and sampled at given
//! times.

use super::gate::Gate;
use super::{CliError, Format, TimeList, bad, check_output_times, parse_number, parse_times};
use crate::math::Real;
use crate::output::shell::{MAX_STEPS, ShellRequest, instability_warning, shell};
use crate::physics::shell::ShellModel;
use crate::sim::shell::default_steps_per_delay;
use clap::Args;
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
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
}

impl ShellArgs {
    fn validate(self) -> Result<ShellRequest, CliError> {
        let model = ShellModel::new(self.tau0, self.delay).map_err(|e| bad(e.to_string()))?;
        let times = self.times.0;
        check_output_times(&times)?;
        let steps = default_steps_per_delay(self.delay);
        let t_last = *times.last().expect("non-empty");
        let work = (t_last / self.delay).ceil().max(1.0) * steps as Real;
        if work > MAX_STEPS {
            return Err(bad(format!(
                "the run needs {work:.1e} RK4 steps ({} per delay up to t = {t_last}), more than {MAX_STEPS:.0e}: {}",
                crate::numbers::fmt_count(steps as Real),
                if self.delay > t_last {
                    "the delay is longer than the run itself; choose a shorter --delay"
                } else {
                    "ask for shorter --times or a longer --delay"
                }
            )));
        }
        Ok(ShellRequest {
            model,
            steps,
            times,
            format: self.format,
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
    // The warning comes before any output, so a reader piping stdout still sees it first.
    if let Some(rate) = model.growth_rate() {
        writeln!(err, "{}", instability_warning(&model, rate))?;
        err.flush()?;
    }
    out.emit(&shell(&request)?, request.format)
}
