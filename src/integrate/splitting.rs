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
//! Two problems are split here:
//!
//! | problem | parts | exact because |
//! |---|---|---|
//! | [`FreeRigidBody`], τ = 0, any I₁, I₂, I₃ | T = L₁²/2I₁ + L₂²/2I₂ + L₃²/2I₃ | each part turns L and O about one body axis |
//! | [`ReducedFlow`], (4.12)–(4.14) | rotation of (Ω₁, Ω₂) + radial damping | the two commute: any composition is the exact flow |
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

use crate::integrate::{
    DEFAULT_MAX_STEPS, IntegrateError, Stats, check_start, check_t_stop, fixed_step_allowed,
};
use crate::math::{Mat3, Real, Vec3, all_finite};
use crate::physics::ParamError;
use crate::physics::rigid_body::BodyDynamics;
use crate::physics::symmetric_top::SymmetricTop;

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

// ---------------------------------------------------------------- the free rigid body

/// A torque-free rigid body (τ = 0) with principal moments (I₁, I₂, I₃), split
/// into its three rotations about the body axes.
///
/// Hamiltonian in the body-frame angular momentum L:
///
/// ```text
/// T = L₁²/2I₁ + L₂²/2I₂ + L₃²/2I₃,   Ω = I⁻¹L,   L̇ = L × Ω,   Ȯ = O Ω̂
/// ```
///
/// Part i keeps only L_i²/2I_i: then Ω = (L_i/I_i) e_i is constant, L turns
/// about e_i by −θ and O by +θ about its own e_i, with θ = h L_i/I_i. Each part
/// is an exact rotation, so |L| and the lab L = O L are kept to rounding by
/// every composition, and the energy error of Strang or Yoshida-4 stays bounded.
///
/// References: J. Touma, J. Wisdom, Astron. J. 107 (1994) 1189; R. I. McLachlan,
/// Phys. Rev. Lett. 71 (1993) 3043; A. Dullweber, B. Leimkuhler, R. McLachlan,
/// J. Chem. Phys. 107 (1997) 5840; Hairer–Lubich–Wanner Sec. VII.5.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeRigidBody {
    inertia: Vec3,
}

/// The state of a free rigid body: body-frame angular momentum and orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidBodyState {
    /// L = IΩ in the body frame.
    pub l_body: Vec3,
    /// O, body → lab.
    pub rotation: Mat3,
}

impl RigidBodyState {
    /// The lab-frame angular momentum O L (constant for a free body).
    pub fn l_lab(&self) -> Vec3 {
        self.rotation * self.l_body
    }
}

impl FreeRigidBody {
    /// Validate the principal moments: finite, positive, each at most the sum of
    /// the other two (the same check as [`crate::physics::general_top::GeneralTop`]).
    pub fn new(inertia: Vec3) -> Result<Self, ParamError> {
        crate::physics::check_principal_moments(&inertia)?;
        Ok(Self { inertia })
    }

    /// The principal moments.
    pub fn inertia(&self) -> Vec3 {
        self.inertia
    }

    /// Ω = I⁻¹L.
    pub fn omega(&self, l_body: &Vec3) -> Vec3 {
        l_body.component_div(&self.inertia)
    }

    /// The kinetic energy T = ½ L·I⁻¹L.
    pub fn energy(&self, l_body: &Vec3) -> Real {
        0.5 * l_body.dot(&self.omega(l_body))
    }

    /// The body-frame Euler equation L̇ = L × Ω (torque-free).
    ///
    /// Paper: Eq. (3.2).
    ///
    /// ```text
    /// 0 = dL_lab/dt = O {L̇ + Ω × L}   ⇒   L̇ = L × Ω,  Ω = I⁻¹L
    /// ```
    pub fn l_dot(&self, l_body: &Vec3) -> Vec3 {
        l_body.cross(&self.omega(l_body))
    }

