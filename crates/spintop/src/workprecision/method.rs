//! spintop's own entries in the sweep: one [`Method`], solved for one [`Target`].
//!
//! | method | knob | Ω alone | Ω and O(t) |
//! |---|---|---|---|
//! | [`Method::ClosedForm`] | – | truncated (4.7), reduced (4.15)–(4.16) | truncated (4.7), (4.9)–(4.11) |
//! | [`Method::ClosedFormDop853`] | rtol | – | reduced: Ω closed form, O by DOP853 on SO(3) |
//! | [`Method::Rk4`] | step h | truncated, reduced, general | the same, O on SO(3) |
//! | [`Method::Dopri5`] | rtol | truncated, reduced, general | the same, O on SO(3) |
//! | [`Method::Dop853`] | rtol | truncated, reduced, general | the same, O on SO(3) |
//! | [`Method::Physical`] | rtol | full ALE (3.4): backward DOP853 + shooting | – |
//! | [`Method::Radau5`] | rtol | truncated, reduced, general | – |
//! | [`Method::RotationDamping`] | step h | reduced: exact rotation ∘ damping splitting | – |
//! | [`Method::Taylor`] | rtol | truncated, reduced, general (each model's own recurrences) | the same, with the orientation quaternion |
//!
//! "Ω alone" integrates Ω̇ = F(Ω), the three equations a student would hand to
//! SciPy, through [`crate::integrate::solve`]: this is the row the peers are
//! compared with. "Ω and O(t)" is what `spintop simulate` computes: Ω and the
//! orientation together through [`crate::sim::Simulation`], with the cost of
//! the orientation and of the observables of each sample.

use super::problem::{OmegaRhs, Problem, ProblemKind};
use super::{KnobKind, Solution, Solver, Target};
use crate::integrate::taylor::{GeneralTruncated, SymmetricReduced, SymmetricTruncated};
use crate::integrate::{
    self, AdaptiveOptions, Composition, Dop853, Dopri5, IntegrateError, Radau5, Rhs, Rk4,
    Splitting, Stepper, Taylor, TaylorRhs,
};
use crate::math::{Real, State, Vec3};
use crate::physics::symmetric_top::{reduced_ale_rhs, reduced_closed_form_many, truncated_ale_rhs};
use crate::sim::physical::physical_solution;
use crate::sim::split::ReducedFlow;
use crate::sim::{Method, MethodOptions, Model, Simulation};

// ANCHOR: method_enum
/// The methods of spintop the sweep runs ([`Method`] is the core's one type
/// of numerical method). To add one: an entry here, its name, its knob and
/// where it applies in the three functions below, and one arm in
/// `solve_omega` (and in `solve_with_orientation` once [`crate::sim`] can
/// run it). The sweep, the table, the charts, the CSV and the join need no
/// change.
pub const SWEPT: [Method; 9] = [
    Method::ClosedForm,
    Method::ClosedFormDop853,
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Physical,
    Method::Radau5,
    Method::RotationDamping,
    Method::Taylor,
];
// NOTE: Strang and Yoshida-4 split the free top (τ = 0), which is not one of
// the four problems here; stability row 4 measures them.

/// A method's name in the sweep's tables and CSV files (the closed forms are
/// `closed-form` there, as in the committed sessions).
pub fn name(method: Method) -> &'static str {
    match method {
        Method::ClosedForm => "closed-form",
        Method::ClosedFormDop853 => "closed-form+dop853",
        other => other.label(),
    }
}
// ANCHOR_END: method_enum

/// The knob the sweep turns.
pub fn knob(method: Method) -> KnobKind {
    match method {
        Method::ClosedForm => KnobKind::None,
        Method::Rk4 | Method::RotationDamping | Method::Strang | Method::Yoshida4 => KnobKind::Step,
        Method::ClosedFormDop853
        | Method::Dopri5
        | Method::Dop853
        | Method::Physical
        | Method::Forward
        | Method::Radau5
        | Method::Taylor => KnobKind::Rtol,
    }
}

/// True when `method` solves `target` of `problem` in the sweep.
pub fn applies_to(method: Method, problem: ProblemKind, target: Target) -> bool {
    use ProblemKind as P;
    match (method, target) {
        (Method::ClosedForm, Target::Omega) => matches!(problem, P::Truncated | P::Reduced),
        (Method::ClosedForm, Target::OmegaOrientation) => problem == P::Truncated,
        (Method::ClosedFormDop853, Target::OmegaOrientation) => problem == P::Reduced,
        (Method::Rk4 | Method::Dopri5 | Method::Dop853 | Method::Taylor, _) => problem != P::Full,
        (Method::Physical, Target::Omega) => problem == P::Full,
        (Method::Radau5, Target::Omega) => problem != P::Full,
        (Method::RotationDamping, Target::Omega) => problem == P::Reduced,
        _ => false,
    }
}

/// One of spintop's methods solving one target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Spintop {
    /// The method.
    pub method: Method,
    /// What it solves for.
    pub target: Target,
}

