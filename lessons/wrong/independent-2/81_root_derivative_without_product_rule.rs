//! assignment: characteristic_root
//! mistake: P'(s) without the product-rule term -s² m_em δ e^{-sδ}: only 2s(m₀ + m_em e^{-sδ}), and Newton given 20 iterations
//! says: newton, derivative, product rule
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..20 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0);
        let step = p / dp;
        s -= step;
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    s
}
