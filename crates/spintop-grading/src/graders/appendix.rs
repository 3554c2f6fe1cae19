//! The appendix: the charged shell's delay equation (A.1), its masses, its
//! method-of-steps update and its characteristic root.

use crate::CASES;
use crate::parts::{named, part};
use crate::{Again, Grade, Grader, Rng, close, mistake};
use spintop::math::Real;
use spintop::physics::shell::{C, ShellModel};
use std::fmt;

#[derive(Clone, Copy)]
struct ShellInput {
    tau0: Real,
    delta: Real,
    z: C,
    z_ddot_ret: C,
}

impl fmt::Debug for ShellInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "tau0 = {}, delta = {}, Z = {}, Z''(t - delta) = {}",
            self.tau0, self.delta, self.z, self.z_ddot_ret
        )
    }
}

fn shell_inputs(seed: u64, delta_max: Real) -> Vec<ShellInput> {
    let mut rng = Rng::new(seed);
    (0..CASES)
        .map(|_| {
            let tau0 = rng.uniform(1e-3, 0.05);
            ShellInput {
                tau0,
                delta: rng.uniform(2.5 * tau0, delta_max),
                z: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
                z_ddot_ret: C::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
            }
        })
        .collect()
}

/// Grade the split of the mass into the bare and the electromagnetic part.
///
/// Paper: Eq. (A.1).
pub fn shell_masses(seed: u64, student: impl Fn(Real, Real) -> (Real, Real)) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => (m.m0(), m.m_em()),
        Err(_) => (Real::NAN, Real::NAN),
    };
    Grader::new(
        "shell_masses",
        "Eq. (A.1), the masses",
        seed,
        shell_inputs(seed, 1.0),
        reference,
        |a: &(Real, Real), b: &(Real, Real)| close(a, b, 1e-13),
    )
    .mistakes(vec![
        mistake(
            "the two masses are swapped (returned in the wrong order): the field's share is the small one when the shell is large",
            move |x: &ShellInput| {
                let (a, b) = reference(x);
                (b, a)
            },
        ),
        mistake(
            "the field's mass m_em is inverted (upside down): it grows as the shell shrinks",
            |x: &ShellInput| (1.0 - x.delta / x.tau0, x.delta / x.tau0),
        ),
        mistake(
            "the bare mass is not the rest of the whole mass: the two add up to m = 1",
            |x: &ShellInput| (1.0, x.tau0 / x.delta),
        ),
        mistake(
            "the bare mass has the field's mass added with the wrong sign: it is the rest of the whole mass, and the two add up to m = 1",
            |x: &ShellInput| (1.0 + x.tau0 / x.delta, x.tau0 / x.delta),
        ),
    ])
    .labels(&["m₀", "m_em"])
    .run(|x| student(x.tau0, x.delta))
}

