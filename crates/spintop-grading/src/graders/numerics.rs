//! The numerical methods: one RK4 step, one Dormand–Prince 5(4) step, and a
//! whole RK4 run of the reduced model.

use super::OMEGA;
use crate::CASES;
use crate::{Again, Grade, Grader, Rng, close, mistake};
use spintop::assignment::DynField;
use spintop::integrate::{dopri5::dopri5_step, rk4::rk4_step as reference_rk4_step};
use spintop::math::{Real, State, Vec3};
use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
use std::fmt;

/// The test problems of the step graders: a non-autonomous linear system and
/// the reduced ALE (4.12), as `(name, f)`.
type Field = fn(Real, &State<3>) -> State<3>;

fn fields() -> [(&'static str, Field); 2] {
    fn linear(t: Real, y: &State<3>) -> State<3> {
        State::<3>::new(
            -0.5 * y[0] + 2.0 * y[1] + t.sin(),
            -2.0 * y[0] - 0.5 * y[1],
            -y[2] + t * t,
        )
    }
    fn reduced(_t: Real, y: &State<3>) -> State<3> {
        let top = SymmetricTop::figure();
        sym::reduced_ale_rhs(&top, &Vec3::new(y[0], y[1], y[2]))
    }
    [("linear", linear), ("reduced ALE (4.12), tau = 1", reduced)]
}

#[derive(Clone, Copy)]
struct StepInput {
    field: usize,
    t: Real,
    y: State<3>,
    h: Real,
}

impl fmt::Debug for StepInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "f = {}, t = {}, y = {:?}, h = {}",
            fields()[self.field].0,
            self.t,
            self.y.as_slice(),
            self.h
        )
    }
}

fn step_inputs(seed: u64) -> Vec<StepInput> {
    let mut rng = Rng::new(seed);
    (0..CASES)
        .map(|i| StepInput {
            field: i % 2,
            t: rng.uniform(-1.0, 3.0),
            y: State::<3>::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            ),
            h: rng.uniform(0.01, 0.4),
        })
        .collect()
}

/// An RK4 step with one thing changed: `weights` of the four slopes (over
/// 6), the time of each stage after the first as a fraction of h (`c`), and
/// for each stage after the first, which slope it steps from and how far
/// (`from`, as (stage, fraction of h)).
#[derive(Clone, Copy)]
struct Rk4Shape {
    weights: [Real; 4],
    c: [Real; 3],
    from: [(usize, Real); 3],
}

const RK4: Rk4Shape = Rk4Shape {
    weights: [1.0, 2.0, 2.0, 1.0],
    c: [0.5, 0.5, 1.0],
    from: [(0, 0.5), (1, 0.5), (2, 1.0)],
};

fn rk4_shaped(
    shape: Rk4Shape,
    f: &dyn Fn(Real, &State<3>) -> State<3>,
    t: Real,
    y: &State<3>,
    h: Real,
) -> State<3> {
    let mut k = [State::<3>::zeros(); 4];
    k[0] = f(t, y);
    for s in 1..4 {
        let (j, a) = shape.from[s - 1];
        k[s] = f(t + shape.c[s - 1] * h, &(y + k[j] * (a * h)));
    }
    y + (k[0] * shape.weights[0]
        + k[1] * shape.weights[1]
        + k[2] * shape.weights[2]
        + k[3] * shape.weights[3])
        * (h / 6.0)
}

