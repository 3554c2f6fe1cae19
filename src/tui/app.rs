//! The state of the live view and the one function that changes it.
//!
//! [`App`] shows the models of one [`Top`] side by side: for a symmetric top
//! the truncated model (left) and the reduced one (right), started from the
//! same parameters; for the full ALE (3.4) its physical solution beside its
//! forward run, which runs away; for a general (asymmetric) top the truncated
//! ALE (3.3), the reduced ALE and the physical solution of (3.4). It owns
//! what the view shows of each model (a [`Column`]), what the view shows, and
//! the mode; the models themselves are stepped by a [`Stepper`], on a thread
//! of their own in the terminal, so that no key waits on them. Keys become
//! [`Command`]s; [`App::apply`] is the only place a command changes
//! anything. Wall-clock time enters through [`App::advance_wall`], which
//! turns it into a whole number of fixed model steps of [`TICK`] (never one
//! model step per frame), so the models do not depend on the frame rate.
//! Settings whose work the view cannot draw live are refused when they are
//! entered ([`LIVE_STEPS_PER_SECOND`]), never started.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `ratio` | I₃/I₁ | moment ratio of the symmetric top | – |
//! | `inertia`, `dipole` | I, d | principal moments and body dipole of a general top | κ = 1 units |
//! | `omega0` | Ω₀ | initial body angular velocity | 1/τ |
//! | [`TICK`] | Δt | one model step of the view | τ |
//! | `warp` | – | model time per wall-clock second | τ/s |

use spintop::integrate::Stats;
use spintop::math::{Real, Vec3};
use spintop::numbers::{fmt_exact, parse_number};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::rigid_body::energy;
use spintop::physics::rigid_body::lab_frame;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::scene::Scene;
use spintop::scene::live::live_scene;
use spintop::sim::{InitialState, Method, MethodChoice, MethodOptions, Model, Sample, SimError};
use std::collections::VecDeque;
use std::time::Duration;

use super::stepper::{Plan, Progress, Report, Stepper, Stopped};

/// Everything a key can ask of the live view (and of the scene beside a
/// chapter of `spintop learn`).
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
    /// `r`: restart every model at t = 0.
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
    /// `m`: the next method (closed form, RK4, DP5, DOP853, Radau5, Taylor).
    CycleMethod,
    /// `l`: log-time charts on or off.
    ToggleLogTime,
    /// `?`: the help overlay on or off.
    ToggleHelp,
    /// Tab: the next model, where the screen shows one at a time.
    NextModel,
    /// The terminal's size changed (columns, rows).
    Resize(u16, u16),
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

/// The most model steps per wall-clock second the view takes on: settings
/// whose estimated work (the core's [`spintop::sim::cost::estimate`], summed
/// over the columns) is above it are refused when they are entered, with the
/// reason and a cheaper way, instead of being started.
///
/// NOTE: about what one core of a laptop steps per second in a release build
/// (a DOP853 step of the coupled Ω and orientation state takes about a
/// microsecond). Below it the models run on their own thread and the view
/// shows how far they lag when the machine is slower; far above it (Ω₃₀ = 10⁹
/// asks for 10¹⁰ steps per second) no machine would draw anything.
pub const LIVE_STEPS_PER_SECOND: Real = 1e6;

/// How far the forward run of the full ALE is tabulated, in τ: it runs away
/// within a few τ; this is the chart's window, where it would show no more.
pub const FORWARD_HORIZON: Real = WINDOW;

/// The methods `m` cycles through: closed form, RK4, DP5, DOP853, Radau IIA 5
/// and the Taylor method (every model the view steps takes it).
pub const METHOD_CYCLE: [MethodChoice; 6] = [
    MethodChoice::Exact,
    MethodChoice::Rk4,
    MethodChoice::Dopri5,
    MethodChoice::Dop853,
    MethodChoice::Radau5,
    MethodChoice::Taylor,
];

/// The method after `method` in [`METHOD_CYCLE`] that `top` takes (a
/// general top has no closed form, so its cycle skips it); `method` itself
/// when no column takes a method (the full ALE's two columns).
pub fn next_method(method: MethodChoice, top: &Top) -> MethodChoice {
    let at = METHOD_CYCLE.iter().position(|m| *m == method).unwrap_or(0);
    if !top.takes_a_method() {
        return method;
    }
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
    /// A symmetric top under the full ALE (3.4): its physical solution beside
    /// the same equation integrated forward, which runs away.
    Full(SymmetricTop),
    /// Any top: the truncated ALE (3.3), the reduced ALE and the physical
    /// solution of the full ALE (3.4), side by side (no closed forms).
    General(GeneralTop),
}

