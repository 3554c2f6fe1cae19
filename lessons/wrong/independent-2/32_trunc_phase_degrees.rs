//! assignment: truncated_closed_form
//! mistake: the precession angle α treated as degrees and converted with to_radians before sin and cos
//! says: degrees, radians, phase
use spintop::assignment::Vec3;

pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let r = (1.0 + 2.0 * tau * u0 * t).sqrt();
    let vartheta = 2.0 * t / (1.0 + r);
    let alpha = (1.0 - ratio) * omega0.z * vartheta;
    let (sa, ca) = alpha.to_radians().sin_cos();
    Vec3::new(
        (omega0.x * ca + omega0.y * sa) / r,
        (omega0.y * ca - omega0.x * sa) / r,
        omega0.z / r,
    )
}
