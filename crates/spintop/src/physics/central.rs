//! One charge in a central potential under radiation reaction (paper §2,
//! Eqs. (2.5)–(2.9)): the Abraham–Lorentz equation, its Landau–Lifshitz
//! reduction, the angular-momentum balance laws, the Coulomb collapse and the
//! oscillator's characteristic roots.
//!
//! Units: m = k = 1, motion in the plane z = 0 (angular momenta are the z
//! component). τ₀ = 2q²/(3mc³) is the only parameter; times are in the
//! potential's natural unit (√(mr₀³/k) for Coulomb with r₀ = 1, 1/ω₀ for the
//! oscillator).
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `tau0` | τ₀ = 2q²/(3mc³) | radiation time | time |
//! | `pos`, `vel`, `acc`, `jerk` | r, v, v̇, v̈ | position and its derivatives | length, … |
//! | [`Potential::dv_dr`] | dV/dr | radial derivative of V | force |
//! | [`Potential::g`] | g(r) = (1/r) dV/dr | F = −g(r) r | force / length |
//! | `l` | L = m r × v | angular momentum (z component) | – |
//! | `a`, `e` | a, e | semi-major axis and eccentricity of a Kepler ellipse | length, – |
//! | `s` | s | characteristic root, x ∝ e^{st} | 1/time |

use super::{ParamError, finite};
use crate::math::{Real, State};
use nalgebra::{Complex, Vector2};

/// A vector in the plane of the orbit.
pub type Vec2 = Vector2<Real>;

/// The z component of a × b for vectors in the plane.
pub fn cross2(a: &Vec2, b: &Vec2) -> Real {
    a.x * b.y - a.y * b.x
}

/// The central potential, with m = k = 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Potential {
    /// V = −k/r.
    Coulomb,
    /// V = k r²/2 (ω₀ = √(k/m) = 1).
    Harmonic,
}

impl Potential {
    /// `coulomb` or `harmonic`.
    pub fn name(&self) -> &'static str {
        match self {
            Potential::Coulomb => "coulomb",
            Potential::Harmonic => "harmonic",
        }
    }

    /// V(r).
    pub fn v(&self, r: Real) -> Real {
        match self {
            Potential::Coulomb => -1.0 / r,
            Potential::Harmonic => 0.5 * r * r,
        }
    }

    /// dV/dr.
    pub fn dv_dr(&self, r: Real) -> Real {
        match self {
            Potential::Coulomb => 1.0 / (r * r),
            Potential::Harmonic => r,
        }
    }

    /// g(r) = (1/r) dV/dr, so that F = −g(r) r: the quantity whose orbit
    /// average enters the corrected (2.9).
    pub fn g(&self, r: Real) -> Real {
        match self {
            Potential::Coulomb => 1.0 / (r * r * r),
            Potential::Harmonic => 1.0,
        }
    }

    /// dg/dr.
    pub fn dg_dr(&self, r: Real) -> Real {
        match self {
            Potential::Coulomb => -3.0 / (r * r * r * r),
            Potential::Harmonic => 0.0,
        }
    }

    /// The external force of (2.5), F = −(dV/dr) r/r.
    pub fn force(&self, pos: &Vec2) -> Vec2 {
        -self.g(pos.norm()) * pos
    }

    /// dF/dt along a motion with velocity `vel`:
    /// −g(r) v − g′(r) (r·v/r) r.
    pub fn force_rate(&self, pos: &Vec2, vel: &Vec2) -> Vec2 {
        let r = pos.norm();
        -self.g(r) * vel - self.dg_dr(r) * (pos.dot(vel) / r) * pos
    }

    /// Speed of the circular orbit of radius r.
    pub fn circular_speed(&self, r: Real) -> Real {
        (r * self.dv_dr(r)).sqrt()
    }

    /// Speed at (r₀, 0) of the orbit of eccentricity e that starts there at its
    /// point nearest the centre: the Kepler pericentre speed √((1 + e)/r₀), or
    /// for the oscillator (an ellipse centred on the origin, r₀ its
    /// semi-minor axis) r₀/√(1 − e²).
    pub fn pericentre_speed(&self, r0: Real, e: Real) -> Real {
        match self {
            Potential::Coulomb => ((1.0 + e) / r0).sqrt(),
            Potential::Harmonic => r0 / (1.0 - e * e).sqrt(),
        }
    }

    /// Mechanical energy m v²/2 + V(r).
    pub fn energy(&self, pos: &Vec2, vel: &Vec2) -> Real {
        0.5 * vel.norm_squared() + self.v(pos.norm())
    }
}

/// A charge in a central potential: the potential and τ₀ > 0, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChargeInField {
    potential: Potential,
    tau0: Real,
}

