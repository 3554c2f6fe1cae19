//! assignment: characteristic_root
//! mistake: a wrong stopping test: it stops once the Newton step is below 1e-3 and throws that last step away instead of applying it
//! says: newton, stopping test, tolerance
use spintop::assignment::C;

pub fn characteristic_root(tau0: f64, delta: f64) -> C {
    let m_em = tau0 / delta;
    let m0 = 1.0 - m_em;
    let mut s = C::new(0.0, 1.0);
    for _ in 0..100 {
        let e = (-s * delta).exp() * m_em;
        let p = s * s * (e + m0) + 1.0;
        let dp = s * 2.0 * (e + m0) - s * s * e * delta;
        let step = p / dp;
        if step.norm() < 1e-3 {
            break;
        }
        s -= step;
    }
    s
}