/// Grade the method-of-steps update of the shell model: Z''(t) from Z(t) and
/// the retarded Z''(t − δ).
///
/// Paper: Eq. (A.1).
pub fn shell_acceleration(seed: u64, student: impl Fn(Real, Real, C, C) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.acceleration(x.z, x.z_ddot_ret),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    Grader::new(
        "shell_acceleration",
        "Eq. (A.1)",
        seed,
        shell_inputs(seed, 1.0),
        reference,
        |a: &C, b: &C| close(a, b, 1e-12),
    )
    .mistakes(vec![
        mistake(
            "the retarded term has the wrong sign: move it to the other side of the equation with care",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (-x.z + x.z_ddot_ret * m_em) / m0
            },
        ),
        mistake(
            "divided by the whole mass: the acceleration now is multiplied by the bare mass only, the rest acts one delay later",
            move |x: &ShellInput| -x.z - x.z_ddot_ret * masses(x).1,
        ),
        mistake(
            "the two masses are swapped: the bare mass multiplies the acceleration now, the field's mass the retarded one",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (-x.z - x.z_ddot_ret * m0) / m_em
            },
        ),
        mistake(
            "the restoring force has the wrong sign: the spring pulls Z back toward 0",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                (x.z - x.z_ddot_ret * m_em) / m0
            },
        ),
        mistake(
            "the retarded acceleration is missing: the field's mass acts with the acceleration one delay earlier",
            move |x: &ShellInput| -x.z / masses(x).0,
        ),
        mistake(
            "divided by the field's mass: the acceleration now is multiplied by the bare mass m0, so solve for it by dividing by m0",
            move |x: &ShellInput| {
                let (_, m_em) = masses(x);
                (-x.z - x.z_ddot_ret * m_em) / m_em
            },
        ),
        mistake(
            "the retarded term is not divided by the bare mass: solving for Z''(t) divides everything on the other side by m0",
            move |x: &ShellInput| {
                let (m0, m_em) = masses(x);
                -x.z / m0 - x.z_ddot_ret * m_em
            },
        ),
    ])
    .parts(
        vec![
            part(
                "with Z''(t - delta) = 0",
                "the restoring force's term",
                "",
                |x: &ShellInput| ShellInput { z_ddot_ret: C::new(0.0, 0.0), ..*x },
            ),
            part("with Z = 0", "the retarded term", "", |x: &ShellInput| ShellInput {
                z: C::new(0.0, 0.0),
                ..*x
            }),
        ],
        vec![
            named("m_em", |x: &ShellInput| masses(x).1),
            named("m0", |x: &ShellInput| masses(x).0),
            named("delta", |x: &ShellInput| x.delta),
        ],
    )
    .run(|x| student(x.tau0, x.delta, x.z, x.z_ddot_ret))
}

/// Newton's method on `p` (with derivative `dp`) from `start`, `steps` at
/// most; every iterate.
fn newton_iterates(p: impl Fn(C) -> C, dp: impl Fn(C) -> C, start: C, steps: usize) -> Vec<C> {
    let mut s = start;
    let mut out = vec![s];
    for _ in 0..steps {
        let step = p(s) / dp(s);
        s -= step;
        out.push(s);
        if step.norm() <= 1e-15 * s.norm().max(1.0) || !(s.re.is_finite() && s.im.is_finite()) {
            break;
        }
    }
    out
}

/// The derivative P'(s) a student hands Newton's method: the right one, or
/// one of the slips of its product rule.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Derivative {
    Right,
    /// Without the term the product rule takes from the delay factor.
    NoProductRule,
    /// That term with the wrong sign.
    ProductRuleSign,
    /// That term without the chain rule's factor delta.
    NoChainRule,
    /// No derivative of the delay term at all.
    NoDelayTerm,
}

impl Derivative {
    const SLIPS: [Derivative; 4] = [
        Derivative::NoProductRule,
        Derivative::ProductRuleSign,
        Derivative::NoChainRule,
        Derivative::NoDelayTerm,
    ];

    fn words(self) -> &'static str {
        match self {
            Derivative::Right => "",
            Derivative::NoProductRule => {
                "your P'(s) lacks a term of the product rule: the delay factor e^(-s delta) depends on s too, so differentiating its product with s^2 gives two terms"
            }
            Derivative::ProductRuleSign => {
                "in your P'(s) the product rule's term from the delay factor has the wrong sign: differentiating e^(-s delta) brings a factor -delta"
            }
            Derivative::NoChainRule => {
                "in your P'(s) the product rule's term from the delay factor lacks the chain rule's factor delta"
            }
            Derivative::NoDelayTerm => {
                "your P'(s) differentiates only the bare mass's term: the delay term m_em s^2 e^(-s delta) has a derivative too (by the product rule)"
            }
        }
    }
}

