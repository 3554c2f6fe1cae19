//! The parameters the live models start from, validated once when they are
//! built: a [`Settings`] the view holds can always be run live. Every change
//! (a key, an edit, an experiment of the book) goes through a method here
//! that validates the new settings whole, so a refusal leaves the old ones.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `ratio` | I₃/I₁ | moment ratio of the symmetric top | – |
//! | `omega0` | Ω₀ | initial body angular velocity | 1/τ |
//! | `warp` | – | model time per wall-clock second | τ/s |

use super::layout::Top;
use super::refusal::Refusal;
use spintop::math::{Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::scene::Scene;
use spintop::scene::live::live_scene;
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model};

/// The time warps offered by `+` and `-`, in τ per wall-clock second.
pub const WARPS: [Real; 11] = [
    0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0,
];

/// Index into [`WARPS`] of the default, 10 τ/s: a precession period of the
/// figure parameters (about 50τ) takes five seconds.
pub const DEFAULT_WARP: usize = 4;

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

/// The parameters the models start from, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    top: Top,
    omega0: [Real; 3],
    method: MethodChoice,
    warp: usize,
    /// O(0) as z-x-z Euler angles, as a scene gives them; `None`: the
    /// paper's frame, lab z along L₀ (the view's own start).
    euler0: Option<[Real; 3]>,
}

impl Default for Settings {
    /// The parameters of the paper's Figures 1 and 2: I₃/I₁ = 2/5,
    /// Ω₀ = (0, 0.1, 0.2)/τ, closed forms, 10 τ/s.
    fn default() -> Self {
        Self {
            top: Top::Symmetric(SymmetricTop::figure()),
            omega0: spintop::figure::FIGURE_OMEGA0,
            method: MethodChoice::Exact,
            warp: DEFAULT_WARP,
            euler0: None,
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
    ) -> Result<Self, Refusal> {
        let top = SymmetricTop::new(ratio, 1.0)?;
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
    ) -> Result<Self, Refusal> {
        Self::validated(Top::General(top), omega0, method, warp)
    }

    /// Validate the settings of a symmetric top under the full ALE (3.4):
    /// its physical solution beside its forward run.
    pub fn full(ratio: Real, omega0: [Real; 3], warp: Real) -> Result<Self, Refusal> {
        let top = SymmetricTop::new(ratio, 1.0)?;
        Self::validated(Top::Full(top), omega0, MethodChoice::Auto, warp)
    }

    /// The settings a top scene opens with (see [`spintop::scene::live`]), at
    /// `warp` τ/s (the default when `None`), and the line the view opens with.
    pub fn for_scene(scene: &Scene, warp: Option<Real>) -> Result<(Self, String), Refusal> {
        let live = live_scene(scene).map_err(Refusal::Scene)?;
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
        // The scene's orientation, as `spintop run` starts it.
        let settings = Self {
            euler0: live.euler0,
            ..settings
        };
        Ok((settings, live.note))
    }

    fn validated(
        top: Top,
        omega0: [Real; 3],
        method: MethodChoice,
        warp: Real,
    ) -> Result<Self, Refusal> {
        top.check_method(method)?;
        check_omega0(omega0)?;
        let warp = WARPS.iter().position(|w| *w == warp).ok_or_else(|| {
            let list: Vec<String> = WARPS.iter().map(|w| w.to_string()).collect();
            Refusal::Warp(list.join(", "))
        })?;
        let settings = Self {
            top,
            omega0,
            method,
            warp,
            euler0: None,
        };
        settings.check_live()?;
        Ok(settings)
    }

    /// The same settings at warp `WARPS[index]`, if the view can step them
    /// live from the models' state `now` (each column's Ω; Ω₀ when `None`).
    pub(super) fn at_warp(&self, index: usize, now: Option<&[[Real; 3]]>) -> Result<Self, Refusal> {
        let settings = Self {
            warp: index,
            ..*self
        };
        settings.check_live_from(now)?;
        Ok(settings)
    }

    /// Refuse settings whose models the view cannot step live (see
    /// [`LIVE_STEPS_PER_SECOND`]), saying what costs so much and what
    /// would not.
    fn check_live(&self) -> Result<(), Refusal> {
        self.check_live_from(None)
    }

    /// [`Self::check_live`] from the state `now` (each column's Ω), not Ω₀.
    fn check_live_from(&self, now: Option<&[[Real; 3]]>) -> Result<(), Refusal> {
        let (total, costliest) = self.live_cost(now)?;
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
                && self.with_method(MethodChoice::Exact).is_ok() =>
            {
                "the closed forms (m) take no steps, and a smaller |Ω₀| costs less".to_string()
            }
            None => "a smaller |Ω₀| costs less (the steps grow with it)".to_string(),
        };
        Err(Refusal::TooCostly {
            what,
            steps: spintop::numbers::fmt_about(total),
            warp,
            unit: u,
            cheaper,
            limit: LIVE_STEPS_PER_SECOND,
        })
    }

