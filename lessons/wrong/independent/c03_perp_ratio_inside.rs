//! assignment: truncated_omega_perp
//! mistake: the ratio I3/I1 slipped into the rate: 1 + 2 tau ratio Omega_perp0^2 t
//! says: does not involve the moment ratio

pub fn truncated_omega_perp(ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    omega_perp0 / (1.0 + 2.0 * tau * ratio * omega_perp0 * omega_perp0 * t).sqrt()
}
