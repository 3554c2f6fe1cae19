//! The numerical methods: one RK4 step and one Dormand–Prince 5(4) step,
//! each graded on test problems, and probed on fields that single out each
//! stage (`tableau`).

use super::tableau::{self, Observed, Tableau};
use crate::CASES;
use crate::{Again, Grade, Grader, Rng, close, mistake};
use spintop::assignment::DynField;
use spintop::integrate::{dopri5::dopri5_step, rk4::rk4_step as reference_rk4_step};
use spintop::math::{Real, State};
use spintop_runner::fields::Field;
use std::fmt;

/// A step's input. Its right-hand side is one of the test problems
/// ([`Field::TESTS`]) or a probe y' = A y + p(t) chosen to single out the
/// stages: named, never passed as a function, so that a student's runner in
/// another process builds the same one (and no field is an answer).
#[derive(Clone, Copy)]
struct StepInput {
    field: Field,
    t: Real,
    y: State<3>,
    h: Real,
}

impl StepInput {
    /// f as the student's step receives it.
    fn rhs(&self) -> impl Fn(Real, &State<3>) -> State<3> + use<> {
        let field = self.field;
        move |t, y| field.eval(t, y)
    }
}

impl fmt::Debug for StepInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "f = {}, t = {}, y = {:?}, h = {}",
            self.field.describe(),
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
            field: Field::TESTS[i % 2],
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
pub(super) struct Rk4Shape {
    pub(super) weights: [Real; 4],
    pub(super) c: [Real; 3],
    pub(super) from: [(usize, Real); 3],
}

pub(super) const RK4: Rk4Shape = Rk4Shape {
    weights: [1.0, 2.0, 2.0, 1.0],
    c: [0.5, 0.5, 1.0],
    from: [(0, 0.5), (1, 0.5), (2, 1.0)],
};

pub(super) fn rk4_shaped(
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
pub(super) fn rk4_slips() -> Vec<(Rk4Shape, &'static str)> {
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
            "stage 4 (k4) is evaluated at the wrong time: right when f does not depend on t, wrong when it does: the fourth stage evaluates f at the start time, not at the end of the step",
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
            "the third stage steps from the wrong slope: stage 3 (k3) steps from k1, where it must step from k2",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (1, 1.0)],
                ..RK4
            },
            "the fourth stage steps from the wrong slope: stage 4 (k4) steps from k2, where it must step from k3",
        ),
        (
            Rk4Shape {
                from: [(0, 1.0), (1, 0.5), (2, 1.0)],
                ..RK4
            },
            "the second stage steps too far: stage 2 (k2) goes a full step along k1, and the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 1.0), (2, 1.0)],
                ..RK4
            },
            "the third stage steps too far: stage 3 (k3) goes a full step along k2, and the middle stages go half a step",
        ),
        (
            Rk4Shape {
                from: [(0, 0.5), (1, 0.5), (2, 0.5)],
                ..RK4
            },
            "the fourth stage steps only half a step: stage 4 (k4) goes a full step along k3, to the end",
        ),
    ]
}

/// Grade one classical RK4 step.
pub fn rk4_step(seed: u64, student: impl Fn(DynField, Real, &State<3>, Real) -> State<3>) -> Grade {
    rk4_step_on(seed, |f: &Field, t, y: &State<3>, h| {
        student(&|t: Real, y: &State<3>| f.eval(t, y), t, y, h)
    })
}

