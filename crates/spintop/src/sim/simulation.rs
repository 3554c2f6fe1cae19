//! A simulation: one model, one method, stepped and sampled on demand.

use super::cost;
use super::method::{MIN_RTOL, Method, MethodChoice, MethodOptions};
use super::model::{FirstOrder, Model};
use super::physical::slow::SlowTable;
use super::physical::{self, general};
use super::state::{InitialState, Sample, SimError};
use super::stepping::{
    AnyStepper, CoupledRhs, MAX_TURN_PER_STEP, OnGroup, OrientationRhs, TaylorRun,
};
use crate::integrate::{Stats, Stepper};
use crate::math::{Mat3, Quat, Real, State, Vec3, all_finite, rot_z};
use crate::physics::general_top;
use crate::physics::symmetric_top::{
    self, SymmetricTop, reduced_closed_form, reduced_corotating_rate, truncated_closed_form,
    truncated_orientation,
};

#[derive(Clone, Debug)]
enum Engine {
    /// Truncated model: everything in closed form.
    ClosedForm(SymmetricTop),
    /// Reduced model: Ω closed form, σ integrated.
    ReducedOrientation(SymmetricTop, Box<OnGroup<3>>),
    /// Ω and σ integrated together by one of the steppers.
    Coupled(Method, FirstOrder, Box<OnGroup<6>>),
    /// Full ALE: Ω from a table (a general top's physical solution, or a
    /// forward run up to its runaway), σ integrated along it.
    Table(Box<physical::OmegaTable>, TableKind, Stats, Box<OnGroup<3>>),
    /// The symmetric top's physical solution of (3.4), in the frame that
    /// turns with the free precession.
    Slow(Box<SlowRun>),
    /// Ω and the orientation quaternion by the Taylor method.
    Taylor(Box<TaylorRun>),
}

/// Where a full-ALE table came from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum TableKind {
    /// The physical solution (backward shooting).
    Physical,
    /// A forward run, with the runaway that stopped it, if any.
    Forward(Option<physical::Runaway>),
}

/// A general top's physical solution of (3.4) through Ω₀ on [0, span] as a
/// table, and the work it took.
fn general_table(
    model: &Model,
    omega0: &Vec3,
    span: Real,
    options: &MethodOptions,
) -> Result<(physical::OmegaTable, Stats), SimError> {
    match model {
        Model::GeneralFull(top) => {
            let (table, sol) = general::general_physical_table(
                top,
                omega0,
                span,
                options.rtol(),
                options.refine(),
            )?;
            Ok((table, sol.stats))
        }
        _ => Err(SimError::MethodNotForModel {
            method: Method::Physical.label(),
            model: model.name(),
        }),
    }
}

/// The symmetric top's physical solution of (3.4) and its orientation
/// O = Q·R_z(Ω̃₃t): Q is driven by the slow rate (Re w, Im w, k), and once
/// w no longer turns it by a rounding, it turns about its third axis at k in
/// closed form.
#[derive(Clone, Debug)]
struct SlowRun {
    top: SymmetricTop,
    table: SlowTable,
    /// The work of the tables built before this one.
    built: Stats,
    group: OnGroup<3>,
    /// From when Q turns at k alone, and Q there.
    still: Option<(Real, Quat)>,
}

impl SlowRun {
    fn stats(&self) -> Stats {
        let mut total = self.built;
        total += self.table.stats;
        total += self.group.stepper.stats();
        total
    }

    fn advance(
        &mut self,
        t: Real,
        horizon: Real,
        options: &MethodOptions,
    ) -> Result<(Vec3, Mat3), SimError> {
        let open = horizon == Real::MAX;
        // Open-ended: carry Q to the end of the chunk, then tabulate the next
        // one from the state there.
        while open && t > self.table.t_end() {
            let end = self.table.t_end();
            self.orientation(end, end)?;
            let omega = self.table.omega_at(end);
            let next = physical::physical_table(
                &self.top,
                &omega,
                CHUNK_TAUS * self.top.tau(),
                options,
                cost::MAX_STEPS as u64,
            )?;
            self.built += self.table.stats;
            self.table = next.starting_at(end);
        }
        let stop = if open {
            self.table.t_end().min(Real::MAX)
        } else {
            horizon
        };
        let q = self.orientation(t, stop)?;
        let precession = rot_z(self.table.precession() * t);
        Ok((self.table.omega_at(t), q * precession))
    }

