//! assignment: truncated_closed_form
//! mistake: the clock ϑ = t/(1 + R) instead of 2t/(1 + R), so the phase runs at half speed
//! says: factor 2, clock, phase
use spintop::assignment::Vec3;

pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let r = (1.0 + 2.0 * tau * u0 * t).sqrt();
    let vartheta = t / (1.0 + r);
    let alpha = (1.0 - ratio) * omega0.z * vartheta;
    let (sa, ca) = alpha.sin_cos();
    Vec3::new(
        (omega0.x * ca + omega0.y * sa) / r,
        (omega0.y * ca - omega0.x * sa) / r,
        omega0.z / r,
    )
}
