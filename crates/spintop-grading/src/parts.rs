//! Which part of a formula is wrong: vary one input at a time.
//!
//! A formula is a sum of terms, and most inputs feed only some of them: with
//! Z = 0 only the retarded term of (A.1) is left, with τ = 0 only the free
//! precession of (4.12), with equal moments of inertia no gyroscopic term. A
//! [`Part`] is such a condition. The probe applies each condition to the
//! failing input and to two more, asks the student's function again, and
//! names the first part that is wrong at two of them or more, with how it
//! is wrong: a factor that is the same at every input (2, −1, 180/π), or a
//! named parameter (m_em, the moment of inertia) to a power, the same at
//! every input; otherwise the shape of the answer at the failing input.

use super::diagnosis::{self, factor_words};
use super::{Again, Answer, Grader};
use spintop::math::Real;
use std::fmt;
use std::rc::Rc;

/// A condition on the input that leaves one part of the formula alone.
pub(crate) struct Part<'a, I> {
    /// The condition, as a clause: "with Z = 0".
    when: String,
    /// What is left: "the retarded term".
    what: String,
    /// Where to look when that part is wrong (may be empty).
    advice: String,
    at: Rc<dyn Fn(&I) -> I + 'a>,
}

/// A part: `at` applies the condition `when`, which leaves `what`.
pub(crate) fn part<'a, I>(
    when: &str,
    what: &str,
    advice: &str,
    at: impl Fn(&I) -> I + 'a,
) -> Part<'a, I> {
    Part {
        when: when.into(),
        what: what.into(),
        advice: advice.into(),
        at: Rc::new(at),
    }
}

/// A parameter (or an expression of the input) a part can be off by.
pub(crate) struct Named<'a, I> {
    name: &'static str,
    value: Rc<dyn Fn(&I) -> Real + 'a>,
}

pub(crate) fn named<'a, I>(name: &'static str, value: impl Fn(&I) -> Real + 'a) -> Named<'a, I> {
    Named {
        name,
        value: Rc::new(value),
    }
}

/// `actual` = k · `expected`, if it is.
fn proportional(actual: &[Real], expected: &[Real]) -> Option<Real> {
    let dot = |a: &[Real], b: &[Real]| a.iter().zip(b).map(|(x, y)| x * y).sum::<Real>();
    let ee = dot(expected, expected);
    if ee == 0.0 {
        return None;
    }
    let k = dot(actual, expected) / ee;
    let off: Real = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| (a - k * e).powi(2))
        .sum::<Real>()
        .sqrt();
    (off <= 1e-9 * (ee.sqrt() * (1.0 + k.abs())) && k != 0.0).then_some(k)
}

/// How a part that is `ks[j]` times the right one at `inputs[j]` is wrong.
fn factor_detail<I>(ks: &[Real], inputs: &[I], named: &[Named<'_, I>]) -> Option<String> {
    let same = |a: Real, b: Real| (a - b).abs() <= 1e-9 * b.abs().max(1e-300);
    if ks.iter().all(|k| same(*k, ks[0])) {
        let k = ks[0];
        let words = factor_words(k);
        let degrees = 180.0 / std::f64::consts::PI;
        return Some(if same(k, -1.0) {
            "it has the wrong sign".into()
        } else if same(k.abs(), degrees) || same(k.abs(), 1.0 / degrees) {
            format!(
                "it is {words} times the right one: an angle in degrees where radians belong, or the reverse"
            )
        } else {
            format!("it is {words} times the right one")
        });
    }
    for n in named {
        for (p, words) in [
            (1, "a factor {} too many"),
            (-1, "a factor {} missing"),
            (2, "a factor {}² too many"),
            (-2, "a factor {}² missing"),
        ] {
            for sign in [1.0, -1.0] {
                let fits = ks
                    .iter()
                    .zip(inputs)
                    .all(|(k, i)| same(*k, sign * (n.value)(i).powi(p)));
                if fits {
                    let sign_words = if sign < 0.0 {
                        ", and the wrong sign"
                    } else {
                        ""
                    };
                    return Some(format!("{}{sign_words}", words.replace("{}", n.name)));
                }
            }
        }
    }
    Some(format!(
        "it is {} times the right one here, and another multiple at another input",
        factor_words(ks[0])
    ))
}

impl<'a, I: Clone + fmt::Debug + 'a, T: Answer + 'a> Grader<'a, I, T> {
    /// A probe that names the first wrong part among `parts`, and how it
    /// is off (by a simple factor, or by one of `named` to a power).
    pub(crate) fn parts(mut self, parts: Vec<Part<'a, I>>, named: Vec<Named<'a, I>>) -> Self {
        let reference = Rc::clone(&self.reference);
        let close = Rc::clone(&self.close);
        let labels = self.labels.clone().unwrap_or_else(T::labels);
        // Two more inputs to confirm on, from the middle of the list (the
        // failing input is the first wrong one, usually near the start).
        let n = self.inputs.len();
        let others: Vec<I> = self.inputs.iter().skip(n / 2).take(3).cloned().collect();
        self.probes
            .push(Box::new(move |x: &I, again: &Again<'_, I, T>| {
                // A whole answer off by a factor is the shape's to name.
                if proportional(&again(x)?.parts(), &reference(x).parts()).is_some() {
                    return None;
                }
                let key = format!("{x:?}");
                let mut at: Vec<I> = vec![x.clone()];
                at.extend(
                    others
                        .iter()
                        .filter(|o| format!("{o:?}") != key)
                        .take(2)
                        .cloned(),
                );
                for p in &parts {
                    let mut wrong: Vec<(I, T, T)> = Vec::new();
                    for input in at.iter().map(|i| (p.at)(i)) {
                        let right = reference(&input);
                        if !right.parts().iter().all(|v| v.is_finite()) {
                            continue;
                        }
                        let theirs = again(&input)?;
                        if !close(&theirs, &right) {
                            wrong.push((input, theirs, right));
                        }
                    }
                    if wrong.is_empty() {
                        continue;
                    }
                    if wrong.len() < 2 {
                        return None;
                    }
                    let ks: Option<Vec<Real>> = wrong
                        .iter()
                        .map(|(_, a, e)| proportional(&a.parts(), &e.parts()))
                        .collect();
                    let inputs: Vec<I> = wrong.iter().map(|(i, _, _)| i.clone()).collect();
                    let detail = ks
                        .and_then(|ks| factor_detail(&ks, &inputs, &named))
                        .unwrap_or_else(|| {
                            let (_, a, e) = &wrong[0];
                            diagnosis::shape(&a.parts(), &e.parts(), &labels, T::kind())
                        });
                    let advice = if p.advice.is_empty() {
                        String::new()
                    } else {
                        format!(": {}", p.advice)
                    };
                    return Some(format!(
                        "{}, only {} is left, and yours is wrong there ({detail}){advice}",
                        p.when, p.what
                    ));
                }
                None
            }));
        self
    }
}