    /// Q at t, stepping toward `stop`.
    fn orientation(&mut self, t: Real, stop: Real) -> Result<Mat3, SimError> {
        if let Some(from) = self.table.still_from()
            && t >= from
        {
            if self.still.is_none() {
                let q = self.step_to(from, from)?;
                self.still = Some((from, Quat::from_matrix(&q)));
            }
            let (from, q) = self.still.expect("set above");
            let turn = rot_z(self.table.spin() * (t - from));
            return Ok(q.to_rotation_matrix().into_inner() * turn);
        }
        self.step_to(t, stop)
    }

    fn step_to(&mut self, t: Real, stop: Real) -> Result<Mat3, SimError> {
        let table = &self.table;
        let rhs = OrientationRhs(|t| table.corotating_rate(t));
        let rate = |t: Real, _: &State<3>| table.corotating_rate(t);
        let (_, q) = self.group.advance(&rhs, &rate, t, stop)?;
        Ok(q)
    }
}

/// The orientation stepped alone (reduced and physical solutions) holds each
/// step to rtol over this.
const ORIENTATION_TIGHTER: Real = 10.0;

/// How many τ an open-ended symmetric full model tabulates at a time.
const CHUNK_TAUS: Real = 50.0;

/// How far ahead an open-ended full model tabulates its physical solution at a
/// time: 50 fast times (τ, or τ_f = |d|²/min Iᵢ for a general top).
fn physical_chunk_length(model: &Model) -> Real {
    match model {
        Model::GeneralFull(top) => 50.0 * general::fast_time(top),
        Model::Full(top) => CHUNK_TAUS * top.tau(),
        _ => Real::MAX,
    }
}

/// Ω and the orientation stepped together by `method` on SO(3) (`None`
/// for a method that is not a Runge–Kutta one).
fn coupled_on_group(
    method: Method,
    initial: &InitialState,
    options: &MethodOptions,
) -> Result<Option<OnGroup<6>>, SimError> {
    let mut y0 = State::<6>::zeros();
    y0.fixed_rows_mut::<3>(0).copy_from(&initial.omega);
    let scale = initial.omega.norm();
    Ok(
        AnyStepper::new(method, y0, options, scale)?.map(|stepper| OnGroup {
            stepper,
            base: Quat::from_matrix(&initial.rotation),
            max_turn: MAX_TURN_PER_STEP * options.refine(),
        }),
    )
}

/// The orientation alone on SO(3) by DOP853, driven by a known Ω(t).
fn orientation_on_group(
    initial: &InitialState,
    options: &MethodOptions,
) -> Result<Option<OnGroup<3>>, SimError> {
    // NOTE: σ alone is a rotation vector of at most 1.5 rad that restarts
    // from 0 at every fold; a tolerance relative to its size would ask
    // for ever more digits right after each fold. Its error is an angle:
    // rtol radians, absolute. Its steps' errors add up over the run:
    // each step is held to a tenth of rtol (DOP853 pays 10^(1/8),
    // a third more steps), so that the run keeps rtol over it.
    let tight = (options.rtol() / ORIENTATION_TIGHTER).max(MIN_RTOL);
    let local = options.with_rtol(tight).unwrap_or(*options);
    let zero = State::<3>::zeros();
    Ok(
        AnyStepper::with_atol(Method::Dop853, zero, &local, tight)?.map(|stepper| OnGroup {
            stepper,
            base: Quat::from_matrix(&initial.rotation),
            max_turn: MAX_TURN_PER_STEP * options.refine(),
        }),
    )
}

/// A top, a method and the current time.
#[derive(Clone, Debug)]
pub struct Simulation {
    options: MethodOptions,
    model: Model,
    initial: InitialState,
    engine: Engine,
    horizon: Real,
    current: Sample,
}

impl Simulation {
    /// Build a simulation at t = 0 with the method `choice` resolves to for
    /// `model` ([`Model::method`]; a choice the model does not take is
    /// refused with what it takes).
    ///
    /// `horizon` is the last time that will be asked for (the adaptive methods
    /// step toward it and never past it); `None` means open-ended, as in the TUI.
    pub fn new(
        model: Model,
        choice: MethodChoice,
        options: MethodOptions,
        initial: InitialState,
        horizon: Option<Real>,
    ) -> Result<Self, SimError> {
        let method = model.method(choice, &options)?;
        Self::with_method(model, method, options, initial, horizon)
    }

