//! Rigid-body kinematics and observables (paper §3, Eqs. (3.1)–(3.2)).
//!
//! A point of the top sits at `r_lab = O ρ` with `ρ` fixed in the body and
//! `O ∈ SO(3)`. The body-frame angular velocity Ω is defined by `Ω̂ = Oᵀ dO/dt`,
//! so `dO/dt = O Ω̂`. The angular momentum is `L = O I Ω` and
//! `Oᵀ dL/dt = I Ω̇ + Ω × IΩ`.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `rotation` | O | body → lab rotation | – |
//! | `omega` | Ω | body-frame angular velocity | 1/τ |
//! | `omega_dot` | Ω̇ | its time derivative | 1/τ² |
//! | `rho` | ρ | a point in the body frame | length |
//! | `inertia` | (I₁, I₂, I₃) | principal moments | I₁ = 1 (symmetric top) |
//! | `alpha` | α | any body-frame vector | – |

use crate::math::{Mat3, Real, Vec3};
use crate::physics::euler_angles::{EulerAngles, frame_with_z_along};

/// An Euler-type equation `Ω̇ = F(Ω)` for the body-frame angular velocity of a
/// free top: the truncated, reduced or general models all have this form.
pub trait BodyDynamics {
    /// The principal moments (I₁, I₂, I₃).
    fn inertia(&self) -> Vec3;
    /// The right-hand side `F(Ω)`.
    fn omega_dot(&self, omega: &Vec3) -> Vec3;
}

/// Lab-frame velocity of the body point `rho`.
///
/// Paper: Eq. (3.1).
///
/// ```text
/// v = dO/dt ρ = O (Ω × ρ)
/// ```
pub fn lab_velocity(rotation: &Mat3, omega: &Vec3, rho: &Vec3) -> Vec3 {
    rotation * omega.cross(rho)
}

/// Lab-frame acceleration of the body point `rho`.
///
/// Paper: Eq. (3.1).
///
/// ```text
/// dv/dt = O {Ω × (Ω × ρ) + Ω̇ × ρ}
/// ```
pub fn lab_acceleration(rotation: &Mat3, omega: &Vec3, omega_dot: &Vec3, rho: &Vec3) -> Vec3 {
    rotation * (omega.cross(&omega.cross(rho)) + omega_dot.cross(rho))
}

/// Time derivative of the lab image `a = O α` of a body-frame vector α(t).
///
/// Paper: Eq. (3.2).
///
/// ```text
/// da/dt = O {dα/dt + Ω × α}
/// ```
pub fn lab_rate(rotation: &Mat3, omega: &Vec3, alpha: &Vec3, alpha_dot: &Vec3) -> Vec3 {
    rotation * (alpha_dot + omega.cross(alpha))
}

/// Body-frame angular momentum `I Ω` for principal moments `inertia`.
pub fn angular_momentum_body(inertia: &Vec3, omega: &Vec3) -> Vec3 {
    inertia.component_mul(omega)
}

/// Kinetic energy `E = ½ Ω · I Ω`.
pub fn energy(inertia: &Vec3, omega: &Vec3) -> Real {
    0.5 * omega.dot(&angular_momentum_body(inertia, omega))
}

/// `Ω⊥ = √(Ω₁² + Ω₂²)`, the rate about axes perpendicular to the symmetry axis.
pub fn omega_perp(omega: &Vec3) -> Real {
    omega.x.hypot(omega.y)
}

/// The angle between the body's third axis (the symmetry axis) and L, in [0, π].
///
/// ```text
/// tan(tilt) = |L⊥| / L₃ = I₁Ω⊥ / (I₃Ω₃)   (symmetric top)
/// ```
///
/// Zero when L = 0 (nothing to tilt against).
pub fn tilt(inertia: &Vec3, omega: &Vec3) -> Real {
    let l = angular_momentum_body(inertia, omega);
    // NOTE: atan2 of the two legs is accurate at every angle, where acos(L₃/|L|)
    // loses half the digits near 0 and π.
    let perp = l.x.hypot(l.y);
    // NOTE: L = 0 written with negative zeros (Ω₀ = (-0, -0, -0)) made
    // atan2(0, -0) = π.
    if perp == 0.0 && l.z == 0.0 {
        return 0.0;
    }
    perp.atan2(l.z)
}

/// Observables of a top in one state, computed in the core so that no front
/// end ever redoes physics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observables {
    /// E = ½ Ω·IΩ.
    pub energy: Real,
    /// L in the body frame, IΩ.
    pub l_body: Vec3,
    /// L in the lab frame, O IΩ.
    pub l_lab: Vec3,
    /// Ω⊥.
    pub omega_perp: Real,
    /// Angle between the symmetry axis and L.
    pub tilt: Real,
}

impl Observables {
    /// Evaluate every observable for principal moments `inertia`, orientation
    /// `rotation` and body rate `omega`.
    pub fn new(inertia: &Vec3, rotation: &Mat3, omega: &Vec3) -> Self {
        let l_body = angular_momentum_body(inertia, omega);
        Self {
            energy: energy(inertia, omega),
            l_body,
            l_lab: rotation * l_body,
            omega_perp: omega_perp(omega),
            tilt: tilt(inertia, omega),
        }
    }
}

