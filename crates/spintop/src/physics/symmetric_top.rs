//! The axially symmetric polarized top (paper §4, Eqs. (4.1)–(4.18)).
//!
//! With I₂ = I₁ and the dipole along the symmetry axis (4.1), the truncated ALE
//! (3.3) splits into (4.2)–(4.4), and the reduced ALE (the Landau–Lifshitz-type
//! reduction of (3.4)) into (4.12)–(4.14). Both are solved here in closed form,
//! for any Ω₁₀ (the paper sets Ω₁₀ = 0; a general start only adds a phase).
//!
//! Units: I₁ = 1 and time in units of τ = 2d²/(3I₁c³); the struct keeps τ as
//! a parameter (τ = 1 in the paper's units, τ = 0 is the free Euler top).
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `ratio` | I₃/I₁ | moment ratio, in (0, 2] | – |
//! | `tau` | τ | radiation time | τ |
//! | `omega` | Ω = (Ω₁, Ω₂, Ω₃) | body angular velocity | 1/τ |
//! | `omega_perp` | Ω⊥ | √(Ω₁² + Ω₂²) | 1/τ |
//! | `omega3_tilde` | Ω̃₃ | (1 − I₃/I₁) Ω₃, body-frame precession rate of Ω⊥ | 1/τ |
//! | `r` | R(t) | √(1 + 2τΩ⊥₀²t), (4.6) | – |
//! | `vartheta` | ϑ | ∫₀ᵗ dt′/R = (R − 1)/(τΩ⊥₀²), (4.9) | τ |
//! | `k` | (I₃/I₁)Ω₃ | the spin term of the reduced damping | 1/τ |
//! | `sigma` | σ | I₁²/(I₃²Ω₃²τ), reduced decay time (4.16) | τ |
//! | `phi_amp` | Φ(t) | reduced amplitude factor (4.16) | – |

use super::rigid_body::{BodyDynamics, angular_momentum_body};
use super::{ParamError, finite};
use crate::math::{Mat3, Real, Vec3, all_finite, rot_axis, rot_z};

/// I₃/I₁ of the paper's Figures 1 and 2 (a prolate top): the default of every
/// entry point that takes a symmetric top.
pub const FIGURE_RATIO: Real = 0.4;

/// Ω₀ of the paper's Figures 1 and 2, in units of 1/τ: the default of every
/// entry point that takes a top.
pub const FIGURE_OMEGA0: [Real; 3] = [0.0, 0.1, 0.2];

/// An axially symmetric top with its dipole on the symmetry axis (4.1), in units I₁ = 1.
///
/// Built only through [`SymmetricTop::new`], so 0 < I₃/I₁ ≤ 2 and τ ≥ 0 always hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetricTop {
    ratio: Real,
    tau: Real,
}

impl SymmetricTop {
    /// Validate I₃/I₁ (in (0, 2] by the triangle inequality I₃ ≤ I₁ + I₂) and τ ≥ 0.
    pub fn new(ratio: Real, tau: Real) -> Result<Self, ParamError> {
        finite("I3/I1", ratio)?;
        finite("tau", tau)?;
        if !(ratio > 0.0 && ratio <= 2.0) {
            return Err(ParamError::RatioOutOfRange(ratio));
        }
        if tau < 0.0 {
            return Err(ParamError::NegativeTau(tau));
        }
        Ok(Self { ratio, tau })
    }

    /// The top of the paper's figures: I₃/I₁ = 2/5 ([`FIGURE_RATIO`]), τ = 1.
    pub fn figure() -> Self {
        Self {
            ratio: FIGURE_RATIO,
            tau: 1.0,
        }
    }

    /// I₃/I₁.
    pub fn ratio(&self) -> Real {
        self.ratio
    }

    /// τ.
    pub fn tau(&self) -> Real {
        self.tau
    }

    /// Principal moments (1, 1, I₃/I₁).
    pub fn inertia(&self) -> Vec3 {
        Vec3::new(1.0, 1.0, self.ratio)
    }

    /// Ω̃₃ = (1 − I₃/I₁) Ω₃.
    pub fn omega3_tilde(&self, omega3: Real) -> Real {
        (1.0 - self.ratio) * omega3
    }
}

