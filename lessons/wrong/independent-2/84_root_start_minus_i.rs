//! assignment: characteristic_root
//! mistake: Newton's method started at s = -i instead of s = i, so it finds the conjugate root
//! says: starting point, conjugate
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, -1.0);
    for _ in 0..100 {
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
