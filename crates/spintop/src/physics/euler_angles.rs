//! Euler angles (paper Eqs. (3.5) and (4.8)): an input and output format only.
//!
//! The convention that makes the paper's (3.5) true is z-x-z and active:
//! `O = R_z(φ) R_x(θ) R_z(ψ)`, with Ω the BODY-frame rate (`Ω̂ = Oᵀ dO/dt`).
//! spintop never integrates the angles themselves: (4.8) divides by sin θ, so
//! it is singular at the pole θ = 0 where the reduced top ends up. Orientations
//! are integrated on SO(3) instead and converted here for display.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `phi` | φ | precession angle | rad |
//! | `theta` | θ | nutation (tilt of the body axis from lab z) | rad, in [0, π] |
//! | `psi` | ψ | proper rotation angle | rad |
//! | `phi_dot`, `theta_dot`, `psi_dot` | φ̇, θ̇, ψ̇ | their rates | 1/τ |

use crate::math::{Mat3, Real, Vec3, rot_x, rot_z};
use serde::Serialize;

/// Below this sin θ the orientation is treated as lying on a pole, where only
/// φ ± ψ is defined.
///
/// NOTE: at sin θ ≈ 1e-12 the individual angles φ and ψ are already determined
/// by rounding noise in the matrix entries; this threshold only keeps the
/// conversion well defined (no 0/0), it cannot make them meaningful.
pub const POLE_SIN_THETA: Real = 1e-12;

/// z-x-z Euler angles (φ, θ, ψ) in radians.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EulerAngles {
    /// Precession angle φ.
    pub phi: Real,
    /// Nutation angle θ ∈ [0, π].
    pub theta: Real,
    /// Proper rotation angle ψ.
    pub psi: Real,
}

/// Rates (φ̇, θ̇, ψ̇) of the Euler angles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EulerRates {
    /// dφ/dt.
    pub phi_dot: Real,
    /// dθ/dt.
    pub theta_dot: Real,
    /// dψ/dt.
    pub psi_dot: Real,
}

impl EulerAngles {
    /// Build from (φ, θ, ψ).
    pub fn new(phi: Real, theta: Real, psi: Real) -> Self {
        Self { phi, theta, psi }
    }

    /// The rotation `O = R_z(φ) R_x(θ) R_z(ψ)` (body → lab).
    pub fn to_rotation(&self) -> Mat3 {
        rot_z(self.phi) * rot_x(self.theta) * rot_z(self.psi)
    }

    /// The angles of a rotation matrix, θ ∈ [0, π], φ and ψ ∈ (−π, π].
    ///
    /// ```text
    /// θ = atan2(√(O₁₃² + O₂₃²), O₃₃),  φ = atan2(O₁₃, −O₂₃),  ψ = atan2(O₃₁, O₃₂)
    /// ```
    ///
    /// On a pole (sin θ below [`POLE_SIN_THETA`]) only φ + ψ (θ = 0) or φ − ψ
    /// (θ = π) is defined; the convention ψ = 0 puts all of it in φ, so the
    /// result is finite and still reproduces `m`.
    pub fn from_rotation(m: &Mat3) -> Self {
        let sin_theta = m[(0, 2)].hypot(m[(1, 2)]);
        // NOTE: atan2 rather than acos(O₃₃): acos loses half the digits near the poles.
        let theta = sin_theta.atan2(m[(2, 2)]);
        if sin_theta < POLE_SIN_THETA {
            // O = R_z(φ ± ψ) up to the sign pattern of R_x(0 or π): the first
            // column is (cos(φ ± ψ), sin(φ ± ψ), 0) either way.
            return Self::new(m[(1, 0)].atan2(m[(0, 0)]), theta, 0.0);
        }
        Self::new(
            m[(0, 2)].atan2(-m[(1, 2)]),
            theta,
            m[(2, 0)].atan2(m[(2, 1)]),
        )
    }

    /// True when sin θ is below [`POLE_SIN_THETA`], where φ and ψ separately,
    /// and the rates (4.8), are undefined.
    pub fn at_pole(&self) -> bool {
        self.theta.sin().abs() < POLE_SIN_THETA
    }
}

/// The orientation that puts the lab z axis along the body-frame vector `v`,
/// with φ = 0. With v = L₀ this is the paper's frame of (4.11) and its
/// figures: θ is then the tilt between the symmetry axis and L.
///
/// ```text
/// third row of R_z(φ)R_x(θ)R_z(ψ) = (sin θ sin ψ, sin θ cos ψ, cos θ) = v/|v|
/// ⇒ θ = atan2(√(v₁² + v₂²), v₃),  ψ = atan2(v₁, v₂)
/// ```
///
/// A zero vector gives the identity.
pub fn frame_with_z_along(v: &Vec3) -> EulerAngles {
    EulerAngles::new(0.0, v.x.hypot(v.y).atan2(v.z), v.x.atan2(v.y))
}

