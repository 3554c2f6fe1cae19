//! An orbit of one charge in a central field under radiation reaction (§2):
//! the Landau–Lifshitz equation, the physical solution of the Abraham–Lorentz
//! equation (2.5), or its forward integration with the runaway detected.
//!
//! Pure: no clock, no I/O. The lightest adequate path is used:
//!
//! | force | oscillator | Coulomb |
//! |---|---|---|
//! | `LandauLifshitz` | closed form (roots of s² + τ₀s + 1) | DOP853 forward |
//! | `AbrahamLorentz` | closed form (roots of τ₀s³ − s² − 1) | DOP853 backward from final data, shot to the initial state |
//! | `AbrahamLorentzForward` | DOP853 forward from the Newtonian v̇(0) until the runaway | same |

use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State};
use crate::physics::ParamError;
use crate::physics::central::{
    ChargeInField, Potential, Vec2, abraham_lorentz_oscillator_roots, abraham_lorentz_rhs,
    angular_momentum, coulomb_collapse_time, landau_lifshitz_acceleration,
    landau_lifshitz_oscillator_root, landau_lifshitz_rhs, oscillator_mode, pos_vel,
};
use serde::Serialize;
use thiserror::Error;

/// Which equation of motion the charge follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Force {
    /// The Landau–Lifshitz reduction of (2.5).
    LandauLifshitz,
    /// The physical (non-runaway) solution of (2.5).
    AbrahamLorentz,
    /// (2.5) integrated forward from the Newtonian acceleration: runs away.
    AbrahamLorentzForward,
}

impl Force {
    /// `ll`, `al` or `al-forward`.
    pub fn name(&self) -> &'static str {
        match self {
            Force::LandauLifshitz => "ll",
            Force::AbrahamLorentz => "al",
            Force::AbrahamLorentzForward => "al-forward",
        }
    }
}

/// The radii whose first crossing a Coulomb run reports.
pub const CROSSING_LEVELS: [Real; 3] = [0.5, 0.2, 0.1];

/// The deviation |v̇ − F(r)/m|, in units of the initial force |F(r₀)|/m, at
/// which forward integration of (2.5) is declared a runaway (the physical
/// solution keeps it O(τ₀)).
pub const RUNAWAY_THRESHOLD: Real = 1e3;

/// A validated orbit problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitConfig {
    /// The potential and τ₀.
    pub charge: ChargeInField,
    /// Starting radius r₀ > 0 (the start is (r₀, 0)).
    pub r0: Real,
    /// Eccentricity in [0, 1); (r₀, 0) is the point nearest the centre.
    pub eccentricity: Real,
    /// The equation of motion.
    pub force: Force,
    /// Relative tolerance of the integrations.
    pub rtol: Real,
}

/// The loosest relative tolerance an orbit is integrated at: (2.5)'s
/// runaway amplifies a looser one beyond what the averaged laws check.
pub const MAX_ORBIT_RTOL: Real = 1e-3;

