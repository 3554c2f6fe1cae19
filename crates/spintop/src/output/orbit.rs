//! `orbit`: one charge in a Coulomb or oscillator field under radiation
//! reaction (§2, (2.5)–(2.9)), sampled at given times.

use super::{Failure, Format, Output, Stop, write_aligned};
use crate::integrate::Stats;
use crate::math::Real;
use crate::numbers::{self, fmt_time, table};
use crate::physics::central::{
    Potential, abraham_lorentz_oscillator_roots, landau_lifshitz_oscillator_root,
};
use crate::sim::orbit::{
    Crossing, Force, OrbitConfig, OrbitError, OrbitSample, Runaway, run_orbit_to_collapse,
};
use serde::Serialize;
use std::io::{self, Write};

/// The largest t_last/τ₀ that backward integration of (2.5) accepts: its steps
/// are a few τ₀ (the runaway mode is stiff backward), so the cost grows like t/τ₀.
pub const MAX_BACKWARD_SPAN: Real = 1e6;

/// A backward integration of (2.5) longer than [`MAX_BACKWARD_SPAN`] τ₀.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "force al for coulomb integrates (2.5) backward in steps of a few tau0, and t_last/tau0, {}, exceeds {}",
    crate::numbers::fmt_about(*span),
    crate::numbers::exponent(MAX_BACKWARD_SPAN, 0)
)]
pub struct BackwardTooLong {
    /// t_last/τ₀.
    pub span: Real,
}

/// Refuse a run of `config` up to `t_last` whose backward integration would
/// be too long: the one check the command line and a scene make before it
/// starts.
pub fn check_backward_span(config: &OrbitConfig, t_last: Real) -> Result<(), BackwardTooLong> {
    let span = t_last / config.charge.tau0();
    let backward =
        config.force == Force::AbrahamLorentz && config.charge.potential() == Potential::Coulomb;
    if backward && span > MAX_BACKWARD_SPAN {
        return Err(BackwardTooLong { span });
    }
    Ok(())
}

/// A validated `orbit` request.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitRequest {
    /// The problem.
    pub config: OrbitConfig,
    /// Output times.
    pub times: Vec<Real>,
    /// Output format.
    pub format: Format,
    /// Where the request came from (for the words of advice).
    pub entry: super::Entry,
}

/// The inputs, echoed in the JSON output.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrbitParameters {
    /// τ₀.
    pub tau0: Real,
    /// r₀.
    pub r0: Real,
    /// e.
    pub eccentricity: Real,
    /// m = 1.
    pub m: Real,
    /// k = 1.
    pub k: Real,
    /// The starting speed.
    pub speed0: Real,
    /// Relative tolerance (integrated runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtol: Option<Real>,
}

/// The oscillator's characteristic roots.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Roots {
    /// Physical root of τ₀s³ − s² − 1 = 0, [Re, Im].
    pub abraham_lorentz: [Real; 2],
    /// Root of s² + τ₀s + 1 = 0, [Re, Im].
    pub landau_lifshitz: [Real; 2],
    /// The real (runaway) root of τ₀s³ − s² − 1 = 0.
    pub runaway: Real,
}

/// Shooting summary (Coulomb `al`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Shooting {
    /// Iterations.
    pub iterations: usize,
    /// Final relative mismatch of (r, v) at t = 0.
    pub mismatch: Real,
}

/// The JSON output of `orbit` (the contract).
#[derive(Debug, Serialize)]
pub struct OrbitOutput {
    /// `coulomb` or `harmonic`.
    pub potential: &'static str,
    /// `ll`, `al` or `al-forward`.
    pub force: &'static str,
    /// The paper's equations.
    pub equations: &'static str,
    /// `exact`, `dop853` or `dop853-backward`.
    pub method: &'static str,
    /// The inputs.
    pub parameters: OrbitParameters,
    /// Work done.
    pub stats: Stats,
    /// One entry per output time (up to the runaway for `al-forward`).
    pub samples: Vec<OrbitSample>,
    /// The averaged closed-form collapse time (Coulomb).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub collapse_time: Option<Real>,
    /// First times r fell to 0.5, 0.2 and 0.1 (Coulomb).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_crossing: Option<Vec<Crossing>>,
    /// The detected runaway (`al-forward`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runaway: Option<Runaway>,
    /// Requested times not sampled because the solution ran away (or the
    /// orbit collapsed) first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples_omitted: Option<usize>,
    /// The oscillator's roots.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roots: Option<Roots>,
    /// Backward shooting (Coulomb `al`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shooting: Option<Shooting>,
    /// Where the request came from (for the words of a stop's advice).
    #[serde(skip)]
    pub entry: super::Entry,
    /// The collapse that ended a Coulomb run before the last time (the rows
    /// before it are kept; JSON has it as `stopped`).
    #[serde(skip)]
    pub collapse: Option<Stop>,
}