/// One column of a layout: its model, the method it always runs (`None`:
/// the one chosen with `m`) and the last time it can reach.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Slot {
    model: Model,
    fixed: Option<MethodChoice>,
    horizon: Option<Real>,
}

impl Top {
    /// The columns, left to right.
    fn slots(&self) -> Vec<Slot> {
        let slot = |model, fixed, horizon| Slot {
            model,
            fixed,
            horizon,
        };
        match *self {
            Top::Symmetric(top) => vec![
                slot(Model::Truncated(top), None, None),
                slot(Model::Reduced(top), None, None),
            ],
            Top::Full(top) => vec![
                slot(Model::Full(top), Some(MethodChoice::Auto), None),
                slot(
                    Model::Full(top),
                    Some(MethodChoice::Forward),
                    Some(FORWARD_HORIZON),
                ),
            ],
            // The full ALE's physical solution has one method (backward
            // shooting, tabulated ahead chunk by chunk).
            Top::General(top) => vec![
                slot(Model::General(top), None, None),
                slot(Model::GeneralReduced(top), None, None),
                slot(Model::GeneralFull(top), Some(MethodChoice::Auto), None),
            ],
        }
    }

    /// True when some column runs the method chosen with `m`.
    pub fn takes_a_method(&self) -> bool {
        self.slots().iter().any(|s| s.fixed.is_none())
    }

    /// Refuse a method the columns that take one do not take, with the
    /// core's reason.
    pub fn check_method(&self, method: MethodChoice) -> Result<(), String> {
        self.slots()
            .iter()
            .filter(|s| s.fixed.is_none())
            .try_for_each(|s| s.model.check_method(method))
            .map_err(|e| e.to_string())
    }