impl OrbitConfig {
    /// Validate r₀ > 0 (and, for Coulomb, above [`OrbitConfig::floor_radius`])
    /// and e ∈ [0, 1); for the oscillator under the Landau–Lifshitz force,
    /// τ₀ < 2, below which s² + τ₀s + 1 = 0 has complex roots (an orbit that
    /// decays; at τ₀ ≥ 2 the charge is overdamped and has none).
    pub fn new(
        charge: ChargeInField,
        r0: Real,
        eccentricity: Real,
        force: Force,
    ) -> Result<Self, ParamError> {
        crate::physics::finite("r0", r0)?;
        crate::physics::finite("eccentricity", eccentricity)?;
        if r0 <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "r0",
                value: r0,
                range: "positive",
            });
        }
        if !(0.0..1.0).contains(&eccentricity) {
            return Err(ParamError::OutOfRange {
                name: "eccentricity",
                value: eccentricity,
                range: "in [0, 1) (a bound orbit)",
            });
        }
        if force == Force::LandauLifshitz
            && charge.potential() == Potential::Harmonic
            && charge.tau0() >= 2.0
        {
            return Err(ParamError::OutOfRange {
                name: "tau0",
                value: charge.tau0(),
                range: "below 2 for the oscillator under force ll: at tau0 >= 2 the roots of s^2 + tau0 s + 1 = 0 are real, the charge is overdamped and has no orbit",
            });
        }
        let config = Self {
            charge,
            r0,
            eccentricity,
            force,
            rtol: 1e-11,
        };
        if r0 <= config.floor_radius() {
            return Err(ParamError::OutOfRange {
                name: "r0",
                value: r0,
                range: "above (10 tau0)^(2/3) for coulomb, where the orbital time r0^(3/2) is still \
                        longer than 10 tau0 (else no orbit exists to decay): raise r0 or lower tau0",
            });
        }
        Ok(config)
    }

    /// This problem at relative tolerance `rtol`, in [1e-14, 1e-3].
    pub fn with_rtol(self, rtol: Real) -> Result<Self, ParamError> {
        if !(crate::sim::MIN_RTOL..=MAX_ORBIT_RTOL).contains(&rtol) {
            return Err(ParamError::OutOfRange {
                name: "rtol",
                value: rtol,
                range: "in [1e-14, 1e-3]",
            });
        }
        Ok(Self { rtol, ..self })
    }

    /// The starting position and velocity.
    pub fn initial(&self) -> (Vec2, Vec2) {
        let v0 = self
            .charge
            .potential()
            .pericentre_speed(self.r0, self.eccentricity);
        (Vec2::new(self.r0, 0.0), Vec2::new(0.0, v0))
    }

    /// The averaged closed-form collapse time (Coulomb only).
    pub fn collapse_time(&self) -> Option<Real> {
        (self.charge.potential() == Potential::Coulomb).then(|| {
            let e = self.eccentricity;
            coulomb_collapse_time(self.charge.tau0(), self.r0 * (1.0 + e), e)
        })
    }

    /// The radius below which a Coulomb run stops: where the orbital time
    /// r^{3/2} (the time to turn one radian) falls below 10 τ₀, so that
    /// neither the Landau–Lifshitz reduction nor a point charge on a slowly
    /// decaying orbit makes sense any more.
    pub fn floor_radius(&self) -> Real {
        match self.charge.potential() {
            Potential::Coulomb => (10.0 * self.charge.tau0()).powf(2.0 / 3.0),
            Potential::Harmonic => 0.0,
        }
    }
}

/// One output sample.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OrbitSample {
    /// Time.
    pub t: Real,
    /// r.
    pub position: [Real; 2],
    /// v.
    pub velocity: [Real; 2],
    /// |r|.
    pub r: Real,
    /// L = m r × v (z component).
    pub l: Real,
    /// m v²/2 + V(r).
    pub energy: Real,
}

impl OrbitSample {
    fn new(potential: Potential, t: Real, pos: &Vec2, vel: &Vec2) -> Self {
        Self {
            t,
            position: [pos.x, pos.y],
            velocity: [vel.x, vel.y],
            r: pos.norm(),
            l: angular_momentum(pos, vel),
            energy: potential.energy(pos, vel),
        }
    }
}

/// When r first fell to a level.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Crossing {
    /// The level.
    pub r: Real,
    /// The first time r(t) ≤ level within the run (`None`: not reached).
    pub t: Option<Real>,
    /// The averaged closed form (r₀³ − r³)/(6τ₀), circular orbits only.
    pub averaged: Option<Real>,
}

/// A detected runaway of forward-integrated (2.5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Runaway {
    /// When |v̇ − F(r)| passed [`RUNAWAY_THRESHOLD`] × |F(r₀)|.
    pub t: Real,
    /// The measured growth rate d ln|v̇ − F(r)|/dt, from where the deviation
    /// passed |F(r₀)| to the detection (three decades).
    pub growth_rate: Option<Real>,
    /// The predicted rate: the real root of τ₀s³ − s² − 1 (oscillator), 1/τ₀
    /// to leading order (Coulomb).
    pub predicted_rate: Real,
    /// The detection threshold.
    pub threshold: Real,
}

/// Everything a run produced.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitRun {
    /// Samples at the requested times (up to the runaway, for `al-forward`).
    pub samples: Vec<OrbitSample>,
    /// First crossings of r = 0.5, 0.2, 0.1 (Coulomb).
    pub first_crossing: Option<Vec<Crossing>>,
    /// The runaway (`al-forward`).
    pub runaway: Option<Runaway>,
    /// `exact`, `dop853` or `dop853-backward`.
    pub method: &'static str,
    /// Shooting iterations and final mismatch (Coulomb `al`).
    pub shooting: Option<(usize, Real)>,
    /// Work done.
    pub stats: Stats,
}

