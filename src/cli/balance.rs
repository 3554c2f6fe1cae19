//! `spintop balance`: the two balance laws of §2 for a built-in dipole
//! trajectory, sampled at given times and averaged over a period.

use super::gate::Gate;
use super::{CliError, Format, TimeList, bad, parse_list, parse_number, parse_times};
use clap::{Args, ValueEnum};
use spintop::math::Real;
use spintop::output::balance::{BalanceConfig, BalanceParameters, DipoleChoice, balance};
use spintop::physics::balance::{Dumbbell, PlanarLoop, PrecessingDipole};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum DipoleArg {
    /// A rigid unit dipole on a cone about z (--cone, --rate): a top in regular precession.
    Precessing,
    /// The planar loop d = (cos t, b sin t + eps sin 2t, 0) (--b, --eps).
    Loop,
    /// A rigid dumbbell spinning about an axis perpendicular to its rod (--charges, --masses, --length, --rate).
    Dumbbell,
}

fn parse_pair(s: &str) -> Result<[Real; 2], String> {
    let v = parse_list(s)?;
    <[Real; 2]>::try_from(v.as_slice())
        .map_err(|_| format!("expected two comma-separated numbers, got {}", v.len()))
}

/// The raw arguments of `balance`, before validation.
#[derive(Debug, Args)]
#[command(
    after_help = "Units: kappa = 2/(3c^3) = 1. Output per sample: the Larmor-like rate (2.1) -d'xd'', \
                  the torque (2.2) dxd''', the Schott angular momentum (2.4) dxd'' and its rate, and the \
                  projections on the dipole direction; then their averages over one period.\n\
                  Example: spintop balance --dipole precessing --cone 0.5 --rate 1 --times 0,1,2"
)]
pub struct BalanceArgs {
    /// Which dipole trajectory.
    #[arg(long, value_enum)]
    dipole: DipoleArg,
    /// Cone half-angle theta of the precessing dipole, radians, in [0, pi] [default: 0.5]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    cone: Option<Real>,
    /// Rate omega of the precessing dipole or the dumbbell, non-zero [default: 1]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    rate: Option<Real>,
    /// Loop parameter b [default: 0.5]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    b: Option<Real>,
    /// Loop parameter eps, the second harmonic [default: 0.2]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    eps: Option<Real>,
    /// Dumbbell charges q1,q2 (kappa = 1 units) [default: 1,-1]
    #[arg(long, value_name = "Q1,Q2", value_parser = parse_pair, allow_hyphen_values = true)]
    charges: Option<[Real; 2]>,
    /// Dumbbell masses m1,m2, positive [default: 1,1]
    #[arg(long, value_name = "M1,M2", value_parser = parse_pair, allow_hyphen_values = true)]
    masses: Option<[Real; 2]>,
    /// Dumbbell rod length, positive [default: 1]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    length: Option<Real>,
    /// Sample times, comma-separated (any finite values).
    #[arg(long, value_name = "T1,T2,...", value_parser = parse_times, allow_hyphen_values = true)]
    times: TimeList,
    /// Output format.
    #[arg(long, value_parser = super::values::format(), default_value = "table")]
    format: Format,
}

impl BalanceArgs {
    fn validate(self) -> Result<BalanceConfig, CliError> {
        let given = |name: &str, present: bool, kinds: &str| -> Result<(), CliError> {
            if present {
                Err(bad(format!("--{name} belongs to --dipole {kinds}")))
            } else {
                Ok(())
            }
        };
        let param = |e: spintop::physics::ParamError| bad(e.to_string());
        let mut p = BalanceParameters::default();
        let dipole = match self.dipole {
            DipoleArg::Precessing => {
                given("b", self.b.is_some(), "loop")?;
                given("eps", self.eps.is_some(), "loop")?;
                given("charges", self.charges.is_some(), "dumbbell")?;
                given("masses", self.masses.is_some(), "dumbbell")?;
                given("length", self.length.is_some(), "dumbbell")?;
                let (cone, rate) = (self.cone.unwrap_or(0.5), self.rate.unwrap_or(1.0));
                p.cone = Some(cone);
                p.rate = Some(rate);
                DipoleChoice::Precessing(PrecessingDipole::new(cone, rate).map_err(param)?)
            }
            DipoleArg::Loop => {
                given("cone", self.cone.is_some(), "precessing")?;
                given("rate", self.rate.is_some(), "precessing or dumbbell")?;
                given("charges", self.charges.is_some(), "dumbbell")?;
                given("masses", self.masses.is_some(), "dumbbell")?;
                given("length", self.length.is_some(), "dumbbell")?;
                let (b, eps) = (self.b.unwrap_or(0.5), self.eps.unwrap_or(0.2));
                p.b = Some(b);
                p.eps = Some(eps);
                DipoleChoice::Loop(PlanarLoop::new(b, eps).map_err(param)?)
            }
            DipoleArg::Dumbbell => {
                given("cone", self.cone.is_some(), "precessing")?;
                given("b", self.b.is_some(), "loop")?;
                given("eps", self.eps.is_some(), "loop")?;
                let charges = self.charges.unwrap_or([1.0, -1.0]);
                let masses = self.masses.unwrap_or([1.0, 1.0]);
                let length = self.length.unwrap_or(1.0);
                let rate = self.rate.unwrap_or(1.0);
                let dumbbell = Dumbbell::new(charges, masses, length, rate).map_err(param)?;
                p.charges = Some(charges);
                p.masses = Some(masses);
                p.length = Some(length);
                p.rate = Some(rate);
                p.dipole_amplitude = Some(dumbbell.amplitude());
                DipoleChoice::Dumbbell(dumbbell)
            }
        };
        if self.times.0.is_empty() {
            return Err(bad("--times needs at least one time"));
        }
        Ok(BalanceConfig {
            dipole,
            parameters: p,
            times: self.times.0,
            format: self.format,
        })
    }
}

/// Validate, run and print `balance`.
pub(crate) fn execute(args: BalanceArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let config = args.validate()?;
    out.emit(&balance(&config), config.format)
}
