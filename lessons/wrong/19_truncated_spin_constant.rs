//! assignment: truncated_closed_form
//! mistake: Omega_3 kept at its start value
//! says: held constant
use spintop::assignment::Vec3;

pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x.hypot(omega0.y);
    let r = (1.0 + 2.0 * tau * u0 * u0 * t).sqrt();
    let alpha = (1.0 - ratio) * omega0.z * 2.0 * t / (1.0 + r);
    let (s, c) = alpha.sin_cos();
    Vec3::new(
        (omega0.x * c + omega0.y * s) / r,
        (omega0.y * c - omega0.x * s) / r,
        omega0.z,
    )
}
