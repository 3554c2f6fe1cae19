//! The two balance laws for the angular momentum of a system of charges
//! (paper §2, Eqs. (2.1)–(2.4)), for any dipole trajectory 𝔡(t).
//!
//! The Larmor-like law (2.1) counts the angular momentum the dipole radiation
//! carries away; the torque law (2.2) adds up the torques of the
//! Abraham–Lorentz forces f = (2q/3c³) 𝔡⃛ on the charges. They differ by the
//! rate of change of the Schott angular momentum L_S (2.4), identity (2.3).
//!
//! Units: κ = 2/(3c³) = 1, so every quantity below is the paper's expression
//! without its prefactor.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `d` | 𝔡 = Σ q r | dipole moment | √κ·charge·length |
//! | `d_dot`, `d_ddot`, `d_dddot` | 𝔡̇, 𝔡̈, 𝔡⃛ | its time derivatives | per time, … |
//! | [`larmor_rate`] | −𝔡̇ × 𝔡̈ | dL/dt by the Larmor-like law (2.1) | angular momentum / time |
//! | [`torque_rate`] | 𝔡 × 𝔡⃛ | dL/dt by the radiation-reaction torque (2.2) | angular momentum / time |
//! | [`schott_angular_momentum`] | L_S = 𝔡 × 𝔡̈ | Schott angular momentum (2.4) | angular momentum |
//! | [`schott_rate`] | L̇_S = 𝔡̇ × 𝔡̈ + 𝔡 × 𝔡⃛ | its rate of change | angular momentum / time |
//! | `axial` | n · (…), n = 𝔡/\|𝔡\| | projection on the dipole direction | – |
//! | `theta`, `omega` | θ, ω | cone angle and rate of the precessing dipole | rad, 1/time |

use super::{ParamError, finite};
use crate::math::{Real, Vec3};
use std::f64::consts::TAU;

/// The dipole and its first three time derivatives at one instant,
/// `[𝔡, 𝔡̇, 𝔡̈, 𝔡⃛]`.
pub type Jet = [Vec3; 4];

// ANCHOR: trajectory_trait
/// A dipole trajectory 𝔡(t), known with its derivatives up to the third.
pub trait DipoleTrajectory {
    /// `[𝔡, 𝔡̇, 𝔡̈, 𝔡⃛]` at time `t`.
    fn jet(&self, t: Real) -> Jet;
    /// The period, when the motion is periodic (needed for [`period_average`]).
    fn period(&self) -> Option<Real>;
}
// ANCHOR_END: trajectory_trait

/// A custom trajectory from a closure that returns the jet `[𝔡, 𝔡̇, 𝔡̈, 𝔡⃛]`.
///
/// ```
/// use spintop::math::Vec3;
/// use spintop::physics::balance::{ClosureDipole, DipoleTrajectory, torque_rate};
/// // A dipole oscillating along x: no angular momentum is lost at all.
/// let linear = ClosureDipole::new(|t: f64| {
///     let (s, c) = t.sin_cos();
///     [Vec3::x() * c, -Vec3::x() * s, -Vec3::x() * c, Vec3::x() * s]
/// }, Some(std::f64::consts::TAU));
/// assert_eq!(torque_rate(&linear.jet(0.3)), Vec3::zeros());
/// ```
#[derive(Clone, Copy, Debug)]
pub struct ClosureDipole<F> {
    jet: F,
    period: Option<Real>,
}

impl<F: Fn(Real) -> Jet> ClosureDipole<F> {
    /// Wrap `jet`; give `period` when the motion is periodic.
    pub fn new(jet: F, period: Option<Real>) -> Self {
        Self { jet, period }
    }
}

impl<F: Fn(Real) -> Jet> DipoleTrajectory for ClosureDipole<F> {
    fn jet(&self, t: Real) -> Jet {
        (self.jet)(t)
    }
    fn period(&self) -> Option<Real> {
        self.period
    }
}

// ANCHOR: laws
/// The angular-momentum loss rate by the Larmor-like law.
///
/// Paper: Eq. (2.1).
///
/// ```text
/// dL/dt = −(2/3c³) 𝔡̇ × 𝔡̈        (κ = 2/3c³ = 1)
/// ```
pub fn larmor_rate(jet: &Jet) -> Vec3 {
    let [_, d_dot, d_ddot, _] = jet;
    -d_dot.cross(d_ddot)
}

/// The torque of the Abraham–Lorentz forces on the charges.
///
/// Paper: Eq. (2.2).
///
/// ```text
/// dL/dt = (2/3c³) 𝔡 × 𝔡⃛        (κ = 1)
/// ```
pub fn torque_rate(jet: &Jet) -> Vec3 {
    let [d, _, _, d_dddot] = jet;
    d.cross(d_dddot)
}

