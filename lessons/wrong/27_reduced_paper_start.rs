//! assignment: reduced_closed_form
//! mistake: Omega_10 = 0 assumed, as the paper prints
//! says: Omega_10 = 0
use spintop::assignment::Vec3;

pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x.hypot(omega0.y);
    let k = ratio * omega0.z;
    let s = 2.0 * tau * k * k * t;
    let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
    let phi = (-0.5 * s).exp() / (1.0 + 2.0 * tau * u0 * u0 * t * g).sqrt();
    let (sa, ca) = ((1.0 - ratio) * omega0.z * t).sin_cos();
    Vec3::new(phi * u0 * sa, phi * u0 * ca, omega0.z)
}