impl Spintop {
    /// Every (method, target) pair that applies to at least one problem.
    pub fn all() -> Vec<Spintop> {
        let mut out = Vec::new();
        for target in [Target::Omega, Target::OmegaOrientation] {
            for method in SWEPT {
                if ProblemKind::ALL
                    .iter()
                    .any(|p| applies_to(method, *p, target))
                {
                    out.push(Spintop { method, target });
                }
            }
        }
        out
    }
}

impl Solver for Spintop {
    fn source(&self) -> &str {
        "spintop"
    }

    fn method(&self) -> &str {
        name(self.method)
    }

    fn target(&self) -> Target {
        self.target
    }

    fn knob(&self) -> KnobKind {
        knob(self.method)
    }

    fn applies_to(&self, problem: &Problem) -> bool {
        applies_to(self.method, problem.kind(), self.target)
    }

    /// The full ALE's reference is the physical solution at rtol 1e-13: a run
    /// at that tolerance or tighter would be measured against itself. Ω and
    /// O(t) go through a [`Simulation`], which takes no rtol below
    /// [`crate::sim::MIN_RTOL`] (the sweep's 1e-15 is for Ω alone).
    fn accepts(&self, problem: &Problem, knob: Option<Real>) -> bool {
        let rtol = knob.filter(|_| self::knob(self.method) == KnobKind::Rtol);
        let reference = self.method == Method::Physical
            && problem.kind() == ProblemKind::Full
            && rtol.is_some_and(|r| r <= super::problem::FULL_REFERENCE_RTOL);
        let simulated = self.target == Target::OmegaOrientation
            && rtol.is_some_and(|r| r < crate::sim::MIN_RTOL);
        !(reference || simulated)
    }

    fn solve(&self, problem: &Problem, knob: Option<Real>) -> Result<Solution, String> {
        match self.target {
            Target::Omega => solve_omega(self.method, problem, knob),
            Target::OmegaOrientation => solve_with_orientation(self.method, problem, knob),
        }
        .map_err(|e| e.to_string())
    }
}

