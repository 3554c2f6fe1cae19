//! The state of the live view and the one function that changes it.
//!
//! [`App`] shows the models of one [`super::Top`] side by side: for a symmetric top
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
//! entered ([`super::settings::LIVE_STEPS_PER_SECOND`]), never started.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `ratio` | I₃/I₁ | moment ratio of the symmetric top | – |
//! | `inertia`, `dipole` | I, d | principal moments and body dipole of a general top | κ = 1 units |
//! | `omega0` | Ω₀ | initial body angular velocity | 1/τ |
//! | [`TICK`] | Δt | one model step of the view | τ |
//! | `warp` | – | model time per wall-clock second | τ/s |

use super::columns::Column;
use super::entry;
use super::refusal::Refusal;
use super::settings::{Settings, WARPS};
pub use super::stepper::TICK;
use super::stepper::{Report, Stepper};
use spintop::math::Real;
use spintop::numbers::fmt_exact;
use spintop::sim::MethodChoice;
use std::time::Duration;

/// Everything a key can ask of the live view (and of the scene beside a
/// chapter of `spintop learn`).
#[derive(Clone, Debug, PartialEq, Eq)]
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
    /// Ctrl-U in the edit field: empty it.
    ClearField,
    /// Text pasted (bracketed paste): typed into the edit field, line breaks
    /// left out (never run as Enter); ignored, with a note, elsewhere.
    Paste(String),
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
    /// ↑ ↓ j k PgUp PgDn in the help: scroll it by this many rows.
    ScrollHelp(i64),
    /// Tab: the next model, where the screen shows one at a time.
    NextModel,
    /// The terminal's size changed (columns, rows).
    Resize(u16, u16),
    /// A key the view does not take, by its name: answered, never ignored
    /// (an old message left on the screen would read as its answer).
    Unknown(String),
}

/// [`TICK`] in thousandths of τ, for the exact integer accounting of the
/// wall clock (see [`App::advance_wall`]).
const TICK_MILLI_TAU: u128 = 100;

/// The step of `[` and `]` on I₃/I₁.
pub const RATIO_STEP: Real = 0.1;

/// The step of ↑ and ↓ on an Ω₀ component while it is edited, in 1/τ.
pub const NUDGE: Real = 0.01;

/// How much wall-clock lag is kept as a backlog; anything older is dropped.
///
/// NOTE: when the machine cannot keep up (a very high warp with RK4), an
/// unbounded backlog would make every frame slower than the last. Dropping it
/// changes only how model time maps to wall time: each model step is still
/// exactly [`TICK`].
pub const MAX_LAG: Duration = Duration::from_millis(250);

/// What `?` shows and what an Ω₀ edit holds.
#[derive(Clone, Debug, PartialEq)]
pub enum Mode {
    /// The main screen.
    Normal,
    /// The help overlay, scrolled to this row.
    Help(usize),
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
    /// The terminal's size (columns, rows), as last reported (in `spintop
    /// learn`, the scene's).
    pub size: (u16, u16),
    /// Colours off (`NO_COLOR`): each curve gets its own mark instead.
    pub monochrome: bool,
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

