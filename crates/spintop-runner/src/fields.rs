//! The right-hand sides `f(t, y)` a step assignment (`rk4_step`,
//! `dp5_step`) is given. A function cannot cross a pipe, so the grader
//! names the field and its parameters, and the runner builds the same
//! field on its side: the grader's reference step and the student's step
//! evaluate the very same code.
//!
//! Each is a test problem and never an assignment's answer (the reduced
//! ALE (4.12), which a step grader once used, is one: a runner handed it
//! would hold a reference answer).

use spintop::assignment::{Real, State};

/// A right-hand side of `y' = f(t, y)` for three components.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field {
    /// A damped rotation of (y₁, y₂) forced by sin t, and y₃ decaying
    /// towards t²: linear in y, and t matters.
    Linear,
    /// A damped pendulum (y₁ the angle, y₂ its rate) driven by cos t, which
    /// drives a decaying y₃ through y₁y₂: nonlinear in y, and t matters.
    Pendulum,
    /// `y' = A y + p(t)`, with `a` the matrix A (by rows) and `p[i]` the
    /// coefficients of a cubic in t for component i (constant term first):
    /// parameters chosen to single out one stage of a method (a field that
    /// depends on t alone tests the nodes and weights as a quadrature; a
    /// nilpotent A, the stages that feed each other).
    Affine {
        /// A, by rows.
        a: [[Real; 3]; 3],
        /// p(t) of each component: p₀ + p₁t + p₂t² + p₃t³.
        p: [[Real; 4]; 3],
    },
}

impl Field {
    /// The fields every step grader tries, in its order.
    pub const TESTS: [Field; 2] = [Field::Linear, Field::Pendulum];

    /// f(t, y).
    pub fn eval(&self, t: Real, y: &State<3>) -> State<3> {
        match self {
            Field::Linear => State::<3>::new(
                -0.5 * y[0] + 2.0 * y[1] + t.sin(),
                -2.0 * y[0] - 0.5 * y[1],
                -y[2] + t * t,
            ),
            Field::Pendulum => State::<3>::new(
                y[1],
                -y[0].sin() - 0.2 * y[1] + 0.5 * t.cos(),
                y[0] * y[1] - 0.5 * y[2],
            ),
            Field::Affine { a, p } => State::<3>::from_fn(|i, _| {
                let ay: Real = (0..3).map(|j| a[i][j] * y[j]).sum();
                let [p0, p1, p2, p3] = p[i];
                ay + p0 + t * (p1 + t * (p2 + t * p3))
            }),
        }
    }

    /// Its name, as a report prints it.
    pub fn describe(&self) -> String {
        match self {
            Field::Linear => "a linear test problem (a damped rotation forced by sin t)".into(),
            Field::Pendulum => "a nonlinear test problem (a driven damped pendulum)".into(),
            Field::Affine { a, p } => format!("y' = A y + p(t), A = {a:?}, p = {p:?}"),
        }
    }

    /// Its numbers on the wire: a kind, then its parameters.
    pub(crate) fn numbers(&self) -> Vec<Real> {
        match self {
            Field::Linear => vec![0.0],
            Field::Pendulum => vec![1.0],
            Field::Affine { a, p } => {
                let mut out = vec![2.0];
                out.extend(a.iter().flatten());
                out.extend(p.iter().flatten());
                out
            }
        }
    }

    /// The field whose numbers start `from` (which it consumes).
    pub(crate) fn from_numbers(from: &mut &[Real]) -> Option<Self> {
        let (kind, rest) = from.split_first()?;
        let field = match *kind {
            0.0 => {
                *from = rest;
                Field::Linear
            }
            1.0 => {
                *from = rest;
                Field::Pendulum
            }
            2.0 if rest.len() >= 21 => {
                let (mine, rest) = rest.split_at(21);
                *from = rest;
                let a = std::array::from_fn(|i| std::array::from_fn(|j| mine[3 * i + j]));
                let p = std::array::from_fn(|i| std::array::from_fn(|k| mine[9 + 4 * i + k]));
                Field::Affine { a, p }
            }
            _ => return None,
        };
        Some(field)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::{numbers, value};

    #[test]
    fn a_field_crosses_the_wire_and_evaluates_the_same() {
        let affine = Field::Affine {
            a: [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]],
            p: [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 2.0, 0.0, 0.0],
                [0.0, 0.0, 0.0, 3.0],
            ],
        };
        let y = State::<3>::new(0.3, -0.2, 0.9);
        for f in [Field::Linear, Field::Pendulum, affine] {
            let back: Field = value(&numbers(&f)).unwrap();
            assert_eq!(back, f);
            assert_eq!(back.eval(0.7, &y), f.eval(0.7, &y));
        }
        // y' = (y₂ + 1, y₃ + 2t, 3t³) at t = 2.
        let v = affine.eval(2.0, &y);
        assert_eq!([v[0], v[1], v[2]], [-0.2 + 1.0, 0.9 + 4.0, 24.0]);
        assert_eq!(value::<Field>(&[7.0]), None);
        assert_eq!(value::<Field>(&[2.0, 1.0]), None);
    }
}
