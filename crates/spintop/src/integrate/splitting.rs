//! Splitting methods: a flow cut into parts that are each solved exactly, and
//! composed with a fixed step.
//!
//! If `y' = f₁(y) + … + f_m(y)` and every part `y' = f_i(y)` has an exact flow
//! φ⁽ⁱ⁾_h, a step of the whole is a product of the parts' flows:
//!
//! ```text
//! Lie–Trotter  Φ_h = φ⁽ᵐ⁾_h ∘ … ∘ φ⁽¹⁾_h                                   order 1
//! Strang       Φ_h = φ⁽¹⁾_{h/2} ∘ … ∘ φ⁽ᵐ⁻¹⁾_{h/2} ∘ φ⁽ᵐ⁾_h ∘ φ⁽ᵐ⁻¹⁾_{h/2} ∘ … ∘ φ⁽¹⁾_{h/2}   order 2, symmetric
//! Yoshida-4    Φ_h = S_{w₁h} ∘ S_{w₀h} ∘ S_{w₁h}  (S = Strang)                order 4, symmetric
//!              w₁ = 1/(2 − 2^{1/3}),  w₀ = −2^{1/3}/(2 − 2^{1/3})
//! ```
//!
//! References: G. Strang, SIAM J. Numer. Anal. 5 (1968) 506; H. Yoshida,
//! "Construction of higher order symplectic integrators", Phys. Lett. A 150
//! (1990) 262; E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical
//! Integration*, 2nd ed., Springer 2006, Sec. II.4 (composition methods,
//! the triple jump), II.5 (splitting) and VII.5 (the free rigid body).
//!
//! When every part is a Hamiltonian flow, each φ⁽ⁱ⁾ is symplectic and so is the
//! composition: the energy error stays bounded over exponentially long times
//! (backward error analysis, Hairer–Lubich–Wanner Sec. IX.8) instead of growing
//! like t, as it does for RK4 or Dormand–Prince. Every quantity that every part
//! conserves exactly (here |L| and the lab-frame L) is conserved by the method
//! to rounding.
//!
//! The machinery here is generic over the problem it splits ([`SplitFlow`]);
//! the problems themselves, with their exact part-flows, are the physics'
//! ([`crate::sim::split`] puts them together):
//!
//! | problem | parts | exact because |
//! |---|---|---|
//! | the free rigid body, τ = 0, any I₁, I₂, I₃ | T = L₁²/2I₁ + L₂²/2I₂ + L₃²/2I₃ | each part turns L and O about one body axis |
//! | the reduced model, (4.12)–(4.14) | rotation of (Ω₁, Ω₂) + radial damping | the two commute: any composition is the exact flow |
//!
//! Counting ([`Stats`]): [`Stats::rhs_evals`] counts sub-flow evaluations and
//! [`Stats::steps`] steps; [`Stats::rejected`] is always 0. Adjacent sub-flows of
//! the same part inside one step are merged (φ⁽ⁱ⁾_a ∘ φ⁽ⁱ⁾_b = φ⁽ⁱ⁾_{a+b}), so a
//! step costs m (Lie–Trotter), 2m − 1 (Strang) or 6m − 5 (Yoshida-4) sub-flows:
//! 5 and 13 for the three-part rigid body, 2 for the reduced flow.
//!
//! Failure: a sub-flow that does not exist over the step (the reduced damping
//! run backward past its blow-up) or a non-finite state ends the step with
//! [`IntegrateError::NonFinite`] at the time of the last finite state, which is
//! kept; the stepper never holds a non-finite state.

use crate::integrate::control::{check_start, check_t_stop, fixed_step_allowed};
use crate::integrate::{DEFAULT_MAX_STEPS, IntegrateError, Stats};
use crate::math::Real;

/// A problem cut into parts whose flows are known exactly.
pub trait SplitFlow {
    /// The state the flows act on (small and `Copy`: no allocation per step).
    type State: Copy;
    /// The number of parts m (≥ 1).
    fn parts(&self) -> usize;
    /// The exact flow of part `part` (0-based, < [`SplitFlow::parts`]) over the
    /// signed time `h`, or `None` if it does not exist that long (a blow-up).
    fn flow(&self, part: usize, h: Real, state: &Self::State) -> Option<Self::State>;
    /// True when every number in `state` is finite.
    fn is_finite(&self, state: &Self::State) -> bool;
}

/// How the parts' flows are composed into one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Composition {
    /// φ⁽ᵐ⁾_h ∘ … ∘ φ⁽¹⁾_h: order 1, exact when the parts commute.
    LieTrotter,
    /// The symmetric Strang splitting: order 2.
    Strang,
    /// Yoshida's triple jump of Strang steps: order 4.
    Yoshida4,
}

