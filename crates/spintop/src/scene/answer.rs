//! A scene answered: the lightest model that is right, run, and reported under
//! the matching command's JSON contract plus `scene`, `chosen` and
//! `warnings` (and, for a real particle, `units`). This is what `spintop run`
//! prints; the lessons, the benches and the tests call [`answer`] directly.

use super::{
    Body, Chosen, GeneralUnits, OmegaSample, Orientation, RealUnits, Scene, TopScene,
    omega_samples, pole_warning,
};
use crate::integrate::{IntegrateError, Stats};
use crate::math::{Real, Vec3};
use crate::numbers::{fmt_value, worked};
use crate::output::balance::{self, BalanceOutput};
use crate::output::orbit::{self, OrbitOutput, OrbitRequest};
use crate::output::shell::{self, ShellOutput, ShellRequest};
use crate::output::simulate::{Parameters, SimulateConfig, SimulateOutput, simulate};
use crate::output::{Entry, Failure, Format};
use crate::physics::general_top::GeneralTop;
use crate::physics::particle::{DEBYE_ESU_CM, RigidShape, SPEED_OF_LIGHT_CM_S};
use crate::sim::Model;
use crate::sim::claim::{ErrorEstimate, TierEstimate, omega_rounding, secular_error};
use crate::sim::secular::{Law, SecularSample, secular};
use crate::stability::Row;
use serde::Serialize;

mod particle;
pub use particle::{MilestoneTimes, PhysicalReport, Span, physical_report};

/// Which scene was run.
#[derive(Clone, Debug, Serialize)]
pub struct SceneInfo {
    /// Its name.
    pub name: String,
    /// Its kind.
    pub kind: &'static str,
    /// The file it came from.
    pub file: String,
    /// What it asks.
    pub description: String,
}

/// A top scene whose orientation was skipped: the `simulate` contract with
/// body-frame samples only.
#[derive(Debug, Serialize)]
pub struct OmegaOnlyOutput {
    /// `truncated` or `reduced`.
    pub model: &'static str,
    /// `exact`.
    pub method: &'static str,
    /// One sentence on what was computed how.
    pub method_detail: &'static str,
    /// The inputs.
    pub parameters: Parameters,
    /// Work done (none).
    pub stats: Stats,
    /// One entry per output time, body-frame quantities only.
    pub samples: Vec<OmegaSample>,
    /// Why the orientation is not given.
    pub orientation_skipped: String,
    /// How far Ω may be from the truth over the run.
    pub error: ErrorEstimate,
}

/// An asymmetric top answered by the secular model: E and |L| only.
#[derive(Debug, Serialize)]
pub struct SecularOutput {
    /// `general` or `general-reduced`.
    pub model: &'static str,
    /// `secular`.
    pub method: &'static str,
    /// One sentence on what was computed how.
    pub method_detail: &'static str,
    /// The inputs.
    pub parameters: Parameters,
    /// Work of the slow integration (each evaluation is one period average).
    pub stats: Stats,
    /// The most quadrature points one period average took.
    pub max_quadrature_points: usize,
    /// One entry per output time.
    pub samples: Vec<SecularRow>,
    /// Why the orientation is not given.
    pub orientation_skipped: String,
    /// How far E and |L| may be from the truth over the run (in `omega`,
    /// each relative to its value at the start).
    pub error: ErrorEstimate,
}

/// One time of a secular run.
#[derive(Debug, Serialize)]
pub struct SecularRow {
    /// The model's state.
    #[serde(flatten)]
    pub sample: SecularSample,
    /// Time in the scene's output unit, when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_unit: Option<Real>,
}

/// What a top scene produced.
#[derive(Debug, Serialize)]
#[serde(untagged)]
pub enum TopRun {
    /// Ω and the orientation: the `simulate` contract.
    Full(SimulateOutput),
    /// Ω only.
    OmegaOnly(OmegaOnlyOutput),
    /// E and |L| only, from the secular model.
    Secular(SecularOutput),
}

