//! The truncated Abraham–Lorentz–Euler equation of a general polarized top
//! (paper §3, Eq. (3.3)).
//!
//! A rigid body with principal moments I = diag(I₁, I₂, I₃) carries a constant
//! body-frame dipole d (the charge-weighted sum Σ q ρ; the paper prints Σ m ρ,
//! erratum 2). Putting the kinematics (3.1) into the Larmor-like loss law (2.1)
//! gives (3.3). Units: κ = 2/(3c³) = 1, so `d` here is √κ times the physical
//! dipole, and for the symmetric top τ = |d|²/I₁.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `inertia` | (I₁, I₂, I₃) | principal moments | any (κ = 1) |
//! | `dipole` | d | body-frame dipole | √(I/time) when κ = 1 |
//! | `omega` | Ω | body angular velocity | 1/time |

use super::rigid_body::BodyDynamics;
use super::{ParamError, check_principal_moments, finite};
use crate::math::Vec3;

/// A free top with principal moments `inertia` and a fixed body dipole `dipole`.
///
/// Built only through [`GeneralTop::new`], so the moments are always positive,
/// obey the triangle inequalities, and the dipole is non-zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralTop {
    inertia: Vec3,
    dipole: Vec3,
}

impl GeneralTop {
    /// Validate the principal moments and the dipole.
    pub fn new(inertia: Vec3, dipole: Vec3) -> Result<Self, ParamError> {
        check_principal_moments(&inertia)?;
        for (i, name) in ["d1", "d2", "d3"].into_iter().enumerate() {
            finite(name, dipole[i])?;
        }
        if dipole == Vec3::zeros() {
            return Err(ParamError::ZeroDipole);
        }
        Ok(Self { inertia, dipole })
    }

    /// The principal moments.
    pub fn inertia(&self) -> Vec3 {
        self.inertia
    }

    /// The body-frame dipole (κ = 1 units).
    pub fn dipole(&self) -> Vec3 {
        self.dipole
    }

    // ANCHOR: general_truncated_ale
    /// The right-hand side of the truncated ALE for any top.
    ///
    /// Paper: Eq. (3.3).
    ///
    /// ```text
    /// I Ω̇ + Ω × IΩ = −{ |d × Ω|² Ω + (d · (Ω × Ω̇)) d }
    /// ```
    ///
    /// Ω̇ stands on both sides. Since d·(Ω × Ω̇) = (d × Ω)·Ω̇, the equation is the
    /// 3×3 linear system `(I + d wᵀ) Ω̇ = b` with `w = d × Ω` and
    /// `b = −Ω × IΩ − |w|² Ω`, solved here at every evaluation.
    pub fn truncated_ale_rhs(&self, omega: &Vec3) -> Vec3 {
        let i = &self.inertia;
        let d = &self.dipole;
        let w = d.cross(omega);
        let b = -omega.cross(&i.component_mul(omega)) - w.norm_squared() * omega;
        // NOTE: the matrix I + d wᵀ is diagonal plus rank one, so the Sherman–Morrison
        // formula solves the system exactly in a dozen flops with no pivoting:
        //   Ω̇ = I⁻¹b − I⁻¹d (wᵀI⁻¹b) / (1 + wᵀI⁻¹d).
        // The denominator is 1 for the symmetric top (w ⊥ d ∥ e₃); in general it can
        // reach 0 only when |d|²|Ω| is of order I, far into the stiff regime, and then
        // the result is non-finite and the integrator reports it with its time.
        let i_inv_b = b.component_div(i);
        let i_inv_d = d.component_div(i);
        let denom = 1.0 + w.dot(&i_inv_d);
        i_inv_b - i_inv_d * (w.dot(&i_inv_b) / denom)
    }
    // ANCHOR_END: general_truncated_ale

    // ANCHOR: general_reduced_ale
    /// The reduced ALE of any top: (3.4) with the Schott term kept and its
    /// runaways removed, as Section 4.2 does for the symmetric top.
    ///
    /// Paper: Eq. (3.4), reduced (the general form of Eq. (4.12)–(4.14)).
    ///
    /// ```text
    /// I Ω̇ + Ω × IΩ = d × { d × (Ω²Ω − Ω̈₀) + (d·Ω̇₀) Ω + 2 (d·Ω) Ω̇₀ }
    /// Ω̇₀ = −I⁻¹(Ω × IΩ),   Ω̈₀ = −I⁻¹(Ω̇₀ × IΩ + Ω × IΩ̇₀)
    /// ```
    ///
    /// Ω̇ and Ω̈ in the small right-hand side are those of the free Euler
    /// motion (the Landau–Lifshitz reduction), so the error is O(τ²) against
    /// the physical solution of (3.4) and no runaway is left. For I₁ = I₂ and
    /// d along e₃ it is (4.12)–(4.14) with τ = d²/I₁ (tested).
    pub fn reduced_ale_rhs(&self, omega: &Vec3) -> Vec3 {
        let (w_dot, torque) = self.reduced_parts(omega);
        w_dot + torque.component_div(&self.inertia)
    }
    // ANCHOR_END: general_reduced_ale