// ANCHOR: yoshida_weights
/// Yoshida's weights `(w₁, w₀)` of the fourth-order triple jump
/// `S_{w₁h} ∘ S_{w₀h} ∘ S_{w₁h}`.
///
/// ```text
/// w₁ = 1/(2 − 2^{1/3}) ≈ 1.3512,  w₀ = −2^{1/3}/(2 − 2^{1/3}) ≈ −1.7024,  2w₁ + w₀ = 1
/// ```
///
/// Reference: H. Yoshida, Phys. Lett. A 150 (1990) 262;
/// Hairer–Lubich–Wanner, *Geometric Numerical Integration*, Sec. II.4 (the triple jump).
pub fn yoshida_weights() -> (Real, Real) {
    let c = 2.0_f64.cbrt();
    (1.0 / (2.0 - c), -c / (2.0 - c))
}
// ANCHOR_END: yoshida_weights

impl Composition {
    /// The order of the method (for smooth flows and any number of parts).
    pub fn order(&self) -> u32 {
        match self {
            Composition::LieTrotter => 1,
            Composition::Strang => 2,
            Composition::Yoshida4 => 4,
        }
    }

    /// A short name: `Lie-Trotter`, `Strang`, `Yoshida-4`.
    pub fn name(&self) -> &'static str {
        match self {
            Composition::LieTrotter => "Lie-Trotter",
            Composition::Strang => "Strang",
            Composition::Yoshida4 => "Yoshida-4",
        }
    }

    /// One step as a list of `(part, fraction of h)`, in the order they are
    /// applied, with adjacent flows of the same part merged. Empty for `parts == 0`.
    pub fn sequence(&self, parts: usize) -> Vec<(usize, Real)> {
        let strang = |w: Real| -> Vec<(usize, Real)> {
            let last = parts.saturating_sub(1);
            let mut s: Vec<(usize, Real)> = (0..last).map(|i| (i, 0.5 * w)).collect();
            if parts > 0 {
                s.push((last, w));
            }
            s.extend((0..last).rev().map(|i| (i, 0.5 * w)));
            s
        };
        let raw = match self {
            Composition::LieTrotter => (0..parts).map(|i| (i, 1.0)).collect(),
            Composition::Strang => strang(1.0),
            Composition::Yoshida4 => {
                let (w1, w0) = yoshida_weights();
                let mut s = strang(w1);
                s.extend(strang(w0));
                s.extend(strang(w1));
                s
            }
        };
        let mut merged: Vec<(usize, Real)> = Vec::with_capacity(raw.len());
        for (part, w) in raw {
            match merged.last_mut() {
                Some(last) if last.0 == part => last.1 += w,
                _ => merged.push((part, w)),
            }
        }
        merged
    }
}

/// A fixed-step splitting method over a [`SplitFlow`], stepping forward or backward.
#[derive(Clone, Debug)]
pub struct Splitting<P: SplitFlow> {
    problem: P,
    composition: Composition,
    /// One step as `(part, fraction of h)`.
    sequence: Vec<(usize, Real)>,
    t: Real,
    state: P::State,
    /// Step size magnitude.
    h: Real,
    /// Time from which full steps are counted: `t = anchor_t + anchor_k·anchor_h`.
    anchor_t: Real,
    /// Full steps since `anchor_t`.
    anchor_k: u64,
    /// Signed step of the run that started at `anchor_t` (0: none yet).
    anchor_h: Real,
    max_steps: u64,
    stats: Stats,
}

