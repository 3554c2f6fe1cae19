//! assignment: reduced_decay_time
//! mistake: 1/(tau ratio Omega3^2): the ratio not squared
//! says: enters squared

pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / (tau * ratio * omega3 * omega3)
}
