//! The recurrences of the tops' right-hand sides for the Taylor method: each
//! model written as sums and Cauchy products of series, one struct per model.
//!
//! | struct | model | products per order | solves per order |
//! |---|---|---|---|
//! | [`SymmetricTruncated`] | (4.2)–(4.4) | 7 (2 of them squares) | – |
//! | [`SymmetricReduced`] | (4.12)–(4.14) | 4 (2 squares; Ω₃ is constant) | – |
//! | [`GeneralTruncated`] | (3.3) | 12 (3 squares) | one 3×3, the same matrix for every order of a step |
//! | [`GeneralReduced`] | (3.4), reduced | 21 (3 squares) | – |
//! | [`WithOrientation`] | any of them, with q̇ = ½ q ⊗ (0, Ω) | + 12 | – |
//!
//! Each also implements [`Rhs`] (the same equations evaluated once, by the
//! physics functions), which is what the coefficient of order 0 must equal.

use super::{Series, TaylorRhs, ZERO_SERIES, cauchy_many};
use crate::integrate::Rhs;
use crate::math::{Real, State, Vec3};
use crate::physics::general_top::GeneralTop;
use crate::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs, truncated_ale_rhs};

/// Component i of Ω at order k.
#[inline(always)]
fn at(y: &[Series], k: usize) -> Vec3 {
    Vec3::new(y[0][k], y[1][k], y[2][k])
}

/// Store a vector as order k of three series.
#[inline(always)]
fn store(s: &mut [Series; 3], k: usize, v: &Vec3) {
    s[0][k] = v.x;
    s[1][k] = v.y;
    s[2][k] = v.z;
}

/// The symmetric top's truncated ALE by recurrence.
///
/// Paper: Eq. (4.2), Eq. (4.3), Eq. (4.4).
///
/// ```text
/// D = τ(Ω₁² + Ω₂²),  Ω̃₃ = (1 − I₃/I₁)Ω₃
/// (Ω̇₁)_k = (1 − I₃/I₁)(Ω₃Ω₂)_k − (DΩ₁)_k
/// (Ω̇₂)_k = −(1 − I₃/I₁)(Ω₃Ω₁)_k − (DΩ₂)_k
/// (Ω̇₃)_k = −(DΩ₃)_k
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetricTruncated(pub SymmetricTop);

// ANCHOR: symmetric_truncated
impl TaylorRhs<3> for SymmetricTruncated {
    /// D = τΩ⊥².
    type Aux = Series;

    fn aux(&self) -> Series {
        ZERO_SERIES
    }

    fn coefficient(&self, d: &mut Series, y: &[Series], k: usize) -> [Real; 3] {
        let (o1, o2, o3) = (&y[0], &y[1], &y[2]);
        let tau = self.0.tau();
        let c = 1.0 - self.0.ratio();
        let [s1, s2] = cauchy_many([(o1, o1), (o2, o2)], k);
        d[k] = tau * (s1 + s2);
        let d = &*d;
        let [o3o2, o3o1, do1, do2, do3] =
            cauchy_many([(o3, o2), (o3, o1), (d, o1), (d, o2), (d, o3)], k);
        [c * o3o2 - do1, -c * o3o1 - do2, -do3]
    }
}
// ANCHOR_END: symmetric_truncated

impl Rhs<3> for SymmetricTruncated {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        truncated_ale_rhs(&self.0, y)
    }
}

/// The symmetric top's reduced ALE by recurrence.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// ```text
/// Ω₃ constant (4.14), so Ω̃₃ and k = (I₃/I₁)Ω₃ are constants of the series
/// D = τ(Ω₁² + Ω₂² + k²)
/// (Ω̇₁)_k = Ω̃₃ (Ω₂)_k − (DΩ₁)_k,   (Ω̇₂)_k = −Ω̃₃ (Ω₁)_k − (DΩ₂)_k,   (Ω̇₃)_k = 0
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetricReduced(pub SymmetricTop);

