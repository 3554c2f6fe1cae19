//! The slow manifold of the symmetric top's (3.4) near rest, as a series in
//! u = |z|², exact in τk.
//!
//! In the frame that turns with the free precession, z = e^{−iΩ̃₃t}w, (3.4)
//! reads τw″ = (1 − 2iτk)w′ + τ(u + k²)w with u = |w|², k = (I₃/I₁)Ω₃: the
//! fast rotation is gone. On the slow manifold w′ = g(u)w, and since
//! u′ = 2u Re g and w″ = (2ug′ Re g + g²)w, g obeys
//!
//! ```text
//! 2τu g′ Re g = g(1 − 2iτk) + τ(u + k²) − τg²        (the invariance equation)
//! ```
//!
//! With g = Σ cₘuᵐ: c₀ is the slow root of τc² − (1 − 2iτk)c − τk² = 0 (the
//! rate of linear theory, [`super::linear_theory_rate`] + iΩ̃₃), and for m ≥ 1
//!
//! ```text
//! cₘ [(1 − 2iτk) − 2τc₀ − 2τm Re c₀] = τ Σⱼ [cⱼcₘ₋ⱼ + 2j cⱼ Re cₘ₋ⱼ] − τδₘ₁
//! ```
//!
//! (the sum over 1 ≤ j ≤ m − 1). For a slow spin the series only converges
//! asymptotically (its coefficients grow like m!), so it is used only where
//! its last terms have fallen below rounding: [`SlowSeries::holds`]. There
//! it is the physical solution's own rate to rounding, and the motion is a
//! first-order equation with nothing fast in it.
//!
//! | code name | symbol | meaning |
//! |---|---|---|
//! | `c` | cₘ | the coefficients, rotating frame |
//! | `u_max` | | the largest u where the series holds to rounding |

use crate::math::Real;
use crate::physics::symmetric_top::SymmetricTop;
use nalgebra::Complex;

/// Terms kept.
const TERMS: usize = 64;

/// The series holds where its last terms are below this share of g.
const CONVERGED: Real = 1e-17;

/// g(u) of the slow manifold near rest (rotating frame), with its reach.
#[derive(Clone, Debug, PartialEq)]
pub struct SlowSeries {
    c: Vec<Complex<Real>>,
    u_max: Real,
}

impl SlowSeries {
    /// The series for the top spinning at Ω₃.
    ///
    /// Paper: Eq. (3.4) (its slow manifold; not in the paper).
    pub fn new(top: &SymmetricTop, omega3: Real) -> Self {
        let tau = top.tau();
        let k = top.ratio() * omega3;
        let a = Complex::new(1.0, -2.0 * tau * k);
        let root = Complex::new(1.0, -4.0 * tau * k).sqrt();
        // The slow root as −k²/(fast root): no cancellation as τk → 0.
        let fast = (a + root) / (2.0 * tau);
        let c0 = if k == 0.0 || tau == 0.0 {
            Complex::new(0.0, 0.0)
        } else {
            -(k * k) / fast
        };
        let mut c = Vec::with_capacity(TERMS);
        c.push(c0);
        for m in 1..TERMS {
            let d = a - c0 * (2.0 * tau) - Complex::new(2.0 * tau * m as Real * c0.re, 0.0);
            let mut sum = Complex::new(0.0, 0.0);
            for j in 1..m {
                sum += c[j] * c[m - j] + c[j] * (2.0 * j as Real * c[m - j].re);
            }
            let mut rhs = sum * tau;
            if m == 1 {
                rhs -= tau;
            }
            c.push(rhs / d);
        }
        let mut series = Self { c, u_max: 0.0 };
        series.u_max = series.reach();
        series
    }

