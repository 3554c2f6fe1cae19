//! The charge as a small shell (paper, Appendix, Eqs. (A.1)–(A.3)): the
//! electromagnetic part of the momentum answers with the delay δ = r₀/c, and
//! the equation of motion becomes a neutral delay equation.
//!
//! Units: m = m₀ + m_em = 1 and k = 1, the isotropic oscillator F = −k r, planar
//! motion written as Z = x + iy. Then m_em δ = 2q²/(3c³) = mτ₀ gives
//! m_em = τ₀/δ and m₀ = 1 − τ₀/δ, and (A.1) with its O(r₀) remainder dropped is
//!
//! ```text
//! m₀ Z''(t) + k Z(t) = −m_em Z''(t − δ)
//! ```
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `tau0` | τ₀ = 2q²/(3mc³) | radiation time | time |
//! | `delta` | δ = r₀/c | light-crossing time of the shell, the delay | time |
//! | `m_em` | m_em = 2q²/(3c²r₀) = τ₀/δ | electromagnetic mass | m |
//! | `m0` | m₀ = 1 − m_em | bare mass | m |
//! | `z`, `z_dot`, `z_ddot` | Z, Ż, Z̈ | position x + iy and its derivatives | length, … |
//! | `z_ret`, … | Z(t − δ), … | the same at the retarded time | |
//! | `l` | l = Im(Z̄ Ż) | angular momentum m r × v (z component) | – |
//! | `j` | J = m₀ l(t) + m_em l(t − δ) | bare plus retarded angular momentum, the bracket of (A.2) | – |
//! | `s` | s | characteristic root, Z ∝ e^{st} | 1/time |

use super::{ParamError, finite};
use crate::math::Real;
use crate::physics::central::abraham_lorentz_oscillator_roots;
use nalgebra::Complex;
use std::f64::consts::PI;

/// A complex number, Z = x + iy.
pub type C = Complex<Real>;

/// How many members of the neutral chain are searched for the largest Re s.
/// NOTE: along the chain Re s falls towards its asymptote as Im s grows (the
/// force term, k/s² in P(s)/s², fades), so the first few members hold the maximum; 16 is a
/// wide margin, checked by a test against 200 members.
pub const CHAIN_SEARCH: usize = 16;

/// The shell model: τ₀ and δ, validated, with the masses they imply (m = 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellModel {
    tau0: Real,
    delta: Real,
    m_em: Real,
    m0: Real,
}

/// The three behaviours of (A.1), decided by its characteristic roots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regime {
    /// Every root has Re s < 0 (needs m₀ > m_em; with the force, exactly
    /// m₀ − m_em > kδ²/(π²m)).
    Stable,
    /// 0 < m₀ and a chain of roots with Re s > 0: oscillations at frequencies
    /// ≈ (2n + 1)π/δ that grow at ≈ ln(m_em/m₀)/δ.
    GrowingOscillation,
    /// m₀ < 0: a real positive root, the Abraham–Lorentz runaway come back.
    Runaway,
}

impl Regime {
    /// `stable`, `growing-oscillation` or `runaway`.
    pub fn name(&self) -> &'static str {
        match self {
            Regime::Stable => "stable",
            Regime::GrowingOscillation => "growing-oscillation",
            Regime::Runaway => "runaway",
        }
    }
}

