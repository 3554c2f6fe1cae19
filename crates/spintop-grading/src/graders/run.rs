//! A whole RK4 run of the reduced model (4.12)–(4.14): its step count, its
//! end, its stages, its model and its order of convergence.

use super::OMEGA;
use super::ch4::reduced_rhs_slips;
use super::numerics::{RK4, Rk4Shape, rk4_shaped, rk4_slips};
use crate::{Again, Grade, Grader, Rng, close, mistake};
use spintop::integrate::rk4::rk4_step as reference_rk4_step;
use spintop::math::{Real, State, Vec3};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use std::fmt;
use std::rc::Rc;

/// A start, an end and a number of steps for [`reduced_rk4`].
#[derive(Clone, Copy)]
struct RunInput {
    ratio: Real,
    tau: Real,
    omega0: Vec3,
    t_end: Real,
    steps: usize,
}

impl fmt::Debug for RunInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ratio = {}, tau = {}, omega0 = {:?}, t_end = {}, steps = {}",
            self.ratio,
            self.tau,
            self.omega0.as_slice(),
            self.t_end,
            self.steps
        )
    }
}

/// A right-hand side of the reduced model (the right one, or a slip of it)
/// from the moment ratio, τ and Ω.
type ModelRhs = fn(Real, Real, &Vec3) -> Vec3;

fn right_model(ratio: Real, tau: Real, w: &Vec3) -> Vec3 {
    match SymmetricTop::new(ratio, tau) {
        Ok(top) => sym::reduced_ale_rhs(&top, w),
        Err(_) => Vec3::repeat(Real::NAN),
    }
}

/// `steps` RK4 steps (of the given shape) of size `h` on the right-hand side
/// `rhs` of the reduced model.
fn run_with(x: &RunInput, shape: Rk4Shape, rhs: ModelRhs, steps: usize, h: Real) -> Vec3 {
    let f = |_t: Real, y: &State<3>| rhs(x.ratio, x.tau, y);
    (0..steps).fold(x.omega0, |y, i| rk4_shaped(shape, &f, i as Real * h, &y, h))
}

/// The reference: `steps` classical RK4 steps of size t_end/steps.
fn reference_run(x: &RunInput) -> Vec3 {
    let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
        return Vec3::repeat(Real::NAN);
    };
    let h = x.t_end / x.steps as Real;
    let f = |_t: Real, y: &State<3>| sym::reduced_ale_rhs(&top, y);
    (0..x.steps).fold(x.omega0, |y, i| {
        reference_rk4_step(&f, i as Real * h, &y, h)
    })
}

/// The order at which the student's run converges, from three step counts.
fn observed_order(x: &RunInput, again: &Again<'_, RunInput, Vec3>) -> Option<(Real, Real)> {
    let top = SymmetricTop::new(x.ratio, x.tau).ok()?;
    let exact = sym::reduced_closed_form(&top, &x.omega0, x.t_end);
    let n = 40;
    let err = |steps: usize| again(&RunInput { steps, ..*x }).map(|w| (w - exact).norm());
    let (e2, e3) = (err(2 * n)?, err(4 * n)?);
    Some(((e2 / e3).log2(), e3 / (1.0 + exact.norm())))
}

/// The end: a run that does not move with t_end, or that stops (or goes on)
/// after another number of the right steps.
fn end_probe(x: &RunInput, again: &Again<'_, RunInput, Vec3>) -> Option<String> {
    let theirs = again(x)?;
    let later = again(&RunInput {
        t_end: 1.37 * x.t_end,
        ..*x
    })?;
    if close(&theirs, &later, 1e-11) {
        return Some(
            "your answer does not change with t_end: the run must end at t_end, so the step size is t_end over the number of steps".to_string(),
        );
    }
    let top = SymmetricTop::new(x.ratio, x.tau).ok()?;
    let h = x.t_end / x.steps as Real;
    let f = |_t: Real, y: &State<3>| sym::reduced_ale_rhs(&top, y);
    let mut y = x.omega0;
    for k in 1..=3 * x.steps {
        y = reference_rk4_step(&f, (k - 1) as Real * h, &y, h);
        if k != x.steps && close(&theirs, &y, 1e-11) {
            return Some(format!(
                "your run takes {k} steps of size t_end/steps, not steps = {}: it ends at t = {}, not at t_end = {} (count the loop's steps)",
                x.steps,
                spintop::numbers::fmt_time(k as Real * h),
                spintop::numbers::fmt_time(x.t_end)
            ));
        }
    }
    None
}