/// Why an orbit could not be computed.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum OrbitError {
    /// The integrator stopped.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// The orbit fell inside [`OrbitConfig::floor_radius`].
    #[error(
        "the orbit fell to r = {r:.3e} at t = {}, where the orbital time r^(3/2) (the time to turn one radian) is below 10 tau0 and the model ends",
        crate::numbers::fmt_time(*t)
    )]
    Collapsed {
        /// When.
        t: Real,
        /// The radius reached.
        r: Real,
    },
    /// Backward shooting did not reach the initial state.
    #[error(
        "backward shooting for the physical solution did not converge (mismatch {mismatch:e} after {iterations} iterations)"
    )]
    ShootingFailed {
        /// Iterations done.
        iterations: usize,
        /// Remaining mismatch of (r, v) at t = 0.
        mismatch: Real,
    },
}

/// Run `config` and sample it at `times` (≥ 0, non-decreasing).
pub fn run_orbit(config: &OrbitConfig, times: &[Real]) -> Result<OrbitRun, OrbitError> {
    let potential = config.charge.potential();
    match (config.force, potential) {
        (Force::LandauLifshitz, Potential::Harmonic) => Ok(exact_oscillator(
            config,
            times,
            landau_lifshitz_oscillator_root(config.charge.tau0()),
        )),
        (Force::AbrahamLorentz, Potential::Harmonic) => Ok(exact_oscillator(
            config,
            times,
            abraham_lorentz_oscillator_roots(config.charge.tau0()).0,
        )),
        (Force::LandauLifshitz, Potential::Coulomb) => {
            let (pos, vel) = config.initial();
            let y0 = State::<4>::new(pos.x, pos.y, vel.x, vel.y);
            let rhs = |_t: Real, y: &State<4>| landau_lifshitz_rhs(&config.charge, y);
            let mut tracker = Tracker::new(config);
            let stats = integrate(config, &rhs, y0, 0.0, times, &mut tracker)?;
            Ok(OrbitRun {
                samples: tracker.samples,
                first_crossing: Some(tracker.crossings),
                runaway: None,
                method: "dop853",
                shooting: None,
                stats,
            })
        }
        (Force::AbrahamLorentz, Potential::Coulomb) => physical_coulomb(config, times),
        (Force::AbrahamLorentzForward, _) => forward_abraham_lorentz(config, times),
    }
}

fn exact_oscillator(config: &OrbitConfig, times: &[Real], s: nalgebra::Complex<Real>) -> OrbitRun {
    let (x0, v0) = config.initial();
    let potential = config.charge.potential();
    let samples = times
        .iter()
        .map(|&t| {
            let (x, v, _) = oscillator_mode(s, &x0, &v0, t);
            OrbitSample::new(potential, t, &x, &v)
        })
        .collect();
    OrbitRun {
        samples,
        first_crossing: None,
        runaway: None,
        method: "exact",
        shooting: None,
        stats: Stats::default(),
    }
}

/// Collects samples and first crossings while an integration moves, in either
/// direction, and stops a Coulomb run at the floor radius.
struct Tracker {
    potential: Potential,
    floor: Real,
    crossings: Vec<Crossing>,
    samples: Vec<OrbitSample>,
}

impl Tracker {
    fn new(config: &OrbitConfig) -> Self {
        let potential = config.charge.potential();
        let circular = config.eccentricity == 0.0;
        let tau0 = config.charge.tau0();
        let crossings: Vec<Crossing> = CROSSING_LEVELS
            .iter()
            .map(|&r| Crossing {
                r,
                t: (config.r0 <= r).then_some(0.0),
                averaged: circular
                    .then(|| ((config.r0.powi(3) - r.powi(3)) / (6.0 * tau0)).max(0.0)),
            })
            .collect();
        Self {
            potential,
            floor: config.floor_radius(),
            crossings,
            samples: Vec::new(),
        }
    }

