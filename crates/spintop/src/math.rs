//! Scalar, vector and rotation types shared by the whole crate, and the few
//! pieces of SO(3) geometry the physics needs.
//!
//! | code name | symbol | meaning |
//! |---|---|---|
//! | [`hat`] | Ω̂ | the skew matrix with `hat(a) * b = a × b` |
//! | [`vee`] | (·)^∨ | the inverse of `hat` |
//! | [`rot_x`], [`rot_z`] | R_x, R_z | active rotations about the lab axes |
//! | [`rot_axis`] | Rot(n, α) | rotation by α about the unit vector n |
//! | [`exp_so3`] | exp(σ̂) | the exponential map of SO(3), as a unit quaternion |
//! | [`dexpinv_right`] | J_r⁻¹(σ) | turns a body rate into d σ / dt for `O = O₀ exp(σ̂)` |

use nalgebra::{Matrix3, SVector, UnitQuaternion, Vector3};

/// The scalar type of the whole crate.
pub type Real = f64;
/// A 3-vector (body or lab frame: the name of the variable says which).
pub type Vec3 = Vector3<Real>;
/// A 3×3 matrix (rotation, inertia tensor).
pub type Mat3 = Matrix3<Real>;
/// A unit quaternion, the storage of an orientation while it is integrated.
pub type Quat = UnitQuaternion<Real>;
/// A fixed-size state vector of dimension `N`.
pub type State<const N: usize> = SVector<Real, N>;
/// A complex number: the roots of characteristic equations (the shell
/// model's chain, the linear theory of (3.4)) that the crate returns. The
/// crate's own, so that a book snippet run by `spintop book` (which
/// depends on spintop alone) can name it.
pub use nalgebra::Complex;

/// The derivative of `f` at `at` along `v`, Df(at)[v], by a central
/// difference of step `rel`·|at|/|v| (|at| floored at the smallest normal
/// double); zero along v = 0.
pub fn directional_derivative(f: &dyn Fn(&Vec3) -> Vec3, at: &Vec3, v: &Vec3, rel: Real) -> Vec3 {
    let n = v.norm();
    if n == 0.0 {
        return Vec3::zeros();
    }
    let h = rel * at.norm().max(Real::MIN_POSITIVE) / n;
    (f(&(at + v * h)) - f(&(at - v * h))) / (2.0 * h)
}

