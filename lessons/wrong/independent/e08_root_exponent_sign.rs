//! assignment: characteristic_root
//! mistake: e^{+s delta}: the delay's exponential with the wrong sign
//! says: sign
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let (m0, m_em) = crate::appendix::shell_masses(tau0, delta);
    let mut s = C::new(0.0, 1.0);
    for _ in 0..100 {
        let e = (s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) + s * s * e * delta;
        let step = p / dp;
        s -= step;
        if step.norm() <= 1e-15 * s.norm().max(1.0) {
            break;
        }
    }
    s
}
