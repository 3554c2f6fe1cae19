//! `spintop simulate`: one model of the top, sampled at given times, as a
//! table, CSV or the JSON contract.

use super::{
    CliError, Format, TimeList, bad, check_output_times, num, parse_number, parse_times,
    parse_vec3, write_aligned,
};
use crate::math::{Real, Vec3};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::{
    InitialState, MethodChoice, MethodOptions, MethodUsed, Model, Sample, SimError, Simulation,
};
use clap::{Args, ValueEnum};
use serde::Serialize;
use std::io::{self, Write};

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

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum MethodArg {
    /// Closed forms where they exist, DOP853 for the rest (Taylor at rtol <= 1e-9).
    Auto,
    /// Closed forms only.
    Exact,
    /// Fixed-step classical RK4 (--step).
    Rk4,
    /// Dormand-Prince 5(4), adaptive (--rtol).
    Dopri5,
    /// DOP853, adaptive (--rtol).
    Dop853,
    /// Radau IIA 5, implicit and L-stable, adaptive (--rtol): for stiff tops.
    Radau5,
    /// Taylor series of variable order, adaptive (--rtol): the fastest at tight tolerances.
    Taylor,
    /// Full model only: integrate (3.4) forward and watch it run away.
    Forward,
}

fn method_name(m: MethodChoice) -> &'static str {
    match m {
        MethodChoice::Auto => "auto",
        MethodChoice::Exact => "exact",
        MethodChoice::Rk4 => "rk4",
        MethodChoice::Dopri5 => "dopri5",
        MethodChoice::Dop853 => "dop853",
        MethodChoice::Radau5 => "radau5",
        MethodChoice::Taylor => "taylor",
        MethodChoice::Forward => "forward",
    }
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
    #[arg(long, allow_hyphen_values = true)]
    samples: Option<usize>,
    /// Numerical method.
    #[arg(long, value_enum, default_value = "auto")]
    method: MethodArg,
    /// Relative tolerance of the adaptive methods [default: 1e-10]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    rtol: Option<Real>,
    /// Step size of RK4, in tau [default: 0.01]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    step: Option<Real>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
}

/// A fully validated `simulate` request.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulateConfig {
    /// The model.
    pub model: Model,
    /// The method asked for.
    pub method: MethodChoice,
    /// Tolerance and step.
    pub options: MethodOptions,
    /// Ω₀ and O(0).
    pub initial: InitialState,
    /// Euler angles of O(0), as given.
    pub euler0: [Real; 3],
    /// Output times.
    pub times: Vec<Real>,
    /// Output format.
    pub format: Format,
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
        let method = match self.method {
            MethodArg::Auto => MethodChoice::Auto,
            MethodArg::Exact => MethodChoice::Exact,
            MethodArg::Rk4 => MethodChoice::Rk4,
            MethodArg::Dopri5 => MethodChoice::Dopri5,
            MethodArg::Dop853 => MethodChoice::Dop853,
            MethodArg::Radau5 => MethodChoice::Radau5,
            MethodArg::Taylor => MethodChoice::Taylor,
            MethodArg::Forward => MethodChoice::Forward,
        };
        // Each model takes only the methods that mean something for it; the
        // others are refused by name rather than silently replaced.
        match (&model, method) {
            (
                Model::Full(_) | Model::GeneralFull(_),
                MethodChoice::Auto | MethodChoice::Forward,
            ) => {}
            (Model::Full(_) | Model::GeneralFull(_), other) => {
                return Err(bad(format!(
                    "--model full takes --method auto (its physical solution, by DOP853 shooting backward in time) or forward (the runaway), not {}",
                    method_name(other)
                )));
            }
            (_, MethodChoice::Forward) => {
                return Err(bad(
                    "--method forward is for --model full only (it shows the runaway of (3.4))",
                ));
            }
            (Model::General(_), MethodChoice::Exact) => {
                return Err(bad(
                    "the general model (3.3) has no closed form; use --method auto (DOP853, or Taylor at rtol <= 1e-9), taylor, dop853, dopri5, radau5 or rk4",
                ));
            }
            (Model::GeneralReduced(_), MethodChoice::Exact) => {
                return Err(bad(
                    "the reduced model of a general top has no closed form; use --method auto (DOP853, or Taylor at rtol <= 1e-9), taylor, dop853, dopri5, radau5 or rk4",
                ));
            }
            _ => {}
        }
        if self.step.is_some() && method != MethodChoice::Rk4 {
            return Err(bad("--step sets the fixed step of --method rk4 only"));
        }
        if self.rtol.is_some() && method == MethodChoice::Rk4 {
            return Err(bad(
                "--rtol applies to the adaptive methods; rk4 takes --step",
            ));
        }
        let mut options = MethodOptions::default();
        if let Some(rtol) = self.rtol {
            if !(rtol > 0.0 && rtol < 1.0) {
                return Err(bad(format!("--rtol must lie in (0, 1), got {rtol}")));
            }
            // NOTE: below ~1e-14 the tolerance asks for digits f64 does not have.
            if rtol < 1e-14 {
                return Err(bad(format!(
                    "--rtol {rtol:e} is below what double precision can deliver; use 1e-14 or more"
                )));
            }
            options.rtol = rtol;
        }
        if let Some(step) = self.step {
            if step <= 0.0 {
                return Err(bad(format!("--step must be positive, got {step}")));
            }
            options.step = step;
        }
        let [phi, theta, psi] = self.euler;
        let initial = InitialState::new(Vec3::from(self.omega), EulerAngles::new(phi, theta, psi))?;
        let times = match self.times {
            Some(TimeList(times)) => times,
            None => {
                let t_end = self.t_end.unwrap_or(100.0);
                let n = self.samples.unwrap_or(11);
                if t_end < 0.0 {
                    return Err(bad(format!("--t-end must be >= 0, got {t_end}")));
                }
                if n == 0 || n > 1_000_000 {
                    return Err(bad(format!("--samples must be in 1..=1000000, got {n}")));
                }
                if n == 1 {
                    vec![t_end]
                } else {
                    (0..n)
                        .map(|i| t_end * i as Real / (n - 1) as Real)
                        .collect()
                }
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
        })
    }
}

