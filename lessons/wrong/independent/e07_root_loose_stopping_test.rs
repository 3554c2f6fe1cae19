//! assignment: characteristic_root
//! mistake: Newton stopped as soon as |P(s)| < 1e-4, a stopping test far too loose
//! says: far above rounding
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let (m0, m_em) = crate::appendix::shell_masses(tau0, delta);
    let mut s = C::new(0.0, 1.0);
    for _ in 0..100 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        if p.norm() < 1e-4 {
            break;
        }
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        s -= p / dp;
    }
    s
}
