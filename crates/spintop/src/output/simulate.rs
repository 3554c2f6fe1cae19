//! `simulate`: one model of the top, sampled at given times, as a table, CSV
//! or the JSON contract.

use super::{Entry, Failure, Format, Output, Stop, sim_failure, write_aligned};
use crate::math::{Real, Vec3};
use crate::numbers::{self, fmt_time, table};
use crate::sim::claim::ErrorEstimate;
use crate::sim::{
    InitialState, Method, MethodChoice, MethodOptions, Model, Sample, SimError, Simulation,
};
use serde::Serialize;
use std::io::{self, Write};

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
    /// Where the request came from (for the words of advice).
    pub entry: Entry,
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
    /// How far the samples may be from the truth over the run (every method
    /// but a forward run, which runs away).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<ErrorEstimate>,
    /// Notes printed with the answer (a scene's are the scene's own).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// A runaway of (3.4) integrated forward.
#[derive(Clone, Debug, Serialize)]
pub struct RunawayReport {
    /// When the monitor stopped the run.
    pub t: Real,
    /// The measured growth rate (about 1/τ).
    pub growth_rate: Real,
    /// What to do instead.
    pub advice: String,
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
pub fn simulate(config: &SimulateConfig) -> Result<SimulateOutput, Failure> {
    let horizon = config.times.last().copied().unwrap_or(0.0);
    let failure = |e| sim_failure(e, &config.model, config.method, config.entry);
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
                    advice: format!(
                        "integrate backward or use the reduced model ({} gives the physical solution)",
                        config.entry.name(super::Knob::MethodAuto)
                    ),
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
    let samples_omitted = runaway.as_ref().map(|_| config.times.len() - samples.len());
    let method = sim.method();
    let error = if method == Method::Forward {
        None
    } else {
        Some(run_error(config, method, &samples).map_err(failure)?)
    };
    let (ratio, tau, dipole) = match &config.model {
        Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => {
            (Some(top.ratio()), Some(top.tau()), None)
        }
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            (None, None, Some(top.dipole().into()))
        }
    };
    let samples_end = samples.last().map_or(0.0, |s| s.t);
    let integrated = method.is_integrated();
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
            rtol: (integrated && !rk4).then_some(config.options.rtol()),
            step: rk4.then_some(config.options.step()),
        },
        stats: sim.stats(),
        samples,
        runaway,
        samples_omitted,
        error,
        // A scene's plan gives the same note among its warnings; the lost
        // orientation, both.
        warnings: match config.entry {
            Entry::CommandLine => {
                crate::sim::regime::fast_spin_note(&config.model, &config.initial.omega)
            }
            Entry::Scene => None,
        }
        .into_iter()
        .chain(crate::sim::claim::orientation_lost(
            crate::sim::cost::turning_angle(&config.model, &config.initial.omega, samples_end),
        ))
        .collect(),
    })
}

/// The error of a run's samples against its model's exact solution
/// ([`crate::sim::claim::numerical_error`]), the one estimate `simulate` and
/// `run` both print.
pub fn run_error(
    config: &SimulateConfig,
    method: Method,
    samples: &[Sample],
) -> Result<ErrorEstimate, SimError> {
    let t_last = samples.last().map_or(0.0, |s| s.t);
    let angle = crate::sim::cost::turning_angle(&config.model, &config.initial.omega, t_last);
    crate::sim::claim::numerical_error(
        &config.model,
        method,
        &config.options,
        &config.initial,
        samples,
        angle,
        true,
    )
}

impl Output for SimulateOutput {
    /// The table or the CSV (JSON through [`super::write`]).
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()> {
        let output = self;
        match format {
            Format::Json => super::write(out, self, format),
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
                    let cells: Vec<String> = row.iter().map(|x| numbers::csv(*x)).collect();
                    writeln!(out, "{}", cells.join(","))?;
                }
                Ok(())
            }
            Format::Table => {
                use crate::numbers::fmt_param as fp;
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
                if let Some(e) = &output.error {
                    writeln!(out, "# error: {}", e.line())?;
                }
                if let Some(r) = &output.runaway {
                    writeln!(
                        out,
                        "# runaway at t = {}, growth rate {}: {} later sample(s) omitted; {}",
                        numbers::fixed(r.t, 3),
                        numbers::fixed(r.growth_rate, 4),
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
                    write_aligned(out, row.iter().map(|x| table(*x)), 14)?;
                }
                Ok(())
            }
        }
    }

    fn advice(&self, _entry: super::Entry) -> String {
        "use smaller rates or moments (in units of 1/tau and I1)".into()
    }

    fn stopped(&self) -> Option<Stop> {
        let r = self.runaway.as_ref()?;
        let omitted = self.samples_omitted.unwrap_or(0);
        Some(Stop {
            line: format!(
                "runaway at t = {}, growth rate {}; {omitted} later sample(s) omitted",
                fmt_time(r.t),
                numbers::fixed(r.growth_rate, 4)
            ),
            message: format!(
                "runaway at t = {}, growing at rate {} per {} (an e-folding time of {}): {omitted} of {} samples omitted; {}",
                numbers::fixed(r.t, 3),
                numbers::fixed(r.growth_rate, 4),
                r.unit,
                numbers::fixed(1.0 / r.growth_rate, 3),
                self.samples.len() + omitted,
                r.advice
            ),
        })
    }
}