    /// The radiation torque of the reduced ALE at Ω: the right-hand side of
    /// [`GeneralTop::reduced_ale_rhs`] beyond Euler's free terms, computed on
    /// its own (adding the free terms and taking them away again would lose
    /// it to rounding when it is 10⁻¹⁵ of them, as for a real molecule).
    ///
    /// Paper: Eq. (3.4), reduced.
    pub fn reduced_torque(&self, omega: &Vec3) -> Vec3 {
        self.reduced_parts(omega).1
    }

    /// The radiation torque of the truncated ALE (3.3) at Ω,
    /// −{|d × Ω|² Ω + (d·(Ω × Ω̇)) d} with Ω̇ of (3.3), computed on its own
    /// (see [`GeneralTop::reduced_torque`]).
    ///
    /// Paper: Eq. (3.3).
    pub fn truncated_torque(&self, omega: &Vec3) -> Vec3 {
        let w = self.dipole.cross(omega);
        let omega_dot = self.truncated_ale_rhs(omega);
        -(w.norm_squared() * omega + w.dot(&omega_dot) * self.dipole)
    }

    /// Ω̇₀ of the free motion and the reduced ALE's torque.
    fn reduced_parts(&self, omega: &Vec3) -> (Vec3, Vec3) {
        let i = &self.inertia;
        let d = &self.dipole;
        let free = |w: &Vec3| -(w.cross(&i.component_mul(w))).component_div(i);
        let w_dot = free(omega);
        let w_ddot = -(w_dot.cross(&i.component_mul(omega))
            + omega.cross(&i.component_mul(&w_dot)))
        .component_div(i);
        let small = d.cross(
            &(d.cross(&(omega.norm_squared() * omega - w_ddot))
                + d.dot(&w_dot) * omega
                + 2.0 * d.dot(omega) * w_dot),
        );
        (w_dot, small)
    }
}

impl BodyDynamics for GeneralTop {
    fn inertia(&self) -> Vec3 {
        self.inertia
    }

    fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        self.truncated_ale_rhs(omega)
    }
}

/// The reduced ALE of a general top as `Ω̇ = F(Ω)` (the top itself is (3.3)).
///
/// Paper: Eq. (3.4), reduced (see [`GeneralTop::reduced_ale_rhs`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reduced(pub GeneralTop);

impl BodyDynamics for Reduced {
    fn inertia(&self) -> Vec3 {
        self.0.inertia
    }

    fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        self.0.reduced_ale_rhs(omega)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::symmetric_top::{SymmetricTop, truncated_ale_rhs};
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    /// The general top as `Ω̇ = F(Ω)`, written in the form of the balance law (2.1)
    /// rather than (3.3): an independent route to the same equation, used by tests.
    ///
    /// From (3.1) the dipole `𝔡 = O d` moves with `Oᵀ𝔡̇ = Ω × d` and
    /// `Oᵀ𝔡̈ = Ω̇ × d + Ω × (Ω × d)`, and (2.1) with κ = 1 reads
    /// `IΩ̇ + Ω × IΩ = −(Ω × d) × (Ω̇ × d + Ω × (Ω × d))`. This is linear in Ω̇, so
    /// its 3×3 matrix is assembled column by column and solved by LU.
    fn truncated_ale_rhs_from_balance_law(top: &GeneralTop, omega: &Vec3) -> Option<Vec3> {
        let i = top.inertia();
        let d = top.dipole();
        let wd = omega.cross(&d);
        // residual(Ω̇) = IΩ̇ + Ω × IΩ + (Ω × d) × (Ω̇ × d + Ω × (Ω × d)), affine in Ω̇.
        let residual = |od: &Vec3| {
            i.component_mul(od)
                + omega.cross(&i.component_mul(omega))
                + wd.cross(&(od.cross(&d) + omega.cross(&wd)))
        };
        let r0 = residual(&Vec3::zeros());
        let m = nalgebra::Matrix3::from_columns(&[
            residual(&Vec3::x()) - r0,
            residual(&Vec3::y()) - r0,
            residual(&Vec3::z()) - r0,
        ]);
        m.lu().solve(&(-r0))
    }

    #[test]
    fn validation_refuses_unphysical_tops() {
        let d = Vec3::new(0.0, 0.0, 1.0);
        assert!(GeneralTop::new(Vec3::new(1.0, 1.0, 2.0), d).is_ok());
        assert!(matches!(
            GeneralTop::new(Vec3::new(1.0, 1.0, 2.5), d),
            Err(ParamError::TriangleInequality(..))
        ));
        assert!(matches!(
            GeneralTop::new(Vec3::new(1.0, -1.0, 1.0), d),
            Err(ParamError::MomentNotPositive { index: 2, .. })
        ));
        assert!(matches!(
            GeneralTop::new(Vec3::new(1.0, 1.0, 1.0), Vec3::zeros()),
            Err(ParamError::ZeroDipole)
        ));
        assert!(matches!(
            GeneralTop::new(Vec3::new(1.0, f64::NAN, 1.0), d),
            Err(ParamError::NotFinite { name: "I2", .. })
        ));
        assert!(matches!(
            GeneralTop::new(Vec3::new(1.0, 1.0, 1.0), Vec3::new(0.0, f64::INFINITY, 0.0)),
            Err(ParamError::NotFinite { name: "d2", .. })
        ));
    }