/// The initial orientation that puts the lab z axis along L₀ = IΩ₀, as in
/// the paper's particular solution (4.11) and its figures: then θ is the tilt
/// between the symmetry axis and L, and φ̇ and ψ̇ are the precession and spin
/// rates. The live view, `plot` and a scene's `frame = "paper"` all start
/// from it.
///
/// Paper: Eq. (4.11).
///
/// ```text
/// third row of O = R_z(φ)R_x(θ)R_z(ψ) = (sin θ sin ψ, sin θ cos ψ, cos θ) = Oᵀẑ = L₀/|L₀|
/// θ = the tilt,  ψ = atan2(L₁, L₂),  φ = 0;   L₀ = 0 keeps O = 1
/// ```
pub fn lab_frame(inertia: &Vec3, omega0: &Vec3) -> EulerAngles {
    frame_with_z_along(&angular_momentum_body(inertia, omega0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tilt is 0 where L = 0 (its doc), whatever the zeros' signs:
    /// Ω₀ = (-0, -0, -0) read π (atan2(0, -0)).
    #[test]
    fn the_tilt_of_no_angular_momentum_is_zero_whatever_the_signs() {
        let inertia = Vec3::new(1.0, 1.0, 0.4);
        for omega in [Vec3::new(0.0, 0.0, 0.0), Vec3::new(-0.0, -0.0, -0.0)] {
            assert_eq!(tilt(&inertia, &omega), 0.0);
        }
        assert_eq!(
            tilt(&inertia, &Vec3::new(0.0, 0.0, -1.0)),
            std::f64::consts::PI
        );
        assert_eq!(
            tilt(&inertia, &Vec3::new(1.0, 0.0, 0.0)),
            std::f64::consts::FRAC_PI_2
        );
    }
    use crate::math::{exp_so3, hat};
    use approx::assert_relative_eq;

    /// A smooth test orientation O(t) = exp(t a) exp(t² b): differentiate it by
    /// central differences and compare with (3.1) and (3.2).
    fn orientation(t: Real) -> Mat3 {
        let a = Vec3::new(0.3, -0.2, 0.5);
        let b = Vec3::new(-0.1, 0.4, 0.2);
        (exp_so3(&(t * a)) * exp_so3(&(t * t * b)))
            .to_rotation_matrix()
            .into_inner()
    }

    fn body_rate(t: Real) -> Vec3 {
        let h = 1e-5;
        let d = (orientation(t + h) - orientation(t - h)) / (2.0 * h);
        crate::math::vee(&(orientation(t).transpose() * d))
    }

    #[test]
    fn eq_3_1_velocity_and_acceleration_match_finite_differences() {
        let rho = Vec3::new(0.7, -0.3, 1.1);
        let t = 0.8;
        let h = 1e-4;
        let pos = |t: Real| orientation(t) * rho;
        let v_fd = (pos(t + h) - pos(t - h)) / (2.0 * h);
        let a_fd = (pos(t + h) - 2.0 * pos(t) + pos(t - h)) / (h * h);
        let omega = body_rate(t);
        let omega_dot = (body_rate(t + h) - body_rate(t - h)) / (2.0 * h);
        let o = orientation(t);
        assert_relative_eq!(lab_velocity(&o, &omega, &rho), v_fd, epsilon = 1e-8);
        assert_relative_eq!(
            lab_acceleration(&o, &omega, &omega_dot, &rho),
            a_fd,
            epsilon = 1e-6
        );
        // The skew matrix really is Oᵀ dO/dt (the body-frame convention).
        let d = (orientation(t + 1e-5) - orientation(t - 1e-5)) / 2e-5;
        assert_relative_eq!(hat(&omega), o.transpose() * d, epsilon = 1e-8);
    }

    #[test]
    fn eq_3_2_rate_of_a_body_vector_matches_finite_differences() {
        let alpha = |t: Real| Vec3::new(t.sin(), t * t, 1.0 - t);
        let alpha_dot = |t: Real| Vec3::new(t.cos(), 2.0 * t, -1.0);
        let t = 0.4;
        let h = 1e-5;
        let a = |t: Real| orientation(t) * alpha(t);
        let fd = (a(t + h) - a(t - h)) / (2.0 * h);
        let got = lab_rate(&orientation(t), &body_rate(t), &alpha(t), &alpha_dot(t));
        assert_relative_eq!(got, fd, epsilon = 1e-8);
    }

    #[test]
    fn tilt_is_the_angle_between_axis_and_l() {
        let inertia = Vec3::new(1.0, 1.0, 0.4);
        let omega = Vec3::new(0.0, 0.1, 0.2);
        // Erratum (4.11): tan θ = I₁Ω₂₀/(I₃Ω₃₀) = 0.1/0.08.
        assert_relative_eq!(
            tilt(&inertia, &omega),
            (0.1f64 / 0.08).atan(),
            epsilon = 1e-15
        );
        // The physics notes' erratum 4 gives it to four places: 0.8961 rad.
        assert!((tilt(&inertia, &omega) - 0.8961).abs() < 5e-5);
        assert_eq!(tilt(&inertia, &Vec3::zeros()), 0.0);
    }
}
