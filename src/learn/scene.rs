//! What each chapter shows beside its text, and that scene running.
//!
//! A chapter about the top shows the live view's own models ([`App`]): the
//! truncated and reduced tops, the full ALE's physical solution beside its
//! runaway, or the general top. Section 2 is about a charge in a central
//! field, so its scene is that charge: its Coulomb orbit decaying under the
//! Landau–Lifshitz force, beside the Abraham–Lorentz equation integrated
//! forward, which runs away. The appendix is about the shell model, so its
//! scene is the delay equation (A.1) against the point charge, in its stable
//! and its unstable regime. A chapter with no fitting scene says so.
//!
//! The orbit and the shell are computed once by the core ([`run_orbit`],
//! [`ShellSolver`]), on a thread of their own, and played back at a warp:
//! the screen shows "computing" until they are there, and never waits.

pub mod draw;

use crate::live::app::TICK;
use crate::live::settings::WARPS;
use crate::live::{App, Command as LiveCommand, Refusal, Settings, Top};
use crate::term::cells::Cell;
use crate::term::theme;
use ratatui::text::Span;
use spintop::math::Real;
use spintop::physics::central::{ChargeInField, Potential};
use spintop::physics::shell::ShellModel;
use spintop::sim::MethodChoice;
use spintop::sim::orbit::{Force, OrbitConfig, OrbitError, OrbitRun, OrbitSample, run_orbit};
use spintop::sim::shell::{History, ShellError, ShellSample, ShellSolver, default_steps_per_delay};
use std::sync::mpsc::{self, Receiver};
use std::time::Duration;

