use spintop::assignment::Vec3;

/// Eqs. (4.5)-(4.6): Ω⊥ = Ω⊥₀/R, R = √(1 + 2τΩ⊥₀²t).
pub fn truncated_omega_perp(_ratio: f64, tau: f64, omega_perp0: f64, t: f64) -> f64 {
    omega_perp0 / (1.0 + 2.0 * tau * omega_perp0 * omega_perp0 * t).sqrt()
}

/// Eq. (4.7) for any start: every component over R, the phase on the clock ϑ = 2t/(1 + R).
pub fn truncated_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let r = (1.0 + 2.0 * tau * u0 * t).sqrt();
    let vartheta = 2.0 * t / (1.0 + r);
    let alpha = (1.0 - ratio) * omega0.z * vartheta;
    let (sa, ca) = alpha.sin_cos();
    Vec3::new(
        (omega0.x * ca + omega0.y * sa) / r,
        (omega0.y * ca - omega0.x * sa) / r,
        omega0.z / r,
    )
}

/// Eq. (4.6) inverted: R = 1/p.
pub fn truncated_time_to_factor(_ratio: f64, tau: f64, omega_perp0: f64, p: f64) -> f64 {
    (1.0 / (p * p) - 1.0) / (2.0 * tau * omega_perp0 * omega_perp0)
}

/// Eq. (4.11), corrected: tan θ = I₁Ω⊥₀/(I₃Ω₃₀).
pub fn precession_tilt(ratio: f64, omega0: Vec3) -> f64 {
    omega0.x.hypot(omega0.y).atan2(ratio * omega0.z)
}

/// Eqs. (4.12)-(4.14).
pub fn reduced_ale_rhs(ratio: f64, tau: f64, omega: Vec3) -> Vec3 {
    let precession = (1.0 - ratio) * omega.z;
    let damping = tau * (omega.x * omega.x + omega.y * omega.y + (ratio * omega.z).powi(2));
    Vec3::new(
        precession * omega.y - damping * omega.x,
        -precession * omega.x - damping * omega.y,
        0.0,
    )
}

/// Eq. (4.16): σ = I₁²/(I₃²Ω₃²τ).
pub fn reduced_decay_time(ratio: f64, tau: f64, omega3: f64) -> f64 {
    1.0 / ((ratio * omega3).powi(2) * tau)
}

/// Eqs. (4.15)-(4.16), with Φ written as e^{−s/2}/√(1 + 2τΩ⊥₀²t (1 − e^{−s})/s).
pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = ratio * omega0.z;
    let s = 2.0 * tau * k * k * t;
    let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
    let phi = (-0.5 * s).exp() / (1.0 + 2.0 * tau * u0 * t * g).sqrt();
    let alpha = (1.0 - ratio) * omega0.z * t;
    let (sa, ca) = alpha.sin_cos();
    Vec3::new(
        phi * (omega0.x * ca + omega0.y * sa),
        phi * (omega0.y * ca - omega0.x * sa),
        omega0.z,
    )
}
