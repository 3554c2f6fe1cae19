//! The appendix: the charged shell's delay equation (A.1), its masses, its
//! method-of-steps update and its characteristic root.

use crate::CASES;
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
            "the two masses are swapped: the field's share is the small one when the shell is large",
            move |x: &ShellInput| {
                let (a, b) = reference(x);
                (b, a)
            },
        ),
        mistake(
            "the field's mass is upside down: it grows as the shell shrinks",
            |x: &ShellInput| (1.0 - x.delta / x.tau0, x.delta / x.tau0),
        ),
        mistake(
            "the bare mass is not the rest of the whole mass: the two add up to m = 1",
            |x: &ShellInput| (1.0, x.tau0 / x.delta),
        ),
        mistake(
            "the bare mass is not the rest of the whole mass: the two add up to m = 1",
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
    let masses = |x: &ShellInput| {
        let m_em = x.tau0 / x.delta;
        (1.0 - m_em, m_em)
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
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    out
}

/// The characteristic function of (A.1) with the delay factor e^{sign·sδ}
/// and the masses given, and its derivative.
fn characteristic(m0: Real, m_em: Real, d: Real, sign: Real) -> (impl Fn(C) -> C, impl Fn(C) -> C) {
    (
        move |s: C| s * s * (m0 + (s * (sign * d)).exp() * m_em) + 1.0,
        move |s: C| {
            let e = (s * (sign * d)).exp() * m_em;
            s * 2.0 * (e + m0) + s * s * e * (sign * d)
        },
    )
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
    let masses = |x: &ShellInput| {
        let m_em = x.tau0 / x.delta;
        (1.0 - m_em, m_em)
    };
    let root_of = move |x: &ShellInput, swap: bool, sign: Real| {
        let (m0, m_em) = masses(x);
        let (m0, m_em) = if swap { (m_em, m0) } else { (m0, m_em) };
        let (p, dp) = characteristic(m0, m_em, x.delta, sign);
        *newton_iterates(p, dp, C::new(0.0, 1.0), 100)
            .last()
            .unwrap_or(&C::new(0.0, 1.0))
    };
    // Newton stopped after a fixed number of iterations.
    let stopped_early = move |x: &ShellInput, again: &Again<'_, ShellInput, C>| {
        let theirs = again(x)?;
        let (m0, m_em) = masses(x);
        let (p, dp) = characteristic(m0, m_em, x.delta, -1.0);
        let iterates = newton_iterates(p, dp, C::new(0.0, 1.0), 12);
        let last = *iterates.last()?;
        iterates
            .iter()
            .enumerate()
            .skip(1)
            .find(|(_, s)| (**s - theirs).norm() <= 1e-13 * s.norm() && (**s - last).norm() > 1e-10)
            .map(|(k, _)| {
                format!(
                    "you stopped Newton's method after {k} step{}: it has not converged yet. Iterate until the Newton step is below rounding (a fixed number of steps, or a test of |P(s)| against a tolerance far above rounding, stops too early)",
                    if k == 1 { "" } else { "s" }
                )
            })
    };
    let not_converged = move |x: &ShellInput, again: &Again<'_, ShellInput, C>| {
        let theirs = again(x)?;
        let (m0, m_em) = masses(x);
        let (p, _) = characteristic(m0, m_em, x.delta, -1.0);
        let right = reference(x);
        let residual = p(theirs).norm();
        let near = (theirs - right).norm() < 1e-3;
        (near && residual > 1e-12).then(|| {
            format!(
                "close to the root but not on it (P(s) is {residual:.1e} there, not zero to rounding): iterate until the Newton step is below rounding; is the derivative P'(s) right?"
            )
        })
    };
    Grader::new(
        "characteristic_root",
        "Eq. (A.1) with Z ~ e^{st}",
        seed,
        shell_inputs(seed, 0.3),
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
            "that is the complex conjugate of the root: the oscillation's root continues s = +i, with a positive imaginary part",
            move |x: &ShellInput| reference(x).conj(),
        ),
    ])
    .probe(stopped_early)
    .probe(not_converged)
    .run(|x| student(x.tau0, x.delta))
}
