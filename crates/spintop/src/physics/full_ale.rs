//! The full Abraham–Lorentz–Euler equation (paper §3, Eq. (3.4)), with its
//! Schott term and second derivative Ω̈, as first-order systems.
//!
//! Putting the kinematics (3.1)–(3.2) into the torque law (2.2) gives (3.4). The
//! small factor κ|d|² multiplies Ω̈, so the equation is singularly perturbed:
//! besides the physical motion it has runaway solutions that grow like e^{t/τ}.
//! The reduced model (4.12)–(4.14) is its Landau–Lifshitz-type reduction. This
//! module only states the equations; integrating them forward shows the
//! runaway, and the physical solution has to be found by other means.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `omega` | Ω | body angular velocity | 1/time |
//! | `w` | W = Ω̇ | its rate | 1/time² |
//! | `z` | Ω₁ + iΩ₂ | perpendicular rate, as a complex number (symmetric top) | 1/τ |
//! | `v` | ż | its rate | 1/τ² |
//! | `kappa` | 2/(3c³) | set to 1: `d` is √κ times the physical dipole | – |

use super::general_top::GeneralTop;
use super::symmetric_top::SymmetricTop;
use crate::math::{Real, State, Vec3, directional_derivative};

/// The full ALE of a general top as a 6-dimensional first-order system in
/// (Ω, W = Ω̇), κ = 1 units.
///
/// Paper: Eq. (3.4).
///
/// ```text
/// I Ω̇ + Ω × IΩ = d × {d × (Ω²Ω − Ω̈) + (d·Ω̇)Ω + 2(d·Ω)Ω̇}
/// ```
///
/// Since d × (d × Ω̈) = −|d|² P Ω̈ with P the projector across d, (3.4) fixes
/// only the part of Ω̈ perpendicular to d:
///
/// ```text
/// |d|² P Ω̈ = P(I Ω̇ + Ω × IΩ − d × X₀),   X₀ = d × (Ω²Ω) + (d·Ω̇)Ω + 2(d·Ω)Ω̇
/// ```
///
/// Its component along d is the first-order constraint d·(IΩ̇ + Ω × IΩ) = 0
/// (the torque (2.2) has no component along the dipole). Differentiating the
/// constraint gives the rest of Ω̈:
///
/// ```text
/// d·(I Ω̈) = −d·(Ω̇ × IΩ + Ω × IΩ̇)
/// ```
///
/// A start (Ω, W) should satisfy the constraint; the flow then keeps it.
pub fn general_full_ale_rhs(top: &GeneralTop, y: &State<6>) -> State<6> {
    let i = top.inertia();
    let d = top.dipole();
    let omega = y.fixed_rows::<3>(0).into_owned();
    let w = y.fixed_rows::<3>(3).into_owned();
    let d2 = d.norm_squared();
    let i_omega = i.component_mul(&omega);
    let i_w = i.component_mul(&w);
    let lhs = i_w + omega.cross(&i_omega);
    let x0 = d.cross(&(omega.norm_squared() * omega)) + d.dot(&w) * omega + 2.0 * d.dot(&omega) * w;
    let across = |v: Vec3| v - d * (d.dot(&v) / d2);
    let a = across(lhs - d.cross(&x0)) / d2;
    let d_hat = d / d2.sqrt();
    let target = -d.dot(&(w.cross(&i_omega) + omega.cross(&i_w)));
    let beta = (target - d.dot(&i.component_mul(&a))) / d.dot(&i.component_mul(&d_hat));
    let omega_ddot = a + beta * d_hat;
    let mut out = State::<6>::zeros();
    out.fixed_rows_mut::<3>(0).copy_from(&w);
    out.fixed_rows_mut::<3>(3).copy_from(&omega_ddot);
    out
}

// ANCHOR: slow_manifold_second_order
/// Q(a, b) = a × Ib + b × Ia: the free motion is G₀(Ω) = −I⁻¹Q(Ω, Ω)/2 and
/// its derivative DG₀(Ω)[V] = −I⁻¹Q(Ω, V) (G₀ is quadratic).
fn free_pair(i: &Vec3, a: &Vec3, b: &Vec3) -> Vec3 {
    a.cross(&i.component_mul(b)) + b.cross(&i.component_mul(a))
}

/// T′(Ω; W, A) = d × {−d × A + (d·W)Ω + 2(d·Ω)W}: the torque's part
/// linear in Ω̇ = W and Ω̈ = A.
fn torque_linear(d: &Vec3, omega: &Vec3, w: &Vec3, a: &Vec3) -> Vec3 {
    d.cross(&(-d.cross(a) + d.dot(w) * omega + 2.0 * d.dot(omega) * w))
}