    /// The exact flow of part `axis` (0, 1, 2 for body axes 1, 2, 3) over time `h`.
    ///
    /// Paper: Eq. (3.1), Eq. (3.2).
    ///
    /// ```text
    /// T_i = L_i²/2I_i:  Ω = θ/h e_i,  θ = h L_i/I_i
    /// L ← R_i(−θ) L,   O ← O R_i(θ)      (so O L is unchanged)
    /// ```
    ///
    /// `axis` must be 0, 1 or 2 (taken modulo 3).
    pub fn axis_flow(&self, axis: usize, h: Real, state: &RigidBodyState) -> RigidBodyState {
        let i = axis % 3;
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let theta = h * state.l_body[i] / self.inertia[i];
        let (s, c) = theta.sin_cos();
        let l = &state.l_body;
        let mut l_new = *l;
        // R_i(−θ) in the (e_j, e_k) plane, cyclic (i, j, k).
        l_new[j] = c * l[j] + s * l[k];
        l_new[k] = c * l[k] - s * l[j];
        // O R_i(θ): R_i(θ) e_j = c e_j + s e_k, R_i(θ) e_k = c e_k − s e_j.
        // NOTE: only two columns of O mix, by the same (c, s) as L, so O L changes
        // by rounding only; no re-orthonormalisation is needed (its error grows
        // like √steps·ε, ~1e-13 after 10⁶ steps).
        let o = &state.rotation;
        let col_j = o.column(j).into_owned();
        let col_k = o.column(k).into_owned();
        let mut o_new = *o;
        o_new.set_column(j, &(col_j * c + col_k * s));
        o_new.set_column(k, &(col_k * c - col_j * s));
        RigidBodyState {
            l_body: l_new,
            rotation: o_new,
        }
    }
}

impl BodyDynamics for FreeRigidBody {
    fn inertia(&self) -> Vec3 {
        self.inertia
    }

    /// Euler's equations with no torque: Ω̇ = I⁻¹(IΩ × Ω).
    fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        let l = self.inertia.component_mul(omega);
        l.cross(omega).component_div(&self.inertia)
    }
}

impl SplitFlow for FreeRigidBody {
    type State = RigidBodyState;

    fn parts(&self) -> usize {
        3
    }

    fn flow(&self, part: usize, h: Real, state: &RigidBodyState) -> Option<RigidBodyState> {
        Some(self.axis_flow(part, h, state))
    }

    fn is_finite(&self, state: &RigidBodyState) -> bool {
        all_finite(&state.l_body) && all_finite(&state.rotation)
    }
}

/// A fixed-step splitting of the free rigid body (see [`FreeRigidBody`]).
pub type RigidBodySplitting = Splitting<FreeRigidBody>;

// ---------------------------------------------------------------- the reduced model

/// The reduced model (4.12)–(4.14) of the symmetric top, split into the
/// rotation of (Ω₁, Ω₂) at the rate Ω̃₃ (part 0) and the radial damping
/// (part 1). Ω₃ is constant, so the two parts commute and every composition,
/// Lie–Trotter included, is the exact flow: only rounding separates n steps from
/// the closed form (4.15)–(4.16), whatever the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedFlow(pub SymmetricTop);

// ANCHOR: reduced_flows
/// The rotation part of the reduced model: (Ω₁, Ω₂) turn clockwise by Ω̃₃h.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// ```text
/// Ω̇₁ = Ω̃₃Ω₂,  Ω̇₂ = −Ω̃₃Ω₁,  Ω̇₃ = 0
/// Ω₁ ← Ω₁ cos Ω̃₃h + Ω₂ sin Ω̃₃h,  Ω₂ ← Ω₂ cos Ω̃₃h − Ω₁ sin Ω̃₃h
/// ```
pub fn reduced_rotation_flow(top: &SymmetricTop, omega: &Vec3, h: Real) -> Vec3 {
    let alpha = top.omega3_tilde(omega.z) * h;
    let (s, c) = alpha.sin_cos();
    Vec3::new(
        omega.x * c + omega.y * s,
        omega.y * c - omega.x * s,
        omega.z,
    )
}