impl ShellModel {
    /// Validate τ₀ > 0 and δ > 0, both finite, and δ ≠ τ₀ (m₀ = 0 leaves no
    /// equation for Z'').
    pub fn new(tau0: Real, delta: Real) -> Result<Self, ParamError> {
        finite("tau0", tau0)?;
        finite("delay", delta)?;
        if tau0 <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "tau0",
                value: tau0,
                range: "positive (it is 2q^2/(3mc^3))",
            });
        }
        if delta <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "delay",
                value: delta,
                range: "positive (it is r0/c, the shell's light-crossing time)",
            });
        }
        let m_em = tau0 / delta;
        let m0 = 1.0 - m_em;
        // NOTE: m₀ = 0 turns (A.1) into Z(t) = −m_em Z''(t − δ), which does not
        // determine Z'' at all; near it the growth rate ln(m_em/|m₀|)/δ diverges.
        if m0.abs() < 1e-9 {
            return Err(ParamError::OutOfRange {
                name: "delay",
                value: delta,
                range: "different from tau0 (delay = tau0 makes the bare mass m0 = 1 - tau0/delay zero)",
            });
        }
        Ok(Self {
            tau0,
            delta,
            m_em,
            m0,
        })
    }

    /// τ₀.
    pub fn tau0(&self) -> Real {
        self.tau0
    }

    /// δ = r₀/c.
    pub fn delta(&self) -> Real {
        self.delta
    }

    /// m_em = τ₀/δ.
    pub fn m_em(&self) -> Real {
        self.m_em
    }

    /// m₀ = 1 − m_em.
    pub fn m0(&self) -> Real {
        self.m0
    }

    // ANCHOR: equation
    /// The acceleration that (A.1) gives at time t from the position now and
    /// the acceleration one delay earlier.
    ///
    /// Paper: Eq. (A.1).
    ///
    /// ```text
    /// d/dt {m₀ v(t) + m_em v(t − δ)} = F(t),  F = −k r
    /// ⇒  Z''(t) = (−k Z(t) − m_em Z''(t − δ)) / m₀
    /// ```
    pub fn acceleration(&self, z: C, z_ddot_ret: C) -> C {
        (-z - z_ddot_ret * self.m_em) / self.m0
    }
    // ANCHOR_END: equation

    // ANCHOR: characteristic
    /// The characteristic function of (A.1): Z = e^{st} solves it exactly when
    /// this vanishes.
    ///
    /// Paper: Eq. (A.1) with Z ∝ e^{st}.
    ///
    /// ```text
    /// P(s) = m₀ s² + m_em s² e^{−sδ} + k
    /// ```
    pub fn characteristic(&self, s: C) -> C {
        s * s * (self.m0 + (-s * self.delta).exp() * self.m_em) + 1.0
    }
    // ANCHOR_END: characteristic

    /// dP/ds.
    fn characteristic_derivative(&self, s: C) -> C {
        let e = (-s * self.delta).exp() * self.m_em;
        s * 2.0 * (e + self.m0) - s * s * e * self.delta
    }

    /// Polish a root of P by Newton's method; `None` if it does not converge.
    pub fn newton(&self, start: C) -> Option<C> {
        let mut s = start;
        for _ in 0..100 {
            let step = self.characteristic(s) / self.characteristic_derivative(s);
            s -= step;
            if !(s.re.is_finite() && s.im.is_finite()) {
                return None;
            }
            if step.norm() <= 1e-15 * s.norm().max(1.0) {
                return Some(s);
            }
        }
        // Converged to rounding but oscillating in the last bit: accept a root
        // whose residual is small against the size of the terms.
        let scale = s.norm_sqr() * (self.m0.abs() + self.m_em * (-s.re * self.delta).exp()) + 1.0;
        (self.characteristic(s).norm() < 1e-12 * scale).then_some(s)
    }

    /// The root that continues the Abraham–Lorentz physical root: Newton from
    /// s_AL, the complex root of τ₀s³ − s² − 1 = 0 with Im s > 0.
    ///
    /// Paper: Eq. (A.1) with Z ∝ e^{st}; as δ → 0 it tends to the root of (2.5).
    ///
    /// ```text
    /// s ≈ s_AL + iτ₀δ/4 + …   (from e^{−sδ} = 1 − sδ + s²δ²/2 − …)
    /// ```
    pub fn root_near_al(&self) -> Option<C> {
        self.newton(abraham_lorentz_oscillator_roots(self.tau0).0)
    }

    // ANCHOR: chain
    /// The asymptotic growth rate of the neutral chain of roots, ln(m_em/|m₀|)/δ:
    /// as |s| → ∞ the force term fades (k/s² in P(s)/s²), and P(s)/s² = 0
    /// becomes e^{−sδ} = −m₀/m_em.
    ///
    /// Paper: Eq. (A.1) with Z ∝ e^{st}, |s| → ∞.
    ///
    /// ```text
    /// Re s → ln(m_em/|m₀|)/δ,   Im s δ → (2n + 1)π (m₀ > 0) or 2nπ (m₀ < 0)
    /// ```
    pub fn chain_rate(&self) -> Real {
        (self.m_em / self.m0.abs()).ln() / self.delta
    }

    /// The n-th root of the neutral chain (n = 0, 1, …; Im s ≥ 0). For m₀ < 0
    /// the member n = 0 is real: the Abraham–Lorentz runaway.
    pub fn chain_root(&self, n: usize) -> Option<C> {
        let theta = if self.m0 > 0.0 {
            (2 * n + 1) as Real * PI
        } else {
            (2 * n) as Real * PI
        };
        // NOTE: a fixed point of s = −(Log w(s) + 2πik)/δ with
        // w(s) = −m₀/m_em − k/(m_em s²), on the branch that keeps Im s δ near θ,
        // brings the asymptotic guess close before Newton polishes it. Its
        // contraction factor is |w′/w|/δ = O(δ²), so it converges fast for the
        // small delays the appendix is about.
        let mut s = C::new(self.chain_rate(), theta / self.delta);
        for _ in 0..60 {
            let w = -(C::new(1.0, 0.0) / (s * s) + self.m0) / self.m_em;
            let log_w = w.ln();
            let k = ((-s.im * self.delta - log_w.im) / (2.0 * PI)).round();
            let next = -(log_w + C::new(0.0, 2.0 * PI * k)) / self.delta;
            if !(next.re.is_finite() && next.im.is_finite()) {
                break;
            }
            let done = (next - s).norm() <= 1e-14 * s.norm();
            s = next;
            if done {
                break;
            }
        }
        let s = self.newton(s)?;
        // A real root found for n = 0 may carry a rounding-size imaginary part.
        Some(if theta == 0.0 && s.im.abs() < 1e-12 * s.norm() {
            C::new(s.re, 0.0)
        } else {
            s
        })
    }
    // ANCHOR_END: chain

    /// The real positive root for m₀ < 0, the Abraham–Lorentz runaway
    /// (→ 1/τ₀ as δ → 0 with m fixed); `None` when m₀ > 0.
    pub fn runaway_root(&self) -> Option<Real> {
        (self.m0 < 0.0)
            .then(|| self.chain_root(0))
            .flatten()
            .map(|s| s.re)
    }

    /// The roots with Im s ≥ 0 that decide the stability: the one near the
    /// Abraham–Lorentz root and the first `n` members of the chain.
    pub fn roots(&self, n: usize) -> Vec<C> {
        self.root_near_al()
            .into_iter()
            .chain((0..n).filter_map(|k| self.chain_root(k)))
            .collect()
    }

    // ANCHOR: stability
    /// The largest Re s over the roots, or `None` when it is negative (stable).
    pub fn growth_rate(&self) -> Option<Real> {
        let largest = self
            .roots(CHAIN_SEARCH)
            .iter()
            .map(|s| s.re)
            .fold(Real::NEG_INFINITY, Real::max);
        (largest >= 0.0).then_some(largest)
    }

    /// Which of the three behaviours (A.1) shows.
    pub fn regime(&self) -> Regime {
        if self.m0 < 0.0 {
            Regime::Runaway
        } else if self.growth_rate().is_some() {
            Regime::GrowingOscillation
        } else {
            Regime::Stable
        }
    }

    /// The exact stability margin for the oscillator: stable iff
    /// m₀ − m_em > kδ²/(π²m). The lowest chain root crosses the imaginary
    /// axis at s = iπ/δ when P(iπ/δ) = 0, i.e. when (m₀ − m_em)π²/δ² = k.
    ///
    /// ```text
    /// P(iω) = 0, ωδ = π  ⇒  −ω²(m₀ − m_em) + k = 0
    /// ```
    pub fn stability_threshold(&self) -> Real {
        self.delta * self.delta / (PI * PI)
    }
    // ANCHOR_END: stability
}

