//! One model as the live screen shows it: its latest sample, its recent
//! history for the charts, its trails for the hodograph and the top in
//! space, and why it stopped (the model itself is stepped by the
//! [`super::stepper::Stepper`]).

use super::refusal::Refusal;
use super::stepper::TICK;
use super::stepper::{Plan, Progress, Stopped};
use spintop::integrate::Stats;
use spintop::math::{Real, Vec3};
use spintop::physics::rigid_body::energy;
use spintop::sim::{InitialState, Method, MethodChoice, MethodOptions, Model, Sample, SimError};
use std::collections::VecDeque;

/// The width of the scrolling time window of the linear charts, in τ.
pub const WINDOW: Real = 200.0;

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
/// model itself is stepped by the [`super::stepper::Stepper`]).
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
    pub(super) fn new(plan: Plan, stand_in: Option<String>) -> Result<Self, Refusal> {
        let model = plan.model;
        let method = model.method(plan.choice, &MethodOptions::default())?;
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
    pub(super) fn take(&mut self, k: u64, outcome: Result<Progress, Stopped>) {
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
                    "ran away at t = {}: it leaves the physical solution at {}/τ, an e-folding time of {}τ, as (3.4) does forward from any start",
                    spintop::numbers::fmt_time(r.t),
                    spintop::numbers::fmt_num(r.growth_rate),
                    spintop::numbers::fmt_num(1.0 / r.growth_rate)
                ));
            }
            Err(e) => self.stop(e.to_string()),
        }
    }

    /// Stop with the reason and what to do about it.
    pub(super) fn stop(&mut self, why: String) {
        self.failure = Some(if self.is_forward() {
            // The forward run is there to run away: the reason says it all.
            why
        } else if self.method == Method::Rk4 {
            // A slower warp takes the same fixed step: it cannot help.
            format!(
                "{why}; RK4's fixed step is unstable here: choose an adaptive method (m), r restarts, a smaller Ω₀ helps"
            )
        } else {
            // NOTE: no word of the warp: it sets how many ticks a second
            // are drawn, not what a tick (one advance to the next Δt) does.
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

    /// The method's name as the whole screen says it (the header's
    /// `closed form`, `DP5`, … for the choice that runs it).
    pub fn method_name(&self) -> &'static str {
        match self.method {
            // Ω from its closed form; the orientation is integrated.
            Method::ClosedFormDop853 => MethodChoice::Exact.title(),
            m => m.choice().map_or(m.label(), MethodChoice::title),
        }
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
