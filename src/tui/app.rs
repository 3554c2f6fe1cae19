//! The state of the live view and the one function that changes it.
//!
//! [`App`] owns the [`Simulation`]s of one [`Top`]: for a symmetric top two
//! started from the same parameters (the truncated model on the left, the
//! reduced one on the right); for a general (asymmetric) top one, the
//! truncated ALE (3.3), which has no closed form and is integrated. It also
//! owns what the view shows, and the mode. Keys become [`Command`]s;
//! [`App::apply`] is the only place a command changes anything. Wall-clock
//! time enters through [`App::advance_wall`], which turns it into a whole
//! number of fixed model steps of [`TICK`] (never one model step per frame),
//! so the models do not depend on the frame rate.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `ratio` | I₃/I₁ | moment ratio of the symmetric top | – |
//! | `inertia`, `dipole` | I, d | principal moments and body dipole of a general top | κ = 1 units |
//! | `omega0` | Ω₀ | initial body angular velocity | 1/τ |
//! | [`TICK`] | Δt | one model step of the view | τ |
//! | `warp` | – | model time per wall-clock second | τ/s |

use crate::math::{Real, Vec3};
use crate::numbers::{fmt_exact, fmt_num, parse_number};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::rigid_body::energy;
use crate::physics::rigid_body::lab_frame;
use crate::physics::symmetric_top::SymmetricTop;
use crate::scene::Scene;
use crate::scene::live::live_scene;
use crate::sim::{InitialState, MethodChoice, MethodOptions, Model, Sample, Simulation};
use std::collections::VecDeque;
use std::time::Duration;

/// Everything a key can ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `q`, Esc or Ctrl-C: leave.
    Quit,
    /// Space: pause or resume.
    TogglePause,
    /// `.` or →: one model step of Δt while paused.
    Step,
    /// `+`: a faster time warp.
    Faster,
    /// `-`: a slower time warp.
    Slower,
    /// `r`: restart both models at t = 0.
    Reset,
    /// `[`: lower I₃/I₁.
    RatioDown,
    /// `]`: raise I₃/I₁.
    RatioUp,
    /// ↑: select the previous Ω₀ component.
    SelectPrevious,
    /// ↓: select the next Ω₀ component.
    SelectNext,
    /// Enter: edit the selected Ω₀ component.
    StartEdit,
    /// A character typed into the edit field.
    Input(char),
    /// Backspace in the edit field.
    Backspace,
    /// ↑ in the edit field: add 0.01.
    NudgeUp,
    /// ↓ in the edit field: subtract 0.01.
    NudgeDown,
    /// Enter in the edit field: apply the value (or refuse it).
    Commit,
    /// Esc in the edit field: keep the old value.
    Cancel,
    /// `m`: the next method (closed form, RK4, DP5, DOP853).
    CycleMethod,
    /// `l`: log-time charts on or off.
    ToggleLogTime,
    /// `?`: the help overlay on or off.
    ToggleHelp,
}

/// One model step of the view, in units of τ: the size of every increment of
/// model time, and what `.` or → advances while paused.
pub const TICK: Real = 0.1;

/// [`TICK`] in thousandths of τ, for the exact integer accounting of the
/// wall clock (see [`App::advance_wall`]).
const TICK_MILLI_TAU: u128 = 100;

/// The time warps offered by `+` and `-`, in τ per wall-clock second.
pub const WARPS: [Real; 11] = [
    0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0,
];

/// Index into [`WARPS`] of the default, 10 τ/s: a precession period of the
/// figure parameters (about 50τ) takes five seconds.
pub const DEFAULT_WARP: usize = 4;

/// The width of the scrolling time window of the linear charts, in τ.
pub const WINDOW: Real = 200.0;

/// The step of `[` and `]` on I₃/I₁.
pub const RATIO_STEP: Real = 0.1;

/// The step of ↑ and ↓ on an Ω₀ component while it is edited, in 1/τ.
pub const NUDGE: Real = 0.01;

/// Keep one point in this many ticks for the scrolling charts.
///
/// NOTE: 200τ at Δt = 0.1τ is 2000 ticks; one in five leaves 400 points per
/// curve, more than twice the Braille resolution of a wide chart, and keeps
/// the drawing cost per frame small.
pub const RECENT_STRIDE: u64 = 5;

/// Points per decade kept for the log-time view.
///
/// NOTE: at t = 1000τ this spacing is 5.8τ, still about nine points per
/// precession period of the figure parameters, so late oscillations do not
/// alias into slow false waves.
pub const LOG_POINTS_PER_DECADE: Real = 400.0;