/// The Schott angular momentum.
///
/// Paper: Eq. (2.4).
///
/// ```text
/// L_S = (2/3c³) 𝔡 × 𝔡̈ = (2/3c³) d/dt (𝔡 × 𝔡̇)        (κ = 1)
/// ```
pub fn schott_angular_momentum(jet: &Jet) -> Vec3 {
    let [d, _, d_ddot, _] = jet;
    d.cross(d_ddot)
}

/// The rate of change of the Schott angular momentum, the difference of the
/// two laws.
///
/// Paper: Eq. (2.3).
///
/// ```text
/// dL_S/dt = 𝔡̇ × 𝔡̈ + 𝔡 × 𝔡⃛,   so   𝔡 × 𝔡⃛ = dL_S/dt − 𝔡̇ × 𝔡̈   (2.3)
/// ```
pub fn schott_rate(jet: &Jet) -> Vec3 {
    let [d, d_dot, d_ddot, d_dddot] = jet;
    d_dot.cross(d_ddot) + d.cross(d_dddot)
}
// ANCHOR_END: laws

/// The component of `v` along the dipole direction n = 𝔡/|𝔡| (0 when 𝔡 = 0,
/// where every law gives zero anyway).
pub fn axial(d: &Vec3, v: &Vec3) -> Real {
    let n = d.norm();
    if n == 0.0 { 0.0 } else { d.dot(v) / n }
}

/// Every quantity of §2 at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Balance {
    /// Time.
    pub t: Real,
    /// 𝔡.
    pub dipole: Vec3,
    /// −𝔡̇ × 𝔡̈, (2.1).
    pub larmor: Vec3,
    /// 𝔡 × 𝔡⃛, (2.2).
    pub torque: Vec3,
    /// L_S = 𝔡 × 𝔡̈, (2.4).
    pub schott: Vec3,
    /// dL_S/dt.
    pub schott_rate: Vec3,
    /// n · (2.1).
    pub larmor_axial: Real,
    /// n · (2.2), zero for every trajectory.
    pub torque_axial: Real,
    /// n · dL_S/dt.
    pub schott_rate_axial: Real,
}

/// Evaluate both laws, L_S, dL_S/dt and their projections at time `t`.
pub fn balance_at(traj: &impl DipoleTrajectory, t: Real) -> Balance {
    let jet = traj.jet(t);
    let d = jet[0];
    let larmor = larmor_rate(&jet);
    let torque = torque_rate(&jet);
    let schott_rate = schott_rate(&jet);
    Balance {
        t,
        dipole: d,
        larmor,
        torque,
        schott: schott_angular_momentum(&jet),
        schott_rate,
        larmor_axial: axial(&d, &larmor),
        torque_axial: axial(&d, &torque),
        schott_rate_axial: axial(&d, &schott_rate),
    }
}

/// The number of quadrature nodes per period used by [`period_average`].
pub const AVERAGE_NODES: usize = 256;

// ANCHOR: period_average
/// The averages over one period of every quantity of [`balance_at`]
/// (the `t` of the result is the period). `None` for a non-periodic motion.
///
/// Paper: Eq. (2.3) (the average of a total derivative over a period vanishes).
///
/// ```text
/// ⟨X⟩ = (1/T) ∫₀ᵀ X(t) dt ≈ (1/N) Σₖ X(kT/N),   N = 256
/// ```
pub fn period_average(traj: &impl DipoleTrajectory) -> Option<Balance> {
    let period = traj.period()?;
    // NOTE: the composite trapezoid rule over a full period is exact for every
    // trigonometric polynomial of degree < N (the nodes kT/N sum e^{2πikt/T} to
    // zero for 0 < |k| < N). The built-in trajectories are trigonometric
    // polynomials of degree ≤ 2, so their products (degree ≤ 6) are averaged to
    // rounding; for a smooth periodic 𝔡 the error falls geometrically with N.
    let n = AVERAGE_NODES;
    let mut sum = Balance {
        t: period,
        dipole: Vec3::zeros(),
        larmor: Vec3::zeros(),
        torque: Vec3::zeros(),
        schott: Vec3::zeros(),
        schott_rate: Vec3::zeros(),
        larmor_axial: 0.0,
        torque_axial: 0.0,
        schott_rate_axial: 0.0,
    };
    for k in 0..n {
        let b = balance_at(traj, period * k as Real / n as Real);
        sum.dipole += b.dipole;
        sum.larmor += b.larmor;
        sum.torque += b.torque;
        sum.schott += b.schott;
        sum.schott_rate += b.schott_rate;
        sum.larmor_axial += b.larmor_axial;
        sum.torque_axial += b.torque_axial;
        sum.schott_rate_axial += b.schott_rate_axial;
    }
    let w = 1.0 / n as Real;
    Some(Balance {
        t: period,
        dipole: sum.dipole * w,
        larmor: sum.larmor * w,
        torque: sum.torque * w,
        schott: sum.schott * w,
        schott_rate: sum.schott_rate * w,
        larmor_axial: sum.larmor_axial * w,
        torque_axial: sum.torque_axial * w,
        schott_rate_axial: sum.schott_rate_axial * w,
    })
}
// ANCHOR_END: period_average

