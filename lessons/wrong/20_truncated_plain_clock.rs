//! assignment: truncated_closed_form
//! mistake: the phase on t instead of the slowed clock
//! says: ordinary clock
use spintop::assignment::Vec3;

pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x.hypot(omega0.y);
    let r = (1.0 + 2.0 * tau * u0 * u0 * t).sqrt();
    let (s, c) = ((1.0 - ratio) * omega0.z * t).sin_cos();
    Vec3::new(
        (omega0.x * c + omega0.y * s) / r,
        (omega0.y * c - omega0.x * s) / r,
        omega0.z / r,
    )
}