/// Why a spintop entry could not run.
#[derive(Debug, thiserror::Error)]
enum RunError {
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    #[error(transparent)]
    Sim(#[from] crate::sim::SimError),
    #[error(transparent)]
    Physical(#[from] crate::sim::physical::PhysicalError),
    #[error(transparent)]
    Options(#[from] crate::sim::OptionsError),
    #[error("{0}")]
    NotApplicable(String),
}

fn not_applicable(method: Method, problem: &Problem) -> RunError {
    RunError::NotApplicable(format!(
        "{} does not apply to the {} problem",
        name(method),
        problem.name()
    ))
}

fn knob_value(method: Method, knob: Option<Real>) -> Result<Real, RunError> {
    knob.ok_or_else(|| RunError::NotApplicable(format!("{} needs a knob value", name(method))))
}

/// The adaptive options for `rtol` on `problem`.
fn adaptive(problem: &Problem, rtol: Real) -> Result<AdaptiveOptions, IntegrateError> {
    AdaptiveOptions::new(rtol, problem.atol(rtol))
}

// ANCHOR: run_stepper
/// Drive any [`Stepper`] through the problem's output times and keep its count.
fn run_stepper<S: Stepper<3>, R: Rhs<3>>(
    mut stepper: S,
    rhs: &R,
    times: &[Real],
) -> Result<Solution, IntegrateError> {
    let omega = integrate::solve(&mut stepper, rhs, times)?;
    Ok(Solution {
        omega,
        rotation: None,
        stats: Some(stepper.stats()),
    })
}
// ANCHOR_END: run_stepper

/// Like [`run_stepper`], but step exactly onto every output time instead of
/// reading it from the continuous extension.
fn run_stepper_onto<S: Stepper<3>, R: Rhs<3>>(
    mut stepper: S,
    rhs: &R,
    times: &[Real],
) -> Result<Solution, IntegrateError> {
    let mut omega = Vec::with_capacity(times.len());
    for &t in times {
        while stepper.t() < t {
            stepper.step(rhs, t)?;
        }
        omega.push(*stepper.y());
    }
    Ok(Solution {
        omega,
        rotation: None,
        stats: Some(stepper.stats()),
    })
}

/// Ω alone.
fn solve_omega(
    method: Method,
    problem: &Problem,
    knob: Option<Real>,
) -> Result<Solution, RunError> {
    let times = problem.times();
    let y0 = problem.initial().omega;
    if method == Method::ClosedForm {
        if let Model::Reduced(top) = problem.model() {
            // Evenly spaced outputs by recurrence, re-anchored exactly.
            return Ok(Solution {
                omega: reduced_closed_form_many(top, &y0, times),
                rotation: None,
                stats: Some(Default::default()),
            });
        }
        let omega = times
            .iter()
            .map(|&t| {
                problem
                    .closed_form(t)
                    .ok_or_else(|| not_applicable(method, problem))
            })
            .collect::<Result<Vec<Vec3>, _>>()?;
        return Ok(Solution {
            omega,
            rotation: None,
            stats: Some(Default::default()),
        });
    }
    if method == Method::Physical {
        let Model::Full(top) = problem.model() else {
            return Err(not_applicable(method, problem));
        };
        let rtol = knob_value(method, knob)?;
        let sol = physical_solution(top, &y0, times, rtol)?;
        return Ok(Solution {
            omega: sol.z.iter().map(|z| Vec3::new(z.re, z.im, y0.z)).collect(),
            rotation: None,
            stats: Some(sol.stats),
        });
    }
    if method == Method::RotationDamping {
        let Model::Reduced(top) = problem.model() else {
            return Err(not_applicable(method, problem));
        };
        let h = knob_value(method, knob)?;
        let mut split = Splitting::new(ReducedFlow(*top), Composition::LieTrotter, 0.0, y0, h)?;
        let mut omega = Vec::with_capacity(times.len());
        for &t in times {
            split.advance_to(t)?;
            omega.push(*split.state());
        }
        return Ok(Solution {
            omega,
            rotation: None,
            stats: Some(split.stats()),
        });
    }
    let rhs = problem
        .omega_rhs()
        .ok_or_else(|| not_applicable(method, problem))?;
    let knob = knob_value(method, knob)?;
    if method == Method::Taylor {
        return taylor_omega(problem, rhs, knob, y0, times);
    }
    // NOTE: the model is chosen here, once per solve: each arm hands the
    // stepper a right-hand side of its own type, so the step loop is
    // monomorphic in it and no evaluation matches on the model.
    match rhs {
        OmegaRhs::Truncated(top) => {
            let f = move |_t: Real, w: &State<3>| truncated_ale_rhs(&top, w);
            integrate_omega(method, problem, knob, y0, times, &f)
        }
        OmegaRhs::Reduced(top) => {
            let f = move |_t: Real, w: &State<3>| reduced_ale_rhs(&top, w);
            integrate_omega(method, problem, knob, y0, times, &f)
        }
        OmegaRhs::General(top) => {
            let f = move |_t: Real, w: &State<3>| top.truncated_ale_rhs(w);
            integrate_omega(method, problem, knob, y0, times, &f)
        }
    }
}

/// Ω alone by one of the integrators, with the right-hand side `rhs`.
fn integrate_omega<R: Rhs<3>>(
    method: Method,
    problem: &Problem,
    knob: Real,
    y0: Vec3,
    times: &[Real],
    rhs: &R,
) -> Result<Solution, RunError> {
    Ok(match method {
        Method::Rk4 => run_stepper(Rk4::new(0.0, y0, knob)?, rhs, times)?,
        Method::Dopri5 => run_stepper(Dopri5::new(0.0, y0, adaptive(problem, knob)?)?, rhs, times)?,
        Method::Dop853 => run_stepper(Dop853::new(0.0, y0, adaptive(problem, knob)?)?, rhs, times)?,
        Method::Radau5 => {
            run_stepper_onto(Radau5::new(0.0, y0, adaptive(problem, knob)?)?, rhs, times)?
        }
        _ => return Err(not_applicable(method, problem)),
    })
}

// ANCHOR: taylor_omega
/// Ω alone by the Taylor method: each model hands the stepper its own
/// recurrences (the [`Rhs`] view is what [`integrate::solve`] is given).
fn taylor_omega(
    problem: &Problem,
    rhs: OmegaRhs,
    rtol: Real,
    y0: Vec3,
    times: &[Real],
) -> Result<Solution, RunError> {
    fn run<S: TaylorRhs<3> + Rhs<3> + Copy>(
        system: S,
        y0: Vec3,
        opts: AdaptiveOptions,
        times: &[Real],
    ) -> Result<Solution, IntegrateError> {
        run_stepper(Taylor::new(system, 0.0, y0, opts)?, &system, times)
    }
    let opts = adaptive(problem, rtol)?;
    Ok(match rhs {
        OmegaRhs::Truncated(top) => run(SymmetricTruncated(top), y0, opts, times)?,
        OmegaRhs::Reduced(top) => run(SymmetricReduced(top), y0, opts, times)?,
        OmegaRhs::General(top) => run(GeneralTruncated(top), y0, opts, times)?,
    })
}
// ANCHOR_END: taylor_omega

/// Ω and O(t), the way `spintop simulate` computes them.
fn solve_with_orientation(
    method: Method,
    problem: &Problem,
    knob: Option<Real>,
) -> Result<Solution, RunError> {
    if !applies_to(method, problem.kind(), Target::OmegaOrientation) {
        return Err(not_applicable(method, problem));
    }
    let options = MethodOptions::default();
    let options = match self::knob(method) {
        KnobKind::Rtol => options.with_rtol(knob_value(method, knob)?)?,
        KnobKind::Step => options.with_step(knob_value(method, knob)?)?,
        KnobKind::None => options,
    };
    let mut sim = Simulation::with_method(
        *problem.model(),
        method,
        options,
        *problem.initial(),
        Some(problem.t_end()),
    )?;
    let samples = sim.run(problem.times())?;
    Ok(Solution {
        omega: samples.iter().map(|s| s.omega_vec()).collect(),
        rotation: Some(samples.iter().map(|s| s.rotation_matrix()).collect()),
        stats: Some(sim.stats()),
    })
}