/// The JSON output of `simulate` (the contract).
#[derive(Debug, Serialize)]
pub struct SimulateOutput {
    /// `truncated`, `reduced`, `general` or `full`.
    pub model: &'static str,
    /// The method used: `exact`, `exact+dop853`, `rk4`, `dopri5`, `dop853`,
    /// `physical` or `forward`.
    pub method: &'static str,
    /// One sentence on what was computed how.
    pub method_detail: &'static str,
    /// The inputs.
    pub parameters: Parameters,
    /// Work done.
    pub stats: crate::integrate::Stats,
    /// One entry per output time.
    pub samples: Vec<Sample>,
    /// Full model, forward method: the runaway that stopped the run.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runaway: Option<RunawayReport>,
    /// Output times after the runaway, not computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples_omitted: Option<usize>,
}

/// A runaway of (3.4) integrated forward.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct RunawayReport {
    /// When the monitor stopped the run.
    pub t: Real,
    /// The measured growth rate (about 1/τ).
    pub growth_rate: Real,
    /// What to do instead.
    pub advice: &'static str,
    /// The unit of time: "tau" for the symmetric top, the kappa = 1 unit for
    /// a general one.
    #[serde(skip)]
    pub unit: &'static str,
}

/// The inputs, echoed in the JSON output.
#[derive(Debug, Serialize)]
pub struct Parameters {
    /// I₃/I₁ (symmetric models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio: Option<Real>,
    /// τ (symmetric models; 1 in the paper's units).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau: Option<Real>,
    /// Principal moments.
    pub inertia: [Real; 3],
    /// Body dipole (general model, κ = 1 units).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dipole: Option<[Real; 3]>,
    /// Ω₀.
    pub omega0: [Real; 3],
    /// Euler angles of O(0).
    pub euler0: [Real; 3],
    /// Relative tolerance (adaptive methods).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtol: Option<Real>,
    /// Step (RK4).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step: Option<Real>,
}

/// Run a validated `simulate` request.
pub fn simulate(config: &SimulateConfig) -> Result<SimulateOutput, CliError> {
    let horizon = config.times.last().copied().unwrap_or(0.0);
    let failure = |e| super::sim_failure(e, &config.model, config.method);
    let mut sim = Simulation::new(
        config.model,
        config.method,
        config.options,
        config.initial,
        Some(horizon),
    )
    .map_err(failure)?;
    // A forward run of the full ALE stops at its runaway: the samples before it
    // are the answer, the runaway is reported beside them.
    let mut samples = Vec::with_capacity(config.times.len());
    let mut runaway = None;
    for &t in &config.times {
        match sim.advance_to(t) {
            Ok(sample) => samples.push(*sample),
            Err(SimError::Runaway(r)) => {
                runaway = Some(RunawayReport {
                    t: r.t,
                    growth_rate: r.growth_rate,
                    advice: "integrate backward or use the reduced model (--model full --method auto gives the physical solution)",
                    unit: if matches!(config.model, Model::GeneralFull(_)) {
                        "time unit (kappa = 1)"
                    } else {
                        "tau"
                    },
                });
                break;
            }
            Err(e) => return Err(failure(e)),
        }
    }
    let samples_omitted = runaway.map(|_| config.times.len() - samples.len());
    let method = sim.method();
    let (ratio, tau, dipole) = match &config.model {
        Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => {
            (Some(top.ratio()), Some(top.tau()), None)
        }
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            (None, None, Some(top.dipole().into()))
        }
    };
    let integrated = !matches!(method, MethodUsed::Exact);
    let rk4 = config.method == MethodChoice::Rk4;
    Ok(SimulateOutput {
        model: config.model.name(),
        method: method.label(),
        method_detail: method.detail(),
        parameters: Parameters {
            ratio,
            tau,
            inertia: config.model.inertia().into(),
            dipole,
            omega0: config.initial.omega.into(),
            euler0: config.euler0,
            rtol: (integrated && !rk4).then_some(config.options.rtol),
            step: rk4.then_some(config.options.step),
        },
        stats: sim.stats(),
        samples,
        runaway,
        samples_omitted,
    })
}