    /// The largest u where the series has converged to rounding: the last
    /// terms below [`CONVERGED`] of g (searched down from the first u where
    /// a term would overflow, by factors of 0.9).
    fn reach(&self) -> Real {
        let tail = |u: Real| {
            (TERMS - 4..TERMS)
                .map(|m| self.c[m].norm() * u.powi(m as i32))
                .fold(0.0, Real::max)
        };
        let mut u: Real = 1e3
            / self.c[TERMS - 1]
                .norm()
                .powf(1.0 / (TERMS - 1) as Real)
                .max(1e-300);
        for _ in 0..2000 {
            let g = self.rate(u).norm();
            if g > 0.0 && tail(u) <= CONVERGED * g {
                return u;
            }
            u *= 0.9;
        }
        0.0
    }

    /// True where the series is the slow manifold to rounding.
    pub fn holds(&self, u: Real) -> bool {
        u <= self.u_max
    }

    /// The largest u where it holds.
    pub fn reach_u(&self) -> Real {
        self.u_max
    }

    /// g(u) = w′/w on the slow manifold, rotating frame.
    pub fn rate(&self, u: Real) -> Complex<Real> {
        self.c
            .iter()
            .rev()
            .fold(Complex::new(0.0, 0.0), |acc, c| acc * u + c)
    }

    /// g′(u).
    pub fn slope(&self, u: Real) -> Complex<Real> {
        self.c
            .iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(Complex::new(0.0, 0.0), |acc, (m, c)| {
                acc * u + c * m as Real
            })
    }

    /// The coefficient cₘ.
    pub fn coefficient(&self, m: usize) -> Complex<Real> {
        self.c[m]
    }

    /// w″/w on the slow manifold: 2u g′ Re g + g².
    pub fn second(&self, u: Real) -> Complex<Real> {
        let g = self.rate(u);
        self.slope(u) * (2.0 * u * g.re) + g * g
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coefficients of the τ-series of the physics notes, read off at
    /// k = 0: g = −τu + 3τ³u² − 24τ⁵u³ + … (h = −w³ + 3w⁵ − 24w⁷ for τ = 1,
    /// the physical solution of hh′ = h + w³), and c₀ = −τk² + 5τ³k⁴ − 2iτ²k³ + …
    #[test]
    fn eq_3_4_slow_series_starts_as_the_notes_say() {
        let top = SymmetricTop::new(0.4, 1.0).unwrap();
        let s = SlowSeries::new(&top, 0.0);
        for (m, want) in [(0, 0.0), (1, -1.0), (2, 3.0), (3, -24.0)] {
            assert!(
                (s.coefficient(m) - Complex::new(want, 0.0)).norm() < 1e-12,
                "{m}"
            );
        }
        let top = SymmetricTop::new(0.5, 0.01).unwrap();
        let s = SlowSeries::new(&top, 1.0);
        let (tau, k): (Real, Real) = (0.01, 0.5);
        let c0 = s.coefficient(0);
        // Re c₀ = −τk² + 5τ³k⁴ − …, Im c₀ = −2τ²k³ + …
        let re = -tau * k * k + 5.0 * tau.powi(3) * k.powi(4);
        assert!(
            (c0.re - re).abs() < 1e-3 * 5.0 * tau.powi(3) * k.powi(4),
            "{c0}"
        );
        assert!((c0.im + 2.0 * tau * tau * k * k * k).abs() < 1e-3 * tau * tau * k * k * k);
    }

    /// Where it holds, the series satisfies the invariance equation.
    #[test]
    fn eq_3_4_slow_series_satisfies_the_invariance_equation() {
        for (ratio, omega3) in [(0.4, 0.0), (0.05, 0.3), (1.5, 0.8), (0.4, 3.0)] {
            let top = SymmetricTop::new(ratio, 1.0).unwrap();
            let s = SlowSeries::new(&top, omega3);
            let k = ratio * omega3;
            let u = 0.5 * s.reach_u();
            let g = s.rate(u);
            let lhs = s.slope(u) * (2.0 * u * g.re);
            let rhs = g * Complex::new(1.0, -2.0 * k) + (u + k * k) - g * g;
            assert!(
                (lhs - rhs).norm() <= 1e-12 * (rhs.norm() + (u + k * k)),
                "{ratio} {omega3}: {lhs} {rhs}"
            );
            assert!(s.reach_u() > 1e-4, "{}", s.reach_u());
        }
    }
}