/// The order at which the run converges, and what it says.
fn order_probe(x: &RunInput, again: &Again<'_, RunInput, Vec3>) -> Option<String> {
    let (order, finest) = observed_order(x, again)?;
    Some(if !order.is_finite() {
        "your answer does not change with the number of steps: it is not a run of `steps` RK4 steps"
            .to_string()
    } else if (3.5..=4.6).contains(&order) && finest > 1e-7 {
        "your run converges at order 4, but to a wrong answer: the right-hand side it integrates is not (4.12)-(4.14), or the start or the end is wrong".to_string()
    } else if order.abs() < 0.3 {
        "the error does not shrink as the steps get smaller: the run converges to a wrong answer (the step size, the number of steps, or the right-hand side)".to_string()
    } else if order < 3.5 {
        format!(
            "your run converges at order {order:.2}, not 4: it is not the classical RK4 (a stage of your step, or a lower-order method)"
        )
    } else {
        format!(
            "your run's error falls at order {order:.2} but it is not N classical RK4 steps: did you take more steps than asked, or a method other than RK4?"
        )
    })
}

/// A plausible wrong run: what it says, and its Ω(t_end).
type RunSlip = (String, Rc<dyn Fn(&RunInput) -> Vec3>);

fn run_slip(text: impl Into<String>, run: impl Fn(&RunInput) -> Vec3 + 'static) -> RunSlip {
    (text.into(), Rc::new(run))
}

/// The plausible wrong runs: a wrong stage of the step, a wrong model (the
/// slips of (4.12)–(4.14)), a wrong number or size of the steps, Euler.
fn run_slips() -> Vec<RunSlip> {
    let h = |x: &RunInput| x.t_end / x.steps as Real;
    let mut out: Vec<RunSlip> = rk4_slips()
        .into_iter()
        .filter(|(s, _)| s.from != RK4.from || s.weights != RK4.weights)
        .map(|(shape, text)| {
            run_slip(
                format!("your RK4 step is wrong: {text}"),
                move |x: &RunInput| run_with(x, shape, right_model, x.steps, h(x)),
            )
        })
        .collect();
    out.extend(reduced_rhs_slips().into_iter().map(|(text, model)| {
        let text = if text.starts_with("that is the truncated model") {
            "you integrated the truncated model (4.2)-(4.4), not the reduced one (4.12)-(4.14)"
                .to_string()
        } else {
            format!("your run integrates a wrong model: {text}")
        };
        run_slip(text, move |x: &RunInput| {
            run_with(x, RK4, model, x.steps, h(x))
        })
    }));
    out.extend([
        run_slip(
            "one step too many: your run takes steps + 1 steps of size t_end/steps and ends past t_end (count the loop's steps)",
            move |x: &RunInput| run_with(x, RK4, right_model, x.steps + 1, h(x)),
        ),
        run_slip(
            "one step too few (an off-by-one in the loop): your run takes steps - 1 steps of size t_end/steps and stops short of t_end (count the loop's steps)",
            move |x: &RunInput| run_with(x, RK4, right_model, x.steps - 1, h(x)),
        ),
        run_slip(
            "the step size is t_end/(steps + 1): with `steps` steps the run stops short of t_end",
            |x: &RunInput| run_with(x, RK4, right_model, x.steps, x.t_end / (x.steps + 1) as Real),
        ),
        run_slip(
            "the step size is t_end/(steps - 1): with `steps` steps the run ends past t_end",
            |x: &RunInput| run_with(x, RK4, right_model, x.steps, x.t_end / (x.steps - 1) as Real),
        ),
        run_slip(
            "the step size is 1/steps: the run ends at t = 1, not at t_end (the step size is t_end over the number of steps)",
            |x: &RunInput| run_with(x, RK4, right_model, x.steps, 1.0 / x.steps as Real),
        ),
        run_slip(
            "the step size is wrong: each of your steps is t_end long, so the run goes on to steps × t_end instead of ending at the end time t_end (divide t_end among the steps)",
            |x: &RunInput| run_with(x, RK4, right_model, x.steps, x.t_end),
        ),
        run_slip(
            "your run returns the start: no step was taken (is the loop empty, or is the state never updated?)",
            |x: &RunInput| x.omega0,
        ),
        run_slip(
            "that is the exact Ω(t_end) of the closed form (4.15)-(4.16), not `steps` RK4 steps: the assignment asks for the numerical run, whose error the book measures against the closed form",
            |x: &RunInput| match SymmetricTop::new(x.ratio, x.tau) {
                Ok(top) => sym::reduced_closed_form(&top, &x.omega0, x.t_end),
                Err(_) => Vec3::repeat(Real::NAN),
            },
        ),
        run_slip(
            "that is Euler's method (order 1), not RK4 (order 4): only the first slope of each step is used",
            move |x: &RunInput| {
                (0..x.steps).fold(x.omega0, |y, _| y + right_model(x.ratio, x.tau, &y) * h(x))
            },
        ),
    ]);
    out
}

