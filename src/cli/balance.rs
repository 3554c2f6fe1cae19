//! `spintop balance`: the two balance laws of §2 for a built-in dipole
//! trajectory, sampled at given times and averaged over a period.

use super::{CliError, Format, TimeList, bad, num, parse_list, parse_number, parse_times};
use crate::math::{Real, Vec3};
use crate::physics::balance::{
    Balance, DipoleTrajectory, Dumbbell, PlanarLoop, PrecessingDipole, balance_at, period_average,
};
use clap::{Args, ValueEnum};
use serde::Serialize;
use std::io::{self, Write};

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
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
}

/// A validated trajectory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DipoleChoice {
    /// Rigid dipole on a cone.
    Precessing(PrecessingDipole),
    /// Two-harmonic planar loop.
    Loop(PlanarLoop),
    /// Rigid rotating dumbbell.
    Dumbbell(Dumbbell),
}

/// The inputs, echoed in the JSON output.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct BalanceParameters {
    /// Cone angle θ (precessing).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cone: Option<Real>,
    /// Rate ω (precessing, dumbbell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate: Option<Real>,
    /// b (loop).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<Real>,
    /// ε (loop).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eps: Option<Real>,
    /// Charges (dumbbell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub charges: Option<[Real; 2]>,
    /// Masses (dumbbell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub masses: Option<[Real; 2]>,
    /// Rod length (dumbbell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<Real>,
    /// The dumbbell's dipole amplitude ℓ(q₁m₂ − q₂m₁)/(m₁ + m₂).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dipole_amplitude: Option<Real>,
}

/// A validated `balance` request.
#[derive(Clone, Debug, PartialEq)]
pub struct BalanceConfig {
    /// The trajectory.
    pub dipole: DipoleChoice,
    /// Its parameters, as given (defaults filled in).
    pub parameters: BalanceParameters,
    /// Sample times.
    pub times: Vec<Real>,
    /// Output format.
    pub format: Format,
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
        let param = |e: crate::physics::ParamError| bad(e.to_string());
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

/// One sample of the JSON contract.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BalanceSample {
    /// Time.
    pub t: Real,
    /// 𝔡.
    pub dipole: [Real; 3],
    /// −𝔡̇ × 𝔡̈, (2.1).
    pub larmor: [Real; 3],
    /// 𝔡 × 𝔡⃛, (2.2).
    pub torque: [Real; 3],
    /// L_S = 𝔡 × 𝔡̈, (2.4).
    pub schott: [Real; 3],
    /// dL_S/dt.
    pub schott_rate: [Real; 3],
    /// n · (2.1).
    pub larmor_axial: Real,
    /// n · (2.2).
    pub torque_axial: Real,
    /// n · dL_S/dt.
    pub schott_rate_axial: Real,
}

/// Period averages, with the sample's keys (no `t`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BalanceAverage {
    /// ⟨𝔡⟩.
    pub dipole: [Real; 3],
    /// ⟨(2.1)⟩.
    pub larmor: [Real; 3],
    /// ⟨(2.2)⟩.
    pub torque: [Real; 3],
    /// ⟨L_S⟩.
    pub schott: [Real; 3],
    /// ⟨dL_S/dt⟩.
    pub schott_rate: [Real; 3],
    /// ⟨n · (2.1)⟩.
    pub larmor_axial: Real,
    /// ⟨n · (2.2)⟩.
    pub torque_axial: Real,
    /// ⟨n · dL_S/dt⟩.
    pub schott_rate_axial: Real,
}

/// A vector for output, with −0 printed as 0 (x + 0.0 turns −0.0 into +0.0).
fn out3(v: Vec3) -> [Real; 3] {
    (v + Vec3::zeros()).into()
}

fn sample(b: &Balance) -> BalanceSample {
    BalanceSample {
        t: b.t,
        dipole: out3(b.dipole),
        larmor: out3(b.larmor),
        torque: out3(b.torque),
        schott: out3(b.schott),
        schott_rate: out3(b.schott_rate),
        larmor_axial: b.larmor_axial + 0.0,
        torque_axial: b.torque_axial + 0.0,
        schott_rate_axial: b.schott_rate_axial + 0.0,
    }
}

/// The JSON output of `balance` (the contract).
#[derive(Debug, Serialize)]
pub struct BalanceOutput {
    /// `precessing`, `loop` or `dumbbell`.
    pub dipole: &'static str,
    /// The inputs.
    pub parameters: BalanceParameters,
    /// Units of every number.
    pub units: &'static str,
    /// The period T of the motion.
    pub period: Real,
    /// One entry per time.
    pub samples: Vec<BalanceSample>,
    /// Averages over one period (composite trapezoid rule, exact for these
    /// trigonometric polynomials).
    pub period_average: BalanceAverage,
}

fn evaluate<T: DipoleTrajectory>(traj: &T, times: &[Real]) -> (Vec<BalanceSample>, Balance) {
    let samples = times
        .iter()
        .map(|&t| sample(&balance_at(traj, t)))
        .collect();
    let avg = period_average(traj).expect("every built-in trajectory is periodic");
    (samples, avg)
}

