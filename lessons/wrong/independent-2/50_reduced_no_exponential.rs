//! assignment: reduced_closed_form
//! mistake: the exponential factor e^{-s/2} of Φ left out, only 1/√(1 + 2τΩ⊥₀²t (1 - e^{-s})/s)
//! says: exponential, missing factor
use spintop::assignment::Vec3;

pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = ratio * omega0.z;
    let s = 2.0 * tau * k * k * t;
    let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
    let phi = 1.0 / (1.0 + 2.0 * tau * u0 * t * g).sqrt();
    let alpha = (1.0 - ratio) * omega0.z * t;
    let (sa, ca) = alpha.sin_cos();
    Vec3::new(
        phi * (omega0.x * ca + omega0.y * sa),
        phi * (omega0.y * ca - omega0.x * sa),
        omega0.z,
    )
}
