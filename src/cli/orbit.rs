//! `spintop orbit`: one charge in a Coulomb or oscillator field under
//! radiation reaction (§2, (2.5)–(2.9)), sampled at given times.

use super::gate::Gate;
use super::values::{self, help, value_name};
use super::{CliError, Format, TimeList, parse_times};
use clap::Args;
use spintop::math::Real;
use spintop::output::orbit::{OrbitRequest, orbit};
use spintop::scene::request::{self, Given, RawOrbit, RawSolve};
use spintop::scene::table::{Command::Orbit as O, FORCES, POTENTIALS};

/// The raw arguments of `orbit`, before validation: the keys of an orbit
/// scene's `[orbit]` and `[solve]` (help, ranges and defaults from the table).
#[derive(Debug, Args)]
#[command(
    after_help = "Units: m = k = 1. The orbit starts at (r0, 0) moving along +y: on the circle, or with \
                  --eccentricity e at its point nearest the centre (Coulomb: the pericentre, a = r0/(1-e); \
                  harmonic: the end of the minor axis of an ellipse centred on the origin).\n\
                  Example: spintop orbit --potential coulomb --tau0 1e-3 --times 0,50,100,150"
)]
pub struct OrbitArgs {
    #[arg(long, value_parser = values::names(&POTENTIALS, |_| true),
          help = help(O, "orbit", "potential"))]
    potential: String,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(O, "orbit", "tau0"), help = help(O, "orbit", "tau0"))]
    tau0: Real,
    #[arg(long, value_parser = values::names(&FORCES, |_| true),
          help = help(O, "orbit", "force"))]
    force: Option<String>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(O, "orbit", "r0"), help = help(O, "orbit", "r0"))]
    r0: Option<Real>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(O, "orbit", "eccentricity"), help = help(O, "orbit", "eccentricity"))]
    eccentricity: Option<Real>,
    #[arg(long, value_parser = parse_times, allow_hyphen_values = true,
          value_name = value_name(O, "solve", "times"), help = help(O, "solve", "times"))]
    times: Option<TimeList>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(O, "solve", "t_end"), help = help(O, "solve", "t_end"))]
    t_end: Option<Real>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(O, "solve", "samples"), help = help(O, "solve", "samples"))]
    samples: Option<i64>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(O, "solve", "rtol"), help = help(O, "solve", "rtol"))]
    rtol: Option<Real>,
    /// Output format.
    #[arg(long, value_parser = values::format(), default_value = "table")]
    format: Format,
}

impl OrbitArgs {
    /// The same validation as an orbit scene's.
    fn validate(self) -> Result<OrbitRequest, CliError> {
        let orbit = RawOrbit {
            potential: Some(Given::flag(self.potential)),
            tau0: Some(Given::flag(self.tau0)),
            force: self.force.map(Given::flag),
            r0: self.r0.map(Given::flag),
            eccentricity: self.eccentricity.map(Given::flag),
        };
        let solve = RawSolve {
            rtol: self.rtol.map(Given::flag),
            times: self.times.map(|t| Given::flag(t.0)),
            t_end: self.t_end.map(Given::flag),
            samples: self.samples.map(Given::flag),
            ..RawSolve::default()
        };
        let scene = request::orbit(&orbit, &solve)?;
        Ok(OrbitRequest {
            config: scene.config,
            times: scene.times,
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