    /// True when the models take turns on the screen (Tab shows the next),
    /// at the size last reported (see [`super::layout::takes_turns`]).
    pub fn takes_turns(&self, n: usize) -> bool {
        super::layout::takes_turns(self.size.0, n)
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
    pub fn new(settings: Settings) -> Result<Self, Refusal> {
        Self::start(settings, false)
    }

    /// [`App::new`] with the models built and stepped on a thread of their
    /// own from the start.
    pub fn background(settings: Settings) -> Result<Self, Refusal> {
        Self::start(settings, true)
    }

    fn start(settings: Settings, background: bool) -> Result<Self, Refusal> {
        let (columns, stepper) = Self::columns_for(&settings, background)?;
        let mut app = Self {
            columns,
            settings,
            view: View {
                log_time: false,
                selected: 0,
                shown: 0,
                size: (MIN_WIDTH, MIN_HEIGHT),
                monochrome: false,
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
    ) -> Result<(Vec<Column>, Stepper), Refusal> {
        let plans =
            settings
                .top()
                .plans(settings.method(), settings.omega0(), settings.euler0())?;
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

    /// The same view with colours off or on (`NO_COLOR`): without them each
    /// curve is drawn with a mark of its own.
    pub fn monochrome(mut self, on: bool) -> Self {
        self.view.monochrome = on;
        self
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
                        c.stop(why.to_string());
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
                    self.ticks = if self.columns.iter().all(|c| c.failure().is_some()) {
                        let reached = self
                            .columns
                            .iter()
                            .map(|c| (c.current().t / TICK).round() as u64)
                            .max()
                            .unwrap_or(tick.k);
                        reached.clamp(self.ticks.min(tick.k), tick.k)
                    } else {
                        tick.k
                    };
                }
                Report::Lost => {
                    for c in &mut self.columns {
                        if c.failure().is_none() {
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
            Err(e) => self.refuse(e.to_string()),
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
    fn change(&mut self, candidate: Result<Settings, Refusal>, what: String) -> bool {
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
            self.scroll_help(0);
            return;
        }
        self.message = None;
        match command {
            Command::Resize(..) => {}
            Command::Quit => self.mode = Mode::Quitting,
            Command::ToggleHelp => {
                self.mode = match self.mode {
                    Mode::Help(_) => Mode::Normal,
                    _ => Mode::Help(0),
                }
            }
            Command::ScrollHelp(n) => self.scroll_help(n),
            Command::TogglePause => self.toggle_pause(),
            Command::Step => self.step(),
            Command::Faster => self.change_warp(true),
            Command::Slower => self.change_warp(false),
            Command::Reset => {
                self.restart();
                let restarted = self.restarted();
                self.inform(format!("{restarted} at t = 0"));
            }
            Command::RatioDown => self.change_ratio(-1.0),
            Command::RatioUp => self.change_ratio(1.0),
            Command::CycleMethod => self.cycle_method(),
            Command::ToggleLogTime => self.view.log_time = !self.view.log_time,
            Command::NextModel => self.next_model(),
            Command::SelectPrevious => self.view.selected = (self.view.selected + 2) % 3,
            Command::SelectNext => self.view.selected = (self.view.selected + 1) % 3,
            Command::StartEdit => {
                let component = self.view.selected;
                self.mode = Mode::Edit {
                    component,
                    buffer: fmt_exact(self.settings.omega0()[component]),
                    pristine: true,
                };
                self.inform(edit_hint(component, self.settings.top().time_unit()));
            }
            Command::Input(c) => self.input(c),
            Command::Paste(text) => self.paste(&text),
            Command::ClearField => {
                if let Mode::Edit {
                    buffer, pristine, ..
                } = &mut self.mode
                {
                    *pristine = false;
                    buffer.clear();
                    self.say_edit();
                }
            }
            Command::Backspace => {
                if let Mode::Edit {
                    buffer, pristine, ..
                } = &mut self.mode
                {
                    *pristine = false;
                    buffer.pop();
                    self.say_edit();
                }
            }
            Command::Unknown(key) => self.refuse(format!("{key}: no such key; ? for help")),
            Command::NudgeUp => self.nudge(NUDGE),
            Command::NudgeDown => self.nudge(-NUDGE),
            Command::Commit => self.commit(),
            Command::Cancel => {
                if matches!(self.mode, Mode::Edit { .. }) {
                    self.mode = Mode::Normal;
                    self.inform("edit cancelled");
                }
            }
        }
    }

    /// Scroll the help by `n` rows, within its length at this size.
    fn scroll_help(&mut self, n: i64) {
        if let Mode::Help(scroll) = self.mode {
            let lines = super::help::lines(self.settings.top());
            let max =
                crate::term::popup::max_scroll(self.view.size, super::help::HELP_WIDTH, &lines);
            let to = scroll.saturating_add_signed(n as isize).min(max);
            self.mode = Mode::Help(to);
        }
    }

    /// Space: pause, or resume.
    fn toggle_pause(&mut self) {
        self.paused = !self.paused;
        self.backlog = 0;
        if self.paused {
            // Nothing more than what is done: the clock stops now, at the
            // ticks the stepper has finished (collected first, so that they
            // do not arrive after the pause).
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

    /// `.`: one tick, while paused.
    fn step(&mut self) {
        if self.paused {
            self.advance_ticks(1);
        } else {
            self.refuse("stepping works while paused: press space first");
        }
    }

    /// `+` or `-`: the next warp, judged on the models' state now (a top
    /// whose large Ω₀ has decayed costs what it costs now, not at t = 0).
    fn change_warp(&mut self, faster: bool) {
        let at = self.settings.warp_index();
        let next = if faster {
            at.checked_add(1).filter(|i| *i < WARPS.len())
        } else {
            at.checked_sub(1)
        };
        let u = self.settings.top().time_unit();
        let now: Vec<[Real; 3]> = self.columns.iter().map(|c| c.current().omega).collect();
        match next.map(|i| self.settings.at_warp(i, Some(&now))) {
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

    /// `[` or `]`: I₃/I₁ one step down or up.
    fn change_ratio(&mut self, sign: Real) {
        let Some(ratio) = self.settings.ratio() else {
            self.refuse(
                "[ and ] change I₃/I₁ of a symmetric top; this general top has three \
                 moments, set in its scene file",
            );
            return;
        };
        // NOTE: stay on the grid of RATIO_STEP so that repeated presses
        // land on 0.4 and 0.5, not on 0.49999999999999994.
        let grid = (ratio / RATIO_STEP).round() + sign;
        let ratio = ((grid * RATIO_STEP) * 1e12).round() / 1e12;
        let candidate = self.settings.with_ratio(ratio);
        self.change(candidate, format!("I₃/I₁ = {ratio}"));
    }

    /// `m`: the next method of the cycle that can run live; the ones too
    /// costly here are skipped and named, so that m never sticks on a
    /// refusal (its advice may be "the closed forms (m)").
    fn cycle_method(&mut self) {
        let top = *self.settings.top();
        if !top.takes_a_method() {
            self.refuse(
                "m has nothing to change here: one column is the physical solution, \
                 the other the forward run, each with its own method",
            );
            return;
        }
        let mut method = self.settings.method();
        let mut skipped: Vec<MethodChoice> = Vec::new();
        let mut first_refusal = None;
        let mut candidate = None;
        let mut unstable: Option<String> = None;
        for _ in 0..super::layout::METHOD_CYCLE.len() {
            method = super::layout::next_method(method, &top);
            if method == self.settings.method() {
                break;
            }
            if let Some(why) = super::layout::fixed_step_unstable(
                method,
                &top,
                // m restarts the models at t = 0: from Ω₀.
                std::iter::once(self.settings.omega0()),
            ) {
                unstable.get_or_insert(why);
                continue;
            }
            match self.settings.with_method(method) {
                Ok(settings) => {
                    candidate = Some(settings);
                    break;
                }
                Err(e) => {
                    skipped.push(method);
                    first_refusal.get_or_insert(e);
                }
            }
        }
        if candidate.is_none() && !skipped.is_empty() {
            return self.refuse(self.no_method_runs(&skipped));
        }
        let candidate = candidate.ok_or_else(|| first_refusal.unwrap_or(Refusal::NoOtherMethod));
        let skipped: Vec<&str> = skipped.iter().map(|m| m.title()).collect();
        let what = if skipped.is_empty() || candidate.is_err() {
            format!("method {}", method_title(method, &top))
        } else {
            format!(
                "method {} ({} skipped: too costly to draw live here)",
                method_title(method, &top),
                skipped.join(", ")
            )
        };
        let what = match unstable {
            Some(why) => format!("{what}; {why}"),
            None => what,
        };
        self.change(candidate, what);
    }

    /// Why `m` changes nothing when every other method (`tried`) is refused
    /// here: the method that runs at the fastest slower warp is named, not
    /// the first refusal's (DP5's "20 τ/s" where auto runs at 500).
    fn no_method_runs(&self, tried: &[MethodChoice]) -> String {
        let top = self.settings.top();
        let u = top.time_unit();
        let best = tried
            .iter()
            .filter_map(|m| Some((*m, self.settings.fastest_warp_for(*m)?)))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        let here = format!(
            "refused: no other method runs this top live at {} {u}/s",
            self.settings.warp()
        );
        match best {
            Some((m, w)) => format!(
                "{here}; {} runs at {w} {u}/s (- slows down)",
                method_title(m, top)
            ),
            None => format!("{here}, nor slower; a smaller |Ω₀| costs less"),
        }
    }

    /// Tab: the next model, where the screen shows one at a time; where all
    /// are on the screen it says so and changes nothing.
    fn next_model(&mut self) {
        let n = self.columns.len().max(1);
        if !self.view.takes_turns(n) {
            let which = if n == 2 {
                "both models are".to_string()
            } else {
                format!("all {n} models are")
            };
            self.refuse(format!(
                "{which} on the screen; Tab shows them one at a time where the screen is narrower"
            ));
            return;
        }
        self.view.shown = (self.view.shown + 1) % n;
        let (name, equations, gist) = self.columns[self.view.shown].title();
        self.inform(format!(
            "model {} of {n}: {name} {equations}, {gist}",
            self.view.shown + 1
        ));
    }

    /// A character typed into the Ω₀ field: kept as typed (never dropped;
    /// `q` is a character here, and Esc leaves the edit), with why at once
    /// when no number holds it; only a full field refuses it.
    fn input(&mut self, c: char) {
        let Mode::Edit {
            buffer, pristine, ..
        } = &mut self.mode
        else {
            return;
        };
        let base = if *pristine { "" } else { buffer.as_str() };
        let checked = entry::check_char(base, c);
        if checked == Err(entry::EntryError::Full) {
            self.refuse(format!("refused: {}", entry::EntryError::Full));
            return;
        }
        if *pristine {
            buffer.clear();
            *pristine = false;
        }
        buffer.push(c);
        self.say_edit();
    }

    /// Pasted text: into the Ω₀ field as if typed, without its line breaks
    /// (a paste never presses Enter); outside an edit, nothing but a note.
    fn paste(&mut self, text: &str) {
        if !matches!(self.mode, Mode::Edit { .. }) {
            self.inform("paste ignored: Enter edits the selected Ω₀ component, then paste");
            return;
        }
        for c in text.chars().filter(|c| !c.is_control()) {
            self.input(c);
            if self
                .message
                .as_ref()
                .is_some_and(|m| m.text.starts_with("refused: "))
            {
                break;
            }
        }
    }

    /// What the Ω₀ field's line says: how to edit it, or why its text is no
    /// number for as long as it holds a character no number holds.
    fn say_edit(&mut self) {
        let Mode::Edit {
            buffer, component, ..
        } = &self.mode
        else {
            return;
        };
        let component = *component;
        match entry::first_foreign(buffer) {
            None => self.inform(edit_hint(component, self.settings.top().time_unit())),
            Some(e) => self.refuse(format!("{e}; Enter refuses it")),
        }
    }

    /// ↑ or ↓ in the Ω₀ field: its number plus `d`.
    fn nudge(&mut self, d: Real) {
        let Mode::Edit {
            buffer,
            component,
            pristine,
        } = &mut self.mode
        else {
            return;
        };
        let component = *component;
        match entry::parse(buffer) {
            Ok(x) => {
                let mut y = x + d;
                // NOTE: snap to the grid of NUDGE (0.1 + 0.01 would print as
                // 0.11000000000000001), where the grid is finer than a
                // double's spacing.
                if y.abs() < 1e6 {
                    y = ((y / NUDGE).round() * NUDGE * 1e6).round() / 1e6;
                }
                *buffer = fmt_exact(y);
                *pristine = false;
                self.inform(edit_hint(component, self.settings.top().time_unit()));
            }
            Err(e) => self.refuse(format!("refused: {e}")),
        }
    }

    /// Enter in the Ω₀ field: the new Ω₀, or the reason it is refused (the
    /// field stays open to correct it).
    fn commit(&mut self) {
        let Mode::Edit {
            component, buffer, ..
        } = &self.mode
        else {
            return;
        };
        let component = *component;
        let candidate = entry::parse(buffer)
            .map_err(Refusal::from)
            .and_then(|x| self.settings.with_omega0(component, x));
        let what = format!("Ω{}₀ = {}", SUBSCRIPTS[component], buffer.trim());
        if self.change(candidate, what) {
            self.mode = Mode::Normal;
        }
    }
}

/// The name of a method choice on the screen (it lives with the cycle it
/// names, in `layout`).
pub use super::layout::method_title;

/// Subscript digits for Ω₁, Ω₂, Ω₃.
pub const SUBSCRIPTS: [char; 3] = ['₁', '₂', '₃'];

fn edit_hint(component: usize, unit: &str) -> String {
    format!(
        "editing Ω{}₀ (1/{unit}): type a number, ↑/↓ ±{NUDGE}, Enter applies, Esc cancels",
        SUBSCRIPTS[component]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    use approx::assert_relative_eq;
    use spintop::math::Vec3;
    use spintop::physics::rigid_body::lab_frame;
    use spintop::physics::symmetric_top::SymmetricTop;

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
            let settings = Settings::default().at_warp(warp, None).unwrap();
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
