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

use super::super::app::{App, Command as LiveCommand, Settings, WARPS};
use super::super::theme;
use super::super::view::Cell;
use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Points};
use ratatui::widgets::{Axis, Block, BorderType, Chart, Dataset, GraphType, Paragraph, Wrap};
use spintop::math::Real;
use spintop::physics::central::{ChargeInField, Potential, coulomb_circular_radius};
use spintop::physics::shell::ShellModel;
use spintop::sim::MethodChoice;
use spintop::sim::orbit::{Force, OrbitConfig, OrbitRun, OrbitSample, run_orbit};
use spintop::sim::shell::{History, ShellSample, ShellSolver, default_steps_per_delay};
use std::sync::mpsc::{self, Receiver};
use std::time::Duration;

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
        let valid = |s: Result<Settings, String>| s.unwrap_or(figure);
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
                valid(Settings::full(0.4, [0.0, 0.1, 0.2], 10.0)),
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
                .map_err(|e| e.to_string())
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
    rx: Option<Receiver<Result<T, String>>>,
    data: Option<Result<T, String>>,
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
        f: impl FnOnce() -> Result<T, String> + Send + 'static,
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
    pub fn data(&self) -> Option<&Result<T, String>> {
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

fn orbit_runs(tau0: Real) -> Result<OrbitRuns, String> {
    let charge = ChargeInField::new(Potential::Coulomb, tau0).map_err(|e| e.to_string())?;
    let ll =
        OrbitConfig::new(charge, 1.0, 0.0, Force::LandauLifshitz).map_err(|e| e.to_string())?;
    let collapse = ll.collapse_time().unwrap_or(0.0);
    // r³ = r₀³ − 6τ₀t: r = 0.1 at t = (1 − 10⁻³)/(6τ₀).
    let t_last = (1.0 - ORBIT_LAST_R.powi(3)) / (6.0 * tau0);
    let n = 4000;
    let times: Vec<Real> = (0..=n).map(|i| t_last * i as Real / n as Real).collect();
    let ll_run = run_orbit(&ll, &times).map_err(|e| e.to_string())?;
    let forward = OrbitConfig::new(charge, 1.0, 0.0, Force::AbrahamLorentzForward)
        .map_err(|e| e.to_string())?;
    let times: Vec<Real> = (0..=400)
        .map(|i| 100.0 * tau0 * i as Real / 400.0)
        .collect();
    let forward = run_orbit(&forward, &times).map_err(|e| e.to_string())?;
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

fn shell_runs(runs: [(Real, Real); 2]) -> Result<Vec<ShellRun>, String> {
    runs.iter()
        .map(|&(tau0, delta)| {
            let model = ShellModel::new(tau0, delta).map_err(|e| e.to_string())?;
            let mut solver = ShellSolver::new(
                model,
                History::abraham_lorentz(tau0),
                default_steps_per_delay(delta),
            )
            .map_err(|e| e.to_string())?;
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

impl Stage {
    /// Start the scene of `spec` (its computations on their own thread when
    /// `background`).
    pub fn start(spec: &Spec, background: bool) -> Result<Stage, String> {
        Ok(match spec {
            Spec::Top {
                settings, log_time, ..
            } => {
                let mut app = if background {
                    App::background(*settings)?
                } else {
                    App::new(*settings)?
                };
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

    /// Pass on the terminal's size (the live view uses it to pick what fits).
    pub fn resize(&mut self, w: u16, h: u16) {
        if let Stage::Top(app) = self {
            app.apply(LiveCommand::Resize(w, h));
        }
    }

    /// Apply a scene key; the line to show, and whether it is a refusal.
    pub fn key(&mut self, key: SceneKey) -> (String, bool) {
        match self {
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
                                super::super::app::TICK
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
            Stage::Orbit(p) => playback_key(p, key, "t"),
            Stage::Shell(p) => playback_key(p, key, "t"),
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
            Stage::Orbit(p) => Some(format!("t = {:.2}", p.t)),
            Stage::Shell(p) => Some(format!("t = {:.2}", p.t)),
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
                    cells.push(Cell::fixed(vec![label(" I₃/I₁ = "), value(fmt(r))]));
                }
                let lead = if cells.is_empty() {
                    " Ω₀ = "
                } else {
                    "Ω₀ = "
                };
                cells.push(Cell::fixed(vec![
                    label(lead),
                    value(format!("({}, {}, {})", fmt(w[0]), fmt(w[1]), fmt(w[2]))),
                ]));
                let method = match settings.top() {
                    super::super::app::Top::Full(_) => "physical, forward".to_string(),
                    _ => settings.method().title().to_string(),
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
                cells.push(Cell::fixed(vec![super::super::view::status(app)]));
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
            Span::styled(format!("{}/s", WARPS[warp]), theme::value()),
        ]),
        Cell::fixed(vec![playback_status(paused)]),
    ]
}

/// "paused" or "running", as the live view shows its clock.
pub fn playback_status(paused: bool) -> Span<'static> {
    if paused {
        Span::styled(" paused ", theme::status(true))
    } else {
        Span::styled(" running ", theme::status(false))
    }
}

fn playback_key<T: Send + 'static>(
    p: &mut Playback<T>,
    key: SceneKey,
    unit: &str,
) -> (String, bool) {
    match key {
        SceneKey::Pause => {
            p.paused = !p.paused;
            if p.paused {
                (format!("scene paused at {unit} = {:.2}", p.t), false)
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
                    (format!("scene warp {}/s", WARPS[w]), false)
                }
                None => ("the warp is already at its end".into(), true),
            }
        }
        SceneKey::Step => ("this scene is computed ahead: p pauses, r restarts".into(), true),
        SceneKey::Log | SceneKey::Method | SceneKey::NextModel => (
            "this scene has one view and its methods are fixed: p pauses, r restarts, + and - set the warp".into(),
            true,
        ),
    }
}

/// Draw the orbit scene in `area`.
pub fn draw_orbit(frame: &mut Frame, area: Rect, p: &Playback<OrbitRuns>) {
    let runs = match p.data() {
        None => return computing(frame, area, "the orbits"),
        Some(Err(e)) => return failed(frame, area, e),
        Some(Ok(runs)) => runs,
    };
    let t = p.t();
    let shown: Vec<&OrbitSample> = runs.ll.iter().take_while(|s| s.t <= t).collect();
    let now = shown.last().copied().or(runs.ll.first());
    let [left, right] = if area.width >= 100 {
        Layout::horizontal([Constraint::Percentage(60), Constraint::Percentage(40)]).areas(area)
    } else {
        Layout::vertical([Constraint::Fill(3), Constraint::Length(7)]).areas(area)
    };
    let block = panel(" Landau–Lifshitz: the orbit decays, r³ = r₀³ − 6τ₀t (2.9) ");
    let inner = block.inner(left);
    frame.render_widget(block, left);
    let [pictures, numbers] =
        Layout::vertical([Constraint::Fill(1), Constraint::Length(3)]).areas(inner);
    let [plane, radius] =
        Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)])
            .areas(pictures);
    // The orbit in its plane: the trail and the charge now.
    let trail: Vec<(f64, f64)> = shown
        .iter()
        .map(|s| (s.position[0], s.position[1]))
        .collect();
    let here = now
        .map(|s| vec![(s.position[0], s.position[1])])
        .unwrap_or_default();
    // The whole orbit (radius 1) in view, round: a cell is two Braille dots
    // wide and four tall, so x spans w/(2h) of y's span per cell ratio.
    let aspect = f64::from(plane.width.max(1)) / (2.0 * f64::from(plane.height.max(1)));
    let (half_w, half_h) = if aspect >= 1.0 {
        (1.1 * aspect, 1.1)
    } else {
        (1.1, 1.1 / aspect)
    };
    frame.render_widget(
        Canvas::default()
            .marker(Marker::Braille)
            .x_bounds([-half_w, half_w])
            .y_bounds([-half_h, half_h])
            .paint(move |ctx| {
                ctx.draw(&Points::new(&trail, theme::TRAIL));
                ctx.draw(&Points::new(&here, theme::MOMENTUM));
                ctx.print(0.0, 0.0, Span::styled("+", theme::key()));
            }),
        plane,
    );
    // r(t) against the averaged closed form.
    let r_data: Vec<(f64, f64)> = shown.iter().map(|s| (s.t, s.r)).collect();
    let t_end = p.t_end;
    let closed: Vec<(f64, f64)> = (0..=100)
        .map(|i| {
            let t = t_end * f64::from(i) / 100.0;
            (t, coulomb_circular_radius(runs.tau0, 1.0, t))
        })
        .collect();
    let chart = Chart::new(vec![
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(theme::frame())
            .data(&closed),
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(theme::OMEGA[2]))
            .data(&r_data),
    ])
    .block(Block::new().title(Line::from(vec![
        Span::styled("r(t): ", theme::title()),
        Span::styled("━run ", Style::new().fg(theme::OMEGA[2])),
        Span::styled("━(2.9) averaged", theme::frame()),
    ])))
    .x_axis(time_axis(t_end))
    .y_axis(value_axis([0.0, 1.05], ["0".into(), "1".into()]));
    frame.render_widget(chart, radius);
    let n = now.map_or(String::new(), |s| {
        format!(
            "t = {:.2}   r = {}   (2.9): {}   L = {}   E = {}",
            s.t,
            spintop::numbers::fmt_num(s.r),
            spintop::numbers::fmt_num(coulomb_circular_radius(runs.tau0, 1.0, s.t)),
            spintop::numbers::fmt_num(s.l),
            spintop::numbers::fmt_num(s.energy)
        )
    });
    frame.render_widget(
        Paragraph::new(vec![
            Line::from(Span::styled(n, theme::value())),
            Line::from(Span::styled(
                format!(
                    "collapse by the averaged law at t_c = r₀³/(6τ₀) = {}",
                    spintop::numbers::fmt_num(runs.collapse)
                ),
                theme::label(),
            )),
        ])
        .wrap(Wrap { trim: true }),
        numbers,
    );
    // The forward Abraham–Lorentz run: its runaway, in numbers.
    let block = panel(" Abraham–Lorentz (2.5), forward: runs away ");
    let inner = block.inner(right);
    frame.render_widget(block, right);
    let mut lines = vec![Line::from(Span::styled(
        "From the Newtonian start v̇ = F/m the third-order equation has a mode that grows as e^(t/τ₀).",
        theme::label(),
    ))];
    match &runs.forward.runaway {
        Some(r) => {
            lines.push(Line::from(Span::styled(
                format!(
                    "runaway at t = {} ({} τ₀): |v̇ − F| passed {} |F(r₀)|",
                    spintop::numbers::fmt_num(r.t),
                    spintop::numbers::fmt_num(r.t / runs.tau0),
                    spintop::numbers::fmt_num(r.threshold)
                ),
                theme::error(),
            )));
            lines.push(Line::from(Span::styled(
                format!(
                    "growth rate {} against 1/τ₀ = {}",
                    r.growth_rate.map_or("—".into(), spintop::numbers::fmt_num),
                    spintop::numbers::fmt_num(r.predicted_rate)
                ),
                theme::value(),
            )));
        }
        None => lines.push(Line::from("no runaway within the run")),
    }
    lines.push(Line::from(Span::styled(
        "Its physical solution is found backward in time: spintop orbit --force al",
        theme::label(),
    )));
    frame.render_widget(Paragraph::new(lines).wrap(Wrap { trim: true }), inner);
}

/// Draw the shell scene in `area`.
pub fn draw_shell(frame: &mut Frame, area: Rect, p: &Playback<Vec<ShellRun>>) {
    let runs = match p.data() {
        None => return computing(frame, area, "the delay equation"),
        Some(Err(e)) => return failed(frame, area, e),
        Some(Ok(runs)) => runs,
    };
    let parts = if area.width >= 100 {
        Layout::horizontal([Constraint::Ratio(1, 2); 2]).split(area)
    } else {
        Layout::vertical([Constraint::Ratio(1, 2); 2]).split(area)
    };
    for (run, part) in runs.iter().zip(parts.iter()) {
        draw_shell_run(frame, *part, run, p.t());
    }
}

fn draw_shell_run(frame: &mut Frame, area: Rect, run: &ShellRun, t: Real) {
    let m = run.model;
    let stable = m.m0() > m.m_em();
    let title = format!(
        " shell δ = {}, τ₀ = {}: {} ",
        spintop::numbers::fmt_param(m.delta()),
        spintop::numbers::fmt_param(m.tau0()),
        if stable {
            "m₀ > mₑₘ, stable"
        } else {
            "mₑₘ > m₀, unstable"
        }
    );
    let block = panel(&title);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let [chart_area, numbers] =
        Layout::vertical([Constraint::Fill(1), Constraint::Length(2)]).areas(inner);
    let shown: Vec<&ShellSample> = run.samples.iter().take_while(|s| s.t <= t).collect();
    let dev = |s: &ShellSample| s.z_minus_z_al[0].hypot(s.z_minus_z_al[1]);
    let data: Vec<(f64, f64)> = shown
        .iter()
        .filter(|s| dev(s) > 0.0)
        .map(|s| (s.t, dev(s).log10()))
        .collect();
    let all: Vec<f64> = run
        .samples
        .iter()
        .map(dev)
        .filter(|d| *d > 0.0)
        .map(f64::log10)
        .collect();
    let lo = all.iter().copied().fold(f64::INFINITY, f64::min).floor();
    let hi = all.iter().copied().fold(f64::NEG_INFINITY, f64::max).ceil();
    let (lo, hi) = if lo.is_finite() && hi > lo {
        (lo, hi)
    } else {
        (-16.0, 0.0)
    };
    let t_end = run.samples.last().map_or(SHELL_T_END, |s| s.t.max(1.0));
    let chart = Chart::new(vec![
        Dataset::default()
            .marker(Marker::Braille)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(if stable {
                theme::OMEGA[1]
            } else {
                theme::OMEGA[0]
            }))
            .data(&data),
    ])
    .block(Block::new().title(Span::styled(
        "log₁₀|Z − Z_AL|: the shell against the point charge",
        theme::title(),
    )))
    .x_axis(time_axis(t_end))
    .y_axis(value_axis(
        [lo, hi],
        [format!("{lo:.0}"), format!("{hi:.0}")],
    ));
    frame.render_widget(chart, chart_area);
    let growth = match m.growth_rate() {
        Some(g) => format!(
            "grows at {} (ln(mₑₘ/m₀)/δ = {})",
            spintop::numbers::fmt_num(g),
            spintop::numbers::fmt_num((m.m_em() / m.m0()).abs().ln() / m.delta())
        ),
        None => "every mode decays: it stays near the point charge".into(),
    };
    let mut text = format!(
        "mₑₘ = {}, m₀ = {}; {growth}",
        spintop::numbers::fmt_num(m.m_em()),
        spintop::numbers::fmt_num(m.m0())
    );
    if let Some(e) = &run.ended
        && shown.len() == run.samples.len()
    {
        text.push_str(&format!("; stopped: {e}"));
    }
    frame.render_widget(
        Paragraph::new(Span::styled(text, theme::value())).wrap(Wrap { trim: true }),
        numbers,
    );
}

/// A time axis from 0 to `t_end`, labelled at its ends.
fn time_axis(t_end: Real) -> Axis<'static> {
    Axis::default()
        .style(theme::frame())
        .bounds([0.0, t_end])
        .labels(["0".to_string(), format!("{t_end:.0}")])
}

/// A value axis over `bounds`, labelled at its ends.
fn value_axis(bounds: [Real; 2], labels: [String; 2]) -> Axis<'static> {
    Axis::default()
        .style(theme::frame())
        .bounds(bounds)
        .labels(labels)
}

fn panel(title: &str) -> Block<'static> {
    Block::bordered()
        .border_type(BorderType::Rounded)
        .border_style(theme::frame())
        .title(Span::styled(title.to_string(), theme::title()))
}

fn computing(frame: &mut Frame, area: Rect, what: &str) {
    frame.render_widget(
        Paragraph::new(Span::styled(format!(" computing {what}…"), theme::label())),
        area,
    );
}

fn failed(frame: &mut Frame, area: Rect, why: &str) {
    frame.render_widget(
        Paragraph::new(Span::styled(
            format!(" the scene failed: {why}"),
            theme::error(),
        ))
        .wrap(Wrap { trim: true }),
        area,
    );
}