impl ChargeInField {
    /// Validate τ₀ (finite and positive).
    pub fn new(potential: Potential, tau0: Real) -> Result<Self, ParamError> {
        finite("tau0", tau0)?;
        if tau0 <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "tau0",
                value: tau0,
                range: "positive (it is 2q^2/(3mc^3))",
            });
        }
        Ok(Self { potential, tau0 })
    }

    /// The potential.
    pub fn potential(&self) -> Potential {
        self.potential
    }

    /// τ₀.
    pub fn tau0(&self) -> Real {
        self.tau0
    }
}

/// Split a state `(x, y, vx, vy, …)` into position and velocity.
pub fn pos_vel<const N: usize>(y: &State<N>) -> (Vec2, Vec2) {
    (Vec2::new(y[0], y[1]), Vec2::new(y[2], y[3]))
}

// ANCHOR: abraham_lorentz
/// The Abraham–Lorentz equation as a first-order system in (r, v, v̇).
///
/// Paper: Eq. (2.5).
///
/// ```text
/// m v̇ = F_ex + (2q²/3c³) v̈,   F_ex = −(dV/dr) r/r
/// ⇒  ṙ = v,  v̇ = a,  ȧ = (a − F_ex(r)/m)/τ₀
/// ```
///
/// It needs the initial acceleration as a third datum, and for almost every
/// choice the solution runs away as e^{t/τ₀}.
pub fn abraham_lorentz_rhs(q: &ChargeInField, y: &State<6>) -> State<6> {
    let (pos, vel) = pos_vel(y);
    let acc = Vec2::new(y[4], y[5]);
    let jerk = (acc - q.potential.force(&pos)) / q.tau0;
    State::<6>::new(vel.x, vel.y, acc.x, acc.y, jerk.x, jerk.y)
}
// ANCHOR_END: abraham_lorentz

// ANCHOR: landau_lifshitz
/// The Landau–Lifshitz reduction of (2.5): the jerk is replaced by the time
/// derivative of the external force along the unperturbed motion.
///
/// Paper: Eq. (2.5), reduced as in the footnote to (2.8).
///
/// ```text
/// m v̇ = F_ex + τ₀ dF_ex/dt,   dF_ex/dt = −g(r) v − g′(r) (r·v/r) r,   g = (1/r) dV/dr
/// ```
pub fn landau_lifshitz_rhs(q: &ChargeInField, y: &State<4>) -> State<4> {
    let (pos, vel) = pos_vel(y);
    let acc = landau_lifshitz_acceleration(q, &pos, &vel);
    State::<4>::new(vel.x, vel.y, acc.x, acc.y)
}
// ANCHOR_END: landau_lifshitz

/// The acceleration of the Landau–Lifshitz equation, F + τ₀ dF/dt (m = 1).
pub fn landau_lifshitz_acceleration(q: &ChargeInField, pos: &Vec2, vel: &Vec2) -> Vec2 {
    q.potential.force(pos) + q.tau0 * q.potential.force_rate(pos, vel)
}

/// The angular momentum L = m r × v (z component, m = 1).
pub fn angular_momentum(pos: &Vec2, vel: &Vec2) -> Real {
    cross2(pos, vel)
}

// ANCHOR: balance_laws
/// The rate of change of L under the Abraham–Lorentz equation: the torque of
/// the reaction force (the central force exerts none).
///
/// Paper: Eq. (2.6).
///
/// ```text
/// dL/dt = (2q²/3c³) r × v̈ = m τ₀ r × v̈
/// ```
pub fn torque_2_6(tau0: Real, pos: &Vec2, jerk: &Vec2) -> Real {
    tau0 * cross2(pos, jerk)
}

/// The Schott term of (2.7), the rate of change of the Schott angular
/// momentum τ₀ d(r × v̇)/dt = τ₀ L̈.
///
/// Paper: Eq. (2.7).
///
/// ```text
/// m τ₀ r × v̈ = τ₀ L̈ − m τ₀ v × v̇,   τ₀ L̈ = m τ₀ (v × v̇ + r × v̈)
/// ```
pub fn schott_term_2_7(tau0: Real, pos: &Vec2, vel: &Vec2, acc: &Vec2, jerk: &Vec2) -> Real {
    tau0 * (cross2(vel, acc) + cross2(pos, jerk))
}

/// The Larmor-like rate of change of L, the Schott term dropped.
///
/// Paper: Eq. (2.8).
///
/// ```text
/// dL/dt = −(2q²/3c³) v × v̇ = −m τ₀ v × v̇
/// ```
pub fn larmor_2_8(tau0: Real, vel: &Vec2, acc: &Vec2) -> Real {
    -tau0 * cross2(vel, acc)
}