// ANCHOR: truncated_rhs
/// The truncated ALE of the symmetric top (no Schott term).
///
/// Paper: Eq. (4.2), Eq. (4.3), Eq. (4.4).
///
/// ```text
/// Ω̇₁ − Ω̃₃Ω₂ = −τΩ⊥²Ω₁
/// Ω̇₂ + Ω̃₃Ω₁ = −τΩ⊥²Ω₂
/// Ω̇₃        = −τΩ⊥²Ω₃
/// ```
pub fn truncated_ale_rhs(top: &SymmetricTop, omega: &Vec3) -> Vec3 {
    let tau = top.tau;
    let omega3_tilde = top.omega3_tilde(omega.z);
    let damping = tau * (omega.x * omega.x + omega.y * omega.y);
    Vec3::new(
        omega3_tilde * omega.y - damping * omega.x,
        -omega3_tilde * omega.x - damping * omega.y,
        -damping * omega.z,
    )
}
// ANCHOR_END: truncated_rhs

// ANCHOR: reduced_rhs
/// The reduced ALE of the symmetric top (Schott term kept, runaways removed).
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// ```text
/// Ω̇₁ − Ω̃₃Ω₂ = −τ{Ω⊥² + (I₃/I₁)²Ω₃²}Ω₁
/// Ω̇₂ + Ω̃₃Ω₁ = −τ{Ω⊥² + (I₃/I₁)²Ω₃²}Ω₂
/// Ω̇₃        = 0
/// ```
pub fn reduced_ale_rhs(top: &SymmetricTop, omega: &Vec3) -> Vec3 {
    let tau = top.tau;
    let omega3_tilde = top.omega3_tilde(omega.z);
    let k = top.ratio * omega.z;
    let damping = tau * (omega.x * omega.x + omega.y * omega.y + k * k);
    Vec3::new(
        omega3_tilde * omega.y - damping * omega.x,
        -omega3_tilde * omega.x - damping * omega.y,
        0.0,
    )
}
// ANCHOR_END: reduced_rhs

/// The truncated model (4.2)–(4.4) as `Ω̇ = F(Ω)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Truncated(pub SymmetricTop);

/// The reduced model (4.12)–(4.14) as `Ω̇ = F(Ω)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reduced(pub SymmetricTop);

impl BodyDynamics for Truncated {
    fn inertia(&self) -> Vec3 {
        self.0.inertia()
    }
    fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        truncated_ale_rhs(&self.0, omega)
    }
}

impl BodyDynamics for Reduced {
    fn inertia(&self) -> Vec3 {
        self.0.inertia()
    }
    fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        reduced_ale_rhs(&self.0, omega)
    }
}

/// The slowed clock of the truncated model: R(t) and ϑ(t).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TruncatedClock {
    /// R(t) = √(1 + 2τΩ⊥₀²t).
    pub r: Real,
    /// ϑ(t) = (R − 1)/(τΩ⊥₀²) = ∫₀ᵗ dt′/R(t′).
    pub vartheta: Real,
}

// ANCHOR: truncated_clock
/// R(t) and the new time ϑ(t) of the truncated model, for t ≥ 0.
///
/// Paper: Eq. (4.6), Eq. (4.9).
///
/// ```text
/// R(t) = √(1 + 2τΩ⊥₀²t),   ϑ = (R − 1)/(τΩ⊥₀²) = 2t/(1 + R)
/// ```
///
/// NOTE: ϑ is evaluated as 2t/(1 + R). The printed (R − 1)/(τΩ⊥₀²) subtracts
/// two numbers that agree to every digit once τΩ⊥₀²t < 1e-16 (it returns 0,
/// or 0/0 when τ = 0); 2t/(1 + R) has no subtraction and no division by a
/// small number, so it is accurate to a few ulps from τΩ⊥₀²t = 0 up to
/// overflow.
pub fn truncated_clock(top: &SymmetricTop, omega_perp0: Real, t: Real) -> TruncatedClock {
    let x = top.tau * omega_perp0 * omega_perp0 * t;
    let r = (1.0 + 2.0 * x).sqrt();
    TruncatedClock {
        r,
        vartheta: 2.0 * t / (1.0 + r),
    }
}
// ANCHOR_END: truncated_clock

/// Ω⊥ of the truncated model.
///
/// Paper: Eq. (4.5), Eq. (4.6).
///
/// ```text
/// dΩ⊥/dt = −τΩ⊥³  ⇒  Ω⊥(t) = Ω⊥₀ / R(t)
/// ```
pub fn truncated_omega_perp(top: &SymmetricTop, omega_perp0: Real, t: Real) -> Real {
    omega_perp0 / truncated_clock(top, omega_perp0, t).r
}