    /// The steps per wall-clock second of every column (a column with a
    /// horizon is tabulated once: its whole cost counts), and the costliest
    /// column's estimate.
    fn live_cost(
        &self,
        now: Option<&[[Real; 3]]>,
    ) -> Result<(Real, Option<spintop::sim::cost::Estimate>), Refusal> {
        let mut total = 0.0;
        let mut costliest: Option<spintop::sim::cost::Estimate> = None;
        for (i, (plan, _)) in self
            .top
            .plans(self.method, self.omega0, self.euler0)?
            .into_iter()
            .enumerate()
        {
            // A column tabulated to its horizon (the forward run) has paid
            // its whole cost at its start.
            if now.is_some() && plan.horizon.is_some() {
                continue;
            }
            let omega = Vec3::from(now.and_then(|n| n.get(i).copied()).unwrap_or(self.omega0));
            // The options the view's simulations run with (`super::stepper`).
            let options = MethodOptions::default();
            let method = plan.model.method(plan.choice, &options)?;
            let t = plan.horizon.unwrap_or(self.warp());
            let Some(e) = second_of_work(&plan.model, method, &options, &omega, t) else {
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

    /// The same settings for a symmetric top of I₃/I₁ = `ratio` (the same
    /// layout), if the view can step them live.
    pub fn with_ratio(&self, ratio: Real) -> Result<Self, Refusal> {
        let settings = Self {
            top: self.top.with_ratio(ratio)?,
            ..*self
        };
        settings.check_live()?;
        Ok(settings)
    }

    /// The same settings by `method`, if every column that takes a method
    /// takes it and the view can step them live.
    pub fn with_method(&self, method: MethodChoice) -> Result<Self, Refusal> {
        self.top.check_method(method)?;
        let settings = Self { method, ..*self };
        settings.check_live()?;
        Ok(settings)
    }

    /// The fastest warp below this one at which `method` runs these
    /// settings live (from Ω₀, where a change of method restarts), if any.
    pub fn fastest_warp_for(&self, method: MethodChoice) -> Option<Real> {
        self.top.check_method(method).ok()?;
        (0..self.warp)
            .rev()
            .find(|&warp| {
                Self {
                    method,
                    warp,
                    ..*self
                }
                .check_live()
                .is_ok()
            })
            .map(|i| WARPS[i])
    }

    /// The same settings with Ω₀'s `component` (0, 1, 2) set to `value`, if
    /// the core takes that start and the view can step it live.
    pub fn with_omega0(&self, component: usize, value: Real) -> Result<Self, Refusal> {
        let mut omega0 = self.omega0;
        omega0[component % 3] = value;
        check_omega0(omega0)?;
        let settings = Self { omega0, ..*self };
        settings.check_live()?;
        Ok(settings)
    }

    /// O(0) as a scene gave it (z-x-z Euler angles); `None`: the paper's
    /// frame, lab z along L₀.
    pub fn euler0(&self) -> Option<[Real; 3]> {
        self.euler0
    }

    /// The index of the warp in [`WARPS`].
    pub fn warp_index(&self) -> usize {
        self.warp
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

/// The core's estimate ([`spintop::sim::cost::estimate`]) of the work of
/// `model` by `method` from `omega` over `t`, with the reduced model's
/// spin-down counted: its Ω₃ is constant and its Ω⊥ falls at least as fast
/// as Ω⊥₀/√(1 + 2τΩ⊥₀²t) ((4.16) without its exponential), so the body
/// turns by at most |Ω₃|t + 2Ω⊥₀t/(1 + √(1 + 2τΩ⊥₀²t)), not |Ω₀|t: the
/// Ω₃ part is estimated over `t`, the Ω⊥ part over the time it would take
/// at Ω⊥₀. The one rule every restart path (r, [, ], m, the Ω₀ editor, the
/// flags) and the warp keys are judged by, from Ω₀ or from the state now.
/// Paper: Eq. (4.16).
///
/// NOTE: `spintop tui --omega 0,10000,0.2 --warp 1000` was refused for
/// "about 1.0e7 steps a second" (|Ω₀|t) while `r` ran the same start live;
/// `tests/tui/live_fit.rs` runs its first 100τ within a tenth of the budget.
pub(super) fn second_of_work(
    model: &Model,
    method: spintop::sim::Method,
    options: &MethodOptions,
    omega: &Vec3,
    t: Real,
) -> Option<spintop::sim::cost::Estimate> {
    use spintop::sim::cost::estimate;
    let Model::Reduced(top) = model else {
        return estimate(model, method, options, omega, t);
    };
    let perp = omega.x.hypot(omega.y);
    // RK4's steps do not depend on Ω; nothing spins down without Ω⊥.
    if method == spintop::sim::Method::Rk4 || perp == 0.0 || !t.is_finite() {
        return estimate(model, method, options, omega, t);
    }
    let axial = estimate(model, method, options, &Vec3::new(0.0, 0.0, omega.z), t);
    let spin_down = 2.0 * t / (1.0 + (1.0 + 2.0 * top.tau() * perp * perp * t).sqrt());
    let lateral = estimate(
        model,
        method,
        options,
        &Vec3::new(omega.x, omega.y, 0.0),
        spin_down,
    );
    match (axial, lateral) {
        (Some(a), Some(l)) => Some(spintop::sim::cost::Estimate {
            steps: a.steps + l.steps,
            ..if a.steps >= l.steps { a } else { l }
        }),
        (a, l) => a.or(l),
    }
}

/// Refuse an Ω₀ the simulation would refuse, with the simulation's reason.
fn check_omega0(omega0: [Real; 3]) -> Result<InitialState, Refusal> {
    Ok(InitialState::new(
        Vec3::from(omega0),
        EulerAngles::new(0.0, 0.0, 0.0),
    )?)
}