/// The balance law (2.8) with v̇ = F/m, as corrected: (1/r) dV/**dr**, not dV/dt.
/// Evaluated at one instant (no orbit average) it is exactly the rate of
/// change of L under the Landau–Lifshitz equation.
///
/// Paper: Eq. (2.9) (erratum: the printed dV/dt must read dV/dr).
///
/// ```text
/// dL/dt = −(τ₀/m) ⟨(1/r) dV/dr⟩ L
/// ```
pub fn eq_2_9_rate(q: &ChargeInField, pos: &Vec2, l: Real) -> Real {
    -q.tau0 * q.potential.g(pos.norm()) * l
}
// ANCHOR_END: balance_laws

// ANCHOR: coulomb_collapse
/// The radius of a circular Coulomb orbit shrinking under the balance law,
/// r³ = r₀³ − 6τ₀kt/m (m = k = 1); 0 after the collapse.
///
/// Paper: Eq. (2.9), integrated for V = −k/r on a circle.
///
/// ```text
/// dL/dt = −τ₀ L/r³,  L = √r   ⇒   dr/dt = −2τ₀/r²   ⇒   r³ = r₀³ − 6τ₀t
/// ```
pub fn coulomb_circular_radius(tau0: Real, r0: Real, t: Real) -> Real {
    (r0.powi(3) - 6.0 * tau0 * t).max(0.0).cbrt()
}

/// The collapse time of a Coulomb orbit under the orbit-averaged law, for
/// semi-latus rectum p₀ = a₀(1 − e₀²) and eccentricity e₀ (m = k = 1).
/// For e₀ = 0 it is the circular t_c = r₀³/(6τ₀).
///
/// Paper: Eq. (2.9), orbit-averaged, with the invariant a(1 − e²)e^{−4/3}.
///
/// ```text
/// t_c = 2p₀³ (1 − √(1 − e₀²))² / (3τ₀ e₀⁴ √(1 − e₀²))
/// ```
pub fn coulomb_collapse_time(tau0: Real, p0: Real, e0: Real) -> Real {
    // NOTE: (1 − √(1 − e²))/e² = 1/(1 + √(1 − e²)) removes the 0/0 at e = 0.
    let w = (1.0 - e0 * e0).sqrt();
    let ratio = 1.0 / (1.0 + w);
    2.0 * p0.powi(3) * ratio * ratio / (3.0 * tau0 * w)
}
// ANCHOR_END: coulomb_collapse

/// The orbit average of (1/r) dV/dr = 1/r³ over a Kepler ellipse (time
/// average, m = k = 1).
///
/// ```text
/// ⟨1/r³⟩ = 1/(a³(1 − e²)^{3/2})
/// ```
pub fn coulomb_mean_inverse_cube(a: Real, e: Real) -> Real {
    1.0 / (a.powi(3) * (1.0 - e * e).powf(1.5))
}

// ANCHOR: coulomb_averaged
/// The orbit-averaged decay of a Kepler ellipse, d(a, e)/dt, from the
/// averaged energy loss ⟨τ₀|v̇|²⟩ and the averaged (2.9) (m = k = 1).
///
/// Paper: Eq. (2.9), orbit-averaged.
///
/// ```text
/// da/dt = −τ₀ (2 + e²) / (a² (1 − e²)^{5/2})
/// de/dt = −(3/2) τ₀ e / (a³ (1 − e²)^{3/2})
/// ```
pub fn coulomb_averaged_rhs(tau0: Real, y: &State<2>) -> State<2> {
    let (a, e) = (y[0], y[1]);
    let one_e2 = 1.0 - e * e;
    State::<2>::new(
        -tau0 * (2.0 + e * e) / (a * a * one_e2.powf(2.5)),
        -1.5 * tau0 * e / (a.powi(3) * one_e2.powf(1.5)),
    )
}

/// The quantity the orbit-averaged decay conserves, a(1 − e²)e^{−4/3}
/// (equivalently L ∝ e^{2/3}).
pub fn coulomb_averaged_invariant(a: Real, e: Real) -> Real {
    a * (1.0 - e * e) * e.powf(-4.0 / 3.0)
}
// ANCHOR_END: coulomb_averaged

/// The osculating Kepler elements (a, e) of a state (m = k = 1, bound orbits).
pub fn osculating_elements(pos: &Vec2, vel: &Vec2) -> (Real, Real) {
    let energy = Potential::Coulomb.energy(pos, vel);
    let a = -0.5 / energy;
    let l = angular_momentum(pos, vel);
    let e = (1.0 - l * l / a).max(0.0).sqrt();
    (a, e)
}