// ANCHOR: bookkeeping
/// The angular momentum of the particle, m = 1 (z component).
///
/// Paper: the L = m r × v of (2.6), in the notation of (A.2).
///
/// ```text
/// l = Im(Z̄ Ż) = x ẏ − y ẋ
/// ```
pub fn angular_momentum(z: C, z_dot: C) -> Real {
    (z.conj() * z_dot).im
}

/// The bracket of (A.2): bare plus retarded (electromagnetic) angular momentum.
///
/// Paper: Eq. (A.2).
///
/// ```text
/// J = m₀ [r × v](t) + m_em [r × v](t − δ)
/// ```
pub fn bracket_j(model: &ShellModel, l: Real, l_ret: Real) -> Real {
    model.m0 * l + model.m_em * l_ret
}

/// The exact rate of change of J along a solution of (A.1): multiply (A.1) by
/// r× and use that the central force has no torque.
///
/// Paper: Eq. (A.2), before the Taylor expansion.
///
/// ```text
/// dJ/dt = m_em Im( conj(Z(t − δ) − Z(t)) Z''(t − δ) )
/// ```
pub fn flux_exact(model: &ShellModel, z: C, z_ret: C, z_ddot_ret: C) -> Real {
    model.m_em * ((z_ret - z).conj() * z_ddot_ret).im
}