    proptest! {
        /// (3.3) solved through its linear system agrees with (2.1) assembled
        /// independently from the kinematics (3.1).
        #[test]
        fn eq_3_3_agrees_with_the_balance_law_2_1(
            i1 in 0.5..2.0f64, i2 in 0.5..2.0f64, i3f in 0.1..1.0f64,
            d in prop::array::uniform3(-1.0..1.0f64),
            w in prop::array::uniform3(-1.0..1.0f64),
        ) {
            let i3 = (i1 + i2) * i3f;
            prop_assume!(i3 >= (i1 - i2).abs());
            let d = Vec3::from(d);
            prop_assume!(d.norm() > 1e-3);
            let top = GeneralTop::new(Vec3::new(i1, i2, i3), d).unwrap();
            let omega = Vec3::from(w);
            let a = top.truncated_ale_rhs(&omega);
            let b = truncated_ale_rhs_from_balance_law(&top, &omega).unwrap();
            prop_assert!((a - b).norm() <= 1e-12 * (1.0 + b.norm()), "{a} vs {b}");
        }

        /// Given symmetric inputs (I₂ = I₁, d ∥ e₃), the general (3.3) reproduces
        /// the symmetric top's (4.2)–(4.4) with τ = d²/I₁ and time in the same units.
        #[test]
        fn eq_3_3_with_symmetric_inputs_reproduces_eq_4_2_to_4_4(
            i1 in 0.1..10.0f64, ratio in 0.01..2.0f64, d3 in -3.0..3.0f64,
            w in prop::array::uniform3(-2.0..2.0f64),
        ) {
            prop_assume!(d3.abs() > 1e-3);
            let general = GeneralTop::new(Vec3::new(i1, i1, ratio * i1), Vec3::new(0.0, 0.0, d3)).unwrap();
            let sym = SymmetricTop::new(ratio, d3 * d3 / i1).unwrap();
            let omega = Vec3::from(w);
            let a = general.truncated_ale_rhs(&omega);
            let b = truncated_ale_rhs(&sym, &omega);
            prop_assert!((a - b).norm() <= 1e-12 * (1.0 + b.norm()), "{a} vs {b}");
        }
    }

    /// For symmetric inputs, (4.2)–(4.4) give dE/dt = −2τΩ⊥²E exactly; the
    /// general solver must reproduce that energy balance.
    #[test]
    fn eq_3_3_energy_balance_for_the_symmetric_case() {
        let top = GeneralTop::new(Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0)).unwrap();
        let omega = Vec3::new(0.05, 0.1, 0.2);
        let od = top.truncated_ale_rhs(&omega);
        let de = omega.dot(&top.inertia().component_mul(&od));
        let e = 0.5 * omega.dot(&top.inertia().component_mul(&omega));
        assert_relative_eq!(
            de,
            -2.0 * omega.x.hypot(omega.y).powi(2) * e,
            epsilon = 1e-15
        );
    }

    /// The torques on their own are the right-hand sides' radiation parts:
    /// I Ω̇ + Ω × IΩ equals them at an ordinary scale (where nothing cancels),
    /// and at a real molecule's scale (τ_f|Ω| ~ 1e-15), where that difference
    /// would be rounding, they still scale exactly as |d|²: the torque of a
    /// dipole 1e-8 times smaller is 1e-16 times the torque.
    #[test]
    fn eq_3_3_and_reduced_eq_3_4_torques_are_the_radiation_part_of_the_rhs() {
        let i = Vec3::new(1.0, 1.5, 2.0);
        let omega = Vec3::new(0.5, -0.3, 0.8);
        let top = GeneralTop::new(i, Vec3::new(0.3, 0.2, 1.0)).unwrap();
        let euler = omega.cross(&i.component_mul(&omega));
        let from_rhs = |w_dot: Vec3| i.component_mul(&w_dot) + euler;
        let t3 = top.truncated_torque(&omega);
        let r4 = top.reduced_torque(&omega);
        assert!((t3 - from_rhs(top.truncated_ale_rhs(&omega))).norm() < 1e-14);
        assert!((r4 - from_rhs(top.reduced_ale_rhs(&omega))).norm() < 1e-14);
        let tiny = GeneralTop::new(i, Vec3::new(0.3, 0.2, 1.0) * 1e-8).unwrap();
        assert_relative_eq!(
            tiny.reduced_torque(&omega),
            r4 * 1e-16,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            tiny.truncated_torque(&omega),
            t3 * 1e-16,
            max_relative = 1e-7
        );
    }
}