/// The second-order term G₂ of the slow manifold of (3.4) for any top:
/// on the physical solution Ω̇ = G₀ + G₁ + G₂ + O(τ_f³), where G₀ + G₁ is the
/// reduced ALE ([`GeneralTop::reduced_ale_rhs`]).
///
/// Paper: Eq. (3.4) (its slow manifold; not in the paper).
///
/// Write (3.4) as IΩ̇ = −Ω × IΩ + T(Ω, Ω̇, Ω̈) with the torque affine in its
/// last two arguments, and put Ω̇ = G(Ω), Ω̈ = DG(Ω)[G(Ω)] (the manifold is
/// invariant). Order by order in |d|²:
///
/// ```text
/// G₀ = −I⁻¹(Ω × IΩ)                                   (free Euler)
/// G₁ = I⁻¹ T(Ω, G₀, DG₀[G₀])                          (the reduced ALE's torque)
/// G₂ = I⁻¹ T′(Ω; G₁, DG₁[G₀] + DG₀[G₁])
/// T′(Ω; W, A) = d × {−d × A + (d·W)Ω + 2(d·Ω)W}        (T's part linear in Ω̇, Ω̈)
/// ```
///
/// DG₁ needs the derivative of T along V with Ω̇ and Ω̈ held, which is
/// d × {d × (2(Ω·V)Ω + |Ω|²V) + (d·W)V + 2(d·V)W}, plus T′ of the
/// derivatives of G₀ and DG₀[G₀] along V; G₀ is quadratic, so each is exact.
/// For the symmetric top G₂ = −2iτ²k(u + k²)z (the notes' series; tested).
pub fn slow_manifold_second_order(top: &GeneralTop, omega: &Vec3) -> Vec3 {
    let i = top.inertia();
    let d = top.dipole();
    let q = |a: &Vec3, b: &Vec3| free_pair(&i, a, b);
    let dg0 = |at: &Vec3, v: &Vec3| -q(at, v).component_div(&i);
    let g0 = -(omega.cross(&i.component_mul(omega))).component_div(&i);
    let a0 = dg0(omega, &g0);
    let t_lin = |w: &Vec3, a: &Vec3| torque_linear(&d, omega, w, a);
    let torque1 = d.cross(&d.cross(&(omega.norm_squared() * omega))) + t_lin(&g0, &a0);
    let g1 = torque1.component_div(&i);
    // DG₁[V]: the explicit Ω-dependence of T, then T′ of DG₀[V] and D(DG₀[G₀])[V].
    let dg1 = |v: &Vec3| -> Vec3 {
        let explicit = d.cross(
            &(d.cross(&(2.0 * omega.dot(v) * omega + omega.norm_squared() * v))
                + d.dot(&g0) * v
                + 2.0 * d.dot(v) * g0),
        );
        let dg0_v = dg0(omega, v);
        // A₀(Ω) = −I⁻¹Q(Ω, G₀(Ω)): its derivative along V.
        let da0_v = -(q(v, &g0) + q(omega, &dg0_v)).component_div(&i);
        (explicit + t_lin(&dg0_v, &da0_v)).component_div(&i)
    };
    let a1 = dg1(&g0) + dg0(omega, &g1);
    t_lin(&g1, &a1).component_div(&i)
}
// ANCHOR_END: slow_manifold_second_order