/// The plausible slips in an RK4 step, each with what it says.
fn rk4_slips() -> Vec<(Rk4Shape, &'static str)> {
    vec![
        (
            Rk4Shape {
                weights: [1.0, 1.0, 2.0, 2.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones: the two middle stages count twice, the ends once",
        ),
        (
            Rk4Shape {
                weights: [2.0, 1.0, 1.0, 2.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones: the two middle stages count twice, the ends once",
        ),
        (
            Rk4Shape {
                weights: [1.0, 1.0, 1.0, 1.0],
                ..RK4
            },
            "the weights of the four stages are not the classical ones (they must add up to 6 with the middle ones doubled)",
        ),
        (
            Rk4Shape {
                c: [0.5, 0.5, 0.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the fourth stage evaluates f at the start time, not at the end of the step",
        ),
        (
            Rk4Shape {
                c: [0.0, 0.0, 0.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the stages evaluate f at the start time, not at the midpoint and the end",
        ),
        (
            Rk4Shape {
                c: [1.0, 1.0, 1.0],
                ..RK4
            },
            "right when f does not depend on t, wrong when it does: the middle stages evaluate f at the end of the step, not at the midpoint",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (0, 0.5), (2, 1.0)],
                ..RK4
            },
            "the third stage steps from the wrong slope: it must step from the second slope, and yours steps from the first",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (1, 1.0)],
                ..RK4
            },
            "the fourth stage steps from the wrong slope: it must step from the third slope, and yours steps from the second",
        ),
        (
            Rk4Shape {
                from: [(0, 1.0), (1, 0.5), (2, 1.0)],
                ..RK4
            },
            "the second stage steps too far: the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 1.0), (2, 1.0)],
                ..RK4
            },
            "the third stage steps too far: the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (2, 0.5)],
                ..RK4
            },
            "the fourth stage steps only half a step: it goes the whole step, to the end",
        ),
    ]
}

/// Grade one classical RK4 step.
pub fn rk4_step(seed: u64, student: impl Fn(DynField, Real, &State<3>, Real) -> State<3>) -> Grade {
    let f = |x: &StepInput| fields()[x.field].1;
    let mut mistakes: Vec<_> = rk4_slips()
        .into_iter()
        .map(|(shape, text)| {
            mistake(text, move |x: &StepInput| {
                rk4_shaped(shape, &f(x), x.t, &x.y, x.h)
            })
        })
        .collect();
    mistakes.extend([
        mistake(
            "your step returns the increment alone: the new state is the old one plus it",
            move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h) - x.y,
        ),
        mistake(
            "that is one step of Euler's method: only the first stage is used",
            move |x: &StepInput| x.y + f(x)(x.t, &x.y) * x.h,
        ),
        mistake(
            "the slopes were not multiplied by the step size h",
            move |x: &StepInput| x.y + (reference_rk4_step(&f(x), x.t, &x.y, x.h) - x.y) / x.h,
        ),
    ]);
    Grader::new(
        "rk4_step",
        "classical RK4, Hairer-Norsett-Wanner I, Table II.1.2",
        seed,
        step_inputs(seed),
        move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h),
        |a: &State<3>, b: &State<3>| close(a, b, 1e-13),
    )
    .mistakes(mistakes)
    .probe(rk4_weights_probe)
    .probe(step_order_probe(
        "classical RK4",
        move |x: &StepInput| reference_rk4_step(&f(x), x.t, &x.y, x.h),
        |y: &State<3>| *y,
    ))
    .labels(&["y₁", "y₂", "y₃"])
    .run(|x| student(&fields()[x.field].1, x.t, &x.y, x.h))
}

/// The inputs a step probe tries beside `x`: the same field, nearby starts.
fn nearby_steps(x: &StepInput) -> [StepInput; 3] {
    [
        *x,
        StepInput {
            t: x.t + 0.37,
            y: x.y * 0.8 + State::<3>::repeat(0.1),
            ..*x
        },
        StepInput {
            t: x.t - 0.21,
            y: x.y.map(|v| -v) + State::<3>::new(0.2, -0.1, 0.05),
            ..*x
        },
    ]
}

/// The weights the student's RK4 step gives its four stages, fitted on
/// three inputs: when the stages are the classical ones and only their
/// weights differ, it says so (and what the weights look like).
fn rk4_weights_probe(x: &StepInput, again: &Again<'_, StepInput, State<3>>) -> Option<String> {
    let mut rows = Vec::new();
    let mut rhs = Vec::new();
    for s in nearby_steps(x) {
        let theirs = again(&s)?;
        let f = fields()[s.field].1;
        let k1 = f(s.t, &s.y);
        let k2 = f(s.t + s.h / 2.0, &(s.y + k1 * (s.h / 2.0)));
        let k3 = f(s.t + s.h / 2.0, &(s.y + k2 * (s.h / 2.0)));
        let k4 = f(s.t + s.h, &(s.y + k3 * s.h));
        for c in 0..3 {
            rows.extend([k1[c], k2[c], k3[c], k4[c]].map(|k| k * s.h));
            rhs.push(theirs[c] - s.y[c]);
        }
    }
    let a = nalgebra::DMatrix::from_row_slice(rhs.len(), 4, &rows);
    let b = nalgebra::DVector::from_vec(rhs);
    let w = a.clone().svd(true, true).solve(&b, 1e-14).ok()?;
    let fits = (&a * &w - &b).norm() <= 1e-10 * (1.0 + b.norm());
    let classical = nalgebra::DVector::from_vec(vec![1.0, 2.0, 2.0, 1.0]) / 6.0;
    (fits && (&w - classical).norm() > 1e-8).then(|| {
        let w6: Vec<String> = w.iter().map(|v| format!("{:.3}", 6.0 * v)).collect();
        format!(
            "your four stages are right, but you combine them with other weights: about ({}) over 6; the classical step counts the middle two twice and the ends once",
            w6.join(", ")
        )
    })
}