/// Run a validated `orbit` request.
pub fn orbit(request: &OrbitRequest) -> Result<OrbitOutput, Failure> {
    let config = &request.config;
    let tau0 = config.charge.tau0();
    let potential = config.charge.potential();
    let collapse = config.collapse_time();
    use super::Knob;
    let k = |knob| request.entry.name(knob);
    let times = request.entry.name(Knob::Times);
    let collapsed = |e: &OrbitError| {
        format!(
            "{e}; the averaged collapse time is t_c = {}: ask for times before it, or a smaller {}",
            table(collapse.unwrap_or(Real::INFINITY)),
            k(Knob::Tau0)
        )
    };
    let run = run_orbit_to_collapse(config, &request.times).map_err(|e| match e {
        OrbitError::Collapsed { .. } => Failure::Stopped(collapsed(&e)),
        OrbitError::ShootingFailed { .. } => Failure::Stopped(format!(
            "{e}; try shorter {times}, a smaller {}, or {}",
            k(Knob::Tau0),
            k(Knob::ForceLl)
        )),
        OrbitError::Integrate(ie) => Failure::Stopped(format!(
            "{ie}; try a looser {}, shorter {times}, or a smaller {}",
            k(Knob::Rtol),
            k(Knob::Tau0)
        )),
    })?;
    let omitted = request.times.len() - run.samples.len();
    let fell = run.collapse.map(|(t, r)| {
        let e = OrbitError::Collapsed { t, r };
        Stop {
            line: format!("{e}; {omitted} later sample(s) omitted"),
            message: collapsed(&e),
        }
    });
    let integrated = run.method != "exact";
    let roots = (potential == Potential::Harmonic).then(|| {
        let (s, s_run) = abraham_lorentz_oscillator_roots(tau0);
        let s_ll = landau_lifshitz_oscillator_root(tau0);
        Roots {
            abraham_lorentz: [s.re, s.im],
            landau_lifshitz: [s_ll.re, s_ll.im],
            runaway: s_run,
        }
    });
    Ok(OrbitOutput {
        potential: potential.name(),
        force: config.force.name(),
        equations: match config.force {
            Force::LandauLifshitz => {
                "Eq. (2.5) reduced (Landau-Lifshitz); L obeys the corrected (2.9) at every instant"
            }
            Force::AbrahamLorentz => "Eq. (2.5), physical solution; L obeys (2.6)",
            Force::AbrahamLorentzForward => "Eq. (2.5) forward from the Newtonian acceleration",
        },
        method: run.method,
        parameters: OrbitParameters {
            tau0,
            r0: config.r0,
            eccentricity: config.eccentricity,
            m: 1.0,
            k: 1.0,
            speed0: config.initial().1.norm(),
            rtol: integrated.then_some(config.rtol),
        },
        stats: run.stats,
        samples: run.samples,
        collapse_time: collapse,
        first_crossing: run.first_crossing,
        runaway: run.runaway,
        samples_omitted: (run.runaway.is_some() || fell.is_some()).then_some(omitted),
        roots,
        shooting: run.shooting.map(|(iterations, mismatch)| Shooting {
            iterations,
            mismatch,
        }),
        entry: request.entry,
        collapse: fell,
    })
}