/// Refuse a rotation rate ω that is zero (a static dipole has no period and
/// does not radiate) or so small that its period 2π/|ω| overflows a double.
fn check_rate(omega: Real) -> Result<(), ParamError> {
    if !(2.0 * std::f64::consts::PI / omega.abs()).is_finite() {
        return Err(ParamError::OutOfRange {
            name: "rate",
            value: omega,
            range: "non-zero, with a period 2 pi/|rate| a double can hold (a static dipole has no period and does not radiate)",
        });
    }
    Ok(())
}

/// A rigid dipole of unit length precessing about lab z on a cone of
/// half-angle θ at rate ω: the dipole of a symmetric top in regular
/// precession.
///
/// ```text
/// 𝔡(t) = (sin θ cos ωt, sin θ sin ωt, cos θ)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrecessingDipole {
    theta: Real,
    omega: Real,
}

impl PrecessingDipole {
    /// Validate the cone angle θ ∈ [0, π] and the rate ω ≠ 0 (finite).
    pub fn new(theta: Real, omega: Real) -> Result<Self, ParamError> {
        finite("cone angle", theta)?;
        finite("rate", omega)?;
        if !(0.0..=std::f64::consts::PI).contains(&theta) {
            return Err(ParamError::OutOfRange {
                name: "cone angle",
                value: theta,
                range: "in [0, pi]",
            });
        }
        check_rate(omega)?;
        Ok(Self { theta, omega })
    }

    /// θ.
    pub fn theta(&self) -> Real {
        self.theta
    }

    /// ω.
    pub fn omega(&self) -> Real {
        self.omega
    }

    /// The closed forms at time `t`:
    /// `(larmor, torque, schott, schott_rate)`.
    ///
    /// Paper: Eq. (2.1), Eq. (2.2), Eq. (2.4).
    ///
    /// ```text
    /// −𝔡̇ × 𝔡̈ = −ω³ sin²θ ẑ
    ///  𝔡 × 𝔡⃛ = ω³ sin θ (cos θ cos ωt, cos θ sin ωt, −sin θ)
    ///  L_S   = ω² sin θ cos θ (sin ωt, −cos ωt, 0)
    ///  L̇_S   = ω³ sin θ cos θ (cos ωt, sin ωt, 0),   n · L̇_S = ω³ sin²θ cos θ
    /// ```
    pub fn closed_forms(&self, t: Real) -> [Vec3; 4] {
        let (theta, omega) = (self.theta, self.omega);
        let (st, ct) = theta.sin_cos();
        let (s, c) = (omega * t).sin_cos();
        let w3 = omega.powi(3);
        [
            Vec3::new(0.0, 0.0, -w3 * st * st),
            w3 * st * Vec3::new(ct * c, ct * s, -st),
            omega * omega * st * ct * Vec3::new(s, -c, 0.0),
            w3 * st * ct * Vec3::new(c, s, 0.0),
        ]
    }
}

impl DipoleTrajectory for PrecessingDipole {
    fn jet(&self, t: Real) -> Jet {
        let (st, ct) = self.theta.sin_cos();
        let w = self.omega;
        let (s, c) = (w * t).sin_cos();
        [
            Vec3::new(st * c, st * s, ct),
            w * st * Vec3::new(-s, c, 0.0),
            -w * w * st * Vec3::new(c, s, 0.0),
            w * w * w * st * Vec3::new(s, -c, 0.0),
        ]
    }
    fn period(&self) -> Option<Real> {
        Some(TAU / self.omega.abs())
    }
}

/// A planar two-harmonic loop, period 2π.
///
/// ```text
/// 𝔡(t) = (cos t, b sin t + ε sin 2t, 0)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarLoop {
    b: Real,
    eps: Real,
}

impl PlanarLoop {
    /// Validate b and ε (any finite numbers).
    pub fn new(b: Real, eps: Real) -> Result<Self, ParamError> {
        Ok(Self {
            b: finite("b", b)?,
            eps: finite("eps", eps)?,
        })
    }