/// An asymmetric real particle's inputs and its conversion to κ = 1 units.
#[derive(Clone, Debug, Serialize)]
pub struct RigidReport {
    /// What it is made of, as given.
    pub shape: RigidShape,
    /// Principal moments, kg·m².
    pub inertia_kg_m2: [Real; 3],
    /// Body-frame dipole, debye.
    pub dipole_debye: [Real; 3],
    /// Body-frame rates, Hz.
    pub omega_hz: [Real; 3],
    /// τ_f = κ|D|²/min I, seconds: the time unit u of its κ = 1 top.
    pub fast_time_s: Real,
    /// The conversion, written out with the numbers.
    pub conversion: String,
    /// τ_f|Ω₀|, the share of spin the radiation takes per radian.
    pub share_per_radian: Real,
    /// The output time unit.
    pub time_unit: &'static str,
    /// Seconds per output time unit.
    pub seconds_per_unit: Real,
    /// u per output time unit.
    pub u_per_unit: Real,
}

/// The report of an ellipsoid or molecule `[units]` scene.
pub fn rigid_report(units: &GeneralUnits) -> RigidReport {
    let p = &units.particle;
    let tau_f = p.fast_time_seconds();
    let i = p.inertia_g_cm2();
    let d = p.dipole_esu_cm();
    let omega0 = p.omega0(units.omega_hz);
    RigidReport {
        shape: p.shape(),
        inertia_kg_m2: (i * 1e-7).into(),
        dipole_debye: (d / DEBYE_ESU_CM).into(),
        omega_hz: units.omega_hz,
        fast_time_s: tau_f,
        conversion: format!(
            "tau_f = 2 |D|^2/(3 c^3 min I) = 2 ({} statC cm)^2 / (3 x ({} cm/s)^3 x {} g cm^2) = {} s (Gaussian units)",
            worked(d.norm()),
            fmt_value(SPEED_OF_LIGHT_CM_S),
            worked(i.min()),
            worked(tau_f)
        ),
        share_per_radian: omega0.norm(),
        time_unit: units.time_unit.name(),
        seconds_per_unit: units.time_unit.seconds(),
        u_per_unit: units.u_per_unit(),
    }
}

/// A top scene's answer.
#[derive(Debug, Serialize)]
pub struct TopAnswer {
    /// The samples.
    #[serde(flatten)]
    pub run: TopRun,
    /// The real particle, when the scene has `[units]` of a sphere or cylinder.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub units: Option<PhysicalReport>,
    /// The real particle, when the scene has `[units]` of an ellipsoid or a molecule.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rigid_units: Option<RigidReport>,
}

/// A stability scene's answer, the `stability --format json` contract.
#[derive(Debug, Serialize)]
pub struct StabilityAnswer {
    /// The one row.
    pub rows: Vec<Row>,
}

/// The answer of any scene, serialised as the matching command's output.
#[derive(Debug, Serialize)]
#[serde(untagged)]
pub enum Answer {
    /// `simulate`.
    Top(Box<TopAnswer>),
    /// `balance`.
    Balance(BalanceOutput),
    /// `orbit`.
    Orbit(OrbitOutput),
    /// `shell`.
    Shell(ShellOutput),
    /// `stability`.
    Stability(StabilityAnswer),
}

/// Everything `spintop run` prints.
#[derive(Debug, Serialize)]
pub struct Report {
    /// Which scene.
    pub scene: SceneInfo,
    /// The method and why.
    pub chosen: Chosen,
    /// Where the question asks more than the model gives.
    pub warnings: Vec<String>,
    /// The answer, under the matching command's contract.
    #[serde(flatten)]
    pub answer: Answer,
}

/// Answer a top scene: the `simulate` contract, or Ω alone, or the secular
/// drift of E and |L|, with the real particle's report beside it.
fn run_top(
    scene: &Scene,
    top: &TopScene,
    warnings: &mut Vec<String>,
) -> Result<TopAnswer, Failure> {
    let run = match (&top.orientation, top.model) {
        (Orientation::Computed, _) => {
            let mut output = run_computed(top)?;
            if let Some(w) = pole_warning(&output.samples) {
                warnings.push(w);
            }
            if let Some(model) = &top.model_error {
                output.error = output
                    .error
                    .take()
                    .map(|error| with_model_error(error, model, &top.model));
            }
            if let Some(e) = &output.error {
                above_rtol(e, top, warnings);
            }
            // NOTE: a runaway is the run's own report (its `runaway` record,
            // the table's line, the gate's `stopped`), not also a warning:
            // it was said three times.
            TopRun::Full(output)
        }
        (Orientation::Skipped(why), Model::General(g)) => {
            run_secular(scene, top, &g, Law::Truncated, why, warnings)?
        }
        (Orientation::Skipped(why), Model::GeneralReduced(g)) => {
            run_secular(scene, top, &g, Law::Reduced, why, warnings)?
        }
        (Orientation::Skipped(why), _) => run_omega_only(scene, top, why, warnings)?,
    };
    Ok(TopAnswer {
        run,
        units: top.units.as_ref().map(physical_report),
        rigid_units: top.general_units.as_ref().map(rigid_report),
    })
}

