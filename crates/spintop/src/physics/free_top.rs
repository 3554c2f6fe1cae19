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
//! The same top split into three exact rotations about its body axes
//! ([`FreeRigidBody`], [`FreeRigidBody::axis_flow`]) is what the splitting
//! methods compose (Strang, Yoshida-4).
//!
//! Beyond the paper: the paper solves only the symmetric top. The secular
//! model of [`crate::sim::secular`] needs these averages to follow a real
//! molecule's or nanoparticle's slow loss over ~10¹⁷ turns, where no
//! integrator can step each turn.

use crate::math::{Mat3, Real, Vec3};
use crate::physics::ParamError;
use crate::physics::rigid_body::BodyDynamics;
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

#[cfg(test)]
mod tests {
    use super::*;

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