    /// Build a simulation at t = 0 that runs `method` itself (the sweeps of
    /// [`crate::workprecision`] name the method, not a choice). A method that
    /// cannot run `model` is refused.
    pub fn with_method(
        model: Model,
        method: Method,
        options: MethodOptions,
        initial: InitialState,
        horizon: Option<Real>,
    ) -> Result<Self, SimError> {
        // NOTE: the steppers take a finite t_stop; the largest double stands for
        // "open-ended" (the TUI), and no run gets anywhere near it.
        let horizon = horizon.unwrap_or(Real::MAX);
        if horizon.is_nan() || horizon < 0.0 {
            return Err(SimError::BadTime(horizon, 0.0));
        }
        let not_for_model = || SimError::MethodNotForModel {
            method: method.label(),
            model: model.name(),
        };
        if horizon < Real::MAX {
            cost::check(&model, method, &options, &initial.omega, horizon)?;
        }
        let base = Quat::from_matrix(&initial.rotation);
        let on_group = |dynamics: FirstOrder| -> Result<Engine, SimError> {
            let group = coupled_on_group(method, &initial, &options)?.ok_or_else(not_for_model)?;
            Ok(Engine::Coupled(method, dynamics, Box::new(group)))
        };
        let orientation_only = || -> Result<Box<OnGroup<3>>, SimError> {
            Ok(Box::new(
                orientation_on_group(&initial, &options)?.ok_or_else(not_for_model)?,
            ))
        };
        let (omega0, rtol) = (&initial.omega, options.rtol());
        let engine = match (method, model.first_order()) {
            (Method::Physical, None) => {
                // Open-ended (the live view): one chunk now, the next
                // when the view gets there (see `advance_to`).
                let span = if horizon == Real::MAX {
                    physical_chunk_length(&model)
                } else {
                    horizon
                };
                match model {
                    Model::Full(top) => {
                        let table = physical::physical_table(
                            &top,
                            omega0,
                            span,
                            &options,
                            cost::MAX_STEPS as u64,
                        )?;
                        Engine::Slow(Box::new(SlowRun {
                            top,
                            table,
                            built: Stats::default(),
                            group: *orientation_only()?,
                            still: None,
                        }))
                    }
                    _ => {
                        let (table, stats) = general_table(&model, omega0, span, &options)?;
                        Engine::Table(
                            Box::new(table),
                            TableKind::Physical,
                            stats,
                            orientation_only()?,
                        )
                    }
                }
            }
            (Method::Forward, None) if horizon == Real::MAX => {
                return Err(SimError::NeedsHorizon(model.name()));
            }
            (Method::Forward, None) => {
                let (table, runaway, stats) = match model {
                    Model::GeneralFull(top) => {
                        let (table, run) =
                            general::general_forward_table(&top, omega0, horizon, rtol)?;
                        (table, run.runaway, run.stats)
                    }
                    Model::Full(top) => {
                        let (table, run) = physical::forward_table(&top, omega0, horizon, rtol)?;
                        (table, run.runaway, run.stats)
                    }
                    _ => return Err(not_for_model()),
                };
                Engine::Table(
                    Box::new(table),
                    TableKind::Forward(runaway),
                    stats,
                    orientation_only()?,
                )
            }
            (Method::ClosedForm, Some(FirstOrder::Truncated(top))) => Engine::ClosedForm(top),
            (Method::ClosedFormDop853, Some(FirstOrder::Reduced(top))) => {
                Engine::ReducedOrientation(top, orientation_only()?)
            }
            (Method::Rk4 | Method::Dopri5 | Method::Dop853 | Method::Radau5, Some(d)) => {
                on_group(d)?
            }
            (Method::Taylor, Some(d)) => {
                Engine::Taylor(Box::new(TaylorRun::new(d, &initial, &base, &options)?))
            }
            _ => return Err(not_for_model()),
        };
        let current = Sample::new(0.0, &model.inertia(), &initial.rotation, &initial.omega);
        Ok(Self {
            options,
            model,
            initial,
            engine,
            horizon,
            current,
        })
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The initial state.
    pub fn initial(&self) -> &InitialState {
        &self.initial
    }

    /// The method in use.
    pub fn method(&self) -> Method {
        match &self.engine {
            Engine::ClosedForm(_) => Method::ClosedForm,
            Engine::ReducedOrientation(..) => Method::ClosedFormDop853,
            Engine::Coupled(which, ..) => *which,
            Engine::Table(_, TableKind::Physical, ..) | Engine::Slow(_) => Method::Physical,
            Engine::Table(_, TableKind::Forward(_), ..) => Method::Forward,
            Engine::Taylor(_) => Method::Taylor,
        }
    }

    /// The latest sample.
    pub fn current(&self) -> &Sample {
        &self.current
    }

    /// The work done so far (all zeros for the closed forms).
    pub fn stats(&self) -> Stats {
        match &self.engine {
            Engine::ClosedForm(_) => Stats::default(),
            Engine::ReducedOrientation(_, g) => g.stepper.stats(),
            Engine::Table(_, _, built, g) => {
                let mut total = *built;
                total += g.stepper.stats();
                total
            }
            Engine::Coupled(_, _, g) => g.stepper.stats(),
            Engine::Slow(run) => run.stats(),
            Engine::Taylor(run) => run.stats(),
        }
    }

    /// The size of the integrator's last accepted step (0 for closed forms).
    pub fn last_step(&self) -> Real {
        match &self.engine {
            Engine::ClosedForm(_) => 0.0,
            Engine::ReducedOrientation(_, g) | Engine::Table(_, _, _, g) => g.stepper.last_step(),
            Engine::Coupled(_, _, g) => g.stepper.last_step(),
            Engine::Slow(run) => run.group.stepper.last_step(),
            Engine::Taylor(run) => run.last_step(),
        }
    }

    /// Advance to time `t` (not earlier than the current sample) and return the sample there.
    pub fn advance_to(&mut self, t: Real) -> Result<&Sample, SimError> {
        let now = self.current.t;
        if !t.is_finite() || t < now || t > self.horizon {
            return Err(SimError::BadTime(t, now));
        }
        let inertia = self.model.inertia();
        let (omega, rotation) = match &mut self.engine {
            Engine::ClosedForm(top) => (
                truncated_closed_form(top, &self.initial.omega, t),
                truncated_orientation(top, &self.initial.omega, &self.initial.rotation, t),
            ),
            Engine::ReducedOrientation(top, g) => {
                // NOTE: in axes that turn with Ω⊥ in the body the rate w(t) has
                // no fast part (see `reduced_corotating_rate`): the integrator
                // follows only the slow decay, and the precession R_z(Ω̃₃t) is
                // multiplied back exactly.
                let omega0 = self.initial.omega;
                let rhs = OrientationRhs(|t| reduced_corotating_rate(top, &omega0, t));
                let rate = |t: Real, _: &State<3>| reduced_corotating_rate(top, &omega0, t);
                let (_, q) = g.advance(&rhs, &rate, t, self.horizon)?;
                let precession = rot_z(top.omega3_tilde(omega0.z) * t);
                (reduced_closed_form(top, &omega0, t), q * precession)
            }
            Engine::Coupled(_, dynamics, g) => {
                let omega = |_: Real, y: &State<6>| y.fixed_rows::<3>(0).into_owned();
                let h = self.horizon;
                // The model is matched here, once per advance, never per evaluation.
                let (y, rotation) = match *dynamics {
                    FirstOrder::Truncated(top) => {
                        g.advance(&CoupledRhs(symmetric_top::Truncated(top)), &omega, t, h)?
                    }
                    FirstOrder::Reduced(top) => {
                        g.advance(&CoupledRhs(symmetric_top::Reduced(top)), &omega, t, h)?
                    }
                    FirstOrder::General(top) => g.advance(&CoupledRhs(top), &omega, t, h)?,
                    FirstOrder::GeneralReduced(top) => {
                        g.advance(&CoupledRhs(general_top::Reduced(top)), &omega, t, h)?
                    }
                };
                (y.fixed_rows::<3>(0).into_owned(), rotation)
            }
            Engine::Taylor(run) => run.advance(t, self.horizon)?,
            Engine::Slow(run) => run.advance(t, self.horizon, &self.options)?,
            Engine::Table(table, kind, built, g) => {
                if let TableKind::Forward(Some(runaway)) = kind
                    && t > runaway.t
                {
                    return Err(SimError::Runaway(*runaway));
                }
                let open = self.horizon == Real::MAX;
                // Open-ended: carry the orientation to the end of the chunk,
                // then tabulate the next one from the state there.
                while open && t > table.t_end() {
                    let end = table.t_end();
                    let rhs = OrientationRhs(|t| table.omega_at(t));
                    let omega = |t: Real, _: &State<3>| table.omega_at(t);
                    g.advance(&rhs, &omega, end, end)?;
                    let span = physical_chunk_length(&self.model);
                    let (next, stats) =
                        general_table(&self.model, &table.omega_at(end), span, &self.options)?;
                    **table = next.starting_at(end);
                    *built += stats;
                }
                let stop = if open { table.t_end() } else { self.horizon };
                let rhs = OrientationRhs(|t| table.omega_at(t));
                let omega = |t: Real, _: &State<3>| table.omega_at(t);
                let (_, rotation) = g.advance(&rhs, &omega, t, stop)?;
                (table.omega_at(t), rotation)
            }
        };
        if !(all_finite(&omega) && all_finite(&rotation)) {
            return Err(SimError::NonFiniteSample(t));
        }
        let sample = Sample::new(t, &inertia, &rotation, &omega);
        // The observables can overflow where Ω does not (E = ΩᵀIΩ/2 with a
        // huge I or Ω): a sample is reported only when every number in it is.
        if !sample.is_finite() {
            return Err(SimError::NonFiniteSample(t));
        }
        self.current = sample;
        Ok(&self.current)
    }

    /// Sample at each of `times` (finite, ≥ 0, non-decreasing).
    pub fn run(&mut self, times: &[Real]) -> Result<Vec<Sample>, SimError> {
        let mut last = self.current.t;
        let mut out = Vec::with_capacity(times.len());
        for &t in times {
            if !t.is_finite() || t < last {
                return Err(SimError::BadTime(t, last));
            }
            last = t;
            out.push(*self.advance_to(t)?);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod method_rule_tests {
    use super::*;
    use crate::physics::euler_angles::EulerAngles;
    use crate::physics::general_top::GeneralTop;
    use crate::sim::{MIN_RTOL, OptionsError, TAYLOR_AUTO_RTOL, auto_integrator};

    fn models() -> Vec<Model> {
        let sym = SymmetricTop::figure();
        let general = GeneralTop::new(Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.3, 0.2, 1.0)).unwrap();
        vec![
            Model::Truncated(sym),
            Model::Reduced(sym),
            Model::Full(sym),
            Model::General(general),
            Model::GeneralReduced(general),
            Model::GeneralFull(general),
        ]
    }

    /// A method's choice is the choice that runs it: for every model and
    /// every choice other than `auto`, the method the rule takes bears the
    /// choice's name or none (`exact+dop853`, `physical`); and `auto`'s
    /// integrator for a general top is named by a choice that runs it.
    #[test]
    fn a_methods_choice_runs_that_method() {
        let options = MethodOptions::default();
        for model in models() {
            for choice in MethodChoice::ALL {
                let Ok(method) = model.method(choice, &options) else {
                    continue;
                };
                match (choice, method.choice()) {
                    (MethodChoice::Auto, Some(named)) => {
                        assert_eq!(model.method(named, &options), Ok(method));
                    }
                    (_, Some(named)) => assert_eq!(named, choice, "{}", model.name()),
                    (_, None) => assert!(matches!(
                        method,
                        Method::ClosedFormDop853 | Method::Physical
                    )),
                }
            }
        }
        let general = models()[3];
        for rtol in [1e-6, 1e-12] {
            let options = MethodOptions::default().with_rtol(rtol).unwrap();
            let auto = general.method(MethodChoice::Auto, &options).unwrap();
            assert_eq!(auto, auto_integrator(rtol));
            assert!(auto.choice().is_some(), "{rtol}: {auto:?}");
        }
    }

    /// The rule every entry point asks (`Model::check_method`) and what a
    /// simulation actually builds agree for every model and every choice: a
    /// choice the rule takes builds and runs, one it refuses is refused by
    /// the simulation with the same reason.
    #[test]
    fn the_method_rule_is_what_the_simulation_runs() {
        let initial =
            InitialState::new(Vec3::new(0.0, 0.1, 0.2), EulerAngles::new(0.0, 0.0, 0.0)).unwrap();
        for model in models() {
            for choice in MethodChoice::ALL {
                let built =
                    Simulation::new(model, choice, MethodOptions::default(), initial, Some(1.0));
                match model.method(choice, &MethodOptions::default()) {
                    Ok(method) => {
                        let mut sim = built.unwrap_or_else(|e| {
                            panic!("{} by {}: {e}", model.name(), choice.name())
                        });
                        assert_eq!(sim.method(), method);
                        assert!(sim.advance_to(1.0).is_ok());
                    }
                    Err(refused) => {
                        assert_eq!(built.unwrap_err(), SimError::Refused(refused));
                        let text = refused.to_string();
                        assert!(text.contains(model.name()), "{text}");
                    }
                }
            }
        }
    }

    /// `auto` takes the closed forms where they exist and the physical
    /// solution for the full ALE at any tolerance; for the asymmetric tops
    /// DOP853 above [`TAYLOR_AUTO_RTOL`] and the Taylor method at and below
    /// it.
    #[test]
    fn auto_takes_the_closed_forms_where_they_exist() {
        let rtols = [1e-3, 1e-8, 2.0 * TAYLOR_AUTO_RTOL, TAYLOR_AUTO_RTOL, 1e-14];
        for (model, rtol) in models().into_iter().flat_map(|m| rtols.map(|r| (m, r))) {
            let options = MethodOptions::default().with_rtol(rtol).unwrap();
            let method = model.method(MethodChoice::Auto, &options).unwrap();
            let integrated = if rtol <= TAYLOR_AUTO_RTOL {
                Method::Taylor
            } else {
                Method::Dop853
            };
            let expected = match model {
                Model::Truncated(_) => Method::ClosedForm,
                Model::Reduced(_) => Method::ClosedFormDop853,
                Model::Full(_) | Model::GeneralFull(_) => Method::Physical,
                Model::General(_) | Model::GeneralReduced(_) => integrated,
            };
            assert_eq!(method, expected, "{} at {rtol:e}", model.name());
            assert_eq!(
                model.closed_form(&Vec3::new(0.0, 0.1, 0.2), 1.0).is_some(),
                model.has_closed_form()
            );
        }
    }

    #[test]
    fn options_are_checked_once_when_built() {
        assert!(MethodOptions::new(1e-10, 0.01).is_ok());
        assert_eq!(
            MethodOptions::new(0.0, 0.01),
            Err(OptionsError::RtolOutOfRange(0.0))
        );
        assert!(MethodOptions::new(Real::NAN, 0.01).is_err());
        assert_eq!(
            MethodOptions::new(1e-15, 0.01),
            Err(OptionsError::RtolBelowDouble(1e-15))
        );
        assert!(MethodOptions::new(MIN_RTOL, 0.01).is_ok());
        assert!(MethodOptions::new(1e-10, 0.0).is_err());
        assert!(MethodOptions::new(1e-10, Real::INFINITY).is_err());
        let rk4 = MethodChoice::Rk4;
        assert_eq!(
            MethodOptions::for_choice(rk4, Some(1e-8), None),
            Err(OptionsError::RtolForRk4)
        );
        assert_eq!(
            MethodOptions::for_choice(MethodChoice::Dop853, None, Some(0.1)),
            Err(OptionsError::StepNotRk4)
        );
        let o = MethodOptions::for_choice(rk4, None, Some(0.1)).unwrap();
        assert_eq!((o.rtol(), o.step()), (1e-10, 0.1));
        for e in [
            OptionsError::RtolForRk4,
            OptionsError::StepNotPositive(-1.0),
        ] {
            assert!(e.to_string().starts_with(e.key()), "{e}");
        }
    }

    #[test]
    fn every_choice_has_its_name() {
        for (choice, name) in MethodChoice::ALL.iter().zip(MethodChoice::NAMES) {
            assert_eq!(choice.name(), name);
            assert_eq!(MethodChoice::from_name(name), Some(*choice));
        }
        assert_eq!(MethodChoice::from_name("euler"), None);
    }
}