/// The longest trail kept for the hodograph and the top in space, in points.
pub const TRAIL_POINTS: usize = 3000;

/// A trail point is added once the curve has moved this far (relative to
/// [`Column::scale`] for the hodograph, in radians for the axis).
pub const TRAIL_SPACING: Real = 0.01;

/// Below this τ_f|Ω₀| the live view's physical column runs the reduced model:
/// the two differ by about (τ_f|Ω₀|)² = 1e-4 relative there, a fraction of a
/// character cell of the charts, while the backward shoot's work per unit of
/// time grows like 1/τ_f.
pub const STAND_IN_BELOW: Real = 1e-2;

/// How much wall-clock lag is kept as a backlog; anything older is dropped.
///
/// NOTE: when the machine cannot keep up (a very high warp with RK4), an
/// unbounded backlog would make every frame slower than the last. Dropping it
/// changes only how model time maps to wall time: each model step is still
/// exactly [`TICK`].
pub const MAX_LAG: Duration = Duration::from_millis(250);

/// The methods `m` cycles through: closed form, RK4, DP5, DOP853, Radau IIA 5.
pub const METHOD_CYCLE: [MethodChoice; 5] = [
    MethodChoice::Exact,
    MethodChoice::Rk4,
    MethodChoice::Dopri5,
    MethodChoice::Dop853,
    MethodChoice::Radau5,
];

/// The method after `method` in [`METHOD_CYCLE`] that `top` takes (a
/// general top has no closed form, so its cycle skips it).
pub fn next_method(method: MethodChoice, top: &Top) -> MethodChoice {
    let at = METHOD_CYCLE.iter().position(|m| *m == method).unwrap_or(0);
    (1..=METHOD_CYCLE.len())
        .map(|k| METHOD_CYCLE[(at + k) % METHOD_CYCLE.len()])
        .find(|m| top.check_method(*m).is_ok())
        .unwrap_or(method)
}

/// The top the view shows, and so its layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Top {
    /// A symmetric top: its truncated (4.2)–(4.4) and reduced (4.12)–(4.14)
    /// models side by side, each with its closed form.
    Symmetric(SymmetricTop),
    /// Any top: the truncated ALE (3.3), the reduced ALE and the physical
    /// solution of the full ALE (3.4), side by side (no closed forms).
    General(GeneralTop),
}

impl Top {
    /// The models the view runs, one per column.
    fn models(&self) -> Vec<Model> {
        match *self {
            Top::Symmetric(top) => vec![Model::Truncated(top), Model::Reduced(top)],
            Top::General(top) => vec![
                Model::General(top),
                Model::GeneralReduced(top),
                Model::GeneralFull(top),
            ],
        }
    }

    /// Refuse a method the columns that take one do not take (the full ALE's
    /// column always runs its physical solution), with the core's reason.
    pub fn check_method(&self, method: MethodChoice) -> Result<(), String> {
        self.models()
            .iter()
            .filter(|m| !m.is_full())
            .try_for_each(|m| m.check_method(method))
            .map_err(|e| e.to_string())
    }

    /// The unit of time: τ for the symmetric top (Section 4's unit), "u" for
    /// a general one, whose numbers are in units where κ = 2/(3c³) = 1.
    pub fn time_unit(&self) -> &'static str {
        self.models()[0].time_unit()
    }
}

/// The parameters the models start from, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    top: Top,
    omega0: [Real; 3],
    method: MethodChoice,
    warp: usize,
}

impl Default for Settings {
    /// The parameters of the paper's Figures 1 and 2: I₃/I₁ = 2/5,
    /// Ω₀ = (0, 0.1, 0.2)/τ, closed forms, 10 τ/s.
    fn default() -> Self {
        Self {
            top: Top::Symmetric(SymmetricTop::figure()),
            omega0: [0.0, 0.1, 0.2],
            method: MethodChoice::Exact,
            warp: DEFAULT_WARP,
        }
    }
}