// ANCHOR: poisson_3_5
/// The body-frame angular velocity from Euler angles and their rates.
///
/// Paper: Eq. (3.5).
///
/// ```text
/// Ω₁ = φ̇ sin θ sin ψ + θ̇ cos ψ
/// Ω₂ = φ̇ sin θ cos ψ − θ̇ sin ψ
/// Ω₃ = φ̇ cos θ + ψ̇
/// ```
pub fn body_rate_from_euler(angles: &EulerAngles, rates: &EulerRates) -> Vec3 {
    let EulerAngles { theta, psi, .. } = *angles;
    let EulerRates {
        phi_dot,
        theta_dot,
        psi_dot,
    } = *rates;
    let (s_th, c_th) = theta.sin_cos();
    let (s_psi, c_psi) = psi.sin_cos();
    Vec3::new(
        phi_dot * s_th * s_psi + theta_dot * c_psi,
        phi_dot * s_th * c_psi - theta_dot * s_psi,
        phi_dot * c_th + psi_dot,
    )
}
// ANCHOR_END: poisson_3_5

// ANCHOR: poisson_4_8
/// The Euler-angle rates from the body rate: (3.5) solved for φ̇, θ̇, ψ̇.
///
/// Paper: Eq. (4.8).
///
/// ```text
/// φ̇ = (Ω₁ sin ψ + Ω₂ cos ψ) / sin θ
/// θ̇ = Ω₁ cos ψ − Ω₂ sin ψ
/// ψ̇ = Ω₃ − (Ω₁ sin ψ + Ω₂ cos ψ) cot θ
/// ```
///
/// Returns `None` on a pole, where φ̇ and ψ̇ are not separately defined (only
/// φ̇ ± ψ̇ is) and (4.8) divides by zero.
pub fn euler_rates(angles: &EulerAngles, omega: &Vec3) -> Option<EulerRates> {
    if angles.at_pole() {
        return None;
    }
    let (s_th, c_th) = angles.theta.sin_cos();
    let (s_psi, c_psi) = angles.psi.sin_cos();
    let a = omega.x * s_psi + omega.y * c_psi;
    Some(EulerRates {
        phi_dot: a / s_th,
        theta_dot: omega.x * c_psi - omega.y * s_psi,
        psi_dot: omega.z - a * c_th / s_th,
    })
}
// ANCHOR_END: poisson_4_8

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{orthonormality_error, vee};
    use approx::assert_relative_eq;

    /// The convention check from the physics notes: with O = R_z(φ)R_x(θ)R_z(ψ)
    /// and Ω̂ = Oᵀ dO/dt, (3.5) holds. Differentiate O along a path of angles.
    #[test]
    fn eq_3_5_holds_for_the_body_rate_of_zxz_active_rotations() {
        let angles = |t: Real| EulerAngles::new(0.3 + 0.7 * t, 1.1 - 0.2 * t, -0.4 + 1.3 * t);
        let rates = EulerRates {
            phi_dot: 0.7,
            theta_dot: -0.2,
            psi_dot: 1.3,
        };
        let t = 0.25;
        let h = 1e-6;
        let o = angles(t).to_rotation();
        let d = (angles(t + h).to_rotation() - angles(t - h).to_rotation()) / (2.0 * h);
        let body = vee(&(o.transpose() * d));
        assert_relative_eq!(
            body_rate_from_euler(&angles(t), &rates),
            body,
            epsilon = 1e-9
        );
        // The lab-frame rate (dO/dt Oᵀ) is a different vector: (3.5) would fail for it.
        let lab = vee(&(d * o.transpose()));
        assert!((body_rate_from_euler(&angles(t), &rates) - lab).norm() > 1e-2);
    }

    #[test]
    fn eq_4_8_inverts_eq_3_5() {
        let angles = EulerAngles::new(-2.0, 0.9, 2.5);
        let omega = Vec3::new(0.31, -0.12, 0.77);
        let rates = euler_rates(&angles, &omega).expect("away from the pole");
        assert_relative_eq!(
            body_rate_from_euler(&angles, &rates),
            omega,
            epsilon = 1e-15
        );
    }

    #[test]
    fn pole_is_handled_without_nan() {
        for theta in [
            0.0,
            1e-14,
            std::f64::consts::PI,
            std::f64::consts::PI - 1e-15,
        ] {
            let o = EulerAngles::new(0.8, theta, -0.3).to_rotation();
            let e = EulerAngles::from_rotation(&o);
            assert!(e.phi.is_finite() && e.theta.is_finite() && e.psi.is_finite());
            assert!(e.at_pole());
            assert_relative_eq!(e.to_rotation(), o, epsilon = 1e-13);
            assert!(euler_rates(&e, &Vec3::new(0.1, 0.2, 0.3)).is_none());
        }
        assert!(orthonormality_error(&EulerAngles::new(1.0, 0.0, 2.0).to_rotation()) < 1e-15);
    }
}