/// How the student's step approaches the right one as h shrinks: a step
/// that gets closer like a power of h is a consistent method with a
/// coefficient or a node wrong; `part` picks the state out of an answer.
fn step_order_probe<'a, T: 'a>(
    method: &'static str,
    reference: impl Fn(&StepInput) -> T + 'a,
    part: impl Fn(&T) -> State<3> + 'a,
) -> impl Fn(&StepInput, &Again<'_, StepInput, T>) -> Option<String> + 'a {
    move |x, again| {
        let dev = |h: Real| -> Option<Real> {
            let s = StepInput { h, ..*x };
            Some((part(&again(&s)?) - part(&reference(&s))).norm())
        };
        let (d1, d2, d3) = (dev(x.h)?, dev(x.h / 2.0)?, dev(x.h / 4.0)?);
        if !(d1 > 0.0 && d2 > 0.0 && d3 > 0.0) {
            return None;
        }
        let p = (d2 / d3).log2();
        (p >= 1.5 && (d1 / d2).log2() >= 1.0).then(|| {
            format!(
                "your step is not {method}, but close to it, and closer as h shrinks (the difference falls like h^{p:.1}): a coefficient, a weight or the time of a stage is wrong; check each against the method's table"
            )
        })
    }
}

/// Grade one Dormand–Prince 5(4) step: (y₅, y₅ − ŷ₄).
pub fn dp5_step(
    seed: u64,
    student: impl Fn(DynField, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    let f = |x: &StepInput| fields()[x.field].1;
    let reference = move |x: &StepInput| dopri5_step(&f(x), x.t, &x.y, x.h);
    Grader::new(
        "dp5_step",
        "Dormand-Prince 5(4), Hairer-Norsett-Wanner I, Table II.5.2",
        seed,
        step_inputs(seed),
        reference,
        |a: &(State<3>, State<3>), b: &(State<3>, State<3>)| {
            close(&a.0, &b.0, 1e-13) && (a.1 - b.1).norm() <= 1e-13 + 1e-9 * b.1.norm()
        },
    )
    .mistakes(vec![
        mistake(
            "the step is right, the error estimate has the wrong sign: it is the fifth-order result minus the fourth",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5, -e)
            },
        ),
        mistake(
            "the fourth-order solution was returned as the step: the step is the fifth-order one (local extrapolation)",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5 - e, e)
            },
        ),
        mistake(
            "the error estimate is the whole new state, not the difference of the two solutions",
            move |x: &StepInput| {
                let (y5, _) = reference(x);
                (y5, y5)
            },
        ),
        mistake(
            "the error estimate is the difference of the two increments divided by h: both solutions already carry the factor h",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5, e / x.h)
            },
        ),
        mistake(
            "your step returns the increment alone: the new state is the old one plus it",
            move |x: &StepInput| {
                let (y5, e) = reference(x);
                (y5 - x.y, e)
            },
        ),
    ])
    .probe(move |x: &StepInput, again: &Again<'_, StepInput, (State<3>, State<3>)>| {
        // The step right, the estimate not: the fourth-order solution. (An
        // estimate right but for signs is left to the shape, which names them.)
        let (theirs, right) = (again(x)?, reference(x));
        let signs_only = theirs
            .1
            .iter()
            .zip(right.1.iter())
            .all(|(a, b)| (a.abs() - b.abs()).abs() <= 1e-9 * (1e-300 + b.abs()));
        (close(&theirs.0, &right.0, 1e-13) && !signs_only).then(|| {
            "the step is right, the error estimate is not: it is the fifth-order result minus the embedded fourth-order one, which has weights of its own and uses a seventh stage, f at the end of the step from the fifth-order result".to_string()
        })
    })
    .probe(step_order_probe("Dormand-Prince 5(4)", reference, |a: &(State<3>, State<3>)| a.0))
    .labels(&[
        "the step's y₁",
        "the step's y₂",
        "the step's y₃",
        "the estimate's y₁",
        "the estimate's y₂",
        "the estimate's y₃",
    ])
    .run(|x| student(&fields()[x.field].1, x.t, &x.y, x.h))
}

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