impl TaylorRhs<3> for SymmetricReduced {
    /// D = τ(Ω⊥² + k²).
    type Aux = Series;

    fn aux(&self) -> Series {
        ZERO_SERIES
    }

    fn coefficient(&self, d: &mut Series, y: &[Series], k: usize) -> [Real; 3] {
        let (o1, o2) = (&y[0], &y[1]);
        let top = &self.0;
        let omega3 = y[2][0];
        let tau = top.tau();
        let spin = top.ratio() * omega3;
        let [s1, s2] = cauchy_many([(o1, o1), (o2, o2)], k);
        d[k] = tau * (s1 + s2);
        if k == 0 {
            d[0] += tau * spin * spin;
        }
        let d = &*d;
        let [do1, do2] = cauchy_many([(d, o1), (d, o2)], k);
        let w = top.omega3_tilde(omega3);
        [w * o2[k] - do1, -w * o1[k] - do2, 0.0]
    }
}

impl Rhs<3> for SymmetricReduced {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        reduced_ale_rhs(&self.0, y)
    }
}

/// The general top's truncated ALE (3.3) by recurrence, one linear solve per
/// order.
///
/// Paper: Eq. (3.3).
///
/// ```text
/// (I + d w₀ᵀ) F_k = b_k − d Σ_{j=1}^{k} w_j · F_{k−j},   F = Ω̇, w = d × Ω
/// b = −Ω × IΩ − |w|² Ω,   (Ω × IΩ)₁ = (I₃ − I₂)Ω₂Ω₃ (and cyclic)
/// ```
///
/// Ω̇ stands on both sides of (3.3), so every order of the series of Ω̇ is
/// the solution of a 3×3 system; its matrix `I + d w₀ᵀ` holds only the state
/// at the start of the step, so it is the same for every order, and
/// Sherman–Morrison solves it (as [`GeneralTop::truncated_ale_rhs`] does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralTruncated(pub GeneralTop);

/// The series [`GeneralTruncated`] keeps.
#[derive(Clone, Debug)]
pub struct GeneralTruncatedAux {
    /// w = d × Ω.
    w: [Series; 3],
    /// |w|².
    s: Series,
    /// F = Ω̇.
    f: [Series; 3],
    /// I⁻¹ (diagonal), I⁻¹d and 1/(1 + w₀·I⁻¹d), for the step's
    /// Sherman–Morrison solves.
    i_inv: Vec3,
    i_inv_d: Vec3,
    inv_denom: Real,
}

// ANCHOR: general_truncated
impl TaylorRhs<3> for GeneralTruncated {
    type Aux = GeneralTruncatedAux;

    fn aux(&self) -> GeneralTruncatedAux {
        GeneralTruncatedAux {
            w: [ZERO_SERIES; 3],
            s: ZERO_SERIES,
            f: [ZERO_SERIES; 3],
            i_inv: Vec3::zeros(),
            i_inv_d: Vec3::zeros(),
            inv_denom: 0.0,
        }
    }