/// The slips again on short runs of a few steps, where every run stays tame
/// (a step t_end long on a long run can blow up, and then no two runs
/// agree): the failing input shortened, with 3 and with 5 steps.
fn tame_probe(
    slips: Vec<RunSlip>,
) -> impl Fn(&RunInput, &Again<'_, RunInput, Vec3>) -> Option<String> {
    move |x, again| {
        let tame = [3, 5].map(|steps| RunInput {
            t_end: x.t_end.min(0.3),
            steps,
            ..*x
        });
        let theirs = [again(&tame[0])?, again(&tame[1])?];
        if tame
            .iter()
            .zip(&theirs)
            .all(|(t, a)| close(a, &reference_run(t), 1e-11))
        {
            return None;
        }
        slips.iter().find_map(|(text, run)| {
            tame.iter()
                .zip(&theirs)
                .all(|(t, a)| close(a, &run(t), 1e-11))
                .then(|| text.clone())
        })
    }
}

/// Grade a whole RK4 run of the reduced model: `steps` equal classical RK4
/// steps from 0 to `t_end` must give the same Ω(t_end) as spintop's, to
/// rounding; a wrong run is told apart by its step count, its end time, its
/// stages, its model or its order of convergence.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
pub fn reduced_rk4(seed: u64, student: impl Fn(Real, Real, Vec3, Real, usize) -> Vec3) -> Grade {
    let mut rng = Rng::new(seed);
    let inputs: Vec<RunInput> = (0..20)
        .map(|_| {
            let mut pick = || rng.sign() * rng.uniform(0.5, 1.5);
            let omega0 = Vec3::new(pick(), pick(), pick());
            RunInput {
                ratio: rng.uniform(0.2, 0.8),
                tau: rng.uniform(0.1, 0.5),
                omega0,
                t_end: rng.uniform(2.0, 4.0),
                steps: 20 + (rng.next_u64() % 181) as usize,
            }
        })
        .collect();
    let mistakes = run_slips()
        .into_iter()
        .map(|(text, run)| mistake(text, move |x: &RunInput| run(x)))
        .collect();
    Grader::new(
        "reduced_rk4",
        "Eqs. (4.12)-(4.14), integrated by RK4",
        seed,
        inputs,
        reference_run,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-11),
    )
    .mistakes(mistakes)
    .probe(tame_probe(run_slips()))
    .probe(end_probe)
    .probe(order_probe)
    .labels(&OMEGA)
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t_end, x.steps))
}
