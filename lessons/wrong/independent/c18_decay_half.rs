//! assignment: reduced_decay_time
//! mistake: the decay time of the energy, half that of Omega_perp
//! says: 1/2

pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / (2.0 * tau * (ratio * omega3).powi(2))
}