/// The Bohr radius in metres (CODATA 2022).
pub const BOHR_RADIUS_M: Real = 5.291_772_105_44e-11;
/// The classical electron radius e²/(4πε₀mc²) in metres (CODATA 2022).
pub const CLASSICAL_ELECTRON_RADIUS_M: Real = 2.817_940_320_5e-15;
/// The speed of light in m/s (exact).
pub const SPEED_OF_LIGHT_M_S: Real = 299_792_458.0;

/// The electron's τ₀ = 2e²/(3mc³) = (2/3) r_e/c in seconds, 6.26×10⁻²⁴ s.
pub fn electron_tau0_seconds() -> Real {
    2.0 * CLASSICAL_ELECTRON_RADIUS_M / (3.0 * SPEED_OF_LIGHT_M_S)
}

/// The classical collapse time of hydrogen from a circular orbit at the Bohr
/// radius, t_c = m a₀³/(6τ₀k) with k/m = r_e c², in seconds (≈ 1.56×10⁻¹¹ s).
pub fn bohr_collapse_time_seconds() -> Real {
    let k_over_m = CLASSICAL_ELECTRON_RADIUS_M * SPEED_OF_LIGHT_M_S * SPEED_OF_LIGHT_M_S;
    BOHR_RADIUS_M.powi(3) / (6.0 * electron_tau0_seconds() * k_over_m)
}

// ANCHOR: oscillator_roots
/// The roots of the Abraham–Lorentz oscillator (ω₀ = 1): the physical complex
/// root s (Im s > 0; its conjugate is the other) and the real runaway root.
///
/// Paper: Eq. (2.5) with V = kr²/2, x ∝ e^{st}.
///
/// ```text
/// τ₀ s³ − s² − 1 = 0,   s_phys = i − τ₀/2 − (5/8) i τ₀² + …,   s_run = 1/τ₀ + τ₀ + …
/// ```
pub fn abraham_lorentz_oscillator_roots(tau0: Real) -> (Complex<Real>, Real) {
    // NOTE: the real root lies beyond 1/τ₀, where the cubic is convex and
    // increasing; Newton started to its right, at 1/τ₀ + τ₀ + 1, falls
    // monotonically onto it. The complex pair then follows from Vieta without
    // the cancellation of s_run − 1/τ₀: the pair's product is γ = 1/(τ₀ s_run)
    // and its sum −β with β = γ/s_run.
    let f = |s: Real| tau0 * s * s * s - s * s - 1.0;
    let df = |s: Real| 3.0 * tau0 * s * s - 2.0 * s;
    let mut s = 1.0 / tau0 + tau0 + 1.0;
    for _ in 0..200 {
        let next = s - f(s) / df(s);
        if next >= s {
            break;
        }
        s = next;
    }
    let gamma = 1.0 / (tau0 * s);
    let beta = gamma / s;
    let im = (gamma - 0.25 * beta * beta).sqrt();
    (Complex::new(-0.5 * beta, im), s)
}
// ANCHOR_END: oscillator_roots

/// The Landau–Lifshitz oscillator's root (Im s > 0): ẍ = −x − τ₀ẋ.
///
/// ```text
/// s² + τ₀ s + 1 = 0,   s = −τ₀/2 + i√(1 − τ₀²/4) = i − τ₀/2 − (1/8) i τ₀² + …
/// ```
pub fn landau_lifshitz_oscillator_root(tau0: Real) -> Complex<Real> {
    Complex::new(-0.5 * tau0, (1.0 - 0.25 * tau0 * tau0).max(0.0).sqrt())
}

/// The damped-oscillation solution x(t) = Re(C e^{st}) with x(0) = x₀,
/// ẋ(0) = v₀, for each component: returns (x, ẋ, ẍ) at `t`. With the physical
/// Abraham–Lorentz root it is the exact non-runaway solution of (2.5); with the
/// Landau–Lifshitz root, the exact solution of its reduction.
///
/// ```text
/// x(t) = e^{σt}(x₀ cos ωt + ((v₀ − σx₀)/ω) sin ωt),   s = σ + iω
/// ```
pub fn oscillator_mode(s: Complex<Real>, x0: &Vec2, v0: &Vec2, t: Real) -> (Vec2, Vec2, Vec2) {
    let mut out = [Vec2::zeros(); 3];
    for i in 0..2 {
        let c = Complex::new(x0[i], -(v0[i] - s.re * x0[i]) / s.im);
        let z = c * (s * t).exp();
        out[0][i] = z.re;
        out[1][i] = (z * s).re;
        out[2][i] = (z * s * s).re;
    }
    (out[0], out[1], out[2])
}