// ANCHOR: slow_manifold_third_order
/// The third-order term G₃ of the slow manifold of (3.4) for any top, the
/// next after [`slow_manifold_second_order`].
///
/// Paper: Eq. (3.4) (its slow manifold; not in the paper).
///
/// The same recursion one order on (T′ as there):
///
/// ```text
/// G₃ = I⁻¹ T′(Ω; G₂, A₂),   A₂ = DG₂[G₀] + DG₁[G₁] + DG₀[G₂]
/// ```
///
/// It carries the first drift of the invariants that the reduced ALE gets
/// wrong (for the symmetric top, the amplitude's −τ³s(3u + 5k²)z): small
/// in Ω, but along L it adds up in the orientation's phase. The derivatives
/// are central differences of G₂ and of G₁ (DG₁[G₂], of fourth order, comes
/// along); DG₀ is exact (G₀ is quadratic).
pub fn slow_manifold_third_order(top: &GeneralTop, omega: &Vec3) -> Vec3 {
    let i = top.inertia();
    let d = top.dipole();
    let along = |f: &dyn Fn(&Vec3) -> Vec3, v: &Vec3| directional_derivative(f, omega, v, 1e-5);
    // G₁ differenced on its own: as (G₀ + G₁) − G₀ it is lost to rounding
    // once it is below 10⁻¹⁶ of G₀ (τ|Ω| ≲ 10⁻¹⁵, a molecule's). DG₀ is exact.
    let first = |w: &Vec3| top.reduced_torque(w).component_div(&i);
    let second = |w: &Vec3| slow_manifold_second_order(top, w);
    let dg0 = |v: &Vec3| -free_pair(&i, omega, v).component_div(&i);
    let g0 = -(omega.cross(&i.component_mul(omega))).component_div(&i);
    let g1 = first(omega);
    let g2 = second(omega);
    let a2 = along(&second, &g0) + along(&first, &(g1 + g2)) + dg0(&g2);
    torque_linear(&d, omega, &g2, &a2).component_div(&i)
}
// ANCHOR_END: slow_manifold_third_order