/// `steps` RK4 steps (of the given shape) of size `h` on the right-hand side
/// `rhs` of the reduced model.
fn run_with(
    x: &RunInput,
    shape: Rk4Shape,
    rhs: fn(&SymmetricTop, &Vec3) -> Vec3,
    steps: usize,
    h: Real,
) -> Vec3 {
    let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
        return Vec3::repeat(Real::NAN);
    };
    let f = |_t: Real, y: &State<3>| rhs(&top, y);
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
    let mut mistakes: Vec<_> = rk4_slips()
        .into_iter()
        .filter(|(s, _)| s.from != RK4.from || s.weights != RK4.weights)
        .map(|(shape, text)| {
            let text = format!("your RK4 step is wrong: {text}");
            mistake(text, move |x: &RunInput| {
                run_with(
                    x,
                    shape,
                    sym::reduced_ale_rhs,
                    x.steps,
                    x.t_end / x.steps as Real,
                )
            })
        })
        .collect();
    mistakes.extend([
        mistake(
            "you integrated the truncated model (4.2)-(4.4), not the reduced one (4.12)-(4.14)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::truncated_ale_rhs, x.steps, x.t_end / x.steps as Real),
        ),
        mistake(
            "one step too many: your run takes steps + 1 steps of size t_end/steps and ends past t_end (count the loop's steps)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps + 1, x.t_end / x.steps as Real),
        ),
        mistake(
            "one step too few: your run takes steps - 1 steps of size t_end/steps and stops short of t_end (count the loop's steps)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps - 1, x.t_end / x.steps as Real),
        ),
        mistake(
            "the step size is t_end/(steps + 1): with `steps` steps the run stops short of t_end".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end / (x.steps + 1) as Real),
        ),
        mistake(
            "the step size is t_end/(steps - 1): with `steps` steps the run ends past t_end".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end / (x.steps - 1) as Real),
        ),
        mistake(
            "your run returns the start: no step was taken (is the loop empty, or is the state never updated?)".to_string(),
            |x: &RunInput| x.omega0,
        ),
        mistake(
            "that is the exact Ω(t_end) of the closed form (4.15)-(4.16), not `steps` RK4 steps: the assignment asks for the numerical run, whose error the book measures against the closed form".to_string(),
            |x: &RunInput| match SymmetricTop::new(x.ratio, x.tau) {
                Ok(top) => sym::reduced_closed_form(&top, &x.omega0, x.t_end),
                Err(_) => Vec3::repeat(Real::NAN),
            },
        ),
        mistake(
            "the run ends at the wrong time: each step is t_end long (h = t_end/steps was not divided)".to_string(),
            |x: &RunInput| run_with(x, RK4, sym::reduced_ale_rhs, x.steps, x.t_end),
        ),
        mistake(
            "that is Euler's method, not RK4: only the first slope of each step is used".to_string(),
            |x: &RunInput| {
                let Ok(top) = SymmetricTop::new(x.ratio, x.tau) else {
                    return Vec3::repeat(Real::NAN);
                };
                let h = x.t_end / x.steps as Real;
                (0..x.steps).fold(x.omega0, |y, _| y + sym::reduced_ale_rhs(&top, &y) * h)
            },
        ),
    ]);
    Grader::new(
        "reduced_rk4",
        "Eqs. (4.12)-(4.14), integrated by RK4",
        seed,
        inputs,
        reference_run,
        |a: &Vec3, b: &Vec3| close(a, b, 1e-11),
    )
    .mistakes(mistakes)
    .probe(end_probe)
    .probe(order_probe)
    .labels(&OMEGA)
    .run(|x| student(x.ratio, x.tau, x.omega0, x.t_end, x.steps))
}