/// A run's error with the chosen model's own error against the physical
/// solution of (3.4) added (`model = "auto"` chose a lighter model).
fn with_model_error(error: ErrorEstimate, model: &TierEstimate, which: &Model) -> ErrorEstimate {
    let how = format!(
        "the {} model's own error against it, estimated before the run ({:.1e}{})",
        which.name(),
        model.omega,
        model
            .orientation
            .map_or(String::new(), |o| format!(", {o:.1e} rad"))
    );
    error.with_model_error(model.omega, model.orientation.unwrap_or(0.0), &how)
}

/// A warning when the error of the run is above the scene's rtol.
fn above_rtol(error: &ErrorEstimate, top: &TopScene, warnings: &mut Vec<String>) {
    // NOTE: the scene's rtol, not the tighter one `auto` may step at (the
    // warning quoted rtol = 2e-10 for a scene at 1e-2).
    let rtol = top.rtol;
    if error.worst() > rtol && top.method != crate::sim::MethodChoice::Rk4 {
        warnings.push(format!(
            "the error over the run, {:.1e}, is above rtol = {rtol:.0e}: {}",
            error.worst(),
            error.line()
        ));
    }
}

/// Ω and the orientation: the `simulate` contract.
fn run_computed(top: &TopScene) -> Result<SimulateOutput, Failure> {
    simulate(&SimulateConfig {
        model: top.model,
        method: top.method,
        options: top.options,
        initial: top.initial,
        euler0: top.euler0,
        times: top.times.clone(),
        format: Format::Json,
        entry: Entry::Scene,
    })
}

/// An asymmetric top by the secular model: E and |L| under `law`.
fn run_secular(
    scene: &Scene,
    top: &TopScene,
    g: &GeneralTop,
    law: Law,
    why: &str,
    warnings: &mut Vec<String>,
) -> Result<TopRun, Failure> {
    let stopped = |e: IntegrateError| {
        Failure::Stopped(format!(
            "{}: the secular model stopped: {e}; it follows the slow drift of a weakly radiating top, so try fewer decay times or a larger rtol",
            scene.file
        ))
    };
    let rtol = top.options.rtol();
    let run = secular(g, law, &top.initial.omega, &top.times, rtol).map_err(stopped)?;
    let mut error = secular_error(g, law, &top.initial.omega, &run, rtol).map_err(stopped)?;
    if let Some(model) = &top.model_error {
        error = with_model_error(error, model, &top.model);
    }
    above_rtol(&error, top, warnings);
    let u_per_unit = top.general_units.as_ref().map(GeneralUnits::u_per_unit);
    Ok(TopRun::Secular(SecularOutput {
        model: top.model.name(),
        method: "secular",
        method_detail: if law == Law::Truncated {
            "E and |L| drift at their rates under (3.3) averaged over the free motion (closed form, Jacobi's elliptic functions); the orientation is not computed (see orientation_skipped)"
        } else {
            "E and |L| drift at their rates under the reduced (3.4) averaged over the free motion (closed form, Jacobi's elliptic functions); the orientation is not computed (see orientation_skipped)"
        },
        parameters: Parameters {
            ratio: None,
            tau: None,
            inertia: g.inertia().into(),
            dipole: Some(g.dipole().into()),
            omega0: top.initial.omega.into(),
            euler0: top.euler0,
            rtol: Some(top.options.rtol()),
            step: None,
        },
        stats: run.stats,
        max_quadrature_points: run.max_points,
        samples: run
            .samples
            .into_iter()
            .map(|sample| SecularRow {
                t_unit: u_per_unit.map(|k| sample.t / k),
                sample,
            })
            .collect(),
        orientation_skipped: why.to_string(),
        error,
    }))
}