    /// Record the crossings inside the last accepted step of `stepper`.
    fn after_step<const N: usize, S: Stepper<N>, R: Rhs<N>>(
        &mut self,
        stepper: &mut S,
        rhs: &R,
    ) -> Result<(), OrbitError> {
        let (t0, t1) = (stepper.t_prev(), stepper.t());
        let r_at = |s: &mut S, t: Real| -> Real {
            let y = s.dense(rhs, t);
            Vec2::new(y[0], y[1]).norm()
        };
        let r1 = Vec2::new(stepper.y()[0], stepper.y()[1]).norm();
        if r1 < self.floor {
            return Err(OrbitError::Collapsed { t: t1, r: r1 });
        }
        // NOTE: r is sampled at 4 points per step; a dip below a level and back
        // within a quarter step would be missed, but the steps are a small
        // fraction of an orbit and the levels are reached on the way down.
        const SUB: usize = 4;
        let mut prev_t = t0;
        let mut prev_r = r_at(stepper, t0);
        for k in 1..=SUB {
            let t = t0 + (t1 - t0) * k as Real / SUB as Real;
            let r = r_at(stepper, t);
            for c in &mut self.crossings {
                if (prev_r > c.r) != (r > c.r) {
                    // Bisect on the continuous extension.
                    let (mut lo, mut hi) = (prev_t, t);
                    let above_lo = prev_r > c.r;
                    for _ in 0..60 {
                        let mid = 0.5 * (lo + hi);
                        if (r_at(stepper, mid) > c.r) == above_lo {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    let tc = 0.5 * (lo + hi);
                    c.t = Some(c.t.map_or(tc, |old| old.min(tc)));
                }
            }
            prev_t = t;
            prev_r = r;
        }
        Ok(())
    }

    fn push(&mut self, t: Real, pos: &Vec2, vel: &Vec2) {
        self.samples
            .push(OrbitSample::new(self.potential, t, pos, vel));
    }
}

/// Integrate from (t0, y0) through `times` (in the direction of the last one),
/// sampling into `tracker`.
fn integrate<const N: usize, R: Rhs<N>>(
    config: &OrbitConfig,
    rhs: &R,
    y0: State<N>,
    t0: Real,
    times: &[Real],
    tracker: &mut Tracker,
) -> Result<Stats, OrbitError> {
    let opts = AdaptiveOptions::new(config.rtol, config.rtol * 1e-3)?;
    let mut stepper = Dop853::new(t0, y0, opts)?;
    let Some(&t_end) = times.last() else {
        return Ok(stepper.stats());
    };
    let forward = t_end >= t0;
    for &t in times {
        while if forward {
            stepper.t() < t
        } else {
            stepper.t() > t
        } {
            stepper.step(rhs, t_end)?;
            tracker.after_step(&mut stepper, rhs)?;
        }
        let y = if t == stepper.t() {
            *stepper.y()
        } else {
            stepper.dense(rhs, t)
        };
        let (pos, vel) = pos_vel(&y);
        tracker.push(t, &pos, &vel);
    }
    Ok(stepper.stats())
}

// ANCHOR: backward_shooting
/// The physical solution of (2.5) for Coulomb: integrate backward from final
/// data at T = t_last + 40τ₀, where the runaway mode decays as e^{−(T−t)/τ₀};
/// choose the final data by shooting so that the solution passes through the
/// given initial state.
fn physical_coulomb(config: &OrbitConfig, times: &[Real]) -> Result<OrbitRun, OrbitError> {
    let q = config.charge;
    let tau0 = q.tau0();
    let (pos0, vel0) = config.initial();
    let target = State::<4>::new(pos0.x, pos0.y, vel0.x, vel0.y);
    let t_last = times.last().copied().unwrap_or(0.0);
    // NOTE: 40 τ₀ of margin: the final acceleration is the Landau–Lifshitz one,
    // off by O(τ₀²); that error is multiplied by e^{−40} before it reaches t_last.
    let t_final = t_last + 40.0 * tau0;
    let ll = |_t: Real, y: &State<4>| landau_lifshitz_rhs(&q, y);
    let al = |_t: Real, y: &State<6>| abraham_lorentz_rhs(&q, y);
    // Backward output times: every requested time, then t = 0, latest first.
    let mut back_times: Vec<Real> = times.iter().rev().copied().collect();
    back_times.push(0.0);
    let mut start = target;
    let mut stats = Stats::default();
    let scale = target.norm();
    let mut mismatch = Real::INFINITY;
    for iteration in 1..=12 {
        // Forward with Landau–Lifshitz to get final data near the physical orbit.
        let mut scout = Tracker::new(config);
        let opts = AdaptiveOptions::new(config.rtol, config.rtol * 1e-3)?;
        let mut fwd = Dop853::new(0.0, start, opts)?;
        while fwd.t() < t_final {
            fwd.step(&ll, t_final)?;
            scout.after_step(&mut fwd, &ll)?;
        }
        stats += fwd.stats();
        let yf = *fwd.y();
        let (pf, vf) = pos_vel(&yf);
        let af = landau_lifshitz_acceleration(&q, &pf, &vf);
        let y_final = State::<6>::new(pf.x, pf.y, vf.x, vf.y, af.x, af.y);
        // Backward with Abraham–Lorentz: the runaway mode is damped this way.
        let mut tracker = Tracker::new(config);
        stats += integrate(config, &al, y_final, t_final, &back_times, &mut tracker)?;
        let last = tracker.samples.last().expect("t = 0 is sampled");
        let reached = State::<4>::new(
            last.position[0],
            last.position[1],
            last.velocity[0],
            last.velocity[1],
        );
        let miss = reached - target;
        mismatch = miss.norm() / scale;
        if mismatch < 1e-9 {
            tracker.samples.pop();
            tracker.samples.reverse();
            return Ok(OrbitRun {
                samples: tracker.samples,
                first_crossing: Some(tracker.crossings),
                runaway: None,
                method: "dop853-backward",
                shooting: Some((iteration, mismatch)),
                stats,
            });
        }
        // NOTE: backward(forward_LL(z)) = z + O(τ₀²) with a slowly varying
        // error, so subtracting the mismatch from the Landau–Lifshitz start is
        // a contraction (a Newton step with the identity as Jacobian).
        start -= miss;
    }
    Err(OrbitError::ShootingFailed {
        iterations: 12,
        mismatch,
    })
}
// ANCHOR_END: backward_shooting

// ANCHOR: runaway_detection
/// Integrate (2.5) forward from the Newtonian acceleration v̇(0) = F(r₀)/m and
/// stop when the deviation |v̇ − F(r)| passes RUNAWAY_THRESHOLD × |F(r₀)|.
///
/// NOTE: the deviation is measured against the initial force, not the local
/// one: once the runaway has grown a thousandfold the charge has moved by only
/// ~10³τ₀², so the growth it shows is still the linear mode e^{st} of the
/// frozen equation τ₀ȧ = a − F, not the later wreck of the orbit.
fn forward_abraham_lorentz(config: &OrbitConfig, times: &[Real]) -> Result<OrbitRun, OrbitError> {
    let q = config.charge;
    let potential = q.potential();
    let (pos0, vel0) = config.initial();
    let a0 = potential.force(&pos0);
    let y0 = State::<6>::new(pos0.x, pos0.y, vel0.x, vel0.y, a0.x, a0.y);
    let rhs = |_t: Real, y: &State<6>| abraham_lorentz_rhs(&q, y);
    let f0 = a0.norm();
    let deviation = |y: &State<6>| {
        let (pos, _) = pos_vel(y);
        (Vec2::new(y[4], y[5]) - potential.force(&pos)).norm() / f0
    };
    let opts = AdaptiveOptions::new(config.rtol, config.rtol * 1e-3)?;
    let mut stepper = Dop853::new(0.0, y0, opts)?;
    let mut tracker = Tracker::new(config);
    let t_end = times.last().copied().unwrap_or(0.0);
    // (t, ln deviation) at the first step end past 1, and at the last step end,
    // for the growth rate.
    let mut mark: Option<(Real, Real)> = None;
    let mut prev: Option<(Real, Real)> = None;
    let mut runaway = None;
    'outer: for &t in times {
        while stepper.t() < t {
            stepper.step(&rhs, t_end)?;
            let dev = deviation(stepper.y());
            let t_now = stepper.t();
            if dev > RUNAWAY_THRESHOLD {
                // NOTE: a step multiplies the deviation by far less than 10³, so
                // the mark normally lies steps earlier; else use the last step.
                let from = mark.filter(|m| m.0 < t_now).or(prev);
                runaway = Some(Runaway {
                    t: t_now,
                    growth_rate: from.map(|(tm, lm)| (dev.ln() - lm) / (t_now - tm)),
                    predicted_rate: match potential {
                        Potential::Harmonic => abraham_lorentz_oscillator_roots(q.tau0()).1,
                        Potential::Coulomb => 1.0 / q.tau0(),
                    },
                    threshold: RUNAWAY_THRESHOLD,
                });
                break 'outer;
            }
            if dev > 0.0 {
                prev = Some((t_now, dev.ln()));
                if dev >= 1.0 && mark.is_none() {
                    mark = prev;
                }
            }
            tracker.after_step(&mut stepper, &rhs)?;
        }
        let y = if t == stepper.t() {
            *stepper.y()
        } else {
            stepper.dense(&rhs, t)
        };
        let (pos, vel) = pos_vel(&y);
        tracker.push(t, &pos, &vel);
    }
    Ok(OrbitRun {
        samples: tracker.samples,
        first_crossing: (potential == Potential::Coulomb).then_some(tracker.crossings),
        runaway,
        method: "dop853",
        shooting: None,
        stats: stepper.stats(),
    })
}
// ANCHOR_END: runaway_detection
