//! The free asymmetric top in closed form (Jacobi's elliptic functions), and
//! averages over its motion.
//!
//! Without torque, Euler's equations keep 2E = Ω·IΩ and L² = |IΩ|², and Ω
//! runs round the polhode where the two ellipsoids meet. With the moments
//! sorted, I_a ≤ I_b ≤ I_c, and L² > 2E I_b (the polhode circles the c axis):
//!
//! ```text
//! Ω_a = A cn(s, m),  Ω_b = B sn(s, m),  Ω_c = C dn(s, m),   s = λ t
//! A² = (2E I_c − L²) / (I_a (I_c − I_a)),   B² = (2E I_c − L²) / (I_b (I_c − I_b))
//! C² = (L² − 2E I_a) / (I_c (I_c − I_a))
//! λ² = (I_c − I_b)(L² − 2E I_a) / (I_a I_b I_c)
//! m  = (I_b − I_a)(2E I_c − L²) / ((I_c − I_b)(L² − 2E I_a))
//! ```
//!
//! and for L² < 2E I_b (round the a axis) the same with a and c exchanged
//! (Landau and Lifshitz, *Mechanics*, §37). One period is 4K(m)/λ.
//!
//! Beyond the paper: the paper solves only the symmetric top. The secular
//! model of [`crate::sim::secular`] needs these averages to follow a real
//! molecule's or nanoparticle's slow loss over ~10¹⁷ turns, where no
//! integrator can step each turn.

use crate::math::{Real, Vec3};
use std::f64::consts::PI;