/// A symmetric top whose orientation is skipped: Ω alone, from its closed form.
fn run_omega_only(
    scene: &Scene,
    top: &TopScene,
    why: &str,
    warnings: &mut Vec<String>,
) -> Result<TopRun, Failure> {
    let tau_per_unit = top.units.as_ref().map(RealUnits::tau_per_unit);
    let only_symmetric = || {
        Failure::BadInput(format!(
            "{}: only the symmetric models can skip the orientation",
            scene.file
        ))
    };
    let (Model::Truncated(t) | Model::Reduced(t)) = top.model else {
        return Err(only_symmetric());
    };
    let samples = omega_samples(&top.model, &top.initial.omega, &top.times, tau_per_unit)
        .ok_or_else(only_symmetric)?;
    let omega_floor = omega_rounding(
        &top.model,
        &top.initial.omega,
        samples.iter().map(|s| (s.t, Vec3::from(s.omega))),
    );
    // NOTE: no orientation is reported, so rounding is Ω's alone (the phase
    // counts only while Ω⊥ turns): the whole turning's, 2e-4 for Figure 2's
    // top at 1e12, was printed as the rounding part of a total of 1e-12.
    let mut error = ErrorEstimate {
        omega: omega_floor,
        orientation: None,
        rounding: omega_floor,
        orientation_rounding: None,
        measured: None,
        against: format!("the exact solution of the {} model", top.model.name()),
        how: format!(
            "closed forms: only rounding, {omega_floor:.0e} (4 eps per radian of the phase, where Omega_perp still turns)"
        ),
    };
    if let Some(model) = &top.model_error {
        error = with_model_error(error, model, &top.model);
    }
    above_rtol(&error, top, warnings);
    Ok(TopRun::OmegaOnly(OmegaOnlyOutput {
        model: top.model.name(),
        method: "exact",
        method_detail: if matches!(top.model, Model::Truncated(_)) {
            "omega from the closed form (4.7); the orientation is not computed (see orientation_skipped)"
        } else {
            "omega from the closed form (4.15)-(4.16); the orientation is not computed (see orientation_skipped)"
        },
        parameters: Parameters {
            ratio: Some(t.ratio()),
            tau: Some(t.tau()),
            inertia: t.inertia().into(),
            dipole: None,
            omega0: top.initial.omega.into(),
            euler0: top.euler0,
            rtol: None,
            step: None,
        },
        stats: Stats::default(),
        samples,
        orientation_skipped: why.to_string(),
        error,
    }))
}

/// Run a validated scene.
pub fn answer(scene: &Scene) -> Result<Report, Failure> {
    let mut warnings = scene.warnings.clone();
    let answer = match &scene.body {
        Body::Top(top) => Answer::Top(Box::new(run_top(scene, top, &mut warnings)?)),
        Body::Balance(b) => Answer::Balance(balance::balance(&b.config(Format::Json))),
        Body::Orbit(o) => {
            // The span of a backward integration was checked with the times.
            let request = OrbitRequest {
                config: o.config,
                times: o.times.clone(),
                format: Format::Json,
                entry: Entry::Scene,
            };
            Answer::Orbit(orbit::orbit(&request)?)
        }
        Body::Shell(s) => {
            let request = ShellRequest {
                model: s.model,
                steps: s.steps,
                times: s.times.clone(),
                format: Format::Json,
                entry: crate::output::Entry::Scene,
            };
            Answer::Shell(shell::shell(&request)?)
        }
        Body::Stability(s) => {
            let row = crate::stability::row(s.row).map_err(|e| Failure::Stopped(e.to_string()))?;
            Answer::Stability(StabilityAnswer { rows: vec![row] })
        }
    };
    Ok(Report {
        scene: SceneInfo {
            name: scene.name.clone(),
            kind: scene.kind().name(),
            file: scene.file.clone(),
            description: scene.description.clone(),
        },
        chosen: scene.chosen.clone(),
        warnings,
        answer,
    })
}
