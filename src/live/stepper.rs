//! The models of the live view, stepped tick by tick: on the caller's thread
//! (the tests, which want every step done when they ask) or on a thread of
//! their own (the terminal), so that the screen and the keys never wait on
//! the model.
//!
//! Either way the same [`Models::tick`] takes every step: tick k advances
//! each model to t = k·Δt and reports the sample, so the bits do not depend
//! on which thread stepped them, nor on the frame rate. On its own thread the
//! stepper is handed a target tick and works toward it; the view collects
//! what is done each frame. A new start (a restart, an edit) replaces the
//! thread: the old one is told to stop, and stops after the model step it is
//! in, which the live cost check ([`super::Settings`]) keeps short.

use spintop::integrate::Stats;
use spintop::math::Real;
use spintop::sim::{
    InitialState, MethodChoice, MethodOptions, Model, Sample, SimError, Simulation,
};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};

/// One model step of the view, in units of τ: the size of every increment of
/// model time, and what `.` or → advances while paused.
pub const TICK: Real = 0.1;

/// How one model is run: the model (after any stand-in), the method it was
/// asked for and its start. Built once per start; the view keeps one for its
/// column and the stepper builds the [`Simulation`] from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The model run.
    pub model: Model,
    /// The method asked for (the full ALE's column runs its own).
    pub choice: MethodChoice,
    /// The start, lab z along L₀.
    pub initial: InitialState,
    /// The last time it runs to (the forward run of the full ALE is
    /// tabulated to a fixed time); `None`: open-ended.
    pub horizon: Option<Real>,
}

impl Plan {
    /// The simulation of this plan, open-ended, at t = 0.
    pub fn build(&self) -> Result<Simulation, SimError> {
        Simulation::new(
            self.model,
            self.choice,
            MethodOptions::default(),
            self.initial,
            self.horizon,
        )
    }
}

/// Why a model stopped in a tick.
#[derive(Clone, Debug, PartialEq)]
pub enum Stopped {
    /// The core's reason.
    Sim(SimError),
    /// It reached the last time it runs to.
    Horizon(Real),
}

impl std::fmt::Display for Stopped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stopped::Sim(e) => write!(f, "{e}"),
            Stopped::Horizon(h) => write!(
                f,
                "the run reached its last time, t = {}, and ends there",
                spintop::numbers::fmt_num(*h)
            ),
        }
    }
}

/// What one model did in one tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// The sample at t = k·Δt.
    pub sample: Sample,
    /// The work done so far.
    pub stats: Stats,
    /// The last accepted step (0 for a closed form).
    pub last_step: Real,
}

/// One tick of every model: `None` for a model stopped before it.
#[derive(Clone, Debug, PartialEq)]
pub struct Tick {
    /// The tick: t = k·Δt.
    pub k: u64,
    /// Each model's progress, or why it stopped now.
    pub outcomes: Vec<Option<Result<Progress, Stopped>>>,
}

/// What the stepper reports.
#[derive(Clone, Debug, PartialEq)]
pub enum Report {
    /// A model could not be built; it stays stopped.
    NotBuilt(usize, SimError),
    /// One more tick done.
    Tick(Tick),
    /// The stepper's thread ended without being told to (it panicked).
    Lost,
}

/// The simulations of one start.
#[derive(Debug)]
pub struct Models {
    sims: Vec<Option<Simulation>>,
    horizons: Vec<Option<Real>>,
    k: u64,
    tick: Real,
}

impl Models {
    /// Build every plan's simulation; the ones that cannot be built are
    /// reported and stay stopped.
    pub fn build(plans: &[Plan], tick: Real) -> (Self, Vec<Report>) {
        let mut reports = Vec::new();
        let sims = plans
            .iter()
            .enumerate()
            .map(|(i, plan)| match plan.build() {
                Ok(sim) => Some(sim),
                Err(e) => {
                    reports.push(Report::NotBuilt(i, e));
                    None
                }
            })
            .collect();
        let horizons = plans.iter().map(|p| p.horizon).collect();
        (
            Self {
                sims,
                horizons,
                k: 0,
                tick,
            },
            reports,
        )
    }

    /// The tick done last.
    pub fn k(&self) -> u64 {
        self.k
    }

    /// True once every model has stopped.
    pub fn all_stopped(&self) -> bool {
        self.sims.iter().all(Option::is_none)
    }

    /// Advance every running model to the next tick; `None` (and no tick)
    /// once all have stopped. A model that fails stops; the others go on.
    pub fn tick(&mut self, cancel: &dyn Fn() -> bool) -> Option<Tick> {
        if self.all_stopped() {
            return None;
        }
        self.k += 1;
        let t = self.k as Real * self.tick;
        let mut outcomes = Vec::with_capacity(self.sims.len());
        for (slot, horizon) in self.sims.iter_mut().zip(&self.horizons) {
            if cancel() {
                return None;
            }
            let outcome = slot.as_mut().map(|sim| match horizon {
                Some(h) if t > *h => Err(Stopped::Horizon(*h)),
                _ => match sim.advance_to(t) {
                    Ok(sample) => Ok(Progress {
                        sample: *sample,
                        stats: sim.stats(),
                        last_step: sim.last_step(),
                    }),
                    Err(e) => Err(Stopped::Sim(e)),
                },
            });
            if matches!(outcome, Some(Err(_))) {
                *slot = None;
            }
            outcomes.push(outcome);
        }
        Some(Tick {
            k: self.k,
            outcomes,
        })
    }
}

