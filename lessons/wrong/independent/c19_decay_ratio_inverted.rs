//! assignment: reduced_decay_time
//! mistake: I3^2/I1^2 in place of I1^2/I3^2: ratio^2/(tau Omega3^2)
//! says: upside down

pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    ratio * ratio / (tau * omega3 * omega3)
}