impl Output for OrbitOutput {
    /// The table or the CSV (JSON through [`super::write`]).
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()> {
        let output = self;
        match format {
            Format::Json => super::write(out, self, format),
            Format::Csv => {
                writeln!(out, "t,x,y,vx,vy,r,l,energy")?;
                for s in &output.samples {
                    let row = [
                        s.t,
                        s.position[0],
                        s.position[1],
                        s.velocity[0],
                        s.velocity[1],
                        s.r,
                        s.l,
                        s.energy,
                    ];
                    let cells: Vec<String> = row.iter().map(|x| numbers::csv(*x)).collect();
                    writeln!(out, "{}", cells.join(","))?;
                }
                Ok(())
            }
            Format::Table => {
                let p = &output.parameters;
                writeln!(
                    out,
                    "# spintop orbit: {} potential, force {} ({}); tau0 = {}, r0 = {}, e = {}, m = k = 1",
                    output.potential,
                    output.force,
                    output.equations,
                    crate::numbers::fmt_param(p.tau0),
                    crate::numbers::fmt_param(p.r0),
                    crate::numbers::fmt_param(p.eccentricity)
                )?;
                writeln!(
                    out,
                    "# method: {}; work: {} rhs evaluations, {} steps, {} rejected",
                    output.method,
                    output.stats.rhs_evals,
                    output.stats.steps,
                    output.stats.rejected
                )?;
                if let Some(r) = &output.roots {
                    writeln!(
                        out,
                        "# roots: Abraham-Lorentz {} + {} i (runaway {}), Landau-Lifshitz {} + {} i",
                        table(r.abraham_lorentz[0]),
                        table(r.abraham_lorentz[1]),
                        table(r.runaway),
                        table(r.landau_lifshitz[0]),
                        table(r.landau_lifshitz[1])
                    )?;
                }
                if let Some(sh) = &output.shooting {
                    writeln!(
                        out,
                        "# backward shooting: {} iterations, mismatch {} at t = 0",
                        sh.iterations,
                        numbers::exponent(sh.mismatch, 1)
                    )?;
                }
                let head = ["t", "x", "y", "vx", "vy", "r", "L", "energy"];
                write_aligned(out, head, 14)?;
                for s in &output.samples {
                    let row = [
                        s.t,
                        s.position[0],
                        s.position[1],
                        s.velocity[0],
                        s.velocity[1],
                        s.r,
                        s.l,
                        s.energy,
                    ];
                    write_aligned(out, row.iter().map(|x| table(*x)), 14)?;
                }
                if let Some(tc) = output.collapse_time {
                    writeln!(
                        out,
                        "# collapse time (orbit-averaged closed form): {}",
                        table(tc)
                    )?;
                }
                if let Some(crossings) = &output.first_crossing {
                    for c in crossings {
                        let measured = c.t.map_or("not reached within the run".to_string(), |t| {
                            format!("first reached at t = {}", table(t))
                        });
                        let averaged = c.averaged.map_or(String::new(), |a| {
                            format!(", averaged closed form {}", table(a))
                        });
                        writeln!(out, "# r = {}: {measured}{averaged}", c.r)?;
                    }
                }
                if let Some(r) = &output.runaway {
                    let rate = r.growth_rate.map_or("unmeasured".to_string(), table);
                    writeln!(
                        out,
                        "# RUNAWAY at t = {}: |a - F(r)| passed {} |F(r0)|, growing at rate {rate} (predicted {}); {} later sample(s) omitted",
                        table(r.t),
                        r.threshold,
                        table(r.predicted_rate),
                        output.samples_omitted.unwrap_or(0)
                    )?;
                }
                Ok(())
            }
        }
    }

    fn advice(&self, entry: super::Entry) -> String {
        format!(
            "keep {} and {} within a few decades of 1 (the radiation rate goes like tau0/r0^3)",
            entry.name(super::Knob::Tau0),
            entry.name(super::Knob::R0)
        )
    }

    fn stopped(&self) -> Option<Stop> {
        let Some(r) = self.runaway.as_ref() else {
            return self.collapse.clone();
        };
        let omitted = self.samples_omitted.unwrap_or(0);
        Some(Stop {
            line: format!(
                "runaway at t = {}: |a - F(r)| passed {} |F(r0)|; {omitted} later sample(s) omitted",
                fmt_time(r.t),
                r.threshold
            ),
            message: format!(
                "runaway at t = {}: (2.5) integrated forward left the physical solution, growing at rate {} (predicted {}); {omitted} of {} samples omitted; use {} (its physical solution) or {}",
                fmt_time(r.t),
                r.growth_rate.map_or("unmeasured".to_string(), table),
                table(r.predicted_rate),
                self.samples.len() + omitted,
                self.entry.name(super::Knob::ForceAl),
                self.entry.name(super::Knob::ForceLl)
            ),
        })
    }
}