impl<P: SplitFlow> Splitting<P> {
    /// A stepper for `problem` at `(t0, state0)` with step size `h` (finite and
    /// > 0; the direction of each step comes from its `t_stop`).
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0` or
    /// `state0`, an `h` that is not finite and positive, or a problem with no parts.
    pub fn new(
        problem: P,
        composition: Composition,
        t0: Real,
        state0: P::State,
        h: Real,
    ) -> Result<Self, IntegrateError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(IntegrateError::InvalidOption(format!(
                "the splitting step size must be finite and > 0, got {h}"
            )));
        }
        check_start(t0, problem.is_finite(&state0))?;
        if problem.parts() == 0 {
            return Err(IntegrateError::InvalidOption(
                "a split problem needs at least one part".into(),
            ));
        }
        let sequence = composition.sequence(problem.parts());
        Ok(Self {
            problem,
            composition,
            sequence,
            t: t0,
            state: state0,
            h,
            anchor_t: t0,
            anchor_k: 0,
            anchor_h: 0.0,
            max_steps: DEFAULT_MAX_STEPS,
            stats: Stats::default(),
        })
    }

    /// Replace the step budget (steps over the life of the stepper; default
    /// [`DEFAULT_MAX_STEPS`]).
    pub fn with_max_steps(mut self, n: u64) -> Self {
        self.max_steps = n;
        self
    }

    /// Current time.
    pub fn t(&self) -> Real {
        self.t
    }

    /// Current state.
    pub fn state(&self) -> &P::State {
        &self.state
    }

    /// The split problem.
    pub fn problem(&self) -> &P {
        &self.problem
    }

    /// The composition.
    pub fn composition(&self) -> Composition {
        self.composition
    }

    /// The step size magnitude.
    pub fn h(&self) -> Real {
        self.h
    }

    /// Work done so far: sub-flow evaluations and steps.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Sub-flow evaluations per step.
    pub fn flows_per_step(&self) -> usize {
        self.sequence.len()
    }

    /// One raw step of signed size `h` from `state`: no counting, no time.
    /// `None` if a sub-flow does not exist over its fraction of the step.
    pub fn step_once(&self, state: &P::State, h: Real) -> Option<P::State> {
        let mut y = *state;
        for &(part, w) in &self.sequence {
            y = self.problem.flow(part, w * h, &y)?;
        }
        Some(y)
    }

    /// Take one step toward `t_stop`, never past it. Backward steps are taken
    /// when `t_stop < t()`; `t_stop == t()` is a no-op.
    pub fn step(&mut self, t_stop: Real) -> Result<(), IntegrateError> {
        check_t_stop(t_stop)?;
        if t_stop == self.t {
            return Ok(());
        }
        fixed_step_allowed(self.stats.steps, self.max_steps, self.t)?;
        let remaining = t_stop - self.t;
        let h_signed = self.h.copysign(remaining);
        if h_signed != self.anchor_h {
            self.anchor_t = self.t;
            self.anchor_k = 0;
            self.anchor_h = h_signed;
        }
        // NOTE: as in `Rk4`, the last step is stretched by up to a relative 1e-9
        // (plus a few ulps of t) rather than leaving a rounding-sized sliver. The
        // time of a full step is anchor + k·h, one rounding from exact however many
        // steps were taken, so n steps of t_end/n land on t_end in exactly n steps.
        let slack = 1e-9 * self.h + 64.0 * Real::EPSILON * self.t.abs().max(t_stop.abs());
        let landing = remaining.abs() <= self.h + slack;
        let (h, t_new) = if landing {
            (remaining, t_stop)
        } else {
            let k = self.anchor_k + 1;
            (h_signed, self.anchor_t + k as Real * h_signed)
        };
        let y_new = self.step_once(&self.state, h);
        self.stats.rhs_evals += self.sequence.len() as u64;
        let y_new = match y_new {
            Some(y) if self.problem.is_finite(&y) => y,
            _ => return Err(IntegrateError::NonFinite { t: self.t }),
        };
        if landing {
            self.anchor_t = t_stop;
            self.anchor_k = 0;
        } else {
            self.anchor_k += 1;
        }
        self.t = t_new;
        self.state = y_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// Step until `t() == t_stop`.
    pub fn advance_to(&mut self, t_stop: Real) -> Result<(), IntegrateError> {
        check_t_stop(t_stop)?;
        while self.t != t_stop {
            self.step(t_stop)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequences_have_the_documented_lengths_and_weights() {
        for parts in 1usize..5 {
            for (comp, len) in [
                (Composition::LieTrotter, parts),
                (Composition::Strang, 2 * parts - 1),
                (Composition::Yoshida4, (6 * parts).saturating_sub(5).max(1)),
            ] {
                let seq = comp.sequence(parts);
                assert_eq!(seq.len(), len, "{comp:?} with {parts} parts");
                // Every part gets a total weight of exactly one step.
                for p in 0..parts {
                    let total: Real = seq.iter().filter(|e| e.0 == p).map(|e| e.1).sum();
                    assert!((total - 1.0).abs() < 1e-14, "{comp:?} part {p}: {total}");
                }
            }
        }
        let (w1, w0) = yoshida_weights();
        assert!((2.0 * w1 + w0 - 1.0).abs() < 1e-15);
        // The fourth-order condition 2w₁³ + w₀³ = 0.
        assert!((2.0 * w1.powi(3) + w0.powi(3)).abs() < 1e-14);
    }
}