/// The skew-symmetric matrix of `a`, so that `hat(a) * b == a.cross(&b)`.
pub fn hat(a: &Vec3) -> Mat3 {
    Mat3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// The vector of a skew-symmetric matrix (the antisymmetric part of any matrix).
pub fn vee(m: &Mat3) -> Vec3 {
    Vec3::new(
        0.5 * (m[(2, 1)] - m[(1, 2)]),
        0.5 * (m[(0, 2)] - m[(2, 0)]),
        0.5 * (m[(1, 0)] - m[(0, 1)]),
    )
}

/// Active rotation by `angle` about the lab x axis.
pub fn rot_x(angle: Real) -> Mat3 {
    let (s, c) = angle.sin_cos();
    Mat3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Active rotation by `angle` about the lab z axis.
pub fn rot_z(angle: Real) -> Mat3 {
    let (s, c) = angle.sin_cos();
    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// Rotation by `angle` about the unit vector `axis` (Rodrigues' formula).
///
/// A zero `axis` gives the identity, so a top with no angular momentum does not
/// produce NaN.
pub fn rot_axis(axis: &Vec3, angle: Real) -> Mat3 {
    let n = axis.norm();
    if n == 0.0 {
        return Mat3::identity();
    }
    let k = hat(&(axis / n));
    let s = angle.sin();
    // NOTE: 1 − cos α written as 2 sin²(α/2) keeps full relative accuracy for small α.
    let one_minus_c = 2.0 * (0.5 * angle).sin().powi(2);
    Mat3::identity() + k * s + k * k * one_minus_c
}

/// The exponential map exp(σ̂) of SO(3), returned as a unit quaternion.
pub fn exp_so3(sigma: &Vec3) -> Quat {
    Quat::from_scaled_axis(*sigma)
}

// ANCHOR: dexpinv_right
/// The inverse right Jacobian of SO(3): if `O(t) = O₀ exp(σ̂(t))` and
/// `Oᵀ dO/dt = Ω̂` (body rate), then `dσ/dt = J_r⁻¹(σ) Ω`.
///
/// ```text
/// J_r⁻¹(σ) = I + ½ σ̂ + (1/θ² − (1 + cos θ)/(2 θ sin θ)) σ̂²,  θ = |σ|
/// ```
///
/// This is the map that lets an ordinary Runge–Kutta method update an
/// orientation by exponentials (Runge–Kutta–Munthe-Kaas): the method integrates
/// the small vector σ, and the orientation is only ever changed by multiplying
/// with exp(σ̂), so it stays a rotation.
pub fn dexpinv_right(sigma: &Vec3, omega: &Vec3) -> Vec3 {
    let theta2 = sigma.norm_squared();
    // NOTE: the coefficient 1/θ² − (1+cos θ)/(2θ sin θ) = 1/12 + θ²/720 + θ⁴/30240 + …
    // cancels badly for small θ, so the series is used below θ = 0.1 (error < 1e-16).
    let coeff = if theta2 < 1e-2 {
        1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0
    } else {
        let theta = theta2.sqrt();
        let half = 0.5 * theta;
        // (1 + cos θ)/(2 θ sin θ) = cot(θ/2) / (2θ)
        1.0 / theta2 - half.cos() / (half.sin() * 2.0 * theta)
    };
    let s_cross_w = sigma.cross(omega);
    omega + 0.5 * s_cross_w + coeff * sigma.cross(&s_cross_w)
}
// ANCHOR_END: dexpinv_right

/// The largest entry of `|MᵀM − I|`: how far `m` is from being orthogonal.
pub fn orthonormality_error(m: &Mat3) -> Real {
    (m.transpose() * m - Mat3::identity()).amax()
}

/// True when every component is finite.
pub fn all_finite<const R: usize, const C: usize>(m: &nalgebra::SMatrix<Real, R, C>) -> bool {
    m.iter().all(|x| x.is_finite())
}

/// The least-squares slope of the line through `points` (x, y); NaN for
/// fewer than two distinct x. Used for growth rates, orders and exponents
/// (pass logarithms for a power law).
pub fn least_squares_slope(points: impl IntoIterator<Item = (Real, Real)>) -> Real {
    let points: Vec<(Real, Real)> = points.into_iter().collect();
    let n = points.len() as Real;
    let mx = points.iter().map(|p| p.0).sum::<Real>() / n;
    let my = points.iter().map(|p| p.1).sum::<Real>() / n;
    let (num, den) = points.iter().fold((0.0, 0.0), |(num, den), &(x, y)| {
        (num + (x - mx) * (y - my), den + (x - mx) * (x - mx))
    });
    num / den
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn hat_is_the_cross_product_and_vee_inverts_it() {
        let a = Vec3::new(0.3, -1.2, 2.0);
        let b = Vec3::new(-0.7, 0.4, 1.1);
        assert_relative_eq!(hat(&a) * b, a.cross(&b), epsilon = 1e-15);
        assert_relative_eq!(vee(&hat(&a)), a, epsilon = 1e-15);
    }

    #[test]
    fn rot_axis_agrees_with_nalgebra_and_the_lab_axes() {
        let axis = Vec3::new(1.0, 2.0, -0.5);
        let r = rot_axis(&axis, 0.7);
        let expected =
            nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), 0.7);
        assert_relative_eq!(r, *expected.matrix(), epsilon = 1e-15);
        assert_relative_eq!(rot_axis(&Vec3::z(), 0.3), rot_z(0.3), epsilon = 1e-15);
        assert_relative_eq!(rot_axis(&Vec3::x(), 0.3), rot_x(0.3), epsilon = 1e-15);
        assert_eq!(rot_axis(&Vec3::zeros(), 1.0), Mat3::identity());
    }

    /// J_r⁻¹ checked against a finite difference of the definition
    /// Ω̂ = exp(−σ̂) d/dt exp(σ̂) with σ(t) = σ₀ + t·J_r⁻¹(σ₀)Ω.
    #[test]
    fn dexpinv_right_inverts_the_right_jacobian() {
        for sigma in [Vec3::new(0.01, -0.02, 0.03), Vec3::new(0.9, -0.4, 1.3)] {
            let omega = Vec3::new(0.2, 0.5, -0.3);
            let sdot = dexpinv_right(&sigma, &omega);
            let eps = 1e-6;
            let rp = exp_so3(&(sigma + eps * sdot))
                .to_rotation_matrix()
                .into_inner();
            let rm = exp_so3(&(sigma - eps * sdot))
                .to_rotation_matrix()
                .into_inner();
            let r = exp_so3(&sigma).to_rotation_matrix().into_inner();
            let body = vee(&(r.transpose() * (rp - rm) / (2.0 * eps)));
            assert_relative_eq!(body, omega, epsilon = 1e-8);
        }
    }
}