impl Settings {
    /// Validate I₃/I₁, Ω₀ and the warp (one of [`WARPS`], in τ/s); the error
    /// is one line for the user.
    pub fn new(
        ratio: Real,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, String> {
        let top = SymmetricTop::new(ratio, 1.0).map_err(|e| e.to_string())?;
        Self::validated(Top::Symmetric(top), omega0, method, warp)
    }

    /// Validate the settings of a general top (one column, the truncated ALE
    /// (3.3)): Ω₀, an integrator (it has no closed form) and the warp.
    pub fn general(
        top: GeneralTop,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, String> {
        Self::validated(Top::General(top), omega0, method, warp)
    }

    /// The settings a top scene opens with (see [`crate::scene::live`]), at
    /// `warp` τ/s (the default when `None`), and the line the view opens with.
    pub fn for_scene(scene: &Scene, warp: Option<Real>) -> Result<(Self, String), String> {
        let live = live_scene(scene)?;
        let warp = warp.unwrap_or(WARPS[DEFAULT_WARP]);
        let settings = match live.model {
            Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
                Self::general(top, live.omega0, live.method, warp)?
            }
            Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => {
                Self::new(top.ratio(), live.omega0, live.method, warp)?
            }
        };
        Ok((settings, live.note))
    }

    fn validated(
        top: Top,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, String> {
        top.check_method(method)?;
        check_omega0(omega0)?;
        let warp = WARPS.iter().position(|w| *w == warp).ok_or_else(|| {
            let list: Vec<String> = WARPS.iter().map(|w| w.to_string()).collect();
            format!("--warp must be one of {} (tau per second)", list.join(", "))
        })?;
        Ok(Self {
            top,
            omega0,
            method,
            warp,
        })
    }

    /// The top.
    pub fn top(&self) -> &Top {
        &self.top
    }

    /// True for a general top (one column, no closed form).
    pub fn is_general(&self) -> bool {
        matches!(self.top, Top::General(_))
    }

    /// I₃/I₁ of a symmetric top; `None` for a general one.
    pub fn ratio(&self) -> Option<Real> {
        match self.top {
            Top::Symmetric(top) => Some(top.ratio()),
            Top::General(_) => None,
        }
    }

    /// Ω₀, body frame, in 1/τ.
    pub fn omega0(&self) -> [Real; 3] {
        self.omega0
    }

    /// The method.
    pub fn method(&self) -> MethodChoice {
        self.method
    }

    /// The time warp, in τ per wall-clock second.
    pub fn warp(&self) -> Real {
        WARPS[self.warp]
    }
}

/// Refuse an Ω₀ the simulation would refuse, with the simulation's reason.
fn check_omega0(omega0: [Real; 3]) -> Result<InitialState, String> {
    InitialState::new(Vec3::from(omega0), EulerAngles::new(0.0, 0.0, 0.0))
        .map_err(|e| e.to_string())
}

/// The most characters the Ω₀ edit field takes (a double needs at most 24).
pub const EDIT_LIMIT: usize = 32;

/// What `?` shows and what an Ω₀ edit holds.
#[derive(Clone, Debug, PartialEq)]
pub enum Mode {
    /// The main screen.
    Normal,
    /// The help overlay.
    Help,
    /// Typing a new value for one component of Ω₀.
    Edit {
        /// 0, 1 or 2 for Ω₁₀, Ω₂₀, Ω₃₀.
        component: usize,
        /// The text typed so far.
        buffer: String,
        /// The buffer still holds the old value: the first character typed
        /// replaces it (arrows and Backspace edit it instead).
        pristine: bool,
    },
    /// Quit was asked for; the loop ends.
    Quitting,
}

/// What the view shows (and nothing about the models).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct View {
    /// The charts use log₁₀ t on the x axis (whole run) instead of a scrolling
    /// linear window.
    pub log_time: bool,
    /// The Ω₀ component that ↑/↓ selected and Enter edits (0, 1, 2).
    pub selected: usize,
}

/// A one-line message under the header.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// The text.
    pub text: String,
    /// A refusal (drawn as an error) rather than a confirmation.
    pub is_error: bool,
}

/// One point of a curve: t, Ω and Ω⊥, copied from a [`Sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// t, in τ.
    pub t: Real,
    /// Body-frame Ω, in 1/τ.
    pub omega: [Real; 3],
    /// Ω⊥, in 1/τ.
    pub omega_perp: Real,
}

impl From<&Sample> for Point {
    fn from(s: &Sample) -> Self {
        Self {
            t: s.t,
            omega: s.omega,
            omega_perp: s.omega_perp,
        }
    }
}

/// One model with its history: one column of the screen.
#[derive(Clone, Debug)]
pub struct Column {
    sim: Simulation,
    omega0: Vec3,
    scale: Real,
    start: Sample,
    recent: VecDeque<Point>,
    log: Vec<Point>,
    next_log_t: Real,
    omega_trail: VecDeque<[Real; 3]>,
    axis_trail: VecDeque<[Real; 3]>,
    failure: Option<String>,
    /// Why this column runs a lighter model than its title's (the physical
    /// solution of a top whose τ_f|Ω₀| is so small that it is the reduced
    /// model to the view's resolution).
    stand_in: Option<String>,
}

