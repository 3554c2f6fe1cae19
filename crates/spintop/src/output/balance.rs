//! `balance`: the two balance laws of §2 for a built-in dipole trajectory,
//! sampled at given times and averaged over a period.

use super::{Format, Output};
use crate::math::{Real, Vec3};
use crate::numbers::{self, table};
use crate::physics::balance::{
    Balance, DipoleTrajectory, Dumbbell, PlanarLoop, PrecessingDipole, balance_at, period_average,
};
use serde::Serialize;
use std::io::{self, Write};

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

impl Output for BalanceOutput {
    /// The table or the CSV (JSON through [`super::write`]).
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()> {
        let output = self;
        match format {
            Format::Json => super::write(out, self, format),
            Format::Csv => {
                let mut head = vec!["t".to_string()];
                for v in VECTORS {
                    head.extend(["x", "y", "z"].map(|c| format!("{v}_{c}")));
                }
                head.extend(
                    ["larmor_axial", "torque_axial", "schott_rate_axial"].map(String::from),
                );
                writeln!(out, "{}", head.join(","))?;
                let row = |t: String, vs: [[Real; 3]; 5], ax: [Real; 3]| {
                    let mut cells = vec![t];
                    cells.extend(vs.iter().flatten().map(|x| numbers::csv(*x)));
                    cells.extend(ax.iter().map(|x| numbers::csv(*x)));
                    cells.join(",")
                };
                for s in &output.samples {
                    let vs = [s.dipole, s.larmor, s.torque, s.schott, s.schott_rate];
                    let ax = [s.larmor_axial, s.torque_axial, s.schott_rate_axial];
                    writeln!(out, "{}", row(numbers::csv(s.t), vs, ax))?;
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
                    table(output.period)
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
                        let axial =
                            a.map_or(String::new(), |a| format!("   axial {:>14}", table(a)));
                        writeln!(
                            out,
                            "  {name:<12}{:>14}{:>14}{:>14}{axial}",
                            table(v[0]),
                            table(v[1]),
                            table(v[2])
                        )?;
                    }
                    Ok(())
                };
                for s in &output.samples {
                    block(
                        out,
                        format!("t = {}", table(s.t)),
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
                    format!("average over one period (T = {})", table(output.period)),
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

    fn advice(&self, entry: super::Entry) -> String {
        let rate = entry.name(super::Knob::Rate);
        format!(
            "the torques grow like the third power of {rate} (and of the loop's size): use a smaller {rate}"
        )
    }
}

fn describe(p: &BalanceParameters) -> String {
    use crate::numbers::fmt_param as fp;
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