/// Write the output in the requested format.
pub fn write_output(
    out: &mut impl Write,
    output: &SimulateOutput,
    format: Format,
) -> io::Result<()> {
    match format {
        Format::Json => {
            serde_json::to_writer(&mut *out, output)?;
            writeln!(out)
        }
        Format::Csv => {
            write!(
                out,
                "t,omega1,omega2,omega3,omega_perp,energy,l_lab_x,l_lab_y,l_lab_z,tilt,phi,theta,psi"
            )?;
            for i in 1..=3 {
                for j in 1..=3 {
                    write!(out, ",r{i}{j}")?;
                }
            }
            writeln!(out)?;
            for s in &output.samples {
                let mut row = vec![s.t];
                row.extend(s.omega);
                row.extend([s.omega_perp, s.energy]);
                row.extend(s.l_lab);
                row.push(s.tilt);
                row.extend(s.euler);
                row.extend(s.rotation.iter().flatten());
                let cells: Vec<String> = row.iter().map(|x| x.to_string()).collect();
                writeln!(out, "{}", cells.join(","))?;
            }
            if let Some(r) = &output.runaway {
                writeln!(
                    out,
                    "# stopped: runaway at t = {}, growth rate {:.4}; {} later sample(s) omitted",
                    crate::math::fmt_time(r.t),
                    r.growth_rate,
                    output.samples_omitted.unwrap_or(0)
                )?;
            }
            Ok(())
        }
        Format::Table => {
            use crate::present::fmt_param as fp;
            let p = &output.parameters;
            let params = match (p.ratio, p.dipole) {
                (Some(ratio), _) => format!("I3/I1 = {}, tau = 1", fp(ratio)),
                (None, Some(d)) => format!(
                    "I = ({}, {}, {}), d = ({}, {}, {}), kappa = 1",
                    fp(p.inertia[0]),
                    fp(p.inertia[1]),
                    fp(p.inertia[2]),
                    fp(d[0]),
                    fp(d[1]),
                    fp(d[2])
                ),
                (None, None) => String::new(),
            };
            writeln!(
                out,
                "# spintop simulate: {} model; {params}; omega0 = ({}, {}, {})",
                output.model,
                fp(p.omega0[0]),
                fp(p.omega0[1]),
                fp(p.omega0[2])
            )?;
            writeln!(
                out,
                "# method: {} ({})",
                output.method, output.method_detail
            )?;
            writeln!(
                out,
                "# work: {} rhs evaluations, {} steps, {} rejected",
                output.stats.rhs_evals, output.stats.steps, output.stats.rejected
            )?;
            if let Some(r) = &output.runaway {
                writeln!(
                    out,
                    "# runaway at t = {:.3}, growth rate {:.4}: {} later sample(s) omitted; {}",
                    r.t,
                    r.growth_rate,
                    output.samples_omitted.unwrap_or(0),
                    r.advice
                )?;
            }
            let head = [
                "t",
                "omega1",
                "omega2",
                "omega3",
                "omega_perp",
                "energy",
                "|L|",
                "tilt",
                "phi",
                "theta",
                "psi",
            ];
            write_aligned(out, head, 14)?;
            for s in &output.samples {
                // Scaled, so that |L| does not overflow where its components do not.
                let l = {
                    let v = Vec3::from(s.l_lab);
                    let m = v.amax();
                    if m > 0.0 { m * (v / m).norm() } else { 0.0 }
                };
                let row = [
                    s.t,
                    s.omega[0],
                    s.omega[1],
                    s.omega[2],
                    s.omega_perp,
                    s.energy,
                    l,
                    s.tilt,
                    s.euler[0],
                    s.euler[1],
                    s.euler[2],
                ];
                write_aligned(out, row.iter().map(|x| num(*x)), 14)?;
            }
            Ok(())
        }
    }
}

/// Validate, run and print `simulate`.
pub(crate) fn execute(
    args: SimulateArgs,
    out: &mut impl Write,
    err: &mut impl Write,
) -> Result<(), CliError> {
    let config = args.validate()?;
    let output = simulate(&config)?;
    super::ensure_finite(
        &output,
        "use smaller rates or moments (in units of 1/tau and I1)",
    )?;
    let _ = err;
    // The samples before a runaway are written (CSV and JSON stay whole and
    // parseable); the run still failed to give what was asked: exit 3.
    write_output(out, &output, config.format)?;
    if let Some(r) = &output.runaway {
        return Err(CliError::Stopped(format!(
            "runaway at t = {:.3}, growing at rate {:.4} per {} (an e-folding time of {:.3}): {} of {} samples omitted; {}",
            r.t,
            r.growth_rate,
            r.unit,
            1.0 / r.growth_rate,
            output.samples_omitted.unwrap_or(0),
            config.times.len(),
            r.advice
        )));
    }
    Ok(())
}