/// [`rk4_step`], with the right-hand side given by name: how a runner in
/// another process is graded (it builds the named field on its side).
pub fn rk4_step_on(
    seed: u64,
    student: impl Fn(&Field, Real, &State<3>, Real) -> State<3>,
) -> Grade {
    let reference = |x: &StepInput| reference_rk4_step(&x.rhs(), x.t, &x.y, x.h);
    let mut mistakes: Vec<_> = rk4_slips()
        .into_iter()
        .map(|(shape, text)| {
            mistake(text, move |x: &StepInput| {
                rk4_shaped(shape, &x.rhs(), x.t, &x.y, x.h)
            })
        })
        .collect();
    mistakes.extend([
        mistake(
            "your step returns the increment alone: the new state is the old one plus it",
            move |x: &StepInput| reference(x) - x.y,
        ),
        mistake(
            "that is one step of Euler's method: only the first stage is used",
            move |x: &StepInput| x.y + x.rhs()(x.t, &x.y) * x.h,
        ),
        mistake(
            "the slopes were not multiplied by the step size h",
            move |x: &StepInput| x.y + (reference(x) - x.y) / x.h,
        ),
    ]);
    Grader::new(
        "rk4_step",
        "classical RK4, Hairer-Norsett-Wanner I, Table II.1.2",
        seed,
        step_inputs(seed),
        reference,
        |a: &State<3>, b: &State<3>| close(a, b, 1e-13),
    )
    .mistakes(mistakes)
    .probe(rk4_weights_probe)
    .probe(stage_probe(Tableau::rk4(), |y: &State<3>| {
        y.as_slice().to_vec()
    }))
    .probe(step_order_probe(
        "classical RK4",
        reference,
        |y: &State<3>| *y,
    ))
    .labels(&["y₁", "y₂", "y₃"])
    .run(|x| student(&x.field, x.t, &x.y, x.h))
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

/// The inputs that single out the stages of a step (see `tableau`): the
/// failing input and two near it, then y' = A y + p(t) with A = 0 (the step
/// is a quadrature of p, which weighs the stages' times), with A a chain
/// (y₂' = y₁, y₃' = y₂: each stage passes its slope on to the next), with A
/// diagonal (the products of the stages' coefficients), and with a mixed A.
fn stage_inputs(x: &StepInput) -> Vec<StepInput> {
    let affine = |a: [[Real; 3]; 3], p: [[Real; 4]; 3], h: Real| StepInput {
        field: Field::Affine { a, p },
        t: x.t,
        y: x.y,
        h,
    };
    let none = [0.0; 4];
    let chain = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut out = nearby_steps(x).to_vec();
    out.extend([
        affine(
            [[0.0; 3]; 3],
            [
                [0.3, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
            1.0,
        ),
        affine(chain, [[0.5, 0.0, 0.0, 1.0], none, none], 1.0),
        affine(
            chain,
            [[0.0, 0.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0], none],
            0.7,
        ),
        affine(
            [[-2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -0.5]],
            [none; 3],
            1.0,
        ),
        affine(
            [[-1.0, 2.0, 0.0], [-2.0, -1.0, 0.5], [0.3, 0.0, -0.5]],
            [
                [0.0, 1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.5],
                [0.0, 0.0, 1.0, 0.0],
            ],
            0.8,
        ),
    ]);
    out
}

/// Which stage of the student's step is wrong: the single entry (or row,
/// or set of weights) of the method's table that reproduces every answer on
/// the stage inputs; `numbers` lists an answer's numbers.
fn stage_probe<'a, T: 'a>(
    right: Tableau,
    numbers: impl Fn(&T) -> Vec<Real> + 'a,
) -> impl Fn(&StepInput, &Again<'_, StepInput, T>) -> Option<String> + 'a {
    move |x, again| {
        let inputs = stage_inputs(x);
        let mut theirs = Vec::new();
        for s in &inputs {
            theirs.push(numbers(&again(s)?));
        }
        let fields: Vec<_> = inputs.iter().map(StepInput::rhs).collect();
        let seen = Observed {
            probes: inputs
                .iter()
                .zip(&fields)
                .map(|(s, f)| (f as tableau::Rhs<'_>, s.t, s.y, s.h))
                .collect(),
            theirs,
        };
        let slip = tableau::find_slip(&right, &seen)?;
        Some(tableau::slip_words(&right, &slip))
    }
}

/// The weights the student's RK4 step gives its four stages, fitted on
/// three inputs: when the stages are the classical ones and only their
/// weights differ, it says so (and what the weights look like).
fn rk4_weights_probe(x: &StepInput, again: &Again<'_, StepInput, State<3>>) -> Option<String> {
    let mut rows = Vec::new();
    let mut rhs = Vec::new();
    for s in nearby_steps(x) {
        let theirs = again(&s)?;
        let f = s.rhs();
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

/// The step right and the estimate not: the fourth-order solution (an
/// estimate right but for signs is left to the shape, which names them).
fn estimate_probe(
    x: &StepInput,
    again: &Again<'_, StepInput, (State<3>, State<3>)>,
) -> Option<String> {
    let (theirs, right) = (again(x)?, dopri5_step(&x.rhs(), x.t, &x.y, x.h));
    let signs_only = theirs
        .1
        .iter()
        .zip(right.1.iter())
        .all(|(a, b)| (a.abs() - b.abs()).abs() <= 1e-9 * (1e-300 + b.abs()));
    (close(&theirs.0, &right.0, 1e-13) && !signs_only).then(|| {
        "the step is right, the error estimate is not: it is the fifth-order result minus the embedded fourth-order one, which has weights of its own and uses a seventh stage, f at the end of the step from the fifth-order result".to_string()
    })
}

/// Grade one Dormand–Prince 5(4) step: (y₅, y₅ − ŷ₄).
pub fn dp5_step(
    seed: u64,
    student: impl Fn(DynField, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    dp5_step_on(seed, |f: &Field, t, y: &State<3>, h| {
        student(&|t: Real, y: &State<3>| f.eval(t, y), t, y, h)
    })
}

/// [`dp5_step`], with the right-hand side given by name (see [`rk4_step_on`]).
pub fn dp5_step_on(
    seed: u64,
    student: impl Fn(&Field, Real, &State<3>, Real) -> (State<3>, State<3>),
) -> Grade {
    let reference = |x: &StepInput| dopri5_step(&x.rhs(), x.t, &x.y, x.h);
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
    .probe(stage_probe(Tableau::dp5(), |a: &(State<3>, State<3>)| {
        [a.0.as_slice(), a.1.as_slice()].concat()
    }))
    .probe(estimate_probe)
    .probe(step_order_probe("Dormand-Prince 5(4)", reference, |a: &(State<3>, State<3>)| a.0))
    .labels(&[
        "the step's y₁",
        "the step's y₂",
        "the step's y₃",
        "the estimate's y₁",
        "the estimate's y₂",
        "the estimate's y₃",
    ])
    .run(|x| student(&x.field, x.t, &x.y, x.h))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graders::tableau::{Entry, Slip, find_slip};

    /// The slip `find_slip` names for a student whose step is `theirs`.
    fn found(right: &Tableau, theirs: &Tableau, x: &StepInput) -> Option<Slip> {
        let inputs = stage_inputs(x);
        let fields: Vec<_> = inputs.iter().map(StepInput::rhs).collect();
        let seen = Observed {
            probes: inputs
                .iter()
                .zip(&fields)
                .map(|(s, f)| (f as tableau::Rhs<'_>, s.t, s.y, s.h))
                .collect(),
            theirs: inputs
                .iter()
                .zip(&fields)
                .map(|(s, f)| theirs.step(f, s.t, &s.y, s.h))
                .collect(),
        };
        find_slip(right, &seen)
    }

    /// The slips of RK4's and DP5's tables that are not found where they
    /// are: each entry i changed to zero, to minus itself or to another
    /// value (those of the three that `slips(i)` selects), which the
    /// diagnosis must name alone, with its value.
    fn slips_found(slips: impl Fn(usize) -> std::ops::Range<usize>) -> Vec<String> {
        let x = step_inputs(2026)[1];
        let mut misses = Vec::new();
        for right in [Tableau::rk4(), Tableau::dp5()] {
            for (i, e) in right.entries().into_iter().enumerate() {
                let v = right.get(e);
                for wrong in [0.0, -v, 0.5 * v + 0.3][slips(i)].iter().copied() {
                    if (wrong - v).abs() < 1e-12 {
                        continue;
                    }
                    let mut theirs = right.clone();
                    theirs.set(e, wrong);
                    let want = Slip {
                        changed: vec![(e, wrong)],
                    };
                    let got = found(&right, &theirs, &x);
                    let same = got.as_ref().is_some_and(|s| {
                        s.changed.len() == 1
                            && s.changed[0].0 == e
                            && (s.changed[0].1 - wrong).abs() < 1e-8
                    });
                    if !same {
                        misses.push(format!("{e:?} = {wrong}: {got:?}, want {want:?}"));
                    }
                }
            }
        }
        misses
    }

    /// Every entry of both tables, each with one of the three slips in
    /// turn (entry i gets slip i mod 3, so each kind of slip is tried on a
    /// third of the entries): the default tier.
    #[test]
    fn every_entry_of_a_table_with_a_slip_is_found_where_it_is() {
        let misses = slips_found(|i| i % 3..i % 3 + 1);
        assert!(misses.is_empty(), "{}\n{}", misses.len(), misses.join("\n"));
    }

    /// Every entry with each of the three slips (three times the work of
    /// the test above; about 20 s of CPU unoptimised).
    #[test]
    #[ignore = "end-to-end tier: every slip of every entry, cargo test -p spintop-grading -- --ignored"]
    fn every_single_slip_of_a_table_is_found_where_it_is() {
        let misses = slips_found(|_| 0..3);
        assert!(misses.is_empty(), "{}\n{}", misses.len(), misses.join("\n"));
        let _ = Entry::C(0);
    }

    /// A table, the entries a student changed (to the value given), and the
    /// words the diagnosis must say.
    type Case<'a> = (&'a Tableau, Vec<(Entry, Real)>, &'a [&'a str]);

    /// The slips students make, each named by its stage and its entry.
    #[test]
    fn a_wrong_stage_is_named_with_its_entry() {
        let x = step_inputs(7)[0];
        let rk4 = Tableau::rk4();
        let dp5 = Tableau::dp5();
        let cases: Vec<Case> = vec![
            (
                &rk4,
                vec![(Entry::C(1), 0.0)],
                &["stage 2", "time", "start of the step"],
            ),
            (
                &rk4,
                vec![(Entry::C(3), 0.5)],
                &["stage 4", "time", "midpoint"],
            ),
            (
                &rk4,
                vec![(Entry::A(2, 0), 0.5), (Entry::A(2, 1), 0.0)],
                &["stage 3", "from k1", "k2"],
            ),
            (
                &rk4,
                vec![(Entry::A(3, 2), 0.5)],
                &["stage 4", "half a step", "a full step"],
            ),
            (
                &dp5,
                vec![(Entry::B(4), 2187.0 / 6784.0)],
                &["stage 5", "weight", "sign"],
            ),
            (
                &dp5,
                vec![(Entry::A(3, 1), 56.0 / 15.0)],
                &["stage 4", "coefficient on k2", "sign"],
            ),
            (
                &dp5,
                vec![(Entry::C(5), 8.0 / 9.0)],
                &["stage 6", "time", "stage 5"],
            ),
            (
                &dp5,
                vec![(Entry::A(2, 0), 9.0 / 40.0), (Entry::A(2, 1), 3.0 / 40.0)],
                &["stage 3", "coefficients", "swapped"],
            ),
            (
                &dp5,
                vec![(Entry::Bhat(6), 0.0)],
                &["error estimate", "stage 7", "missing"],
            ),
            (
                &dp5,
                vec![(Entry::C(1), 0.25), (Entry::A(1, 0), 0.25)],
                &["stage 2", "time", "coefficient"],
            ),
        ];
        for (right, changes, says) in cases {
            let mut theirs = right.clone();
            for (e, v) in &changes {
                theirs.set(*e, *v);
            }
            let slip =
                found(right, &theirs, &x).unwrap_or_else(|| panic!("{changes:?}: not found"));
            let words = tableau::slip_words(right, &slip);
            for w in says {
                assert!(words.contains(w), "{changes:?}: '{w}' not in: {words}");
            }
        }
    }
}