/// Jacobi's elliptic functions sn, cn, dn of `u` for the parameter `m`
/// (0 ≤ m < 1), by the arithmetic–geometric mean and descending Landen
/// transformation (Abramowitz and Stegun 16.4).
pub fn sn_cn_dn(u: Real, m: Real) -> (Real, Real, Real) {
    if m <= 0.0 {
        return (u.sin(), u.cos(), 1.0);
    }
    let mut a = [0.0; 16];
    let mut c = [0.0; 16];
    a[0] = 1.0;
    let mut b = (1.0 - m).sqrt();
    c[0] = m.sqrt();
    let mut n = 0;
    while n < 15 && c[n].abs() > Real::EPSILON {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = (1u64 << n) as Real * a[n] * u;
    for k in (1..=n).rev() {
        phi = 0.5 * (phi + (c[k] / a[k] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    // NOTE: dn² = 1 − m sn² = (1 − m) + m cn², a sum of two non-negative
    // terms: no cancellation, where A&S's cos φ₀ / cos(φ₁ − φ₀) is 0/0 at
    // the quarter period.
    let dn = ((1.0 - m) + m * cn * cn).sqrt();
    (sn, cn, dn)
}

/// The complete elliptic integral of the first kind K(m), 0 ≤ m < 1:
/// π / (2 AGM(1, √(1 − m))).
pub fn complete_k(m: Real) -> Real {
    let (mut a, mut b) = (1.0, (1.0 - m).sqrt());
    for _ in 0..40 {
        if (a - b).abs() <= Real::EPSILON * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The parameter m is kept this far below 1: on the separatrix itself the
/// period is infinite and Ω creeps towards the middle axis.
const M_MAX: Real = 1.0 - 1e-12;

/// One free polhode, ready to be sampled over its period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polhode {
    /// Amplitudes of the cn, sn and dn components, and the axes they sit on.
    amp: [Real; 3],
    on: [usize; 3],
    /// λ, the rate of the elliptic argument.
    lambda: Real,
    /// The parameter m.
    m: Real,
    /// Pure rotation about one principal axis (no motion on the polhode).
    fixed: Option<Vec3>,
}

impl Polhode {
    /// The polhode through `omega` of a top with principal moments `inertia`.
    pub fn through(inertia: &Vec3, omega: &Vec3) -> Self {
        let two_e = omega.dot(&inertia.component_mul(omega));
        let l2 = inertia.component_mul(omega).norm_squared();
        let mut p = Self::of(inertia, two_e, l2);
        if p.fixed.is_some() {
            p.fixed = Some(*omega);
        }
        p
    }

    /// The polhode with invariants 2E = `two_e` and L² = `l2`. Where it
    /// degenerates to a rotation about one axis, Ω lies on that axis with a
    /// positive component (every average used here is even in Ω).
    pub fn of(inertia: &Vec3, two_e: Real, l2: Real) -> Self {
        let mut axes = [0, 1, 2];
        axes.sort_by(|&i, &j| inertia[i].total_cmp(&inertia[j]));
        let [a, b, c] = axes;
        let (ia, ib, ic) = (inertia[a], inertia[b], inertia[c]);
        let fixed_on = |k: usize| {
            let mut w = Vec3::zeros();
            w[k] = (two_e / inertia[k]).max(0.0).sqrt();
            w
        };
        let span = two_e * (ic - ia);
        // NOTE: relative to the width of the band 2E I_a ≤ L² ≤ 2E I_c.
        let upper = two_e * ic - l2; // ≥ 0
        let lower = l2 - two_e * ia; // ≥ 0
        let degenerate = |fixed| Self {
            amp: [0.0; 3],
            on: [a, b, c],
            lambda: 0.0,
            m: 0.0,
            fixed: Some(fixed),
        };
        if span.is_nan() || span <= 0.0 || upper <= 1e-14 * span {
            return degenerate(fixed_on(c));
        }
        if lower <= 1e-14 * span {
            return degenerate(fixed_on(a));
        }
        let (upper, lower) = (upper.max(0.0), lower.max(0.0));
        // Round the axis q, from the axis p at the other end: q = c when
        // L² ≥ 2E I_b, else the same formulas with a and c exchanged. With
        // dq = 2E I_q − L² and dp = L² − 2E I_p (both of the sign of
        // I_q − I_p), every ratio below is positive.
        let (p, q, dp, dq) = if l2 >= two_e * ib {
            (a, c, lower, upper)
        } else {
            (c, a, -upper, -lower)
        };
        let (ip, iq) = (inertia[p], inertia[q]);
        Self {
            amp: [
                (dq / (ip * (iq - ip))).sqrt(),
                if iq != ib {
                    (dq / (ib * (iq - ib))).sqrt()
                } else {
                    0.0
                },
                (dp / (iq * (iq - ip))).sqrt(),
            ],
            on: [p, b, q],
            lambda: ((iq - ib) * dp / (ia * ib * ic)).sqrt(),
            m: ((ib - ip) * dq / ((iq - ib) * dp)).min(M_MAX),
            fixed: None,
        }
    }

    /// The body axis (0, 1 or 2) the polhode circles.
    pub fn axis(&self) -> usize {
        match self.fixed {
            Some(w) => w.iamax(),
            None => self.on[2],
        }
    }

    /// The period of the motion round the polhode (infinite for a rotation
    /// about a principal axis, which never comes round).
    pub fn period(&self) -> Real {
        if self.fixed.is_some() {
            Real::INFINITY
        } else {
            4.0 * complete_k(self.m) / self.lambda
        }
    }

    /// Ω at elliptic argument `s` = λt (from the point where the sn
    /// component vanishes).
    pub fn omega_at_argument(&self, s: Real) -> Vec3 {
        if let Some(w) = self.fixed {
            return w;
        }
        let (sn, cn, dn) = sn_cn_dn(s, self.m);
        let mut w = Vec3::zeros();
        w[self.on[0]] = self.amp[0] * cn;
        w[self.on[1]] = self.amp[1] * sn;
        w[self.on[2]] = self.amp[2] * dn;
        w
    }

    /// Ω at time `t` along the free motion.
    pub fn omega_at(&self, t: Real) -> Vec3 {
        self.omega_at_argument(self.lambda * t)
    }

    /// The time average of `f(Ω)` over one period, by the trapezoid rule in
    /// the elliptic argument (spectrally accurate for a periodic analytic
    /// integrand), doubling the points from 16 until two estimates agree to
    /// `rtol` (at most 2¹⁴ points, which the separatrix's neighbourhood needs).
    /// Returns the average and the number of points used.
    pub fn average<const N: usize>(
        &self,
        f: impl Fn(&Vec3) -> [Real; N],
        rtol: Real,
    ) -> ([Real; N], usize) {
        if let Some(w) = self.fixed {
            return (f(&w), 1);
        }
        let period = 4.0 * complete_k(self.m);
        let mut n = 16usize;
        let mut sum = [0.0; N];
        // The largest |f| met: the mean may be far smaller than the values it
        // averages (a drift that nearly cancels round the period), and is
        // then known only to the rounding of those values.
        let mut scale: Real = 0.0;
        let sample = |s: Real, sum: &mut [Real; N], scale: &mut Real| {
            let v = f(&self.omega_at_argument(s));
            *scale = v.iter().fold(*scale, |a, x| a.max(x.abs()));
            add(sum, &v);
        };
        for j in 0..n {
            sample(period * j as Real / n as Real, &mut sum, &mut scale);
        }
        let mut mean = sum.map(|x| x / n as Real);
        while n < 1 << 14 {
            // The new points sit halfway between the old ones.
            for j in 0..n {
                let s = period * (2 * j + 1) as Real / (2 * n) as Real;
                sample(s, &mut sum, &mut scale);
            }
            n *= 2;
            let next = sum.map(|x| x / n as Real);
            let change = next
                .iter()
                .zip(&mean)
                .fold(0.0, |a: Real, (x, y)| a.max((x - y).abs()));
            mean = next;
            if change <= rtol * scale {
                break;
            }
        }
        (mean, n)
    }
}

fn add<const N: usize>(sum: &mut [Real; N], x: &[Real; N]) {
    for (s, v) in sum.iter_mut().zip(x) {
        *s += v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{AdaptiveOptions, Dop853, solve};
    use crate::math::State;

    #[test]
    fn sn_cn_dn_meet_their_limits_and_identities() {
        for &u in &[0.0, 0.3, 1.7, -2.9, 11.0] {
            let (s, c, d) = sn_cn_dn(u, 0.0);
            assert!(
                (s - Real::sin(u)).abs() < 1e-15 && (c - Real::cos(u)).abs() < 1e-15 && d == 1.0
            );
            // Near m = 1: sn → tanh, cn, dn → sech.
            let (s, c, d) = sn_cn_dn(u, 1.0 - 1e-13);
            assert!((s - u.tanh()).abs() < 1e-5, "{u}: {s} vs {}", u.tanh());
            assert!((c - 1.0 / u.cosh()).abs() < 1e-5 && (d - 1.0 / u.cosh()).abs() < 1e-5);
            for &m in &[0.1, 0.5, 0.9, 0.999] {
                let (s, c, d) = sn_cn_dn(u, m);
                assert!((s * s + c * c - 1.0).abs() < 1e-14);
                assert!((d * d + m * s * s - 1.0).abs() < 1e-14);
            }
        }
        // A value from Abramowitz and Stegun's Table 16.5-style check:
        // sn(K(m), m) = 1, cn = 0, dn = √(1 − m).
        for &m in &[0.2, 0.7, 0.95] {
            let (s, c, d) = sn_cn_dn(complete_k(m), m);
            assert!(
                (s - 1.0).abs() < 1e-13 && c.abs() < 1e-7 && (d - (1.0 - m).sqrt()).abs() < 1e-13
            );
        }
        // K(1/2) = Γ(1/4)² / (4√π) = 1.854074677301372 (DLMF 19.6.E1 with 19.20).
        assert!((complete_k(0.5) - 1.854_074_677_301_372).abs() < 1e-14);
    }

    /// The closed form against Euler's equations integrated by DOP853 from
    /// the same point: both families, an elongated and a flat top.
    #[test]
    fn the_polhode_is_the_free_motion_of_euler_equations() {
        for (inertia, omega0) in [
            (Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.3, 0.0, 1.0)), // round c
            (Vec3::new(2.0, 1.5, 1.0), Vec3::new(0.2, 0.0, 1.0)), // c is axis 0
            (Vec3::new(1.0, 1.5, 2.0), Vec3::new(1.0, 0.0, 0.4)), // round a
            (Vec3::new(0.6, 1.15, 1.75), Vec3::new(0.5, 0.0, -0.7)),
        ] {
            let p = Polhode::through(&inertia, &omega0);
            // The closed form starts where the sn component is zero, with
            // positive cn and dn: flip signs of the data to match it.
            let start = p.omega_at(0.0);
            let flip = Vec3::new(
                omega0[0].signum() * start[0].signum(),
                1.0,
                omega0[2].signum() * start[2].signum(),
            );
            assert!(
                (start.component_mul(&flip) - omega0).norm() < 1e-12,
                "{start} vs {omega0}"
            );
            let rhs = |_t: Real, y: &State<3>| -> State<3> {
                let w = Vec3::new(y[0], y[1], y[2]);
                -(w.cross(&inertia.component_mul(&w))).component_div(&inertia)
            };
            let times: Vec<Real> = (1..=40).map(|k| k as Real * 0.37).collect();
            let mut s =
                Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-13, 1e-15).unwrap()).unwrap();
            let got = solve(&mut s, &rhs, &times).unwrap();
            // Which way round the polhode the data go is the sign of λ.
            let err = |dir: Real| {
                times
                    .iter()
                    .zip(&got)
                    .map(|(&t, y)| (p.omega_at(dir * t).component_mul(&flip) - y).norm())
                    .fold(0.0, Real::max)
            };
            let e = err(1.0).min(err(-1.0));
            assert!(e < 1e-10, "{inertia} {omega0}: {e:e}");
            // And the period: Ω returns to its start after 4K/λ.
            let back = {
                let mut s =
                    Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-13, 1e-15).unwrap()).unwrap();
                solve(&mut s, &rhs, &[p.period()]).unwrap()[0]
            };
            assert!((back - omega0).norm() < 1e-10, "period {}", p.period());
        }
    }

    /// The average over one period equals the average over a long DOP853
    /// run (many periods, ends trimmed to whole periods).
    #[test]
    fn period_averages_match_a_long_run() {
        let inertia = Vec3::new(1.0, 1.5, 2.0);
        let omega0 = Vec3::new(0.6, 0.1, 0.8);
        let f = |w: &Vec3| [w.x * w.x * w.y * w.y, w.z.powi(4), (w.x * w.z).powi(2)];
        let p = Polhode::through(&inertia, &omega0);
        let (avg, n) = p.average(f, 1e-13);
        assert!(n <= 256, "{n} points");
        let periods = 50.0;
        let t_end = periods * p.period();
        let steps = 200_000;
        let rhs = |_t: Real, y: &State<3>| -> State<3> {
            let w = Vec3::new(y[0], y[1], y[2]);
            -(w.cross(&inertia.component_mul(&w))).component_div(&inertia)
        };
        let times: Vec<Real> = (0..=steps)
            .map(|k| t_end * k as Real / steps as Real)
            .collect();
        let mut s = Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-12, 1e-14).unwrap()).unwrap();
        let ys = solve(&mut s, &rhs, &times).unwrap();
        let mut long = [0.0; 3];
        for (k, y) in ys.iter().enumerate() {
            let w = Vec3::new(y[0], y[1], y[2]);
            let weight = if k == 0 || k == steps { 0.5 } else { 1.0 };
            for (l, v) in long.iter_mut().zip(f(&w)) {
                *l += weight * v / steps as Real;
            }
        }
        for (a, b) in avg.iter().zip(long) {
            assert!((a - b).abs() < 1e-8 * a.abs().max(1e-3), "{a} vs {b}");
        }
    }

    #[test]
    fn rotations_about_an_axis_and_symmetric_tops_degenerate_gracefully() {
        let i = Vec3::new(1.0, 1.5, 2.0);
        let p = Polhode::through(&i, &Vec3::new(0.0, 0.0, 2.0));
        assert_eq!(p.period(), Real::INFINITY);
        assert_eq!(p.average(|w| [w.z], 1e-12).0, [2.0]);
        // I₁ = I₂: m = 0, uniform precession of Ω⊥ at Ω̃₃ = (I₃/I₁ − 1)Ω₃.
        let sym = Vec3::new(1.0, 1.0, 0.4);
        let w0 = Vec3::new(0.3, 0.0, 0.5);
        let p = Polhode::through(&sym, &w0);
        let rate = ((sym.z / sym.x) - 1.0) * w0.z;
        assert!((p.period() - 2.0 * PI / rate.abs()).abs() < 1e-12);
        let avg = p.average(|w| [w.x * w.x, w.z], 1e-14).0;
        assert!((avg[0] - 0.045).abs() < 1e-15 && (avg[1] - 0.5).abs() < 1e-15);
    }
}