    fn coefficient(&self, a: &mut GeneralTruncatedAux, y: &[Series], k: usize) -> [Real; 3] {
        let i = self.0.inertia();
        let d = self.0.dipole();
        let w_k = d.cross(&at(y, k));
        store(&mut a.w, k, &w_k);
        if k == 0 {
            a.i_inv = Vec3::new(1.0 / i.x, 1.0 / i.y, 1.0 / i.z);
            a.i_inv_d = d.component_mul(&a.i_inv);
            a.inv_denom = 1.0 / (1.0 + w_k.dot(&a.i_inv_d));
        }
        let (o1, o2, o3) = (&y[0], &y[1], &y[2]);
        let [w1, w2, w3] = &a.w;
        let [s1, s2, s3, o2o3, o3o1, o1o2] = cauchy_many(
            [(w1, w1), (w2, w2), (w3, w3), (o2, o3), (o3, o1), (o1, o2)],
            k,
        );
        a.s[k] = s1 + s2 + s3;
        // F_k is the unknown: with it at 0, (w·F)_k is Σ_{j≥1} w_j·F_{k−j}.
        store(&mut a.f, k, &Vec3::zeros());
        let s = &a.s;
        let [f1, f2, f3] = &a.f;
        let [so1, so2, so3, c1, c2, c3] =
            cauchy_many([(s, o1), (s, o2), (s, o3), (w1, f1), (w2, f2), (w3, f3)], k);
        let gyro = Vec3::new((i.z - i.y) * o2o3, (i.x - i.z) * o3o1, (i.y - i.x) * o1o2);
        let r = -gyro - Vec3::new(so1, so2, so3) - d * (c1 + c2 + c3);
        // Sherman–Morrison: (I + d w₀ᵀ)⁻¹ r = I⁻¹r − I⁻¹d (w₀·I⁻¹r)/(1 + w₀·I⁻¹d).
        let w0 = at(&a.w, 0);
        let i_inv_r = r.component_mul(&a.i_inv);
        let f_k = i_inv_r - a.i_inv_d * (w0.dot(&i_inv_r) * a.inv_denom);
        store(&mut a.f, k, &f_k);
        f_k.into()
    }
}
// ANCHOR_END: general_truncated

impl Rhs<3> for GeneralTruncated {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        self.0.truncated_ale_rhs(y)
    }
}

/// The general top's reduced ALE by recurrence.
///
/// Paper: Eq. (3.4), reduced (see [`GeneralTop::reduced_ale_rhs`]).
///
/// ```text
/// Ω̇₀ = −I⁻¹(Ω × IΩ):        (Ω̇₀)₁ = a₁ Ω₂Ω₃,  a₁ = (I₂ − I₃)/I₁ (and cyclic)
/// Ω̈₀ = −I⁻¹(Ω̇₀ × IΩ + Ω × IΩ̇₀): (Ω̈₀)₁ = a₁ ((Ω̇₀)₂Ω₃ + Ω₂(Ω̇₀)₃)
/// X = d × (|Ω|²Ω − Ω̈₀) + (d·Ω̇₀) Ω + 2 (d·Ω) Ω̇₀,   Ω̇ = Ω̇₀ + I⁻¹(d × X)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralReduced(pub GeneralTop);

/// The series [`GeneralReduced`] keeps.
#[derive(Clone, Debug)]
pub struct GeneralReducedAux {
    /// Ω̇₀, the free top's rate of change.
    free: [Series; 3],
    /// |Ω|².
    u: Series,
    /// d·Ω̇₀.
    e: Series,
    /// d·Ω.
    g: Series,
}

impl TaylorRhs<3> for GeneralReduced {
    type Aux = GeneralReducedAux;

    fn aux(&self) -> GeneralReducedAux {
        GeneralReducedAux {
            free: [ZERO_SERIES; 3],
            u: ZERO_SERIES,
            e: ZERO_SERIES,
            g: ZERO_SERIES,
        }
    }

