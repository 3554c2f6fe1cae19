//! assignment: reduced_closed_form
//! mistake: the paper's start Ω₁₀ = 0 assumed: Ω⊥ = Φ Ω⊥₀ (sin α, cos α) with phase 0 on Ω₂, so any start with Ω₁₀ ≠ 0 gets the wrong initial phase
//! says: initial phase, phase
use spintop::assignment::Vec3;

pub fn reduced_closed_form(ratio: f64, tau: f64, omega0: Vec3, t: f64) -> Vec3 {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let perp0 = u0.sqrt();
    let k = ratio * omega0.z;
    let s = 2.0 * tau * k * k * t;
    let g = if s == 0.0 { 1.0 } else { -(-s).exp_m1() / s };
    let phi = (-0.5 * s).exp() / (1.0 + 2.0 * tau * u0 * t * g).sqrt();
    let alpha = (1.0 - ratio) * omega0.z * t;
    let (sa, ca) = alpha.sin_cos();
    Vec3::new(phi * perp0 * sa, phi * perp0 * ca, omega0.z)
}