/// The models on a thread of their own.
#[derive(Debug)]
pub struct Worker {
    target: Sender<u64>,
    reports: Receiver<Report>,
    stop: Arc<AtomicBool>,
    asked: u64,
    lost: bool,
}

impl Worker {
    /// Build the plans' simulations on a new thread, and step them as asked.
    pub fn spawn(plans: Vec<Plan>, tick: Real) -> Self {
        Self::start(move || Models::build(&plans, tick))
    }

    /// Move already built models onto a new thread.
    pub fn adopt(models: Models) -> Self {
        Self::start(move || (models, Vec::new()))
    }

    fn start(make: impl FnOnce() -> (Models, Vec<Report>) + Send + 'static) -> Self {
        let (target_tx, target_rx) = mpsc::channel::<u64>();
        let (report_tx, report_rx) = mpsc::channel::<Report>();
        let stop = Arc::new(AtomicBool::new(false));
        let stopped = Arc::clone(&stop);
        std::thread::spawn(move || {
            let (mut models, first) = make();
            for r in first {
                if report_tx.send(r).is_err() {
                    return;
                }
            }
            let cancel = || stopped.load(Ordering::Relaxed);
            let mut target = models.k();
            loop {
                // Wait while caught up (or once every model has stopped).
                while models.k() >= target || models.all_stopped() {
                    match target_rx.recv() {
                        Ok(t) => target = t,
                        Err(_) => return,
                    }
                }
                // Take any newer target without waiting.
                while let Ok(t) = target_rx.try_recv() {
                    target = t;
                }
                if cancel() {
                    return;
                }
                if let Some(tick) = models.tick(&cancel)
                    && report_tx.send(Report::Tick(tick)).is_err()
                {
                    return;
                }
            }
        });
        Self {
            target: target_tx,
            reports: report_rx,
            stop,
            asked: 0,
            lost: false,
        }
    }

    /// Ask for every tick up to `k` (a lower `k` than before stops the
    /// thread after the tick it is in: a pause).
    pub fn request(&mut self, k: u64) {
        if k != self.asked {
            self.asked = k;
            // A send fails only when the thread has ended; `collect` says so.
            let _ = self.target.send(k);
        }
    }

    /// Everything done since the last call, without waiting.
    pub fn collect(&mut self) -> Vec<Report> {
        let mut out = Vec::new();
        loop {
            match self.reports.try_recv() {
                Ok(r) => out.push(r),
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    if !self.lost {
                        self.lost = true;
                        out.push(Report::Lost);
                    }
                    break;
                }
            }
        }
        out
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // The thread sees the flag between models and the closed channel when
        // it next waits; either way it ends without being joined.
        self.stop.store(true, Ordering::Relaxed);
    }
}

/// The models of the view: stepped on the caller's thread, or on their own.
#[derive(Debug)]
pub enum Stepper {
    /// Every request is done before it returns.
    Inline {
        /// The models.
        models: Models,
        /// Done, not yet collected.
        done: Vec<Report>,
    },
    /// On a thread of their own.
    Background(Worker),
}

impl Stepper {
    /// The plans' models: built now on this thread (`background` false), or
    /// built and stepped on a thread of their own.
    pub fn new(plans: Vec<Plan>, tick: Real, background: bool) -> Self {
        if background {
            Stepper::Background(Worker::spawn(plans, tick))
        } else {
            let (models, done) = Models::build(&plans, tick);
            Stepper::Inline { models, done }
        }
    }

    /// True when the models run on a thread of their own.
    pub fn is_background(&self) -> bool {
        matches!(self, Stepper::Background(_))
    }

    /// The same models, moved onto a thread of their own, and what was done
    /// inline and not yet collected.
    pub fn into_background(self) -> (Self, Vec<Report>) {
        match self {
            Stepper::Inline { models, done } => (Stepper::Background(Worker::adopt(models)), done),
            background => (background, Vec::new()),
        }
    }

    /// Ask for every tick up to `k` (done at once inline).
    pub fn request(&mut self, k: u64) {
        match self {
            Stepper::Inline { models, done } => {
                while models.k() < k {
                    match models.tick(&|| false) {
                        Some(tick) => done.push(Report::Tick(tick)),
                        None => break,
                    }
                }
            }
            Stepper::Background(worker) => worker.request(k),
        }
    }

    /// What was done since the last call.
    pub fn collect(&mut self) -> Vec<Report> {
        match self {
            Stepper::Inline { done, .. } => std::mem::take(done),
            Stepper::Background(worker) => worker.collect(),
        }
    }
}