/// The full ALE of the symmetric top (4.1) as a 4-dimensional system in
/// (Ω₁, Ω₂, V₁, V₂) with V = ż, z = Ω₁ + iΩ₂, at a constant Ω₃ (units τ = 1 = I₁
/// as in Section 4, τ kept as a parameter).
///
/// Paper: Eq. (3.4) (with (4.1)).
///
/// ```text
/// τ z̈ = ż + iΩ̃₃ z + τ(|z|² + Ω₃²) z − 2iτΩ₃ ż,     Ω̇₃ = 0 exactly
/// ```
///
/// The third component of (3.4) reads I₃Ω̇₃ = 0 for this top, so Ω₃ is a
/// parameter, not a state.
pub fn symmetric_full_ale_rhs(top: &SymmetricTop, omega3: Real, y: &State<4>) -> State<4> {
    let tau = top.tau();
    let (z_re, z_im, v_re, v_im) = (y[0], y[1], y[2], y[3]);
    let omega3_tilde = top.omega3_tilde(omega3);
    let g = tau * (z_re * z_re + z_im * z_im + omega3 * omega3);
    // τ z̈ = v + iΩ̃₃z + g z − 2iτΩ₃ v, written out in real and imaginary parts.
    let acc_re = v_re - omega3_tilde * z_im + g * z_re + 2.0 * tau * omega3 * v_im;
    let acc_im = v_im + omega3_tilde * z_re + g * z_im - 2.0 * tau * omega3 * v_re;
    State::<4>::new(v_re, v_im, acc_re / tau, acc_im / tau)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::symmetric_top::reduced_ale_rhs;
    use proptest::prelude::*;

    /// (3.4) built independently from the torque law (2.2), dL/dt = 𝔡 × 𝔡⃛ with
    /// 𝔡 = O d: the body-frame third derivative is
    /// Oᵀ𝔡⃛ = Ω̈×d + Ω̇×(Ω×d) + 2Ω×(Ω̇×d) + Ω×(Ω×(Ω×d)), and Oᵀ dL/dt = IΩ̇ + Ω×IΩ.
    fn torque_law_residual(top: &GeneralTop, omega: &Vec3, w: &Vec3, omega_ddot: &Vec3) -> Vec3 {
        let i = top.inertia();
        let d = top.dipole();
        let jerk = omega_ddot.cross(&d)
            + w.cross(&omega.cross(&d))
            + 2.0 * omega.cross(&w.cross(&d))
            + omega.cross(&omega.cross(&omega.cross(&d)));
        i.component_mul(w) + omega.cross(&i.component_mul(omega)) - d.cross(&jerk)
    }

    /// A W that satisfies the constraint d·(IW + Ω×IΩ) = 0: any W, corrected along I⁻¹d.
    fn admissible_w(top: &GeneralTop, omega: &Vec3, w: Vec3) -> Vec3 {
        let i = top.inertia();
        let d = top.dipole();
        let i_inv_d = d.component_div(&i);
        let excess = d.dot(&(i.component_mul(&w) + omega.cross(&i.component_mul(omega))));
        w - i_inv_d * (excess / d.dot(&d))
    }

    proptest! {
        #[test]
        fn eq_3_4_general_system_satisfies_the_torque_law_2_2(
            i1 in 0.5..2.0f64, i2 in 0.5..2.0f64, i3f in 0.1..1.0f64,
            d in prop::array::uniform3(-1.0..1.0f64),
            om in prop::array::uniform3(-1.0..1.0f64),
            wv in prop::array::uniform3(-1.0..1.0f64),
        ) {
            let i3 = (i1 + i2) * i3f;
            prop_assume!(i3 >= (i1 - i2).abs());
            let d = Vec3::from(d);
            prop_assume!(d.norm() > 0.1);
            let top = GeneralTop::new(Vec3::new(i1, i2, i3), d).unwrap();
            let omega = Vec3::from(om);
            let w = admissible_w(&top, &omega, Vec3::from(wv));
            let mut y = State::<6>::zeros();
            y.fixed_rows_mut::<3>(0).copy_from(&omega);
            y.fixed_rows_mut::<3>(3).copy_from(&w);
            let f = general_full_ale_rhs(&top, &y);
            prop_assert_eq!(f.fixed_rows::<3>(0).into_owned(), w);
            let omega_ddot = f.fixed_rows::<3>(3).into_owned();
            let r = torque_law_residual(&top, &omega, &w, &omega_ddot);
            prop_assert!(r.norm() < 1e-12, "residual {}", r);
        }

        /// With symmetric inputs (I₂ = I₁, d ∥ e₃, τ = d²/I₁ with I₁ = 1) the general
        /// system reduces to the symmetric one, and Ω̇₃ = 0.
        #[test]
        fn eq_3_4_with_symmetric_inputs_reduces_to_the_symmetric_system(
            ratio in 0.05..2.0f64, d3 in 0.2..2.0f64,
            om in prop::array::uniform3(-1.0..1.0f64),
            v in prop::array::uniform2(-1.0..1.0f64),
        ) {
            let general = GeneralTop::new(Vec3::new(1.0, 1.0, ratio), Vec3::new(0.0, 0.0, d3)).unwrap();
            let sym = SymmetricTop::new(ratio, d3 * d3).unwrap();
            let y6 = State::<6>::from_column_slice(&[om[0], om[1], om[2], v[0], v[1], 0.0]);
            let y4 = State::<4>::new(om[0], om[1], v[0], v[1]);
            let f6 = general_full_ale_rhs(&general, &y6);
            let f4 = symmetric_full_ale_rhs(&sym, om[2], &y4);
            prop_assert!(f6[5].abs() < 1e-13, "Omega3 must stay constant: {}", f6[5]);
            for (a, b) in [(f6[3], f4[2]), (f6[4], f4[3])] {
                prop_assert!((a - b).abs() < 1e-12 * (1.0 + b.abs()), "{} vs {}", a, b);
            }
        }
    }

    /// On the slow manifold the full ALE reduces to (4.12)–(4.13) at O(τ):
    /// with ż taken from the reduced model, τ z̈ − (the rest) is O(τ²).
    #[test]
    fn eq_3_4_agrees_with_the_reduced_model_to_first_order_in_tau() {
        for tau in [1e-2, 1e-3] {
            let top = SymmetricTop::new(0.4, tau).unwrap();
            let omega = Vec3::new(0.3, -0.5, 0.8);
            let reduced = reduced_ale_rhs(&top, &omega);
            // Residual of (3.4) when z follows the reduced flow: compute z̈ from the
            // reduced flow by differentiating once more (central difference).
            let h = 1e-6;
            let step = |om: Vec3, s: f64| om + s * reduced_ale_rhs(&top, &om);
            let zdd = (reduced_ale_rhs(&top, &step(omega, h))
                - reduced_ale_rhs(&top, &step(omega, -h)))
                / (2.0 * h);
            let y = State::<4>::new(omega.x, omega.y, reduced.x, reduced.y);
            let f = symmetric_full_ale_rhs(&top, omega.z, &y);
            let residual = ((f[2] - zdd.x).powi(2) + (f[3] - zdd.y).powi(2)).sqrt() * tau;
            // τ z̈ − RHS is O(τ²) while each term is O(1).
            assert!(
                residual < 5.0 * tau * tau,
                "tau = {tau}: residual {residual:e}"
            );
        }
    }
}

#[cfg(test)]
mod runaway_tests {
    use super::*;
    use crate::physics::symmetric_top::reduced_ale_rhs;
    use nalgebra::SMatrix;