impl Column {
    fn new(model: Model, method: MethodChoice, omega0: [Real; 3]) -> Result<Self, String> {
        // Model no more than the view can show: the physical solution of a
        // general top differs from its reduced model by O((τ_f|Ω|)²)
        // relative, and costs work in proportion to 1/τ_f per unit of time.
        let mut stand_in = None;
        let mut model = model;
        if let Model::GeneralFull(top) = model {
            let small = crate::sim::physical::general::fast_time(&top) * Vec3::from(omega0).norm();
            if small < STAND_IN_BELOW {
                stand_in = Some(format!(
                    "τ_f|Ω₀| = {}: the physical solution is the reduced model to about {}, so the reduced model stands in",
                    fmt_num(small),
                    fmt_num(small * small)
                ));
                model = Model::GeneralReduced(top);
            }
        }
        // The full ALE's physical solution has one method (backward
        // shooting, tabulated ahead chunk by chunk); `m` changes the others.
        let choice = if model.is_full() {
            MethodChoice::Auto
        } else {
            method
        };
        let inertia = model.inertia();
        let initial =
            InitialState::new(Vec3::from(omega0), lab_frame(&inertia, &Vec3::from(omega0)))
                .map_err(|e| e.to_string())?;
        let sim = Simulation::new(model, choice, MethodOptions::default(), initial, None)
            .map_err(|e| e.to_string())?;
        let start = *sim.current();
        let mut column = Self {
            scale: plot_scale(&model, omega0),
            start,
            sim,
            omega0: Vec3::from(omega0),
            recent: VecDeque::with_capacity((WINDOW / TICK) as usize / RECENT_STRIDE as usize + 2),
            log: Vec::new(),
            next_log_t: TICK,
            omega_trail: VecDeque::with_capacity(TRAIL_POINTS),
            axis_trail: VecDeque::with_capacity(TRAIL_POINTS),
            failure: None,
            stand_in,
        };
        column.recent.push_back(Point::from(&start));
        column.omega_trail.push_back(start.omega);
        column.axis_trail.push_back(axis_of(&start));
        Ok(column)
    }

    /// Advance to tick `k` (t = k·Δt); a failure stops this column only.
    fn advance(&mut self, k: u64, t: Real) {
        if self.failure.is_some() {
            return;
        }
        match self.sim.advance_to(t) {
            Ok(sample) => {
                let sample = *sample;
                self.record(k, &sample);
            }
            Err(e) => {
                self.failure = Some(format!(
                    "{e}; m switches the method, r restarts, a smaller Ω₀ helps"
                ))
            }
        }
    }

    fn record(&mut self, k: u64, s: &Sample) {
        let point = Point::from(s);
        if k.is_multiple_of(RECENT_STRIDE) {
            self.recent.push_back(point);
        }
        while self.recent.front().is_some_and(|p| p.t < s.t - WINDOW) {
            self.recent.pop_front();
        }
        if s.t >= self.next_log_t {
            self.log.push(point);
            self.next_log_t = s.t * (10.0 as Real).powf(1.0 / LOG_POINTS_PER_DECADE);
        }
        let scale = self.scale();
        push_trail(&mut self.omega_trail, s.omega, TRAIL_SPACING * scale);
        push_trail(&mut self.axis_trail, axis_of(s), TRAIL_SPACING);
    }

    /// The simulation.
    pub fn sim(&self) -> &Simulation {
        &self.sim
    }

    /// The latest sample.
    pub fn current(&self) -> &Sample {
        self.sim.current()
    }

    /// The sample at t = 0.
    pub fn start(&self) -> &Sample {
        &self.start
    }