/// Rotate (Ω₁₀, Ω₂₀) by the body-frame precession angle α (clockwise, as
/// (4.7) and (4.15) turn it) and scale by `scale`.
fn precess(omega0: &Vec3, alpha: Real, scale: Real) -> (Real, Real) {
    let (s, c) = alpha.sin_cos();
    (
        scale * (omega0.x * c + omega0.y * s),
        scale * (omega0.y * c - omega0.x * s),
    )
}

/// The closed-form Ω(t) of the truncated model, for any Ω₀ and t ≥ 0.
///
/// Paper: Eq. (4.7).
///
/// ```text
/// Ω₁ = (Ω₁₀ cos α + Ω₂₀ sin α)/R,  Ω₂ = (Ω₂₀ cos α − Ω₁₀ sin α)/R,  Ω₃ = Ω₃₀/R
/// α = Ω̃₃₀ ϑ(t)
/// ```
///
/// With Ω₁₀ = 0 this is the printed (4.7).
pub fn truncated_closed_form(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Vec3 {
    let clock = truncated_clock(top, omega0.x.hypot(omega0.y), t);
    let alpha = top.omega3_tilde(omega0.z) * clock.vartheta;
    let (o1, o2) = precess(omega0, alpha, 1.0 / clock.r);
    Vec3::new(o1, o2, omega0.z / clock.r)
}

/// σ = I₁²/(I₃²Ω₃²τ), the late-time decay time of Ω⊥ in the reduced model
/// (infinite when Ω₃ = 0 or τ = 0).
///
/// Paper: Eq. (4.16).
pub fn reduced_decay_time(top: &SymmetricTop, omega3: Real) -> Real {
    let k = top.ratio * omega3;
    1.0 / (k * k * top.tau)
}

// ANCHOR: reduced_amplitude
/// The amplitude factor Φ(t) = Ω⊥(t)/Ω⊥₀ of the reduced model, t ≥ 0.
///
/// Paper: Eq. (4.16).
///
/// ```text
/// Φ(t) = √((β − 1)/(β e^{2t/σ} − 1)),  β = 1 + (I₃Ω₃)²/(I₁Ω⊥₀)²,  σ = I₁²/(I₃²Ω₃²τ)
/// ```
///
/// NOTE: the printed form overflows (β e^{2t/σ} = ∞ once 2t/σ > 709) and, for
/// small t/σ, divides two differences of nearly equal numbers. With k = I₃Ω₃/I₁,
/// s = 2t/σ = 2τk²t and g(s) = (1 − e^{−s})/s = −expm1(−s)/s, it equals
///
/// ```text
/// Φ = e^{−s/2} / √(1 + 2τΩ⊥₀² t g(s))
/// ```
///
/// which has no subtraction and no overflow, tends to 1/R(t) of (4.6) as
/// Ω₃ → 0 (g → 1), and to 1 as τ → 0.
pub fn reduced_amplitude(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio * omega0.z;
    let s = 2.0 * top.tau * k * k * t;
    let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
    (-0.5 * s).exp() / (1.0 + 2.0 * top.tau * u0 * t * g).sqrt()
}
// ANCHOR_END: reduced_amplitude

/// The closed-form Ω(t) of the reduced model, for any Ω₀ and t ≥ 0.
///
/// Paper: Eq. (4.15), Eq. (4.16).
///
/// ```text
/// Ω₁ = Φ(t)(Ω₁₀ cos Ω̃₃t + Ω₂₀ sin Ω̃₃t),  Ω₂ = Φ(t)(Ω₂₀ cos Ω̃₃t − Ω₁₀ sin Ω̃₃t),  Ω₃ = Ω₃₀
/// ```
pub fn reduced_closed_form(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Vec3 {
    let phi_amp = reduced_amplitude(top, omega0, t);
    let alpha = top.omega3_tilde(omega0.z) * t;
    let (o1, o2) = precess(omega0, alpha, phi_amp);
    Vec3::new(o1, o2, omega0.z)
}

/// Points between exact re-anchorings of [`reduced_closed_form_many`]'s
/// recurrences: each step of a recurrence adds about one rounding, so the
/// drift stays below ~64ε before it is reset.
pub const REANCHOR_EVERY: usize = 64;

/// The closed-form Ω of the reduced model at many times (ascending).
///
/// Paper: Eq. (4.15), Eq. (4.16).
///
/// Where the times are evenly spaced, t_j = t₀ + jΔ (to 4 ulps), the
/// precession angle and the decay factors advance by recurrence, each point
/// costing a few multiplications, a division and a square root instead of a
/// sine, a cosine and two exponentials:
///
/// ```text
/// (cos, sin)(α + Ω̃₃Δ) by one complex multiplication,
/// H = e^{−s/2}:  H ← H e^{−τk²Δ},     D = 1 − e^{−s}:  D ← D e^{−2τk²Δ} + (1 − e^{−2τk²Δ})
/// Φ = H / √(1 + (Ω⊥₀²/k²) D)          (= (4.16) in the form of [`reduced_amplitude`])
/// ```
///
/// and every [`REANCHOR_EVERY`] points all three are recomputed exactly, so
/// the result stays within ~10⁻¹⁴ of [`reduced_closed_form`] however long the
/// run (tested). Other times are evaluated one by one.
pub fn reduced_closed_form_many(top: &SymmetricTop, omega0: &Vec3, times: &[Real]) -> Vec<Vec3> {
    let pointwise = || {
        times
            .iter()
            .map(|&t| reduced_closed_form(top, omega0, t))
            .collect()
    };
    let n = times.len();
    if n < 3 {
        return pointwise();
    }
    let t0 = times[0];
    let dt = (times[n - 1] - t0) / (n - 1) as Real;
    let even = dt > 0.0
        && times.iter().enumerate().all(|(j, &t)| {
            (t - (t0 + j as Real * dt)).abs() <= 4.0 * Real::EPSILON * t.abs().max(dt)
        });
    if !even {
        return pointwise();
    }
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio * omega0.z;
    let w = top.omega3_tilde(omega0.z);
    let rate = top.tau * k * k; // e^{−s/2} = e^{−rate·t}
    // Ω⊥₀²/k²; where k is 0 (or so small that this overflows) the load is
    // 2τΩ⊥₀²t itself, the limit g(s) → 1.
    let ratio = u0 / (k * k);
    let linear = !ratio.is_finite();
    let (sd, cd) = (w * dt).sin_cos();
    let h_step = (-rate * dt).exp();
    let q = h_step * h_step;
    let d_step = -(-2.0 * rate * dt).exp_m1();
    let mut out = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        // Exact values at the anchor.
        let t = t0 + j as Real * dt;
        let (mut s, mut c) = (w * t).sin_cos();
        let mut h = (-rate * t).exp();
        let mut d = -(-2.0 * rate * t).exp_m1();
        let mut a = 2.0 * top.tau * u0 * t; // only when linear
        for _ in j..(j + REANCHOR_EVERY).min(n) {
            let load = if linear { a } else { ratio * d };
            let phi = h / (1.0 + load).sqrt();
            out.push(Vec3::new(
                phi * (omega0.x * c + omega0.y * s),
                phi * (omega0.y * c - omega0.x * s),
                omega0.z,
            ));
            (c, s) = (c * cd - s * sd, s * cd + c * sd);
            h *= h_step;
            d = d * q + d_step;
            a += 2.0 * top.tau * u0 * dt;
        }
        j += REANCHOR_EVERY;
    }
    out
}

// ANCHOR: time_to_factor
/// How long the truncated model takes to slow every rate by the factor `p`.
///
/// Paper: Eq. (4.6) (inverted).
///
/// ```text
/// Ω(t) = Ω₀/R(t),  R = 1/p  ⇒  t = (1/p² − 1) / (2τΩ⊥₀²)
/// ```
///
/// Infinite when τΩ⊥₀² = 0 (nothing radiates), zero for p ≥ 1; `p` in (0, 1].
pub fn truncated_time_to_factor(top: &SymmetricTop, omega_perp0: Real, p: Real) -> Real {
    if p >= 1.0 {
        return 0.0;
    }
    let rate = 2.0 * top.tau * omega_perp0 * omega_perp0;
    if rate == 0.0 {
        return Real::INFINITY;
    }
    (1.0 / (p * p) - 1.0) / rate
}

/// How long the reduced model takes to bring Ω⊥ down to `p` Ω⊥₀.
///
/// Paper: Eq. (4.16) (inverted).
///
/// ```text
/// Φ(t) = p  ⇒  t = (σ/2) ln(1 + (β − 1)(1/p² − 1)/β)
/// ```
///
/// NOTE: with u₀ = Ω⊥₀², k = I₃Ω₃/I₁ and x = k²(1/p² − 1)/(u₀ + k²) this is
/// t = (1/p² − 1)/(2τ(u₀ + k²)) · ln(1 + x)/x, which needs neither σ (infinite
/// when Ω₃ = 0) nor β (infinite when Ω⊥₀ = 0), and tends to the truncated
/// model's time as Ω₃ → 0, where ln(1 + x)/x → 1.
pub fn reduced_time_to_factor(top: &SymmetricTop, omega0: &Vec3, p: Real) -> Real {
    if p >= 1.0 {
        return 0.0;
    }
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio * omega0.z;
    let s = u0 + k * k;
    let rate = 2.0 * top.tau * s;
    if rate == 0.0 {
        return Real::INFINITY;
    }
    let q = 1.0 / (p * p) - 1.0;
    let x = k * k * q / s;
    let log_factor = if x == 0.0 { 1.0 } else { x.ln_1p() / x };
    q / rate * log_factor
}
// ANCHOR_END: time_to_factor

/// The reduced model's body rate seen from axes that turn with Ω⊥ in the body.
///
/// Paper: Eq. (4.15), Eq. (4.16).
///
/// ```text
/// Ω(t) = R_z(−Ω̃₃t) (ΦΩ₁₀, ΦΩ₂₀, Ω₃)   ⇒   with O = Q·R_z(Ω̃₃t):  Q′ = Q ŵ,
/// w(t) = R_z(Ω̃₃t)Ω(t) − Ω̃₃ẑ = (Φ(t)Ω₁₀, Φ(t)Ω₂₀, (I₃/I₁)Ω₃)
/// ```
///
/// The fast precession R_z(Ω̃₃t) is exact; w only changes on the slow scales
/// of Φ(t) and tends to the constant (0, 0, I₃Ω₃/I₁), about which Q turns as
/// the free top's axis does. So an integrator for Q has nothing fast to follow
/// (the reduced orientation has no closed form: w turns, so its values at
/// different times do not commute).
pub fn reduced_corotating_rate(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Vec3 {
    let phi_amp = reduced_amplitude(top, omega0, t);
    Vec3::new(phi_amp * omega0.x, phi_amp * omega0.y, top.ratio * omega0.z)
}

// ANCHOR: truncated_orientation
/// The closed-form orientation of the truncated model, for any start `o0` and Ω₀.
///
/// Paper: Eq. (4.9), Eq. (4.10), Eq. (4.11).
///
/// ```text
/// O(t) = Rot(n_L, |L₀| ϑ / I₁) · O(0) · R_z(Ω̃₃₀ ϑ),   n_L = L_lab(0)/|L₀|
/// ```
///
/// The truncated top moves exactly like the free Euler top run on the clock ϑ(t):
/// regular precession about the fixed direction of L, at rates that fall as
/// 1/R(t). The paper's particular solution (4.11) is the case with L along lab z.
pub fn truncated_orientation(top: &SymmetricTop, omega0: &Vec3, o0: &Mat3, t: Real) -> Mat3 {
    let clock = truncated_clock(top, omega0.x.hypot(omega0.y), t);
    let l_lab0 = o0 * angular_momentum_body(&top.inertia(), omega0);
    let precession = l_lab0.norm() * clock.vartheta; // I₁ = 1
    let spin = top.omega3_tilde(omega0.z) * clock.vartheta;
    rot_axis(&l_lab0, precession) * o0 * rot_z(spin)
}
// ANCHOR_END: truncated_orientation

/// The constant tilt θ of the truncated model's particular solution: the angle
/// between the symmetry axis and L.
///
/// Paper: Eq. (4.11) (corrected, erratum 4).
///
/// ```text
/// θ = arctan(I₁Ω⊥₀ / (I₃Ω₃₀))
/// ```
///
/// The paper prints arctan(Ω₂₀/Ω̃₃₀), see [`printed_tilt_4_11`].
pub fn precession_tilt(top: &SymmetricTop, omega0: &Vec3) -> Real {
    omega0.x.hypot(omega0.y).atan2(top.ratio * omega0.z)
}

/// The tilt as printed in the paper's (4.11), arctan(Ω₂₀/Ω̃₃₀): erratum 4.
/// Kept only to demonstrate that it is not constant along the motion.
///
/// Paper: Eq. (4.11) (as printed).
pub fn printed_tilt_4_11(top: &SymmetricTop, omega0: &Vec3) -> Real {
    (omega0.y / top.omega3_tilde(omega0.z)).atan()
}

/// The Poisson equations of the truncated model in the clock ϑ, for Ω₁₀ = 0.
/// `angles` = (φ, θ, ψ̃) with ψ̃ = ψ − Ω̃₃₀ϑ; returns d/dϑ of each.
///
/// Paper: Eq. (4.10).
///
/// ```text
/// dφ/dϑ = Ω₂₀ cos ψ̃ / sin θ
/// dθ/dϑ = −Ω₂₀ sin ψ̃
/// dψ̃/dϑ = Ω₃₀ I₃/I₁ − Ω₂₀ cos ψ̃ cot θ
/// ```
pub fn truncated_poisson_rhs(
    top: &SymmetricTop,
    omega20: Real,
    omega30: Real,
    angles: &Vec3,
) -> Vec3 {
    let (s_th, c_th) = angles.y.sin_cos();
    let (s_psi, c_psi) = angles.z.sin_cos();
    Vec3::new(
        omega20 * c_psi / s_th,
        -omega20 * s_psi,
        omega30 * top.ratio - omega20 * c_psi * c_th / s_th,
    )
}

// ANCHOR: reduced_jacobian
/// The Jacobian ∂F/∂Ω of the reduced ALE's right-hand side F(Ω): what an
/// implicit method needs to step it at τΩ² ≫ 1.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// ```text
/// D = τ(Ω₁² + Ω₂² + k²),  k = (I₃/I₁)Ω₃,  Ω̃₃ = (1 − I₃/I₁)Ω₃
///
///         ⎡ −D − 2τΩ₁²      Ω̃₃ − 2τΩ₁Ω₂    (1 − I₃/I₁)Ω₂ − 2τk(I₃/I₁)Ω₁ ⎤
/// ∂F/∂Ω = ⎢ −Ω̃₃ − 2τΩ₁Ω₂   −D − 2τΩ₂²     −(1 − I₃/I₁)Ω₁ − 2τk(I₃/I₁)Ω₂ ⎥
///         ⎣ 0               0              0                             ⎦
/// ```
///
/// Its eigenvalues are 0 (Ω₃ is constant) and, at Ω⊥ → 0, −τk² ± iΩ̃₃; when
/// τΩ² ≫ |Ω̃₃| they are close to −τ(3Ω⊥² + k²) (the amplitude) and
/// −τ(Ω⊥² + k²) (the phase). They grow like the square of Ω, which is why an
/// explicit method's step must shrink like 1/(τΩ²).
pub fn reduced_ale_jacobian(top: &SymmetricTop, omega: &Vec3) -> Mat3 {
    let tau = top.tau;
    let ratio = top.ratio;
    let omega3_tilde = top.omega3_tilde(omega.z);
    let k = ratio * omega.z;
    let (o1, o2) = (omega.x, omega.y);
    let d = tau * (o1 * o1 + o2 * o2 + k * k);
    Mat3::new(
        -d - 2.0 * tau * o1 * o1,
        omega3_tilde - 2.0 * tau * o1 * o2,
        (1.0 - ratio) * o2 - 2.0 * tau * k * ratio * o1,
        -omega3_tilde - 2.0 * tau * o1 * o2,
        -d - 2.0 * tau * o2 * o2,
        -(1.0 - ratio) * o1 - 2.0 * tau * k * ratio * o2,
        0.0,
        0.0,
        0.0,
    )
}
// ANCHOR_END: reduced_jacobian

// ---------------------------------------------------------------- the reduced model split

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

#[cfg(test)]
mod tests {

    /// The recurrences of the grid version against the pointwise (4.15)–(4.16),
    /// over horizons up to 10⁶ (10⁶ rad of precession) and 10⁴ points, with
    /// Ω₃ = 0 (no decay of the load's exponential) and a top that decays
    /// to nothing; uneven times fall back to the pointwise form.
    #[test]
    fn eq_4_15_on_an_even_grid_matches_the_pointwise_closed_form() {
        for (top, omega0) in [
            (SymmetricTop::figure(), Vec3::new(0.0, 0.1, 0.2)),
            (
                SymmetricTop::new(1.7, 1.0).unwrap(),
                Vec3::new(0.3, -0.2, 1.0),
            ),
            (
                SymmetricTop::new(0.4, 1e-3).unwrap(),
                Vec3::new(0.5, 0.2, 0.0),
            ),
        ] {
            for (t_end, n) in [(10.0, 200), (1e4, 10_000), (1e6, 10_000)] {
                let times: Vec<Real> = (0..n)
                    .map(|j| t_end * j as Real / (n - 1) as Real)
                    .collect();
                let grid = reduced_closed_form_many(&top, &omega0, &times);
                let worst = times
                    .iter()
                    .zip(&grid)
                    .map(|(&t, w)| (reduced_closed_form(&top, &omega0, t) - w).norm())
                    .fold(0.0, Real::max)
                    / omega0.norm();
                // The pointwise form's own angle α = Ω̃₃t carries ~ε·α.
                let alpha = (top.omega3_tilde(omega0.z) * t_end).abs();
                assert!(
                    worst <= 1e-14 + 8.0 * Real::EPSILON * alpha,
                    "{t_end} {n}: {worst:e}"
                );
            }
        }
        let uneven = [0.0, 1.0, 2.5, 7.0];
        let top = SymmetricTop::figure();
        let w0 = Vec3::new(0.0, 0.1, 0.2);
        let got = reduced_closed_form_many(&top, &w0, &uneven);
        for (&t, w) in uneven.iter().zip(&got) {
            assert_eq!(*w, reduced_closed_form(&top, &w0, t));
        }
    }

    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn validation_refuses_ratios_outside_the_triangle_inequality() {
        assert!(SymmetricTop::new(2.0, 1.0).is_ok());
        assert!(SymmetricTop::new(1e-9, 1.0).is_ok());
        for bad in [0.0, -0.4, 2.000001, 3.0] {
            assert_eq!(
                SymmetricTop::new(bad, 1.0),
                Err(ParamError::RatioOutOfRange(bad))
            );
        }
        assert!(matches!(
            SymmetricTop::new(Real::NAN, 1.0),
            Err(ParamError::NotFinite { .. })
        ));
        assert!(matches!(
            SymmetricTop::new(0.4, Real::INFINITY),
            Err(ParamError::NotFinite { .. })
        ));
        assert_eq!(
            SymmetricTop::new(0.4, -1.0),
            Err(ParamError::NegativeTau(-1.0))
        );
    }

    /// Central differences of a closed form against its right-hand side.
    fn check_solves(
        closed: fn(&SymmetricTop, &Vec3, Real) -> Vec3,
        rhs: fn(&SymmetricTop, &Vec3) -> Vec3,
    ) {
        let top = SymmetricTop::new(0.4, 1.0).unwrap();
        let omega0 = Vec3::new(0.07, -0.1, 0.2);
        assert_eq!(closed(&top, &omega0, 0.0), omega0);
        for t in [0.0, 0.5, 3.0, 40.0] {
            let h = 1e-4;
            let t = t + 2.0 * h;
            let d = (closed(&top, &omega0, t + h) - closed(&top, &omega0, t - h)) / (2.0 * h);
            assert_relative_eq!(d, rhs(&top, &closed(&top, &omega0, t)), epsilon = 1e-9);
        }
    }

    #[test]
    fn eq_4_2_eq_4_3_eq_4_4_are_solved_by_the_closed_form_eq_4_7() {
        check_solves(truncated_closed_form, truncated_ale_rhs);
    }

    #[test]
    fn eq_4_12_eq_4_13_eq_4_14_are_solved_by_the_closed_form_eq_4_15() {
        check_solves(reduced_closed_form, reduced_ale_rhs);
    }

    /// Ω⊥ obeys its own equation dΩ⊥/dt = −τΩ⊥³ (multiply (4.2) by Ω₁ and
    /// (4.3) by Ω₂ and add; the paper's recipe swaps them, erratum 3).
    #[test]
    fn eq_4_5_omega_perp_obeys_d_omega_perp_dt_equals_minus_tau_omega_perp_cubed() {
        let top = SymmetricTop::new(1.3, 0.7).unwrap();
        let omega0 = Vec3::new(0.2, -0.3, 0.5);
        let w0 = omega0.x.hypot(omega0.y);
        for t in [0.01, 1.0, 25.0] {
            let h = 1e-5;
            let d = (truncated_omega_perp(&top, w0, t + h) - truncated_omega_perp(&top, w0, t - h))
                / (2.0 * h);
            let w = truncated_omega_perp(&top, w0, t);
            assert_relative_eq!(d, -top.tau() * w.powi(3), max_relative = 1e-8);
            assert_relative_eq!(
                w,
                truncated_closed_form(&top, &omega0, t).xy().norm(),
                max_relative = 1e-15
            );
        }
        // The printed recipe, Ω₂·(4.2) + Ω₁·(4.3), is not d(Ω⊥²/2)/dt.
        let w = omega0;
        let f = truncated_ale_rhs(&top, &w);
        let printed = w.y * f.x + w.x * f.y;
        let right = w.x * f.x + w.y * f.y;
        assert_relative_eq!(right, -top.tau() * w0.powi(4), max_relative = 1e-14);
        assert!((printed - right).abs() > 1e-3);
    }

    /// The inverted closed forms give back the factor they were asked for.
    #[test]
    fn eq_4_6_and_eq_4_16_inverted_return_the_requested_factor() {
        let top = SymmetricTop::new(0.7, 1.0).unwrap();
        for omega0 in [
            Vec3::new(0.03, 0.1, 0.2),
            Vec3::new(0.0, 0.1, 0.0),
            Vec3::new(0.0, 2e-26, 3e-26),
        ] {
            for p in [0.999, 0.5, 1e-3] {
                let t = reduced_time_to_factor(&top, &omega0, p);
                assert_relative_eq!(reduced_amplitude(&top, &omega0, t), p, max_relative = 1e-9);
                let w0 = omega0.x.hypot(omega0.y);
                let t = truncated_time_to_factor(&top, w0, p);
                assert_relative_eq!(1.0 / truncated_clock(&top, w0, t).r, p, max_relative = 1e-9);
            }
        }
        assert_eq!(
            reduced_time_to_factor(&top, &Vec3::zeros(), 0.5),
            Real::INFINITY
        );
        assert_eq!(truncated_time_to_factor(&top, 0.0, 0.5), Real::INFINITY);
        assert_eq!(truncated_time_to_factor(&top, 0.1, 1.0), 0.0);
    }

    /// Seen from axes turned by R_z(Ω̃₃t), the reduced body rate minus the
    /// frame's own Ω̃₃ẑ is (ΦΩ₁₀, ΦΩ₂₀, (I₃/I₁)Ω₃).
    #[test]
    fn eq_4_15_corotating_rate_removes_the_body_frame_precession() {
        let top = SymmetricTop::new(0.4, 1.0).unwrap();
        let omega0 = Vec3::new(0.03, 0.1, 0.2);
        for t in [0.0, 3.0, 70.0, 900.0] {
            let turned = crate::math::rot_z(top.omega3_tilde(omega0.z) * t)
                * reduced_closed_form(&top, &omega0, t)
                - top.omega3_tilde(omega0.z) * Vec3::z();
            assert_relative_eq!(
                turned,
                reduced_corotating_rate(&top, &omega0, t),
                epsilon = 1e-15
            );
        }
    }

    /// (4.16) in the paper's printed form agrees with the rewritten one where the
    /// printed one is well conditioned; Φ → 1/R as Ω₃ → 0.
    #[test]
    fn eq_4_16_careful_form_equals_the_printed_form() {
        let top = SymmetricTop::figure();
        let omega0 = Vec3::new(0.0, 0.1, 0.2);
        let k = top.ratio() * omega0.z;
        let beta = 1.0 + k * k / (omega0.y * omega0.y);
        let sigma = reduced_decay_time(&top, omega0.z);
        for t in [0.3, 10.0, 100.0, 1000.0] {
            let printed = ((beta - 1.0) / (beta * (2.0 * t / sigma).exp() - 1.0)).sqrt();
            assert_relative_eq!(
                reduced_amplitude(&top, &omega0, t),
                printed,
                max_relative = 1e-13
            );
        }
        let no_spin = Vec3::new(0.03, 0.1, 0.0);
        for t in [0.0, 1.0, 1e5] {
            let r = truncated_clock(&top, no_spin.x.hypot(no_spin.y), t).r;
            assert_relative_eq!(
                reduced_amplitude(&top, &no_spin, t),
                1.0 / r,
                max_relative = 1e-15
            );
        }
    }

    /// The analytic Jacobian of (4.12)–(4.14) against central differences of
    /// the right-hand side, at random-looking states and several tops.
    #[test]
    fn eq_4_12_eq_4_13_eq_4_14_jacobian_matches_finite_differences() {
        let tops = [
            SymmetricTop::figure(),
            SymmetricTop::new(1.7, 0.3).unwrap(),
            SymmetricTop::new(0.05, 2.0).unwrap(),
        ];
        let states = [
            Vec3::new(0.0, 0.1, 0.2),
            Vec3::new(-0.7, 0.4, 1.3),
            Vec3::new(30.0, -20.0, 50.0),
        ];
        for top in &tops {
            for omega in &states {
                let jac = reduced_ale_jacobian(top, omega);
                for j in 0..3 {
                    let h = 1e-6 * omega.amax();
                    let mut plus = *omega;
                    let mut minus = *omega;
                    plus[j] += h;
                    minus[j] -= h;
                    let column =
                        (reduced_ale_rhs(top, &plus) - reduced_ale_rhs(top, &minus)) / (2.0 * h);
                    let scale = jac.amax().max(1.0);
                    for i in 0..3 {
                        assert!(
                            (jac[(i, j)] - column[i]).abs() <= 1e-8 * scale,
                            "∂F{}/∂Ω{} = {} but differences give {} (top {top:?}, Ω {omega:?})",
                            i + 1,
                            j + 1,
                            jac[(i, j)],
                            column[i]
                        );
                    }
                }
            }
        }
    }
}
