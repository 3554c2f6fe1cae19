//! assignment: truncated_omega_perp
//! mistake: 1 + 2 tau Omega_perp0 t under the root: Omega_perp0 not squared
//! says: once, not squared

pub fn truncated_omega_perp(_ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    omega_perp0 / (1.0 + 2.0 * tau * omega_perp0 * t).sqrt()
}