/// The characteristic function of (A.1) with the delay factor e^{sign·sδ}
/// and the masses given, and its derivative (or a slip of it).
fn characteristic(
    m0: Real,
    m_em: Real,
    d: Real,
    sign: Real,
    derivative: Derivative,
) -> (impl Fn(C) -> C, impl Fn(C) -> C) {
    (
        move |s: C| s * s * (m0 + (s * (sign * d)).exp() * m_em) + 1.0,
        move |s: C| {
            let e = (s * (sign * d)).exp() * m_em;
            let product_rule = s * s * e * (sign * d);
            match derivative {
                Derivative::Right => s * 2.0 * (e + m0) + product_rule,
                Derivative::NoProductRule => s * 2.0 * (e + m0),
                Derivative::ProductRuleSign => s * 2.0 * (e + m0) - product_rule,
                Derivative::NoChainRule => s * 2.0 * (e + m0) + product_rule / (sign * d),
                Derivative::NoDelayTerm => s * 2.0 * m0,
            }
        },
    )
}

/// The masses (m₀, m_em) of an input.
fn masses(x: &ShellInput) -> (Real, Real) {
    let m_em = x.tau0 / x.delta;
    (1.0 - m_em, m_em)
}

/// The iterates of Newton's method from s = i with `derivative`.
fn newton_from_i(x: &ShellInput, derivative: Derivative, steps: usize) -> Vec<C> {
    let (m0, m_em) = masses(x);
    let (p, dp) = characteristic(m0, m_em, x.delta, -1.0, derivative);
    newton_iterates(p, dp, C::new(0.0, 1.0), steps)
}

/// Shells where Newton's method from s = i needs several iterations: a
/// delay of 1.4 to 1.65 and a field's mass of 0.45 to 0.75 of the whole
/// (the oscillation's root moves far from i). Four iterations leave it 1e-9
/// to 1e-2 off, and a derivative without its product-rule term 1e-8 to 1e-5
/// after twenty; the full method converges in at most 10, to the same root
/// as spintop's search from the Abraham–Lorentz root.
fn hard_shells(seed: u64) -> Vec<ShellInput> {
    let mut rng = Rng::new(seed ^ 0xA1);
    (0..8)
        .map(|_| {
            let delta = rng.uniform(1.4, 1.65);
            let m_em = rng.uniform(0.45, 0.75);
            ShellInput {
                tau0: m_em * delta,
                delta,
                z: C::new(0.0, 0.0),
                z_ddot_ret: C::new(0.0, 0.0),
            }
        })
        .collect()
}

/// Newton's method stopped early or iterated with a wrong derivative: the
/// student's root is an iterate of Newton from s = i (with the right
/// derivative, or a slip of it) before it has converged, on the failing
/// input and on a hard shell (`others`) too.
fn newton_probe(
    others: Vec<ShellInput>,
) -> impl Fn(&ShellInput, &Again<'_, ShellInput, C>) -> Option<String> {
    move |x, again| {
        let other = others
            .iter()
            .find(|o| (o.tau0, o.delta) != (x.tau0, x.delta))?;
        // Which iterate of which method the student's root is, if any.
        let which = |input: &ShellInput, theirs: C, derivative: Derivative| {
            let iterates = newton_from_i(input, derivative, 200);
            let last = *iterates.last()?;
            iterates.iter().enumerate().skip(1).find_map(|(k, s)| {
                let same = (*s - theirs).norm() <= 1e-12 * s.norm().max(1.0);
                let early = derivative != Derivative::Right || (*s - last).norm() > 1e-10;
                (same && early).then_some(k)
            })
        };
        let (here, there) = (again(x)?, again(other)?);
        for derivative in std::iter::once(Derivative::Right).chain(Derivative::SLIPS) {
            let (Some(k1), Some(k2)) =
                (which(x, here, derivative), which(other, there, derivative))
            else {
                continue;
            };
            let plural = |k: usize| if k == 1 { "" } else { "s" };
            if derivative != Derivative::Right {
                let (m0, m_em) = masses(x);
                let residual =
                    characteristic(m0, m_em, x.delta, -1.0, Derivative::Right).0(here).norm();
                return Some(format!(
                    "Newton's method with a wrong derivative: {}. With it Newton converges slowly, if at all, and your root is where it stands after {k1} iteration{} (P(s) is {residual:.1e} there, not zero to rounding)",
                    derivative.words(),
                    plural(k1)
                ));
            }
            return Some(if k1 == k2 {
                format!(
                    "you stopped Newton's method after {k1} step{}: it has not converged yet, {k1} iteration{} not enough here. Iterate until the Newton step is below rounding (a fixed number of iterations, or a stopping test on |P(s)| or on the step with a tolerance far above rounding, stops too early)",
                    plural(k1),
                    if k1 == 1 { " is" } else { "s are" }
                )
            } else {
                format!(
                    "your stopping test ends Newton's method too early (after {k1} iteration{} here, {k2} on another shell), before it has converged: its tolerance is far above rounding. Iterate until the Newton step is below rounding, and apply the last step too",
                    plural(k1)
                )
            });
        }
        None
    }
}