/// Why a chapter's scene could not start or compute.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The live models refused the settings.
    #[error(transparent)]
    Refused(#[from] Refusal),
    /// An experiment of the chapter is wrong.
    #[error(transparent)]
    Experiment(#[from] super::experiment::ExperimentError),
    /// A parameter of the charge or the shell.
    #[error(transparent)]
    Param(#[from] spintop::physics::ParamError),
    /// The orbit could not be computed.
    #[error(transparent)]
    Orbit(#[from] OrbitError),
    /// The shell's delay equation could not be solved.
    #[error(transparent)]
    Shell(#[from] ShellError),
}

/// The unit of time of the played-back scenes (the charge's orbit and the
/// shell: m = k = 1, so the oscillator's and the circular orbit's ω₀ = 1).
pub const PLAYBACK_UNIT: &str = "1/ω₀";

/// What a chapter shows beside its text.
#[derive(Debug, Clone, PartialEq)]
pub enum Spec {
    /// The live view's models: their settings, the columns shown, and
    /// whether the charts start on the log-time axis.
    Top {
        /// The settings.
        settings: Settings,
        /// The columns shown (0 truncated, 1 reduced; for the full ALE 0
        /// physical, 1 forward; for a general top 0 (3.3), 1 reduced, 2
        /// physical).
        columns: Vec<usize>,
        /// Log-time charts from the start.
        log_time: bool,
    },
    /// A charge on a Coulomb orbit (m = k = 1, r₀ = 1): the Landau–Lifshitz
    /// collapse beside the Abraham–Lorentz runaway.
    Orbit {
        /// τ₀.
        tau0: Real,
    },
    /// The shell (A.1) against the point charge: (τ₀, δ) of each run.
    Shell {
        /// The runs.
        runs: [(Real, Real); 2],
    },
    /// No scene fits the chapter.
    None,
}

/// A chapter's scene: what it is, and one line about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// What it shows.
    pub spec: Spec,
    /// One line about it (for a chapter without a scene, why).
    pub about: &'static str,
}

impl Scene {
    /// The line that says what the scene is: its `about`, or for a chapter
    /// with none, "no scene: " and why.
    pub fn describe(&self) -> String {
        match self.spec {
            Spec::None => format!("no scene: {}", self.about),
            _ => self.about.to_string(),
        }
    }

    /// The scene of the chapter in `file` (a file name of `book/src`).
    pub fn of(file: &str) -> Scene {
        let figure = Settings::default();
        let top = |settings: Settings, columns: Vec<usize>, about| Scene {
            spec: Spec::Top {
                settings,
                columns,
                log_time: false,
            },
            about,
        };
        let none = |about| Scene {
            spec: Spec::None,
            about,
        };
        let both = || {
            top(
                figure,
                vec![0, 1],
                "the paper's top, I₃/I₁ = 2/5: truncated and reduced side by side",
            )
        };
        // A solutions page shows the scene of the chapter it solves.
        let file = match file.strip_prefix("solutions-") {
            Some("appendix.md") => "appendix.md",
            Some(rest) => rest,
            None => file,
        };
        let valid = |s: Result<Settings, Refusal>| s.unwrap_or(figure);
        // The figures' top (I₃/I₁ = 2/5, Ω₀ = (0, 0.1, 0.2)) by `method` at `warp`.
        let figure_by = |method, warp| {
            valid(Settings::new(
                spintop::figure::FIGURE_RATIO,
                spintop::figure::FIGURE_OMEGA0,
                method,
                warp,
            ))
        };
        match file {
            "preface.md" | "errata.md" => both(),
            "section-2.md" => Scene {
                spec: Spec::Orbit { tau0: 1e-3 },
                about: "a charge on a Coulomb orbit: Landau–Lifshitz collapses, Abraham–Lorentz runs away",
            },
            "section-3.md" | "full-ale.md" => top(
                valid(Settings::full(
                    spintop::figure::FIGURE_RATIO,
                    spintop::figure::FIGURE_OMEGA0,
                    10.0,
                )),
                vec![0, 1],
                "the full ALE (3.4): its physical solution beside the forward runaway",
            ),
            "section-4-1.md" => top(
                figure,
                vec![0],
                "the truncated top (4.2)–(4.4) at I₃/I₁ = 2/5",
            ),
            "section-4-2.md" => top(
                figure,
                vec![1],
                "the reduced top (4.12)–(4.14) at I₃/I₁ = 2/5",
            ),
            "section-5.md" => Scene {
                spec: Spec::Top {
                    settings: figure_by(MethodChoice::Exact, 1000.0),
                    columns: vec![0, 1],
                    log_time: true,
                },
                about: "both end states on a log time axis: the truncated top runs down, the reduced one stands up",
            },
            "appendix.md" => Scene {
                spec: Spec::Shell {
                    runs: [(1e-3, 0.03), (0.06, 0.1)],
                },
                about: "the shell's delay equation (A.1) against the point charge, stable and unstable",
            },
            "asymmetric-top.md" => {
                // The chapter's top: three models side by side.
                match spintop::physics::general_top::GeneralTop::new(
                    spintop::math::Vec3::new(1.0, 2.0, 2.5),
                    spintop::math::Vec3::new(1.0, 0.5, 0.2),
                )
                .map_err(Refusal::from)
                .and_then(|t| Settings::general(t, [0.3, -0.2, 0.1], MethodChoice::Dop853, 10.0))
                {
                    Ok(settings) => top(
                        settings,
                        vec![0, 1, 2],
                        "I = (1, 2, 2.5), d = (1, 0.5, 0.2): (3.3), reduced and physical (3.4), in u",
                    ),
                    Err(_) => none("the chapter's top could not be built"),
                }
            }
            "numerical-methods.md" => top(
                figure_by(MethodChoice::Rk4, 100.0),
                vec![0, 1],
                "both models under fixed-step RK4 at 100 τ/s; m changes the method",
            ),
            "where-methods-fail.md" => top(
                figure_by(MethodChoice::Rk4, 100.0),
                vec![0, 1],
                "both models under fixed-step RK4 at 100 τ/s: press x to break it",
            ),
            "speed-accuracy.md" => top(
                figure_by(MethodChoice::Dop853, 10.0),
                vec![0, 1],
                "both models by DOP853 beside their closed forms",
            ),
            "question-and-scales.md" | "real-particles.md" => none(
                "a real particle turns far too slowly to watch; `spintop run nanoparticle-1e3-debye` prints its times",
            ),
            "assignments.md" => none("the assignments are in the course panel (a)"),
            _ => none("this page is reference, with nothing to run"),
        }
    }
}

/// A computation done once on its own thread and played back by the clock.
pub struct Playback<T> {
    rx: Option<Receiver<Result<T, SceneError>>>,
    data: Option<Result<T, SceneError>>,
    t: Real,
    t_end: Real,
    paused: bool,
    warp: usize,
    default_warp: usize,
}

impl<T: Send + 'static> Playback<T> {
    /// Compute `f` (on its own thread when `background`), to be played from
    /// t = 0 to `t_end` at `WARPS[warp]` per second.
    fn new(
        f: impl FnOnce() -> Result<T, SceneError> + Send + 'static,
        t_end: Real,
        warp: usize,
        background: bool,
    ) -> Self {
        let (rx, data) = if background {
            let (tx, rx) = mpsc::channel();
            std::thread::spawn(move || {
                let _ = tx.send(f());
            });
            (Some(rx), None)
        } else {
            (None, Some(f()))
        };
        Self {
            rx,
            data,
            t: 0.0,
            t_end,
            paused: false,
            warp,
            default_warp: warp,
        }
    }

    fn advance(&mut self, elapsed: Duration) {
        if let Some(rx) = &self.rx
            && let Ok(data) = rx.try_recv()
        {
            self.data = Some(data);
            self.rx = None;
        }
        if self.data.is_some() && !self.paused {
            self.t = (self.t + WARPS[self.warp] * elapsed.as_secs_f64()).min(self.t_end);
        }
    }

    /// The result, once computed.
    pub fn data(&self) -> Option<&Result<T, SceneError>> {
        self.data.as_ref()
    }

    /// The time played to.
    pub fn t(&self) -> Real {
        self.t
    }
}

/// Section 2's two runs of a charge on a Coulomb orbit.
#[derive(Debug, Clone)]
pub struct OrbitRuns {
    /// τ₀.
    pub tau0: Real,
    /// The Landau–Lifshitz orbit, densely sampled up to near the collapse.
    pub ll: Vec<OrbitSample>,
    /// The Abraham–Lorentz equation integrated forward, to its runaway.
    pub forward: OrbitRun,
    /// The averaged closed-form collapse time r₀³/(6τ₀).
    pub collapse: Real,
}

/// Where the Landau–Lifshitz orbit is played to: r = 0.1, before the
/// floor where the model ends ((10τ₀)^{2/3}).
const ORBIT_LAST_R: Real = 0.1;

fn orbit_runs(tau0: Real) -> Result<OrbitRuns, SceneError> {
    let charge = ChargeInField::new(Potential::Coulomb, tau0)?;
    let ll = OrbitConfig::new(charge, 1.0, 0.0, Force::LandauLifshitz)?;
    let collapse = ll.collapse_time().unwrap_or(0.0);
    // r³ = r₀³ − 6τ₀t: r = 0.1 at t = (1 − 10⁻³)/(6τ₀).
    let t_last = (1.0 - ORBIT_LAST_R.powi(3)) / (6.0 * tau0);
    let n = 4000;
    let times: Vec<Real> = (0..=n).map(|i| t_last * i as Real / n as Real).collect();
    let ll_run = run_orbit(&ll, &times)?;
    let forward = OrbitConfig::new(charge, 1.0, 0.0, Force::AbrahamLorentzForward)?;
    let times: Vec<Real> = (0..=400)
        .map(|i| 100.0 * tau0 * i as Real / 400.0)
        .collect();
    let forward = run_orbit(&forward, &times)?;
    Ok(OrbitRuns {
        tau0,
        ll: ll_run.samples,
        forward,
        collapse,
    })
}

/// One run of the shell model, sampled.
#[derive(Debug, Clone)]
pub struct ShellRun {
    /// The model.
    pub model: ShellModel,
    /// The samples, every [`SHELL_DT`].
    pub samples: Vec<ShellSample>,
    /// Why the run ended early, if it did.
    pub ended: Option<String>,
}

/// The sampling interval of the shell runs.
const SHELL_DT: Real = 0.02;

/// How long the shell runs are played (in units of 1/ω₀).
const SHELL_T_END: Real = 20.0;

fn shell_runs(runs: [(Real, Real); 2]) -> Result<Vec<ShellRun>, SceneError> {
    runs.iter()
        .map(|&(tau0, delta)| {
            let model = ShellModel::new(tau0, delta)?;
            let mut solver = ShellSolver::new(
                model,
                History::abraham_lorentz(tau0),
                default_steps_per_delay(delta),
            )?;
            let mut samples = Vec::new();
            let mut ended = None;
            let n = (SHELL_T_END / SHELL_DT).round() as usize;
            for i in 0..=n {
                match solver.sample(i as Real * SHELL_DT) {
                    Ok(s) => samples.push(s),
                    Err(e) => {
                        ended = Some(e.to_string());
                        break;
                    }
                }
            }
            Ok(ShellRun {
                model,
                samples,
                ended,
            })
        })
        .collect()
}

/// A chapter's scene, running.
pub enum Stage {
    /// The live view's models.
    Top(Box<App>),
    /// Section 2's charge.
    Orbit(Playback<OrbitRuns>),
    /// The appendix's shell.
    Shell(Playback<Vec<ShellRun>>),
    /// Nothing to run.
    None,
}

/// What a scene key asks of the stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneKey {
    /// Pause or resume.
    Pause,
    /// Restart at t = 0.
    Reset,
    /// A faster warp.
    Faster,
    /// A slower warp.
    Slower,
    /// Log-time charts.
    Log,
    /// The next method.
    Method,
    /// One step while paused.
    Step,
    /// The next model, where they take turns.
    NextModel,
}

/// `v` in a chapter's scene: the next of the models it draws, where they
/// take turns; otherwise why nothing changes (one model, or all of them on
/// the screen). Said of the models the chapter draws, not of all the live
/// view has (Section 4.2 draws the reduced top alone).
fn next_model(app: &mut App, shown: &[usize]) -> (String, bool) {
    let shown: Vec<usize> = shown
        .iter()
        .copied()
        .filter(|c| *c < app.columns().len())
        .collect();
    let name = |app: &App, i: usize| {
        let (name, equations, gist) = app.columns()[i].title();
        format!("{name} {equations}, {gist}")
    };
    match shown.as_slice() {
        [] => ("this scene draws no model to change".into(), true),
        [one] => (
            format!(
                "this scene draws one model, the {}: v has no other to show",
                name(app, *one)
            ),
            true,
        ),
        _ if !app.view().takes_turns(shown.len()) => (
            format!(
                "all {} models of this scene are on the screen; v shows them one at a time where the scene is narrower",
                shown.len()
            ),
            true,
        ),
        _ => {
            app.apply(LiveCommand::NextModel);
            let at = app.view().shown % shown.len();
            (
                format!(
                    "scene: model {} of {}: {}",
                    at + 1,
                    shown.len(),
                    name(app, shown[at])
                ),
                false,
            )
        }
    }
}

impl Stage {
    /// Start the scene of `spec` (its computations on their own thread when
    /// `background`).
    pub fn start(spec: &Spec, background: bool) -> Result<Stage, SceneError> {
        Ok(match spec {
            Spec::Top {
                settings, log_time, ..
            } => {
                let app = if background {
                    App::background(*settings)?
                } else {
                    App::new(*settings)?
                };
                let mut app = app.monochrome(theme::no_color());
                if *log_time {
                    app.apply(LiveCommand::ToggleLogTime);
                }
                Stage::Top(Box::new(app))
            }
            Spec::Orbit { tau0 } => {
                let tau0 = *tau0;
                let t_end = (1.0 - ORBIT_LAST_R.powi(3)) / (6.0 * tau0);
                Stage::Orbit(Playback::new(
                    move || orbit_runs(tau0),
                    t_end,
                    4,
                    background,
                ))
            }
            Spec::Shell { runs } => {
                let runs = *runs;
                Stage::Shell(Playback::new(
                    move || shell_runs(runs),
                    SHELL_T_END,
                    1,
                    background,
                ))
            }
            Spec::None => Stage::None,
        })
    }

    /// The live view's models, when this is one.
    pub fn app(&self) -> Option<&App> {
        match self {
            Stage::Top(app) => Some(app),
            _ => None,
        }
    }

    /// Let wall-clock time pass.
    pub fn advance(&mut self, elapsed: Duration) {
        match self {
            Stage::Top(app) => {
                app.advance_wall(elapsed);
            }
            Stage::Orbit(p) => p.advance(elapsed),
            Stage::Shell(p) => p.advance(elapsed),
            Stage::None => {}
        }
    }

    /// Pass on the size the scene is drawn at (the live models use it to
    /// pick what fits, and whether they take turns).
    pub fn resize(&mut self, w: u16, h: u16) {
        if let Stage::Top(app) = self {
            app.apply(LiveCommand::Resize(w, h));
        }
    }

    /// Apply a scene key; the line to show, and whether it is a refusal.
    /// `shown`: the live view's columns the chapter's scene draws.
    pub fn key(&mut self, key: SceneKey, shown: &[usize]) -> (String, bool) {
        match self {
            Stage::Top(app) if key == SceneKey::NextModel => next_model(app, shown),
            Stage::Top(app) => {
                let command = match key {
                    SceneKey::Pause => LiveCommand::TogglePause,
                    SceneKey::Reset => LiveCommand::Reset,
                    SceneKey::Faster => LiveCommand::Faster,
                    SceneKey::Slower => LiveCommand::Slower,
                    SceneKey::Log => LiveCommand::ToggleLogTime,
                    SceneKey::Method => LiveCommand::CycleMethod,
                    SceneKey::Step => LiveCommand::Step,
                    SceneKey::NextModel => LiveCommand::NextModel,
                };
                app.apply(command);
                let u = app.settings().top().time_unit();
                if key == SceneKey::Pause {
                    // The live view's own words name its keys (space, →);
                    // here the scene pauses on p.
                    return if app.paused() {
                        (
                            format!(
                                "scene paused at t = {:.2}{u}: . steps Δt = {}{u}, p resumes",
                                app.time(),
                                TICK
                            ),
                            false,
                        )
                    } else {
                        ("scene running".into(), false)
                    };
                }
                match app.message() {
                    Some(m) => (format!("scene: {}", m.text), m.is_error),
                    None if key == SceneKey::Log => (
                        format!(
                            "scene: {} time axis",
                            if app.view().log_time { "log" } else { "linear" }
                        ),
                        false,
                    ),
                    None => (String::new(), false),
                }
            }
            Stage::Orbit(p) => playback_key(p, key),
            Stage::Shell(p) => playback_key(p, key),
            Stage::None => ("this chapter has no scene to control".into(), true),
        }
    }

    /// True while paused.
    pub fn paused(&self) -> bool {
        match self {
            Stage::Top(app) => app.paused(),
            Stage::Orbit(p) => p.paused,
            Stage::Shell(p) => p.paused,
            Stage::None => false,
        }
    }

    /// The scene's clock for the header: "t = 42.6τ".
    pub fn clock(&self) -> Option<String> {
        match self {
            Stage::Top(app) => Some(format!(
                "t = {:.1}{}",
                app.time(),
                app.settings().top().time_unit()
            )),
            Stage::Orbit(p) => Some(format!("t = {:.2} {PLAYBACK_UNIT}", p.t)),
            Stage::Shell(p) => Some(format!("t = {:.2} {PLAYBACK_UNIT}", p.t)),
            Stage::None => None,
        }
    }

    /// The parameters, as cells of one line (the last ones shorten or go
    /// first on a narrow screen), the clock's state at the end.
    pub fn parameters(&self) -> Vec<Cell> {
        let label = |s: &str| Span::styled(s.to_string(), theme::label());
        let value = |s: String| Span::styled(s, theme::value());
        let fmt = spintop::numbers::fmt_param;
        let mut cells = Vec::new();
        match self {
            Stage::Top(app) => {
                let settings = app.settings();
                let w = settings.omega0();
                if let Some(r) = settings.ratio() {
                    // Tight where the header beside the text is narrow
                    // (80 columns), so that Ω₀ keeps its unit there.
                    cells.push(Cell(vec![
                        vec![label(" I₃/I₁ = "), value(fmt(r))],
                        vec![label("I₃/I₁="), value(fmt(r))],
                    ]));
                }
                let lead = if cells.is_empty() {
                    " Ω₀ = "
                } else {
                    "Ω₀ = "
                };
                cells.push(Cell::fixed(vec![
                    label(lead),
                    value(format!("({}, {}, {})", fmt(w[0]), fmt(w[1]), fmt(w[2]))),
                    // In the unit of time the live view names (τ, or u).
                    label(&format!("/{}", settings.top().time_unit())),
                ]));
                let method = match settings.top() {
                    Top::Full(_) => "physical, forward".to_string(),
                    top => crate::live::app::method_title(settings.method(), top),
                };
                cells.push(Cell::or(
                    vec![label("method "), value(method.clone())],
                    vec![value(method)],
                ));
                let warp = format!("{} {}/s", settings.warp(), settings.top().time_unit());
                cells.push(Cell(vec![
                    vec![label("warp "), value(warp.clone())],
                    vec![value(warp)],
                    Vec::new(),
                ]));
                cells.push(Cell::fixed(vec![crate::live::draw::status(app)]));
            }
            Stage::Orbit(p) => {
                let units = (" m = k = 1, r₀ = 1, τ₀ = 10⁻³", " τ₀ = 10⁻³");
                cells.extend(playback_cells(units, p.warp, p.paused));
            }
            Stage::Shell(p) => {
                let units = (" m = k = 1, the oscillator, Z = x + iy", " m = k = 1");
                cells.extend(playback_cells(units, p.warp, p.paused));
            }
            Stage::None => {}
        }
        cells
    }
}

/// "paused" or "running", as the live view shows its clock.
pub fn playback_status(paused: bool) -> Span<'static> {
    if paused {
        Span::styled(" paused ", theme::status(true))
    } else {
        Span::styled(" running ", theme::status(false))
    }
}