/// The paper's right-hand side of (A.2): Z(t) − Z(t − δ) ≈ δ Ż(t − δ), so
/// m_em δ = mτ₀ turns the exact flux into the retarded Larmor-like term.
///
/// Paper: Eq. (A.2).
///
/// ```text
/// dJ/dt ≈ −(2q²/3c³) [v × v̇]_ret = −τ₀ Im( conj(Ż(t − δ)) Z''(t − δ) )
/// ```
pub fn flux_paper(model: &ShellModel, z_dot_ret: C, z_ddot_ret: C) -> Real {
    -model.tau0 * (z_dot_ret.conj() * z_ddot_ret).im
}

/// L − J, the part of the angular momentum the bracket of (A.2) leaves out.
/// As δ → 0 it tends to τ₀ dL/dt, the Schott angular momentum L_S.
///
/// Paper: Eq. (A.3).
///
/// ```text
/// L − J = m_em (l(t) − l(t − δ)) → τ₀ L̇ = L_S
/// ```
pub fn l_minus_j(model: &ShellModel, l: Real, l_ret: Real) -> Real {
    model.m_em * (l - l_ret)
}

/// The Schott angular momentum τ₀ L̇ with L̇ = Im(Z̄ Z'') (m = 1).
///
/// Paper: Eq. (A.3).
///
/// ```text
/// L_S = τ₀ L̇ = τ₀ Im(Z̄ Z'')
/// ```
pub fn schott_angular_momentum(model: &ShellModel, z: C, z_ddot: C) -> Real {
    model.tau0 * (z.conj() * z_ddot).im
}
// ANCHOR_END: bookkeeping

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq_a_1_masses_add_up_to_one() {
        let m = ShellModel::new(1e-3, 0.01).unwrap();
        assert!((m.m0() + m.m_em() - 1.0).abs() < 1e-15);
        assert!((m.m_em() * m.delta() - m.tau0()).abs() < 1e-18);
    }

    #[test]
    fn eq_a_1_refuses_bad_parameters() {
        assert!(ShellModel::new(0.0, 0.1).is_err());
        assert!(ShellModel::new(-1e-3, 0.1).is_err());
        assert!(ShellModel::new(1e-3, 0.0).is_err());
        assert!(ShellModel::new(1e-3, -0.1).is_err());
        assert!(ShellModel::new(Real::NAN, 0.1).is_err());
        assert!(ShellModel::new(1e-3, Real::INFINITY).is_err());
        assert!(ShellModel::new(0.1, 0.1).is_err());
    }
}