    fn coefficient(&self, a: &mut GeneralReducedAux, y: &[Series], k: usize) -> [Real; 3] {
        let i = self.0.inertia();
        let d = self.0.dipole();
        let (o1, o2, o3) = (&y[0], &y[1], &y[2]);
        let c = Vec3::new((i.y - i.z) / i.x, (i.z - i.x) / i.y, (i.x - i.y) / i.z);
        let [o2o3, o3o1, o1o2, s1, s2, s3] = cauchy_many(
            [(o2, o3), (o3, o1), (o1, o2), (o1, o1), (o2, o2), (o3, o3)],
            k,
        );
        let free_k = Vec3::new(c.x * o2o3, c.y * o3o1, c.z * o1o2);
        store(&mut a.free, k, &free_k);
        a.u[k] = s1 + s2 + s3;
        a.e[k] = d.dot(&free_k);
        a.g[k] = d.dot(&at(y, k));
        let [f1, f2, f3] = &a.free;
        let (u, e, g) = (&a.u, &a.e, &a.g);
        let [f2o3, o2f3, f3o1, o3f1, f1o2, o1f2] = cauchy_many(
            [(f2, o3), (o2, f3), (f3, o1), (o3, f1), (f1, o2), (o1, f2)],
            k,
        );
        let [uo1, uo2, uo3, eo1, eo2, eo3, gf1, gf2, gf3] = cauchy_many(
            [
                (u, o1),
                (u, o2),
                (u, o3),
                (e, o1),
                (e, o2),
                (e, o3),
                (g, f1),
                (g, f2),
                (g, f3),
            ],
            k,
        );
        let free_dot = Vec3::new(
            c.x * (f2o3 + o2f3),
            c.y * (f3o1 + o3f1),
            c.z * (f1o2 + o1f2),
        );
        let x = d.cross(&(Vec3::new(uo1, uo2, uo3) - free_dot))
            + Vec3::new(eo1, eo2, eo3)
            + 2.0 * Vec3::new(gf1, gf2, gf3);
        (free_k + d.cross(&x).component_div(&i)).into()
    }
}

impl Rhs<3> for GeneralReduced {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        self.0.reduced_ale_rhs(y)
    }
}

/// A model's Ω together with the orientation as a unit quaternion
/// q = (q_w, q_x, q_y, q_z), body → lab: the state (Ω, q) has 7 components.
///
/// Paper: Eq. (3.1) (the body rate turns the body: dO/dt = O Ω̂).
///
/// ```text
/// q̇ = ½ q ⊗ (0, Ω):   q̇_w = −½ q_v·Ω,   q̇_v = ½ (q_w Ω + q_v × Ω)
/// ```
///
/// The equation is linear in q, so a q whose length has drifted by rounding
/// is still the same rotation, scaled: normalise it when it is read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WithOrientation<M>(pub M);

impl<M: TaylorRhs<3>> TaylorRhs<7> for WithOrientation<M> {
    type Aux = M::Aux;
    /// Ω and q, each against its own size.
    const BLOCK_ENDS: &'static [usize] = &[3, 7];

    fn aux(&self) -> M::Aux {
        self.0.aux()
    }

    fn coefficient(&self, aux: &mut M::Aux, y: &[Series], k: usize) -> [Real; 7] {
        let [f1, f2, f3] = self.0.coefficient(aux, y, k);
        let (o1, o2, o3) = (&y[0], &y[1], &y[2]);
        let (qw, qx, qy, qz) = (&y[3], &y[4], &y[5], &y[6]);
        let [x1, y2, z3, w1, y3, z2, w2, z1, x3, w3, x2, y1] = cauchy_many(
            [
                (qx, o1),
                (qy, o2),
                (qz, o3),
                (qw, o1),
                (qy, o3),
                (qz, o2),
                (qw, o2),
                (qz, o1),
                (qx, o3),
                (qw, o3),
                (qx, o2),
                (qy, o1),
            ],
            k,
        );
        [
            f1,
            f2,
            f3,
            -0.5 * (x1 + y2 + z3),
            0.5 * (w1 + y3 - z2),
            0.5 * (w2 + z1 - x3),
            0.5 * (w3 + x2 - y1),
        ]
    }
}

impl<M: Rhs<3>> Rhs<7> for WithOrientation<M> {
    fn eval(&self, t: Real, y: &State<7>) -> State<7> {
        let omega = Vec3::new(y[0], y[1], y[2]);
        let f = self.0.eval(t, &omega);
        let (qw, qv) = (y[3], Vec3::new(y[4], y[5], y[6]));
        let q_dot_v = 0.5 * (qw * omega + qv.cross(&omega));
        State::<7>::from_column_slice(&[
            f.x,
            f.y,
            f.z,
            -0.5 * qv.dot(&omega),
            q_dot_v.x,
            q_dot_v.y,
            q_dot_v.z,
        ])
    }
}