/// Run a validated `balance` request.
pub fn balance(config: &BalanceConfig) -> BalanceOutput {
    let (name, (samples, avg)) = match &config.dipole {
        DipoleChoice::Precessing(d) => ("precessing", evaluate(d, &config.times)),
        DipoleChoice::Loop(d) => ("loop", evaluate(d, &config.times)),
        DipoleChoice::Dumbbell(d) => ("dumbbell", evaluate(d, &config.times)),
    };
    BalanceOutput {
        dipole: name,
        parameters: config.parameters,
        units: "kappa = 2/(3c^3) = 1",
        period: avg.t,
        samples,
        period_average: BalanceAverage {
            dipole: avg.dipole.into(),
            larmor: avg.larmor.into(),
            torque: avg.torque.into(),
            schott: avg.schott.into(),
            schott_rate: avg.schott_rate.into(),
            larmor_axial: avg.larmor_axial,
            torque_axial: avg.torque_axial,
            schott_rate_axial: avg.schott_rate_axial,
        },
    }
}

const VECTORS: [&str; 5] = ["dipole", "larmor", "torque", "schott", "schott_rate"];

/// Write the output in the requested format.
pub fn write_output(
    out: &mut impl Write,
    output: &BalanceOutput,
    format: Format,
) -> io::Result<()> {
    match format {
        Format::Json => {
            serde_json::to_writer(&mut *out, output)?;
            writeln!(out)
        }
        Format::Csv => {
            let mut head = vec!["t".to_string()];
            for v in VECTORS {
                head.extend(["x", "y", "z"].map(|c| format!("{v}_{c}")));
            }
            head.extend(["larmor_axial", "torque_axial", "schott_rate_axial"].map(String::from));
            writeln!(out, "{}", head.join(","))?;
            let row = |t: String, vs: [[Real; 3]; 5], ax: [Real; 3]| {
                let mut cells = vec![t];
                cells.extend(vs.iter().flatten().map(|x| x.to_string()));
                cells.extend(ax.iter().map(|x| x.to_string()));
                cells.join(",")
            };
            for s in &output.samples {
                let vs = [s.dipole, s.larmor, s.torque, s.schott, s.schott_rate];
                let ax = [s.larmor_axial, s.torque_axial, s.schott_rate_axial];
                writeln!(out, "{}", row(s.t.to_string(), vs, ax))?;
            }
            // NOTE: the period average is the last row, its t cell reads `average`.
            let a = &output.period_average;
            let vs = [a.dipole, a.larmor, a.torque, a.schott, a.schott_rate];
            let ax = [a.larmor_axial, a.torque_axial, a.schott_rate_axial];
            writeln!(out, "{}", row("average".into(), vs, ax))
        }
        Format::Table => {
            writeln!(
                out,
                "# spintop balance: {} dipole; {}; period T = {}",
                output.dipole,
                describe(&output.parameters),
                num(output.period)
            )?;
            writeln!(
                out,
                "# (2.1) larmor = -d' x d'', (2.2) torque = d x d''', (2.4) schott = d x d''; \
                 torque = larmor + schott_rate (2.3); axial = component along d; kappa = 1"
            )?;
            let block = |out: &mut dyn Write,
                         title: String,
                         vs: [[Real; 3]; 5],
                         ax: [Option<Real>; 5]|
             -> io::Result<()> {
                writeln!(out, "{title}")?;
                for ((name, v), a) in VECTORS.iter().zip(vs).zip(ax) {
                    let axial = a.map_or(String::new(), |a| format!("   axial {:>14}", num(a)));
                    writeln!(
                        out,
                        "  {name:<12}{:>14}{:>14}{:>14}{axial}",
                        num(v[0]),
                        num(v[1]),
                        num(v[2])
                    )?;
                }
                Ok(())
            };
            for s in &output.samples {
                block(
                    out,
                    format!("t = {}", num(s.t)),
                    [s.dipole, s.larmor, s.torque, s.schott, s.schott_rate],
                    [
                        None,
                        Some(s.larmor_axial),
                        Some(s.torque_axial),
                        None,
                        Some(s.schott_rate_axial),
                    ],
                )?;
            }
            let a = &output.period_average;
            block(
                out,
                format!("average over one period (T = {})", num(output.period)),
                [a.dipole, a.larmor, a.torque, a.schott, a.schott_rate],
                [
                    None,
                    Some(a.larmor_axial),
                    Some(a.torque_axial),
                    None,
                    Some(a.schott_rate_axial),
                ],
            )
        }
    }
}

fn describe(p: &BalanceParameters) -> String {
    use crate::present::fmt_param as fp;
    let mut parts = Vec::new();
    if let Some(x) = p.cone {
        parts.push(format!("cone = {}", fp(x)));
    }
    if let Some(x) = p.rate {
        parts.push(format!("rate = {}", fp(x)));
    }
    if let Some(x) = p.b {
        parts.push(format!("b = {}", fp(x)));
    }
    if let Some(x) = p.eps {
        parts.push(format!("eps = {}", fp(x)));
    }
    if let Some([q1, q2]) = p.charges {
        parts.push(format!("charges = ({}, {})", fp(q1), fp(q2)));
    }
    if let Some([m1, m2]) = p.masses {
        parts.push(format!("masses = ({}, {})", fp(m1), fp(m2)));
    }
    if let Some(x) = p.length {
        parts.push(format!("length = {}", fp(x)));
    }
    if let Some(x) = p.dipole_amplitude {
        parts.push(format!("|d| = {}", fp(x)));
    }
    parts.join(", ")
}

/// Validate, run and print `balance`.
pub(crate) fn execute(args: BalanceArgs, out: &mut impl Write) -> Result<(), CliError> {
    let config = args.validate()?;
    let output = balance(&config);
    super::ensure_finite(
        &output,
        "the torques grow like the third power of --rate (and of the loop's size): use a smaller --rate",
    )?;
    write_output(out, &output, config.format)?;
    Ok(())
}