    /// The z components of the closed forms at time `t`:
    /// `(larmor, torque, schott, schott_rate)` (the x, y components vanish).
    ///
    /// Paper: Eq. (2.1), Eq. (2.2), Eq. (2.4).
    ///
    /// ```text
    /// −𝔡̇ × 𝔡̈ = −b − 3ε cos t + ε cos 3t
    ///  𝔡 × 𝔡⃛ = −b − (9/2)ε cos t − (7/2)ε cos 3t
    ///  L_S   = −(3/2)ε (sin t + sin 3t)
    ///  L̇_S   = −(3/2)ε cos t − (9/2)ε cos 3t
    /// ```
    ///
    /// Over a period both laws give −b ẑ; at an instant they differ unless ε = 0.
    pub fn closed_forms(&self, t: Real) -> [Real; 4] {
        let (b, eps) = (self.b, self.eps);
        let (c1, c3) = (t.cos(), (3.0 * t).cos());
        let (s1, s3) = (t.sin(), (3.0 * t).sin());
        [
            -b - 3.0 * eps * c1 + eps * c3,
            -b - 4.5 * eps * c1 - 3.5 * eps * c3,
            -1.5 * eps * (s1 + s3),
            -1.5 * eps * c1 - 4.5 * eps * c3,
        ]
    }
}

impl DipoleTrajectory for PlanarLoop {
    fn jet(&self, t: Real) -> Jet {
        let (b, eps) = (self.b, self.eps);
        let (s1, c1) = t.sin_cos();
        let (s2, c2) = (2.0 * t).sin_cos();
        [
            Vec3::new(c1, b * s1 + eps * s2, 0.0),
            Vec3::new(-s1, b * c1 + 2.0 * eps * c2, 0.0),
            Vec3::new(-c1, -b * s1 - 4.0 * eps * s2, 0.0),
            Vec3::new(s1, -b * c1 - 8.0 * eps * c2, 0.0),
        ]
    }
    fn period(&self) -> Option<Real> {
        Some(TAU)
    }
}

/// A rigid dumbbell, charges q₁, q₂ and masses m₁, m₂ at the ends of a rod of
/// length ℓ, spinning at rate ω about an axis through its centre of mass and
/// perpendicular to the rod (lab z), the rod along x at t = 0.
///
/// ```text
/// 𝔡(t) = ℓ (q₁m₂ − q₂m₁)/(m₁ + m₂) (cos ωt, sin ωt, 0)
/// ```
///
/// A planar rigid rotor turning at a constant rate: 𝔡̈ = −ω²𝔡, so L_S = 𝔡 × 𝔡̈ ≡ 0
/// and the two laws agree at every instant (a rotor that speeds up or slows
/// down has L_S = κ|𝔡|²ω̇ ẑ ≠ 0); equal charge-to-mass ratios give no dipole at all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dumbbell {
    amplitude: Real,
    omega: Real,
}

impl Dumbbell {
    /// Validate charges (finite), masses (> 0), length (> 0) and rate (≠ 0).
    pub fn new(
        charges: [Real; 2],
        masses: [Real; 2],
        length: Real,
        omega: Real,
    ) -> Result<Self, ParamError> {
        let [q1, q2] = [finite("q1", charges[0])?, finite("q2", charges[1])?];
        let [m1, m2] = [finite("m1", masses[0])?, finite("m2", masses[1])?];
        finite("length", length)?;
        finite("rate", omega)?;
        for (name, value) in [("m1", m1), ("m2", m2), ("length", length)] {
            if value <= 0.0 {
                return Err(ParamError::OutOfRange {
                    name,
                    value,
                    range: "positive",
                });
            }
        }
        check_rate(omega)?;
        Ok(Self {
            amplitude: length * (q1 * m2 - q2 * m1) / (m1 + m2),
            omega,
        })
    }

    /// |𝔡| with its sign: ℓ (q₁m₂ − q₂m₁)/(m₁ + m₂).
    pub fn amplitude(&self) -> Real {
        self.amplitude
    }
}

impl DipoleTrajectory for Dumbbell {
    fn jet(&self, t: Real) -> Jet {
        let (d0, w) = (self.amplitude, self.omega);
        let (s, c) = (w * t).sin_cos();
        let u = Vec3::new(c, s, 0.0);
        let u_perp = Vec3::new(-s, c, 0.0);
        [
            d0 * u,
            d0 * w * u_perp,
            -d0 * w * w * u,
            -d0 * w * w * w * u_perp,
        ]
    }
    fn period(&self) -> Option<Real> {
        Some(TAU / self.omega.abs())
    }
}