    /// The unit of time: τ for a symmetric top (Section 4's unit), "u" for a
    /// general one, whose numbers are in units where κ = 2/(3c³) = 1.
    pub fn time_unit(&self) -> &'static str {
        self.slots()[0].model.time_unit()
    }

    /// I₃/I₁ of a symmetric top; `None` for a general one.
    pub fn ratio(&self) -> Option<Real> {
        match self {
            Top::Symmetric(top) | Top::Full(top) => Some(top.ratio()),
            Top::General(_) => None,
        }
    }

    /// The same layout for a symmetric top of another I₃/I₁.
    fn with_ratio(&self, ratio: Real) -> Result<Top, String> {
        let top = SymmetricTop::new(ratio, 1.0).map_err(|e| e.to_string())?;
        match self {
            Top::Full(_) => Ok(Top::Full(top)),
            _ => Ok(Top::Symmetric(top)),
        }
    }

    /// How each column runs from `omega0` by `method`, and why a column
    /// runs a lighter model than its title's, if it does.
    fn plans(
        &self,
        method: MethodChoice,
        omega0: [Real; 3],
    ) -> Result<Vec<(Plan, Option<String>)>, String> {
        self.slots()
            .into_iter()
            .map(|slot| {
                // Model no more than the view can show: the physical solution
                // of a general top differs from its reduced model by
                // O((τ_f|Ω|)²) relative, and costs work in proportion to 1/τ_f
                // per unit of time.
                let mut stand_in = None;
                let mut model = slot.model;
                let mut fixed = slot.fixed;
                if let Model::GeneralFull(top) = model {
                    let small = spintop::sim::physical::general::fast_time(&top)
                        * Vec3::from(omega0).norm();
                    if small < STAND_IN_BELOW {
                        stand_in = Some(format!(
                            "τ_f|Ω₀| = {}: the physical solution is the reduced model to about {}, so the reduced model stands in",
                            spintop::numbers::fmt_num(small),
                            spintop::numbers::fmt_num(small * small)
                        ));
                        model = Model::GeneralReduced(top);
                        fixed = None;
                    }
                }
                let initial =
                    InitialState::new(Vec3::from(omega0), lab_frame(&model.inertia(), &Vec3::from(omega0)))
                        .map_err(|e| e.to_string())?;
                let plan = Plan {
                    model,
                    choice: fixed.unwrap_or(method),
                    initial,
                    horizon: slot.horizon,
                };
                Ok((plan, stand_in))
            })
            .collect()
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
    /// Validate I₃/I₁, Ω₀ and the warp (one of [`WARPS`], in τ/s), and that
    /// the view can step the models live; the error is one line for the user.
    pub fn new(
        ratio: Real,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, String> {
        let top = SymmetricTop::new(ratio, 1.0).map_err(|e| e.to_string())?;
        Self::validated(Top::Symmetric(top), omega0, method, warp)
    }

    /// Validate the settings of a general top (three columns: the truncated
    /// ALE (3.3), the reduced ALE, the physical solution of (3.4)): Ω₀, an
    /// integrator (it has no closed form) and the warp.
    pub fn general(
        top: GeneralTop,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, String> {
        Self::validated(Top::General(top), omega0, method, warp)
    }

    /// Validate the settings of a symmetric top under the full ALE (3.4):
    /// its physical solution beside its forward run.
    pub fn full(ratio: Real, omega0: [Real; 3], warp: Real) -> Result<Self, String> {
        let top = SymmetricTop::new(ratio, 1.0).map_err(|e| e.to_string())?;
        Self::validated(Top::Full(top), omega0, MethodChoice::Auto, warp)
    }

    /// The settings a top scene opens with (see [`spintop::scene::live`]), at
    /// `warp` τ/s (the default when `None`), and the line the view opens with.
    pub fn for_scene(scene: &Scene, warp: Option<Real>) -> Result<(Self, String), String> {
        let live = live_scene(scene)?;
        let warp = warp.unwrap_or(WARPS[DEFAULT_WARP]);
        let settings = match live.model {
            Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
                Self::general(top, live.omega0, live.method, warp)?
            }
            Model::Full(top) => Self::full(top.ratio(), live.omega0, warp)?,
            Model::Truncated(top) | Model::Reduced(top) => {
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
        let settings = Self {
            top,
            omega0,
            method,
            warp,
        };
        settings.check_live()?;
        Ok(settings)
    }

    /// The same settings at warp `WARPS[index]`, if the view can step them live.
    fn at_warp(&self, index: usize) -> Result<Self, String> {
        let settings = Self {
            warp: index,
            ..*self
        };
        settings.check_live()?;
        Ok(settings)
    }

    /// Refuse settings whose models the view cannot step live (see
    /// [`LIVE_STEPS_PER_SECOND`]), saying what costs so much and what
    /// would not.
    fn check_live(&self) -> Result<(), String> {
        let (total, costliest) = self.live_cost()?;
        if total <= LIVE_STEPS_PER_SECOND {
            return Ok(());
        }
        let u = self.top.time_unit();
        let what = costliest.map_or("the models".to_string(), |e| e.what);
        let warp = self.warp();
        // The work per second is proportional to the warp (or grows more
        // slowly): a slower warp that fits is named first.
        let slower = WARPS[..self.warp]
            .iter()
            .rev()
            .find(|w| total * **w / warp <= LIVE_STEPS_PER_SECOND);
        let cheaper = match slower {
            Some(w) => format!("at {w} {u}/s or slower it runs live (- slows down)"),
            None if self.top.ratio().is_some()
                && self.method != MethodChoice::Exact
                && self.top.takes_a_method()
                && Self {
                    method: MethodChoice::Exact,
                    ..*self
                }
                .check_live()
                .is_ok() =>
            {
                "the closed forms (m) take no steps, and a smaller |Ω₀| costs less".to_string()
            }
            None => "a smaller |Ω₀| costs less (the steps grow with it)".to_string(),
        };
        Err(format!(
            "{what} needs about {} steps a second at {warp} {u}/s, the view {LIVE_STEPS_PER_SECOND:.0e}; {cheaper}",
            spintop::numbers::fmt_count(total),
        ))
    }

    /// The steps per wall-clock second of every column (a column with a
    /// horizon is tabulated once: its whole cost counts), and the costliest
    /// column's estimate.
    fn live_cost(&self) -> Result<(Real, Option<spintop::sim::cost::Estimate>), String> {
        let omega0 = Vec3::from(self.omega0);
        let mut total = 0.0;
        let mut costliest: Option<spintop::sim::cost::Estimate> = None;
        for (plan, _) in self.top.plans(self.method, self.omega0)? {
            // The options the view's simulations run with (`tui::stepper`).
            let options = MethodOptions::default();
            let method = plan
                .model
                .method(plan.choice, &options)
                .map_err(|e| e.to_string())?;
            let t = plan.horizon.unwrap_or(self.warp());
            let Some(e) = spintop::sim::cost::estimate(&plan.model, method, &options, &omega0, t)
            else {
                continue;
            };
            // NaN (an overflowing estimate) counts as too much.
            let steps = if e.steps.is_nan() {
                Real::INFINITY
            } else {
                e.steps
            };
            total += steps;
            if costliest.as_ref().is_none_or(|c| c.steps < steps) {
                costliest = Some(spintop::sim::cost::Estimate { steps, ..e });
            }
        }
        Ok((total, costliest))
    }

    /// The top.
    pub fn top(&self) -> &Top {
        &self.top
    }

    /// True for a general top (three columns, no closed form).
    pub fn is_general(&self) -> bool {
        matches!(self.top, Top::General(_))
    }

    /// I₃/I₁ of a symmetric top; `None` for a general one.
    pub fn ratio(&self) -> Option<Real> {
        self.top.ratio()
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
    /// The model shown where the screen has room for one at a time.
    pub shown: usize,
    /// The terminal's size (columns, rows), as last reported.
    pub size: (u16, u16),
}

/// The smallest terminal the live view fits, in columns.
pub const MIN_WIDTH: u16 = 80;
/// The smallest terminal the live view fits, in rows.
pub const MIN_HEIGHT: u16 = 24;

impl View {
    /// True when the terminal is smaller than the layout needs: only quit is
    /// taken then (nothing else would be seen).
    pub fn too_small(&self) -> bool {
        self.size.0 < MIN_WIDTH || self.size.1 < MIN_HEIGHT
    }
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

/// One model as the view shows it: its latest sample and its history (the
/// model itself is stepped by the [`Stepper`]).
#[derive(Clone, Debug)]
pub struct Column {
    plan: Plan,
    method: Method,
    scale: Real,
    start: Sample,
    current: Sample,
    stats: Stats,
    last_step: Real,
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
    fn new(plan: Plan, stand_in: Option<String>) -> Result<Self, String> {
        let model = plan.model;
        let method = model
            .method(plan.choice, &MethodOptions::default())
            .map_err(|e| e.to_string())?;
        let initial = plan.initial;
        let start = Sample::new(0.0, &model.inertia(), &initial.rotation, &initial.omega);
        let mut column = Self {
            scale: plot_scale(&model, initial.omega.into()),
            method,
            start,
            current: start,
            stats: Stats::default(),
            last_step: 0.0,
            plan,
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

    /// Take tick `k`'s outcome; a failure stops this column only.
    fn take(&mut self, k: u64, outcome: Result<Progress, Stopped>) {
        if self.failure.is_some() {
            return;
        }
        match outcome {
            Ok(p) => {
                self.current = p.sample;
                self.stats = p.stats;
                self.last_step = p.last_step;
                self.record(k, &p.sample);
            }
            // The forward run is there to run away: said as what it shows.
            Err(Stopped::Sim(SimError::Runaway(r))) if self.is_forward() => {
                self.failure = Some(format!(
                    "ran away at t = {:.3}: it leaves the physical solution at {}/τ, an e-folding time of {}τ, as (3.4) does forward from any start",
                    r.t,
                    spintop::numbers::fmt_num(r.growth_rate),
                    spintop::numbers::fmt_num(1.0 / r.growth_rate)
                ));
            }
            Err(e) => self.stop(e.to_string()),
        }
    }

    /// Stop with the reason and what to do about it.
    fn stop(&mut self, why: String) {
        self.failure = Some(if self.is_forward() {
            // The forward run is there to run away: the reason says it all.
            why
        } else {
            format!("{why}; m switches the method, r restarts, a smaller Ω₀ helps")
        });
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

    /// Its name, its equations and their gist, for its title: ("reduced",
    /// "(4.12)–(4.14)", "Schott term kept").
    pub fn title(&self) -> (&'static str, &'static str, &'static str) {
        match (self.plan.model, self.method) {
            (Model::Truncated(_), _) => ("truncated", "(4.2)–(4.4)", "no Schott term"),
            (Model::Reduced(_), _) => ("reduced", "(4.12)–(4.14)", "Schott term kept"),
            (Model::GeneralReduced(_), _) => {
                ("reduced", "(3.4)", "Schott term kept, runaways removed")
            }
            (Model::Full(_) | Model::GeneralFull(_), Method::Forward) => {
                ("forward", "(3.4)", "the same start, integrated forward")
            }
            (Model::GeneralFull(_) | Model::Full(_), _) => {
                ("physical", "(3.4)", "its non-runaway solution, Ω̈ kept")
            }
            (Model::General(_), _) => ("truncated", "(3.3)", "no Schott term"),
        }
    }

    /// The model this column runs.
    pub fn model(&self) -> &Model {
        &self.plan.model
    }

    /// The method it runs.
    pub fn method(&self) -> Method {
        self.method
    }

    /// True for the forward run of the full ALE, which is there to run away.
    pub fn is_forward(&self) -> bool {
        self.method == Method::Forward
    }

    /// The start.
    pub fn initial(&self) -> &InitialState {
        &self.plan.initial
    }

    /// The work done so far (zero for the closed forms).
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// The last accepted step (0 for a closed form, or before the first).
    pub fn last_step(&self) -> Real {
        self.last_step
    }

    /// The latest sample.
    pub fn current(&self) -> &Sample {
        &self.current
    }

    /// The sample at t = 0.
    pub fn start(&self) -> &Sample {
        &self.start
    }

    /// The unit of time of this model's numbers: τ for the symmetric top,
    /// "u" (κ = 1 units) for a general one.
    pub fn time_unit(&self) -> &'static str {
        self.plan.model.time_unit()
    }

    /// `truncated`, `reduced`, `general`, …
    pub fn name(&self) -> &'static str {
        self.plan.model.name()
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
    /// forms (4.7) and (4.15)–(4.16); `None` for a model with no closed form.
    pub fn closed_form_error(&self) -> Option<Real> {
        let s = &self.current;
        let exact = self.plan.model.closed_form(&self.plan.initial.omega, s.t)?;
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

/// How fast the models actually went, measured over about a second of wall time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Pace {
    wall: Duration,
    ticks: u64,
    /// Model time per wall-clock second over the last full window, once the
    /// models lagged the clock in it.
    behind: Option<Real>,
    lagged: bool,
}

/// The whole state of the live view.
#[derive(Debug)]
pub struct App {
    settings: Settings,
    columns: Vec<Column>,
    view: View,
    mode: Mode,
    paused: bool,
    /// Ticks done (the models' time is ticks·Δt).
    ticks: u64,
    /// Ticks asked of the stepper.
    requested: u64,
    /// Model time owed, in thousandths of τ times nanoseconds of wall time.
    backlog: u128,
    message: Option<Message>,
    stepper: Stepper,
    pace: Pace,
}

impl App {
    /// Start the models of `settings` at t = 0, running, stepped on this
    /// thread whenever asked (see [`App::in_background`]).
    pub fn new(settings: Settings) -> Result<Self, String> {
        Self::start(settings, false)
    }

    /// [`App::new`] with the models built and stepped on a thread of their
    /// own from the start.
    pub fn background(settings: Settings) -> Result<Self, String> {
        Self::start(settings, true)
    }

    fn start(settings: Settings, background: bool) -> Result<Self, String> {
        let (columns, stepper) = Self::columns_for(&settings, background)?;
        let mut app = Self {
            columns,
            settings,
            view: View {
                log_time: false,
                selected: 0,
                shown: 0,
                size: (MIN_WIDTH, MIN_HEIGHT),
            },
            mode: Mode::Normal,
            paused: false,
            ticks: 0,
            requested: 0,
            backlog: 0,
            message: None,
            stepper,
            pace: Pace::default(),
        };
        app.absorb();
        Ok(app)
    }

    /// The same view with its models stepped on a thread of their own, so
    /// that drawing and keys never wait for them (the terminal loop's way).
    pub fn in_background(mut self) -> Self {
        self.absorb();
        let stepper = std::mem::replace(&mut self.stepper, Stepper::new(Vec::new(), TICK, false));
        let (stepper, left) = stepper.into_background();
        self.stepper = stepper;
        self.take(left);
        self
    }

    /// True when the models run on a thread of their own.
    pub fn is_background(&self) -> bool {
        self.stepper.is_background()
    }

    fn columns_for(
        settings: &Settings,
        background: bool,
    ) -> Result<(Vec<Column>, Stepper), String> {
        let plans = settings.top.plans(settings.method, settings.omega0)?;
        let columns = plans
            .iter()
            .map(|(plan, stand_in)| Column::new(plan.clone(), stand_in.clone()))
            .collect::<Result<Vec<_>, _>>()?;
        let stepper = Stepper::new(
            plans.into_iter().map(|(p, _)| p).collect(),
            TICK,
            background,
        );
        Ok((columns, stepper))
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
    /// physical (0) and forward (1) for the full ALE; truncated (3.3),
    /// reduced and physical (3.4) for a general top.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// "both models" or "all three models": what a restart restarts.
    fn restarted(&self) -> &'static str {
        if self.columns.len() == 3 {
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

    /// The model time per wall-clock second the models actually reached over
    /// the last second, when they fell behind the warp (a slow machine, a
    /// costly method); `None` while they keep up.
    pub fn behind(&self) -> Option<Real> {
        self.pace.behind
    }

    /// Turn elapsed wall-clock time into whole model steps: the time is
    /// accumulated (times the warp) into a backlog, and every whole [`TICK`]
    /// of it is asked of the models. Returns the number of steps asked for.
    /// Nothing happens while paused. Stepped inline, they are done on return;
    /// in the background, what is done by now is taken.
    ///
    /// NOTE: the backlog is kept in integers (nanoseconds × thousandths of
    /// τ per second), so the number of steps after a total wall time W is
    /// exactly ⌊W·warp/Δt⌋ however W was cut into frames: the models do not
    /// depend on the frame rate, not even by one step of rounding.
    pub fn advance_wall(&mut self, elapsed: Duration) -> u64 {
        if self.paused {
            self.backlog = 0;
            self.absorb();
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
        let before = self.ticks;
        self.ask(n, (cap / per_tick) as u64);
        self.measure(elapsed, self.ticks - before);
        n
    }

    /// Advance every model by `n` model steps of [`TICK`] (done on return
    /// when stepped inline). Once every model has stopped (a numerical
    /// failure), the clock stops with them: the header's t is the time they
    /// stopped at.
    pub fn advance_ticks(&mut self, n: u64) {
        self.ask(n, u64::MAX);
    }

    /// Ask for `n` more ticks, never more than `lag` ahead of what is done
    /// (work the models are behind on is dropped, not queued for ever).
    fn ask(&mut self, n: u64, lag: u64) {
        let want = self.requested.max(self.ticks).saturating_add(n);
        let limit = self.ticks.saturating_add(lag);
        self.pace.lagged |= want > limit;
        self.requested = want.min(limit);
        self.stepper.request(self.requested);
        self.absorb();
    }

    fn measure(&mut self, elapsed: Duration, ticks: u64) {
        self.pace.wall += elapsed;
        self.pace.ticks += ticks;
        if self.pace.wall >= Duration::from_secs(1) {
            let rate = self.pace.ticks as Real * TICK / self.pace.wall.as_secs_f64();
            self.pace = Pace {
                behind: self.pace.lagged.then_some(rate),
                ..Pace::default()
            };
        }
    }

    /// Take what the models did since the last call.
    fn absorb(&mut self) {
        let reports = self.stepper.collect();
        self.take(reports);
    }

    fn take(&mut self, reports: Vec<Report>) {
        for report in reports {
            match report {
                Report::NotBuilt(i, why) => {
                    if let Some(c) = self.columns.get_mut(i) {
                        c.stop(why);
                    }
                }
                Report::Tick(tick) => {
                    for (column, outcome) in self.columns.iter_mut().zip(tick.outcomes) {
                        if let Some(outcome) = outcome {
                            column.take(tick.k, outcome);
                        }
                    }
                    // Once every model has stopped, the clock shows the last
                    // time one of them reached (what its panel shows), not
                    // the tick that failed.
                    self.ticks = if self.columns.iter().all(|c| c.failure.is_some()) {
                        let reached = self
                            .columns
                            .iter()
                            .map(|c| (c.current.t / TICK).round() as u64)
                            .max()
                            .unwrap_or(tick.k);
                        reached.clamp(self.ticks.min(tick.k), tick.k)
                    } else {
                        tick.k
                    };
                }
                Report::Lost => {
                    for c in &mut self.columns {
                        if c.failure.is_none() {
                            c.stop("the models' thread stopped unexpectedly".into());
                        }
                    }
                }
            }
        }
    }

    /// Restart the models from the settings, keeping the view and the pause.
    fn restart(&mut self) {
        // Settings are validated before they are stored, so this cannot fail;
        // if it ever did, the old models keep running and the reason is shown.
        match Self::columns_for(&self.settings, self.is_background()) {
            Ok((columns, stepper)) => self.replace(columns, stepper),
            Err(e) => self.refuse(e),
        }
    }

    fn replace(&mut self, columns: Vec<Column>, stepper: Stepper) {
        self.columns = columns;
        self.stepper = stepper;
        self.ticks = 0;
        self.requested = 0;
        self.backlog = 0;
        self.pace = Pace::default();
        self.view.shown = self.view.shown.min(self.columns.len().saturating_sub(1));
        self.absorb();
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
        let background = self.is_background();
        match candidate.and_then(|s| Self::columns_for(&s, background).map(|c| (s, c))) {
            Ok((settings, (columns, stepper))) => {
                self.settings = settings;
                self.replace(columns, stepper);
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
        if let Command::Resize(w, h) = command {
            self.view.size = (w, h);
            return;
        }
        self.message = None;
        match command {
            Command::Resize(..) => {}
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
                    // Nothing more than what is done: the clock stops now,
                    // at the ticks the stepper has finished (collected
                    // first, so that they do not arrive after the pause).
                    self.absorb();
                    self.requested = self.ticks;
                    self.stepper.request(self.ticks);
                    let u = self.settings.top().time_unit();
                    self.inform(format!(
                        "paused at t = {:.2}{u}: . or → steps Δt = {TICK}{u}, space resumes",
                        self.time()
                    ));
                } else {
                    self.inform("running");
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
                let u = self.settings.top().time_unit();
                match next.map(|i| self.settings.at_warp(i)) {
                    Some(Ok(settings)) => {
                        self.settings = settings;
                        self.backlog = 0;
                        self.inform(format!("warp {} {u}/s", settings.warp()));
                    }
                    Some(Err(e)) => self.refuse(format!("refused: {e}")),
                    None => self.refuse(format!(
                        "the warp is already at its {} ({} {u}/s)",
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
                let candidate = self.settings.top.with_ratio(ratio).and_then(|top| {
                    let s = Settings {
                        top,
                        ..self.settings
                    };
                    s.check_live().map(|()| s)
                });
                self.change(candidate, format!("I₃/I₁ = {ratio}"));
            }
            Command::CycleMethod => {
                if !self.settings.top.takes_a_method() {
                    self.refuse(
                        "m has nothing to change here: one column is the physical solution, \
                         the other the forward run, each with its own method",
                    );
                    return;
                }
                // The next method that can run live; the ones too costly
                // here are skipped and named, so that m never sticks on a
                // refusal (its advice may be "the closed forms (m)").
                let mut method = self.settings.method;
                let mut skipped: Vec<&str> = Vec::new();
                let mut first_refusal = None;
                let mut candidate = None;
                for _ in 0..METHOD_CYCLE.len() {
                    method = next_method(method, &self.settings.top);
                    if method == self.settings.method {
                        break;
                    }
                    let settings = Settings {
                        method,
                        ..self.settings
                    };
                    match settings.check_live() {
                        Ok(()) => {
                            candidate = Some(settings);
                            break;
                        }
                        Err(e) => {
                            skipped.push(method.title());
                            first_refusal.get_or_insert(e);
                        }
                    }
                }
                let candidate = candidate.ok_or_else(|| {
                    first_refusal.unwrap_or_else(|| "no other method can run this top".into())
                });
                let what = if skipped.is_empty() || candidate.is_err() {
                    format!("method {}", method.title())
                } else {
                    format!(
                        "method {} ({} skipped: too costly to draw live here)",
                        method.title(),
                        skipped.join(", ")
                    )
                };
                self.change(candidate, what);
            }
            Command::ToggleLogTime => self.view.log_time = !self.view.log_time,
            Command::NextModel => {
                let n = self.columns.len().max(1);
                self.view.shown = (self.view.shown + 1) % n;
                let (name, equations, gist) = self.columns[self.view.shown].title();
                self.inform(format!(
                    "model {} of {n}: {name} {equations}, {gist}",
                    self.view.shown + 1
                ));
            }
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
                        check_omega0(omega0)?;
                        let s = Settings {
                            omega0,
                            ..self.settings
                        };
                        s.check_live().map(|()| s)
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
        let mut many = App::new(Settings::default()).unwrap();
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
