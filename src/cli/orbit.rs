//! `spintop orbit`: one charge in a Coulomb or oscillator field under
//! radiation reaction (§2, (2.5)–(2.9)), sampled at given times.

use super::gate::Gate;
use super::{CliError, Format, TimeList, bad, check_output_times, parse_number, parse_times};
use clap::{Args, ValueEnum};
use spintop::math::Real;
use spintop::output::orbit::{OrbitRequest, check_backward_span, orbit};
use spintop::physics::central::{ChargeInField, Potential};
use spintop::sim::orbit::{Force, OrbitConfig};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum PotentialArg {
    /// V = -k/r.
    Coulomb,
    /// V = k r^2 / 2.
    Harmonic,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ForceArg {
    /// The Landau-Lifshitz reduction of (2.5).
    Ll,
    /// The physical (non-runaway) solution of (2.5): exact roots (harmonic), backward integration (Coulomb).
    Al,
    /// (2.5) integrated forward from the Newtonian acceleration: the runaway, detected and reported.
    AlForward,
}

/// The raw arguments of `orbit`, before validation.
#[derive(Debug, Args)]
#[command(
    after_help = "Units: m = k = 1. The orbit starts at (r0, 0) moving along +y: on the circle, or with \
                  --eccentricity e at its point nearest the centre (Coulomb: the pericentre, a = r0/(1-e); \
                  harmonic: the end of the minor axis of an ellipse centred on the origin).\n\
                  Example: spintop orbit --potential coulomb --tau0 1e-3 --times 0,50,100,150"
)]
pub struct OrbitArgs {
    /// The central potential.
    #[arg(long, value_enum)]
    potential: PotentialArg,
    /// tau0 = 2q^2/(3mc^3), positive.
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    tau0: Real,
    /// The equation of motion.
    #[arg(long, value_enum, default_value = "ll")]
    force: ForceArg,
    /// Starting radius, positive [default: 1]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    r0: Option<Real>,
    /// Eccentricity, in [0, 1) [default: 0]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    eccentricity: Option<Real>,
    /// Output times, comma-separated, >= 0 and non-decreasing.
    #[arg(long, value_name = "T1,T2,...", value_parser = parse_times, allow_hyphen_values = true)]
    times: TimeList,
    /// Relative tolerance of the integrations, in [1e-14, 1e-3] [default: 1e-11]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    rtol: Option<Real>,
    /// Output format.
    #[arg(long, value_parser = super::values::format(), default_value = "table")]
    format: Format,
}

impl OrbitArgs {
    fn validate(self) -> Result<OrbitRequest, CliError> {
        let potential = match self.potential {
            PotentialArg::Coulomb => Potential::Coulomb,
            PotentialArg::Harmonic => Potential::Harmonic,
        };
        let force = match self.force {
            ForceArg::Ll => Force::LandauLifshitz,
            ForceArg::Al => Force::AbrahamLorentz,
            ForceArg::AlForward => Force::AbrahamLorentzForward,
        };
        let charge = ChargeInField::new(potential, self.tau0).map_err(|e| bad(e.to_string()))?;
        let config = OrbitConfig::new(
            charge,
            self.r0.unwrap_or(1.0),
            self.eccentricity.unwrap_or(0.0),
            force,
        )
        .map_err(|e| bad(e.to_string()))?;
        let config = match self.rtol {
            Some(rtol) => config.with_rtol(rtol).map_err(|e| bad(format!("--{e}")))?,
            None => config,
        };
        let times = self.times.0;
        check_output_times(&times)?;
        let t_last = *times.last().expect("non-empty");
        check_backward_span(&config, t_last).map_err(|e| {
            bad(format!(
                "--{e}; use --force ll (equal to it up to O(tau0^2)) or shorter --times"
            ))
        })?;
        Ok(OrbitRequest {
            config,
            times,
            format: self.format,
            entry: spintop::output::Entry::CommandLine,
        })
    }
}

/// Validate, run and print `orbit`.
pub(crate) fn execute(args: OrbitArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let request = args.validate()?;
    out.emit(&orbit(&request)?, request.format)
}