    /// The unit of time of this model's numbers: τ for the symmetric top,
    /// "u" (κ = 1 units) for a general one.
    pub fn time_unit(&self) -> &'static str {
        self.sim.model().time_unit()
    }

    /// `truncated`, `reduced` or `general`.
    pub fn name(&self) -> &'static str {
        self.sim.model().name()
    }

    /// Points of the last [`WINDOW`] (one in [`RECENT_STRIDE`] ticks), oldest first.
    pub fn recent(&self) -> &VecDeque<Point> {
        &self.recent
    }

    /// Points spaced evenly in log t ([`LOG_POINTS_PER_DECADE`]), t > 0, oldest first.
    pub fn log_points(&self) -> &[Point] {
        &self.log
    }

    /// The trail of Ω in the body frame, oldest first.
    pub fn omega_trail(&self) -> &VecDeque<[Real; 3]> {
        &self.omega_trail
    }

    /// The trail of the body axis O·e₃ (the symmetry axis of a symmetric
    /// top) in the lab frame, oldest first.
    pub fn axis_trail(&self) -> &VecDeque<[Real; 3]> {
        &self.axis_trail
    }

    /// Why this column runs a lighter model than asked (see [`STAND_IN_BELOW`]).
    pub fn stand_in(&self) -> Option<&str> {
        self.stand_in.as_deref()
    }

    /// Why this model stopped, if it did.
    pub fn failure(&self) -> Option<&str> {
        self.failure.as_deref()
    }

    /// The scale of the plots, in 1/τ: a bound on every component of Ω at
    /// all times (see [`plot_scale`]).
    pub fn scale(&self) -> Real {
        self.scale
    }

    /// |Ω − Ω_closed form| at the current time, in 1/τ, from the core's closed
    /// forms (4.7) and (4.15)–(4.16); `None` for the general top (3.3), which
    /// has no closed form.
    pub fn closed_form_error(&self) -> Option<Real> {
        let s = self.sim.current();
        let exact = self.sim.model().closed_form(&self.omega0, s.t)?;
        Some((s.omega_vec() - exact).norm())
    }
}

/// The scale of a column's plots (1 for a top at rest).
///
/// For the symmetric models it is the larger of Ω⊥₀ and |Ω₃₀|: neither model
/// ever makes Ω⊥ or |Ω₃| grow. For the general top it is max_i √(2E₀/I_i),
/// the most any |Ω_i| can reach at energy E₀ (from ½ I_i Ω_i² ≤ E).
///
/// NOTE: (3.3) does not make E fall monotonically for an asymmetric top: the
/// loss law's power is −|Ω × ḋ|² − (Ω̇ × d)·(Ω × ḋ), and the second term has
/// no sign (I = (1, 2, 2.5), d = (1, 0.5, 0.2), Ω₀ = (0.3, −0.2, 0.1): E
/// rises by 1.5e-6 between t = 10.9 and 11, while it falls from 0.0975 to
/// 0.0027 by t = 400). On the whole it drains, and E stayed below E₀ in
/// every run tried, so E₀ serves as the bound; this is only a drawing
/// scale, and a curve beyond it would be clipped, not wrong.
pub fn plot_scale(model: &Model, omega0: [Real; 3]) -> Real {
    let w = Vec3::from(omega0);
    let s = match model {
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            let e0 = energy(&top.inertia(), &w);
            (2.0 * e0 / top.inertia().min()).sqrt()
        }
        _ => w.x.hypot(w.y).max(w.z.abs()),
    };
    if s > 0.0 { s } else { 1.0 }
}

/// The body axis O·e₃ in the lab frame: the third column of O.
fn axis_of(s: &Sample) -> [Real; 3] {
    let r = &s.rotation;
    [r[0][2], r[1][2], r[2][2]]
}

fn push_trail(trail: &mut VecDeque<[Real; 3]>, p: [Real; 3], spacing: Real) {
    let far = trail.back().is_none_or(|q| {
        let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() > spacing
    });
    if far {
        if trail.len() == TRAIL_POINTS {
            trail.pop_front();
        }
        trail.push_back(p);
    }
}

/// The whole state of the live view.
#[derive(Clone, Debug)]
pub struct App {
    settings: Settings,
    columns: Vec<Column>,
    view: View,
    mode: Mode,
    paused: bool,
    ticks: u64,
    /// Model time owed, in thousandths of τ times nanoseconds of wall time.
    backlog: u128,
    message: Option<Message>,
}

impl App {
    /// Start the models of `settings` at t = 0, running.
    pub fn new(settings: Settings) -> Result<Self, String> {
        Ok(Self {
            columns: Self::columns_for(&settings)?,
            settings,
            view: View {
                log_time: false,
                selected: 0,
            },
            mode: Mode::Normal,
            paused: false,
            ticks: 0,
            backlog: 0,
            message: None,
        })
    }

    fn columns_for(settings: &Settings) -> Result<Vec<Column>, String> {
        settings
            .top
            .models()
            .into_iter()
            .map(|model| Column::new(model, settings.method, settings.omega0))
            .collect()
    }

    /// Show `text` under the header until the first key (how a scene opens).
    pub fn with_message(mut self, text: impl Into<String>) -> Self {
        self.inform(text);
        self
    }

