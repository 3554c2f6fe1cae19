//! `spintop balance`: the two balance laws of §2 for a built-in dipole
//! trajectory, sampled at given times and averaged over a period.

use super::gate::Gate;
use super::values::{self, help, value_name};
use super::{CliError, Format, TimeList, parse_times};
use clap::Args;
use spintop::math::Real;
use spintop::output::balance::{BalanceConfig, balance};
use spintop::scene::request::{self, Given, RawBalance, RawSolve};
use spintop::scene::table::{Command::Balance as B, DIPOLES};

/// The raw arguments of `balance`, before validation: the keys of a balance
/// scene's `[balance]` and `[solve]` (help, ranges and defaults from the table).
#[derive(Debug, Args)]
#[command(
    after_help = "Units: kappa = 2/(3c^3) = 1. Output per sample: the Larmor-like rate (2.1) -d'xd'', \
                  the torque (2.2) dxd''', the Schott angular momentum (2.4) dxd'' and its rate, and the \
                  projections on the dipole direction; then their averages over one period.\n\
                  Example: spintop balance --dipole precessing --cone 0.5 --rate 1 --times 0,1,2"
)]
pub struct BalanceArgs {
    #[arg(long, value_parser = values::names(&DIPOLES, |_| true),
          help = help(B, "balance", "dipole"))]
    dipole: String,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "cone"), help = help(B, "balance", "cone"))]
    cone: Option<Real>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "rate"), help = help(B, "balance", "rate"))]
    rate: Option<Real>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "b"), help = help(B, "balance", "b"))]
    b: Option<Real>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "eps"), help = help(B, "balance", "eps"))]
    eps: Option<Real>,
    #[arg(long, value_parser = values::array::<2>, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "charges"), help = help(B, "balance", "charges"))]
    charges: Option<[Real; 2]>,
    #[arg(long, value_parser = values::array::<2>, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "masses"), help = help(B, "balance", "masses"))]
    masses: Option<[Real; 2]>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "balance", "length"), help = help(B, "balance", "length"))]
    length: Option<Real>,
    #[arg(long, value_parser = parse_times, allow_hyphen_values = true,
          value_name = value_name(B, "solve", "times"), help = help(B, "solve", "times"))]
    times: Option<TimeList>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(B, "solve", "t_end"), help = help(B, "solve", "t_end"))]
    t_end: Option<Real>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(B, "solve", "samples"), help = help(B, "solve", "samples"))]
    samples: Option<i64>,
    /// Output format.
    #[arg(long, value_parser = values::format(), default_value = "table")]
    format: Format,
}

impl BalanceArgs {
    /// The same validation as a balance scene's.
    fn validate(self) -> Result<BalanceConfig, CliError> {
        let raw = RawBalance {
            dipole: Some(Given::flag(self.dipole)),
            cone: self.cone.map(Given::flag),
            rate: self.rate.map(Given::flag),
            b: self.b.map(Given::flag),
            eps: self.eps.map(Given::flag),
            charges: self.charges.map(Given::flag),
            masses: self.masses.map(Given::flag),
            length: self.length.map(Given::flag),
        };
        let solve = RawSolve {
            times: self.times.map(|t| Given::flag(t.0)),
            t_end: self.t_end.map(Given::flag),
            samples: self.samples.map(Given::flag),
            ..RawSolve::default()
        };
        Ok(request::balance(&raw, &solve)?.config(self.format))
    }
}

/// Validate, run and print `balance`.
pub(crate) fn execute(args: BalanceArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let config = args.validate()?;
    out.emit(&balance(&config), config.format)
}
