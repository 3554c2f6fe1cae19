//! assignment: reduced_decay_time
//! mistake: the moment ratio not squared
//! says: enters squared
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / (ratio * omega3 * omega3 * tau)
}