    /// The parameters.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The columns: truncated (0) and reduced (1) for a symmetric top;
    /// truncated (3.3), reduced and physical (3.4) for a general top.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// "both models" or "the model": what a restart restarts.
    fn restarted(&self) -> &'static str {
        if self.settings.is_general() {
            "all three models restarted"
        } else {
            "both models restarted"
        }
    }

    /// What the view shows.
    pub fn view(&self) -> &View {
        &self.view
    }

    /// The mode.
    pub fn mode(&self) -> &Mode {
        &self.mode
    }

    /// True while paused.
    pub fn paused(&self) -> bool {
        self.paused
    }

    /// True once quit was asked for.
    pub fn should_quit(&self) -> bool {
        self.mode == Mode::Quitting
    }

    /// The message under the header, if any.
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }

    /// Model steps taken since the last (re)start.
    pub fn ticks(&self) -> u64 {
        self.ticks
    }

    /// Model time, ticks·Δt, in τ.
    pub fn time(&self) -> Real {
        self.ticks as Real * TICK
    }

    /// Turn elapsed wall-clock time into whole model steps: the time is
    /// accumulated (times the warp) into a backlog, and every whole [`TICK`]
    /// of it is stepped. Returns the number of steps taken. Nothing happens
    /// while paused.
    ///
    /// NOTE: the backlog is kept in integers (nanoseconds × thousandths of
    /// τ per second), so the number of steps after a total wall time W is
    /// exactly ⌊W·warp/Δt⌋ however W was cut into frames: the models do not
    /// depend on the frame rate, not even by one step of rounding.
    pub fn advance_wall(&mut self, elapsed: Duration) -> u64 {
        if self.paused {
            self.backlog = 0;
            return 0;
        }
        let warp = (self.settings.warp() * 1000.0).round() as u128;
        let per_tick = TICK_MILLI_TAU * 1_000_000_000;
        // What is left over is always less than one tick, so a frame shorter
        // than MAX_LAG is never cut, at any warp.
        let cap = MAX_LAG.as_nanos() * warp + per_tick;
        self.backlog = (self.backlog + elapsed.as_nanos() * warp).min(cap);
        let n = (self.backlog / per_tick) as u64;
        self.backlog %= per_tick;
        self.advance_ticks(n);
        n
    }

    /// Advance every model by `n` model steps of [`TICK`].
    /// Once every model has stopped (a numerical failure), the clock stops
    /// with them: the header's t is the time they stopped at.
    pub fn advance_ticks(&mut self, n: u64) {
        for _ in 0..n {
            if self.columns.iter().all(|c| c.failure().is_some()) {
                self.backlog = 0;
                break;
            }
            self.ticks += 1;
            let t = self.time();
            for column in &mut self.columns {
                column.advance(self.ticks, t);
            }
        }
    }

    /// Restart the models from the settings, keeping the view and the pause.
    fn restart(&mut self) {
        // Settings are validated before they are stored, so this cannot fail;
        // if it ever did, the old models keep running and the reason is shown.
        match Self::columns_for(&self.settings) {
            Ok(columns) => {
                self.columns = columns;
                self.ticks = 0;
                self.backlog = 0;
            }
            Err(e) => self.refuse(e),
        }
    }

    fn inform(&mut self, text: impl Into<String>) {
        self.message = Some(Message {
            text: text.into(),
            is_error: false,
        });
    }

    fn refuse(&mut self, text: impl Into<String>) {
        self.message = Some(Message {
            text: text.into(),
            is_error: true,
        });
    }

    /// Try new settings: on success restart the models, else keep the old
    /// ones and say why.
    fn change(&mut self, candidate: Result<Settings, String>, what: String) -> bool {
        match candidate.and_then(|s| Self::columns_for(&s).map(|c| (s, c))) {
            Ok((settings, columns)) => {
                self.settings = settings;
                self.columns = columns;
                self.ticks = 0;
                self.backlog = 0;
                let restarted = self.restarted();
                self.inform(format!("{what}: {restarted}"));
                true
            }
            Err(e) => {
                self.refuse(format!("refused: {e}"));
                false
            }
        }
    }

    /// Apply one command: the only place the state changes (besides the clock).
    pub fn apply(&mut self, command: Command) {
        self.message = None;
        match command {
            Command::Quit => self.mode = Mode::Quitting,
            Command::ToggleHelp => {
                self.mode = match self.mode {
                    Mode::Help => Mode::Normal,
                    _ => Mode::Help,
                }
            }
            Command::TogglePause => {
                self.paused = !self.paused;
                self.backlog = 0;
                if self.paused {
                    let u = self.settings.top().time_unit();
                    self.inform(format!(
                        "paused: . or → steps Δt = {TICK}{u}, space resumes"
                    ));
                }
            }
            Command::Step => {
                if self.paused {
                    self.advance_ticks(1);
                } else {
                    self.refuse("stepping works while paused: press space first");
                }
            }
            Command::Faster | Command::Slower => {
                let faster = command == Command::Faster;
                let next = if faster {
                    self.settings
                        .warp
                        .checked_add(1)
                        .filter(|i| *i < WARPS.len())
                } else {
                    self.settings.warp.checked_sub(1)
                };
                match next {
                    Some(i) => {
                        self.settings.warp = i;
                        self.backlog = 0;
                        self.inform(format!("warp {} τ/s", WARPS[i]));
                    }
                    None => self.refuse(format!(
                        "the warp is already at its {} ({} τ/s)",
                        if faster { "fastest" } else { "slowest" },
                        self.settings.warp()
                    )),
                }
            }
            Command::Reset => {
                self.restart();
                let restarted = self.restarted();
                self.inform(format!("{restarted} at t = 0"));
            }
            Command::RatioDown | Command::RatioUp => {
                let Some(ratio) = self.settings.ratio() else {
                    self.refuse(
                        "[ and ] change I₃/I₁ of a symmetric top; this general top has three \
                         moments, set in its scene file",
                    );
                    return;
                };
                let sign = if command == Command::RatioUp {
                    1.0
                } else {
                    -1.0
                };
                // NOTE: stay on the grid of RATIO_STEP so that repeated presses
                // land on 0.4 and 0.5, not on 0.49999999999999994.
                let grid = (ratio / RATIO_STEP).round() + sign;
                let ratio = grid * RATIO_STEP;
                let ratio = (ratio * 1e12).round() / 1e12;
                let candidate = SymmetricTop::new(ratio, 1.0)
                    .map(|top| Settings {
                        top: Top::Symmetric(top),
                        ..self.settings
                    })
                    .map_err(|e| e.to_string());
                self.change(candidate, format!("I₃/I₁ = {ratio}"));
            }
            Command::CycleMethod => {
                let method = next_method(self.settings.method, &self.settings.top);
                let candidate = Ok(Settings {
                    method,
                    ..self.settings
                });
                self.change(candidate, format!("method {}", method.title()));
            }
            Command::ToggleLogTime => self.view.log_time = !self.view.log_time,
            Command::SelectPrevious => self.view.selected = (self.view.selected + 2) % 3,
            Command::SelectNext => self.view.selected = (self.view.selected + 1) % 3,
            Command::StartEdit => {
                let component = self.view.selected;
                self.mode = Mode::Edit {
                    component,
                    buffer: fmt_exact(self.settings.omega0[component]),
                    pristine: true,
                };
                self.inform(edit_hint(component));
            }
            Command::Input(c) => {
                if let Mode::Edit {
                    buffer,
                    component,
                    pristine,
                } = &mut self.mode
                {
                    if *pristine {
                        buffer.clear();
                        *pristine = false;
                    }
                    if buffer.len() < EDIT_LIMIT {
                        buffer.push(c);
                        let hint = edit_hint(*component);
                        self.inform(hint);
                    } else {
                        // Said, not silently dropped: a number needs far fewer.
                        self.refuse(format!(
                            "the field holds {EDIT_LIMIT} characters; Backspace edits, Enter applies"
                        ));
                    }
                }
            }
            Command::Backspace => {
                if let Mode::Edit {
                    buffer,
                    component,
                    pristine,
                } = &mut self.mode
                {
                    *pristine = false;
                    buffer.pop();
                    let hint = edit_hint(*component);
                    self.inform(hint);
                }
            }
            Command::NudgeUp | Command::NudgeDown => {
                if let Mode::Edit {
                    buffer,
                    component,
                    pristine,
                } = &mut self.mode
                {
                    let component = *component;
                    match parse_number(buffer) {
                        Ok(x) => {
                            let d = if command == Command::NudgeUp {
                                NUDGE
                            } else {
                                -NUDGE
                            };
                            let mut y = x + d;
                            // NOTE: snap to the grid of NUDGE (0.1 + 0.01 would
                            // print as 0.11000000000000001), where the grid is
                            // finer than a double's spacing.
                            if y.abs() < 1e6 {
                                y = ((y / NUDGE).round() * NUDGE * 1e6).round() / 1e6;
                            }
                            *buffer = fmt_exact(y);
                            *pristine = false;
                            self.inform(edit_hint(component));
                        }
                        Err(e) => self.refuse(format!("refused: {e}")),
                    }
                }
            }
            Command::Commit => {
                if let Mode::Edit {
                    component, buffer, ..
                } = &self.mode
                {
                    let component = *component;
                    let value = parse_number(buffer).map_err(|e| {
                        if buffer.trim().is_empty() {
                            "type a number first".to_string()
                        } else {
                            e
                        }
                    });
                    let candidate = value.and_then(|x| {
                        let mut omega0 = self.settings.omega0;
                        omega0[component] = x;
                        check_omega0(omega0).map(|_| Settings {
                            omega0,
                            ..self.settings
                        })
                    });
                    let what = format!("Ω{}₀ = {}", SUBSCRIPTS[component], buffer.trim());
                    if self.change(candidate, what) {
                        self.mode = Mode::Normal;
                    }
                }
            }
            Command::Cancel => {
                if matches!(self.mode, Mode::Edit { .. }) {
                    self.mode = Mode::Normal;
                    self.inform("edit cancelled");
                }
            }
        }
    }
}

