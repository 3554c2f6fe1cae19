//! `spintop simulate`: one model of the top, sampled at given times, as a
//! table, CSV or the JSON contract.

use super::gate::Gate;
use super::{
    CliError, Format, TimeList, bad, check_output_times, parse_number, parse_times, parse_vec3,
};
use clap::{Args, ValueEnum};
use spintop::math::{Real, Vec3};
use spintop::numbers::fmt_value;
use spintop::output::simulate::{SimulateConfig, simulate};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::times::{MAX_SAMPLES, even_times};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, SimError};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ModelArg {
    /// Eqs. (4.2)-(4.4): the symmetric top without the Schott term.
    Truncated,
    /// Eqs. (4.12)-(4.14): the symmetric top with the Schott term, reduced; with --inertia and --dipole, (3.4) reduced the same way for any top
    Reduced,
    /// Eq. (3.3): any top, given --inertia and --dipole.
    General,
    /// Eq. (3.4): the symmetric top under the full ALE, Schott term kept (its physical solution).
    Full,
}

/// The raw arguments of `simulate`, before validation.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Which equations of motion.
    #[arg(long, value_enum)]
    model: ModelArg,
    /// I3/I1 of the symmetric models, in (0, 2] [default: 0.4]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    ratio: Option<Real>,
    /// Principal moments of the general model (kappa = 1 units).
    #[arg(long, value_name = "I1,I2,I3", value_parser = parse_vec3, allow_hyphen_values = true)]
    inertia: Option<[Real; 3]>,
    /// Body-frame dipole of the general model (kappa = 1 units).
    #[arg(long, value_name = "D1,D2,D3", value_parser = parse_vec3, allow_hyphen_values = true)]
    dipole: Option<[Real; 3]>,
    /// Initial body angular velocity, in 1/tau.
    #[arg(long, value_name = "W1,W2,W3", value_parser = parse_vec3, allow_hyphen_values = true,
          default_value = "0,0.1,0.2")]
    omega: [Real; 3],
    /// Initial orientation as z-x-z Euler angles, radians.
    #[arg(long, value_name = "PHI,THETA,PSI", value_parser = parse_vec3, allow_hyphen_values = true,
          default_value = "0,0,0")]
    euler: [Real; 3],
    /// Output times, comma-separated, >= 0 and non-decreasing.
    #[arg(long, value_name = "T1,T2,...", value_parser = parse_times, allow_hyphen_values = true, conflicts_with_all = ["t_end", "samples"])]
    times: Option<TimeList>,
    /// Last output time (with --samples evenly spaced times from 0) [default: 100]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    t_end: Option<Real>,
    /// Number of evenly spaced output times from 0 to --t-end [default: 11]
    #[arg(long, value_parser = spintop::numbers::parse_count::<usize>, allow_hyphen_values = true)]
    samples: Option<usize>,
    /// Numerical method.
    #[arg(long, value_parser = super::values::method(), default_value = "auto")]
    method: MethodChoice,
    /// Relative tolerance of the adaptive methods [default: 1e-10]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    rtol: Option<Real>,
    /// Step size of RK4, in tau [default: 0.01]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    step: Option<Real>,
    /// Output format.
    #[arg(long, value_parser = super::values::format(), default_value = "table")]
    format: Format,
}

impl SimulateArgs {
    /// Turn raw arguments into a validated configuration.
    fn validate(self) -> Result<SimulateConfig, CliError> {
        let symmetric = |ratio: Option<Real>| -> Result<SymmetricTop, CliError> {
            if self.inertia.is_some() || self.dipole.is_some() {
                return Err(bad(
                    "--inertia and --dipole belong to --model general; the symmetric models take --ratio",
                ));
            }
            Ok(SymmetricTop::new(ratio.unwrap_or(0.4), 1.0).map_err(SimError::from)?)
        };
        // Any top: --inertia and --dipole, never --ratio.
        let general = |what: &str| -> Result<GeneralTop, CliError> {
            if self.ratio.is_some() {
                return Err(bad(format!(
                    "--ratio belongs to the symmetric models; {what} takes --inertia and --dipole"
                )));
            }
            let (Some(inertia), Some(dipole)) = (self.inertia, self.dipole) else {
                return Err(bad(format!(
                    "{what} needs --inertia I1,I2,I3 and --dipole D1,D2,D3"
                )));
            };
            Ok(GeneralTop::new(Vec3::from(inertia), Vec3::from(dipole)).map_err(SimError::from)?)
        };
        let model = match self.model {
            ModelArg::Truncated => Model::Truncated(symmetric(self.ratio)?),
            // With --inertia and --dipole: the reduced ALE of any top.
            ModelArg::Reduced if self.inertia.is_some() || self.dipole.is_some() => {
                Model::GeneralReduced(general("--model reduced for a general top")?)
            }
            ModelArg::Reduced => Model::Reduced(symmetric(self.ratio)?),
            // With --inertia and --dipole: the full ALE of any top.
            ModelArg::Full if self.inertia.is_some() || self.dipole.is_some() => {
                Model::GeneralFull(general("--model full for a general top")?)
            }
            ModelArg::Full => Model::Full(symmetric(self.ratio)?),
            ModelArg::General => Model::General(general("--model general")?),
        };
        // Each model takes only the methods that mean something for it; the
        // others are refused by name rather than silently replaced.
        let method = self.method;
        model
            .check_method(method)
            .map_err(|e| bad(format!("--method {}: {e}", method.name())))?;
        let options = MethodOptions::for_choice(method, self.rtol, self.step)
            .map_err(|e| bad(format!("--{e}")))?;
        let [phi, theta, psi] = self.euler;
        let initial = InitialState::new(Vec3::from(self.omega), EulerAngles::new(phi, theta, psi))?;
        let times = match self.times {
            Some(TimeList(times)) => times,
            None => {
                let t_end = self.t_end.unwrap_or(100.0);
                let n = self.samples.unwrap_or(11);
                if t_end < 0.0 {
                    return Err(bad(format!(
                        "--t-end must be >= 0, got {}",
                        fmt_value(t_end)
                    )));
                }
                if !(1..=MAX_SAMPLES).contains(&n) {
                    return Err(bad(format!(
                        "--samples must be in 1..={MAX_SAMPLES}, got {n}"
                    )));
                }
                even_times(t_end, n)
            }
        };
        check_output_times(&times)?;
        Ok(SimulateConfig {
            model,
            method,
            options,
            initial,
            euler0: self.euler,
            times,
            format: self.format,
            entry: spintop::output::Entry::CommandLine,
        })
    }
}

/// Validate, run and print `simulate`.
pub(crate) fn execute(args: SimulateArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let config = args.validate()?;
    let output = simulate(&config)?;
    // The samples before a runaway are written (CSV and JSON stay whole and
    // parseable, with their `stopped` line); the run still failed to give
    // what was asked: the gate exits 3.
    out.emit(&output, config.format)
}