/// A played-back scene's parameters: its units (long, short), its warp and
/// its clock.
fn playback_cells(units: (&str, &str), warp: usize, paused: bool) -> [Cell; 3] {
    [
        Cell::or(
            vec![Span::styled(units.0.to_string(), theme::label())],
            vec![Span::styled(units.1.to_string(), theme::label())],
        ),
        Cell::fixed(vec![
            Span::styled("warp ", theme::label()),
            Span::styled(
                format!("{} ({PLAYBACK_UNIT})/s", WARPS[warp]),
                theme::value(),
            ),
        ]),
        Cell::fixed(vec![playback_status(paused)]),
    ]
}

fn playback_key<T: Send + 'static>(p: &mut Playback<T>, key: SceneKey) -> (String, bool) {
    match key {
        SceneKey::Pause => {
            p.paused = !p.paused;
            if p.paused {
                (format!("scene paused at t = {:.2} {PLAYBACK_UNIT}", p.t), false)
            } else {
                ("scene running".into(), false)
            }
        }
        SceneKey::Reset => {
            p.t = 0.0;
            p.warp = p.default_warp;
            ("scene restarted at t = 0".into(), false)
        }
        SceneKey::Faster | SceneKey::Slower => {
            let next = if key == SceneKey::Faster {
                Some(p.warp + 1).filter(|w| *w < WARPS.len())
            } else {
                p.warp.checked_sub(1)
            };
            match next {
                Some(w) => {
                    p.warp = w;
                    (
                        format!("scene warp {} ({PLAYBACK_UNIT})/s", WARPS[w]),
                        false,
                    )
                }
                None => (
                    format!(
                        "the warp is already at its {} ({} ({PLAYBACK_UNIT})/s)",
                        if key == SceneKey::Faster { "fastest" } else { "slowest" },
                        WARPS[p.warp]
                    ),
                    true,
                ),
            }
        }
        SceneKey::Step => ("this scene is computed ahead: p pauses, r restarts".into(), true),
        SceneKey::Log | SceneKey::Method | SceneKey::NextModel => (
            "this scene has one view and its methods are fixed: p pauses, r restarts, + and - set the warp".into(),
            true,
        ),
    }
}