/// Subscript digits for Ω₁, Ω₂, Ω₃.
pub const SUBSCRIPTS: [char; 3] = ['₁', '₂', '₃'];

fn edit_hint(component: usize) -> String {
    format!(
        "editing Ω{}₀: type a number, ↑/↓ ±{NUDGE}, Enter applies, Esc cancels",
        SUBSCRIPTS[component]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    use approx::assert_relative_eq;

    #[test]
    fn paper_frame_puts_lab_z_along_l0() {
        for omega0 in [[0.0, 0.1, 0.2], [0.3, -0.2, 0.05], [0.1, 0.0, -0.4]] {
            for ratio in [0.4, 1.3, 2.0] {
                let top = SymmetricTop::new(ratio, 1.0).unwrap();
                let o = lab_frame(&top.inertia(), &Vec3::from(omega0)).to_rotation();
                let l_lab = o * top.inertia().component_mul(&Vec3::from(omega0));
                assert_relative_eq!(l_lab.x, 0.0, epsilon = 1e-15);
                assert_relative_eq!(l_lab.y, 0.0, epsilon = 1e-15);
                assert!(l_lab.z > 0.0);
            }
        }
    }

    #[test]
    fn tick_constants_agree() {
        assert_eq!(TICK_MILLI_TAU as Real / 1000.0, TICK);
        for w in WARPS {
            assert_eq!(
                (w * 1000.0).round() / 1000.0,
                w,
                "warps are whole thousandths"
            );
        }
    }

    #[test]
    fn wall_clock_becomes_whole_ticks_at_any_frame_rate() {
        // 0.2 s at 10 τ/s is 20 ticks, in one frame or in six uneven ones.
        let mut one = App::new(Settings::default()).unwrap();
        let mut many = one.clone();
        one.advance_wall(Duration::from_millis(200));
        for ms in [33, 34, 33, 50, 17, 33] {
            many.advance_wall(Duration::from_millis(ms));
        }
        assert_eq!(one.ticks(), 20);
        assert_eq!(many.ticks(), 20);
        // The models only ever see t = k·Δt, so equal tick counts give equal bits.
        assert_eq!(one.columns()[1].current(), many.columns()[1].current());
    }

    proptest::proptest! {
        #[test]
        fn any_cut_of_the_wall_clock_gives_the_same_ticks(
            frames in proptest::collection::vec(0u64..200_000_000, 1..40),
            warp in 0..WARPS.len(),
        ) {
            let settings = Settings { warp, ..Settings::default() };
            let mut app = App::new(settings).unwrap();
            // Frames shorter than MAX_LAG: the cap never drops anything.
            let total: u64 = frames.iter().sum();
            for ns in &frames {
                app.advance_wall(Duration::from_nanos(*ns));
            }
            let expected = u128::from(total) * (WARPS[warp] * 1000.0).round() as u128
                / (TICK_MILLI_TAU * 1_000_000_000);
            proptest::prop_assert_eq!(u128::from(app.ticks()), expected);
        }
    }

    #[test]
    fn backlog_is_capped() {
        let mut app = App::new(Settings::default()).unwrap();
        app.advance_wall(Duration::from_secs(100));
        // At most MAX_LAG of wall time (0.25 s · 10 τ/s = 2.5τ) plus one
        // tick is stepped.
        assert_eq!(app.ticks(), 26);
    }
}
