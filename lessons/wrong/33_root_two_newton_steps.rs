//! assignment: characteristic_root
//! mistake: two Newton steps from s = i, then stopped
//! says: after 2 steps
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..2 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        s -= p / dp;
    }
    s
}