    /// The frozen linearisation of (3.4) at the figure state (I₃/I₁ = 2/5,
    /// Ω₀ = (0, 0.1, 0.2), ż from the reduced model), two ways.
    ///
    /// By hand: with z = z₀ + δz, (3.4) gives
    /// τδz̈ = (1 − 2iτΩ₃)δż + (iΩ̃₃ + τ(|z₀|² + Ω₃²))δz + τz₀(z̄₀δz + z₀δz̄),
    /// a real 4×4 system in (δz, δż), whose eigenvalues are the roots of its
    /// characteristic polynomial. In the frame that co-rotates with the
    /// body-frame precession (z = w e^{−iΩ̃₃t}, where the reduced motion is
    /// nearly at rest) the matrix becomes J + Ω̃₃S, S the generator
    /// (x, y) → (−y, x) on both δz and δż: the runaway pair is
    /// 1.025085 ± 0.155894i there, growing at about 1/τ.
    ///
    /// From the code: the eigenvalues of a central-difference Jacobian of
    /// `symmetric_full_ale_rhs` must agree with the hand-built ones to 1e-8.
    #[test]
    fn eq_3_4_runaway_eigenvalues_at_the_figure_state_are_1_025085_pm_0_155894i() {
        let top = SymmetricTop::figure();
        let omega = Vec3::new(0.0, 0.1, 0.2);
        let slope = reduced_ale_rhs(&top, &omega);
        let y0 = State::<4>::new(omega.x, omega.y, slope.x, slope.y);
        let (tau, w3) = (top.tau(), omega.z);
        let w3t = top.omega3_tilde(w3);
        // The hand-built linearisation: rows (δx, δy, δvx, δvy)' in terms of
        // (δx, δy, δvx, δvy), z₀ = x₀ + iy₀.
        let (x0, y0r) = (omega.x, omega.y);
        let g = tau * (x0 * x0 + y0r * y0r + w3 * w3);
        // τ z₀(z̄₀δz + z₀δz̄) = τ(2x₀(x₀δx + y₀δy), 2y₀(x₀δx + y₀δy)) in (re, im).
        let mut by_hand = SMatrix::<f64, 4, 4>::zeros();
        by_hand[(0, 2)] = 1.0;
        by_hand[(1, 3)] = 1.0;
        let rows = [
            // d(δvx)/dt · τ = δvx + 2τΩ₃δvy − Ω̃₃δy + gδx + 2τx₀(x₀δx + y₀δy)
            [
                g + 2.0 * tau * x0 * x0,
                -w3t + 2.0 * tau * x0 * y0r,
                1.0,
                2.0 * tau * w3,
            ],
            // d(δvy)/dt · τ = δvy − 2τΩ₃δvx + Ω̃₃δx + gδy + 2τy₀(x₀δx + y₀δy)
            [
                w3t + 2.0 * tau * x0 * y0r,
                g + 2.0 * tau * y0r * y0r,
                -2.0 * tau * w3,
                1.0,
            ],
        ];
        for (r, row) in rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                by_hand[(2 + r, c)] = v / tau;
            }
        }
        let h = 1e-6;
        let mut jac = SMatrix::<f64, 4, 4>::zeros();
        for j in 0..4 {
            let mut e = State::<4>::zeros();
            e[j] = h;
            let col = (symmetric_full_ale_rhs(&top, omega.z, &(y0 + e))
                - symmetric_full_ale_rhs(&top, omega.z, &(y0 - e)))
                / (2.0 * h);
            jac.set_column(j, &col);
        }
        let mut generator = SMatrix::<f64, 4, 4>::zeros();
        for k in [0, 2] {
            generator[(k, k + 1)] = -1.0;
            generator[(k + 1, k)] = 1.0;
        }
        let sorted = |m: SMatrix<f64, 4, 4>| {
            let mut v: Vec<_> = m.complex_eigenvalues().iter().copied().collect();
            v.sort_by(|a, b| (a.re, a.im).partial_cmp(&(b.re, b.im)).unwrap());
            v
        };
        for shift in [0.0, w3t] {
            let ours = sorted(jac + shift * generator);
            let hand = sorted(by_hand + shift * generator);
            for (a, b) in ours.iter().zip(&hand) {
                assert!((a - b).norm() < 1e-8, "{ours:?} vs {hand:?}");
            }
        }
        let runaway: Vec<_> = sorted(by_hand + w3t * generator)
            .into_iter()
            .filter(|l| l.re > 0.5)
            .collect();
        assert_eq!(runaway.len(), 2, "{runaway:?}");
        for l in runaway {
            assert!(
                (l.re - 1.025085).abs() < 1e-6 && (l.im.abs() - 0.155894).abs() < 1e-6,
                "{l}"
            );
        }
    }
}