/// Grade the root of the characteristic function of (A.1) that continues
/// the undamped oscillation s = i.
///
/// Paper: Eq. (A.1) with Z ∝ e^{st}.
pub fn characteristic_root(seed: u64, student: impl Fn(Real, Real) -> C) -> Grade {
    let reference = |x: &ShellInput| match ShellModel::new(x.tau0, x.delta) {
        Ok(m) => m.root_near_al().unwrap_or(C::new(Real::NAN, Real::NAN)),
        Err(_) => C::new(Real::NAN, Real::NAN),
    };
    let root_of = move |x: &ShellInput, swap: bool, sign: Real| {
        let (m0, m_em) = masses(x);
        let (m0, m_em) = if swap { (m_em, m0) } else { (m0, m_em) };
        let (p, dp) = characteristic(m0, m_em, x.delta, sign, Derivative::Right);
        *newton_iterates(p, dp, C::new(0.0, 1.0), 100)
            .last()
            .unwrap_or(&C::new(0.0, 1.0))
    };
    let not_converged = move |x: &ShellInput, again: &Again<'_, ShellInput, C>| {
        let theirs = again(x)?;
        let (m0, m_em) = masses(x);
        let (p, _) = characteristic(m0, m_em, x.delta, -1.0, Derivative::Right);
        let right = reference(x);
        let residual = p(theirs).norm();
        let near = (theirs - right).norm() < 1e-3;
        (near && residual > 1e-12).then(|| {
            format!(
                "close to the root but not on it (P(s) is {residual:.1e} there, not zero to rounding): iterate until the Newton step is below rounding; is the derivative P'(s) right?"
            )
        })
    };
    let hard = hard_shells(seed);
    let mut inputs = shell_inputs(seed, 0.3);
    inputs.extend(hard.iter().copied());
    Grader::new(
        "characteristic_root",
        "Eq. (A.1) with Z ~ e^{st}",
        seed,
        inputs,
        reference,
        |a: &C, b: &C| close(a, b, 1e-10),
    )
    .mistakes(vec![
        mistake(
            "that is where the search starts, the oscillation without radiation: the root itself is shifted by the radiation (iterate)",
            |_: &ShellInput| C::new(0.0, 1.0),
        ),
        mistake(
            "the retarded factor has the wrong sign in the exponent: a delay brings a decaying exponential of s times delta",
            move |x: &ShellInput| root_of(x, false, 1.0),
        ),
        mistake(
            "the two masses are swapped in the characteristic function: the bare mass goes with s^2 alone, the field's mass with the delay factor",
            move |x: &ShellInput| root_of(x, true, -1.0),
        ),
        mistake(
            "that is the complex conjugate of the root: Newton's starting point decides which root it finds, and the oscillation's root continues s = +i, with a positive imaginary part",
            move |x: &ShellInput| reference(x).conj(),
        ),
    ])
    .probe(newton_probe(hard))
    .probe(not_converged)
    .run(|x| student(x.tau0, x.delta))
}
