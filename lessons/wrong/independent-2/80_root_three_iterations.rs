//! assignment: characteristic_root
//! mistake: Newton's method stopped after 3 iterations (for _ in 0..3), before it has converged
//! says: newton, iterations
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..3 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        let step = p / dp;
        s -= step;
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    s
}