/// The damping part of the reduced model over time `h`: Ω⊥ shrinks along its
/// own direction. `None` when a backward step (h < 0) reaches the blow-up of
/// Ω⊥, where the flow stops existing.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.16).
///
/// ```text
/// Ω̇⊥ = −τ(Ω⊥² + k²)Ω⊥,  k = (I₃/I₁)Ω₃
/// Ω⊥(h) = Ω⊥ e^{−s/2} / √(1 + Ω⊥² a²),  s = 2τk²h,  a² = 2τh g(s) = (1 − e^{−s})/k²
/// ```
///
/// with g(s) = (1 − e^{−s})/s as in [`crate::physics::symmetric_top::reduced_amplitude`].
///
/// NOTE: a² is −expm1(−s)/k² (no cancellation for tiny s, no overflow for huge
/// s: it tends to 1/k²), or 2τh when k²·τh is zero to the last bit. Forward, the
/// denominator is hypot(1, Ω⊥a), which cannot overflow; once Ω⊥a > 1 the new
/// rate is computed as e^{−s/2}/(a·hypot(1, 1/(Ω⊥a))), the late-time
/// 1/√(2τhg) form that does not depend on Ω⊥ at all, so huge τΩ⊥²h loses no
/// digits. e^{−s/2} underflowing to 0 is the right answer (Ω⊥ below 1e-300).
pub fn reduced_damping_flow(top: &SymmetricTop, omega: &Vec3, h: Real) -> Option<Vec3> {
    let tau = top.tau();
    let k = top.ratio() * omega.z;
    let k2 = k * k;
    let s = 2.0 * tau * k2 * h;
    let a2 = if s != 0.0 && k2 > 0.0 {
        -(-s).exp_m1() / k2
    } else {
        2.0 * tau * h
    };
    let omega_perp = omega.x.hypot(omega.y);
    if omega_perp == 0.0 {
        return Some(*omega);
    }
    let decay = (-0.5 * s).exp();
    let (o1, o2) = if a2 >= 0.0 {
        let a = a2.sqrt();
        let w = omega_perp * a;
        if w <= 1.0 {
            let factor = decay / w.hypot(1.0);
            (omega.x * factor, omega.y * factor)
        } else {
            let magnitude = decay / (a * (1.0 / w).hypot(1.0));
            (
                omega.x / omega_perp * magnitude,
                omega.y / omega_perp * magnitude,
            )
        }
    } else {
        // Backward: 1 + Ω⊥²a² reaches 0 at the blow-up of the backward flow.
        let d = 1.0 + omega_perp * omega_perp * a2;
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        let factor = decay / d.sqrt();
        (omega.x * factor, omega.y * factor)
    };
    let out = Vec3::new(o1, o2, omega.z);
    all_finite(&out).then_some(out)
}
// ANCHOR_END: reduced_flows

impl SplitFlow for ReducedFlow {
    type State = Vec3;

    fn parts(&self) -> usize {
        2
    }

    fn flow(&self, part: usize, h: Real, omega: &Vec3) -> Option<Vec3> {
        if part == 0 {
            Some(reduced_rotation_flow(&self.0, omega, h))
        } else {
            reduced_damping_flow(&self.0, omega, h)
        }
    }

    fn is_finite(&self, omega: &Vec3) -> bool {
        all_finite(omega)
    }
}

/// A fixed-step splitting of the reduced model (see [`ReducedFlow`]).
pub type ReducedSplitting = Splitting<ReducedFlow>;

/// Ω(t_end) of the reduced model from Ω(0) = `omega0` in `steps` equal
/// Lie–Trotter steps of the exact rotation/damping split (exact, since the parts
/// commute: equal to [`crate::physics::symmetric_top::reduced_closed_form`] to
/// rounding for any `steps` ≥ 1, that is to a relative error of a few ε per step
/// plus ε|Ω̃₃t| in the phase). Negative `t_end` steps backward.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// Returns [`IntegrateError::InvalidOption`] for `steps == 0` with
/// `t_end ≠ 0`, a non-finite `t_end` or `omega0`; [`IntegrateError::NonFinite`]
/// when a backward run meets the blow-up of Ω⊥.
pub fn reduced_split_solve(
    top: &SymmetricTop,
    omega0: &Vec3,
    t_end: Real,
    steps: u64,
) -> Result<(Vec3, Stats), IntegrateError> {
    check_t_stop(t_end)?;
    if !all_finite(omega0) {
        return Err(IntegrateError::InvalidOption(
            "the initial angular velocity must be finite".into(),
        ));
    }
    if t_end == 0.0 {
        return Ok((*omega0, Stats::default()));
    }
    if steps == 0 {
        return Err(IntegrateError::InvalidOption(
            "at least one step is needed to reach t_end != 0".into(),
        ));
    }
    let h = t_end.abs() / steps as Real;
    let mut stepper =
        ReducedSplitting::new(ReducedFlow(*top), Composition::LieTrotter, 0.0, *omega0, h)?
            .with_max_steps(steps);
    stepper.advance_to(t_end)?;
    Ok((*stepper.state(), stepper.stats()))
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
