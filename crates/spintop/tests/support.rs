//! Helpers shared by the core's tests: independent references written from
//! their derivations (never calling the code under test for the answer).

#![allow(dead_code)]

use nalgebra::Complex;
use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::{State, Vec3};
use spintop::physics::symmetric_top::SymmetricTop;

/// The physical solution of (3.4) for the symmetric top from its slow
/// manifold's invariance equation, independently of the 4-dimensional
/// shooting: on the manifold ż = f(u)z, z̈ = (f′(u)u̇ + f²)z with
/// u̇ = 2Re f·u, so (3.4) becomes, in s = ln u,
///
/// ```text
/// df/ds = N(f, u)/(2τ Re f),   N = f + iΩ̃₃ + τ(u + Ω₃²) − 2iτΩ₃f − τf²
/// ```
///
/// started at the slow root f(u → 0) of N(f, 0) = 0 (at u = e⁻⁴⁰, where the
/// root is right to 10⁻¹⁷). Along the way the time spent, dt = ds/(2 Re f),
/// and the phase turned, dθ = Im f ds/(2 Re f), are accumulated; inverting
/// t(s) on a grid of 200 000 points in s gives z(t) (to about 1e-8).
/// Returns z at each of `times`, starting at Ω₁₀ + iΩ₂₀.
pub fn physical_by_invariance_equation(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[f64],
) -> Vec<Complex<f64>> {
    let (tau, omega3) = (top.tau(), omega0.z);
    let k = top.ratio() * omega3;
    let w3t = top.omega3_tilde(omega3);
    let i = Complex::<f64>::new(0.0, 1.0);
    let root = ((Complex::new(1.0, 0.0) - 2.0 * i * tau * omega3)
        - (Complex::<f64>::new(1.0, 0.0) - 4.0 * i * tau * k).sqrt())
        / (2.0 * tau);
    // State (Re f, Im f, elapsed, phase) as functions of s; elapsed = ∫ ds/(−2 Re f),
    // the time to decay from u = e^s down to e^s_min; phase = ∫ Im f ds/(2 Re f).
    let rhs = |s: f64, y: &State<4>| {
        let u = s.exp();
        let f = Complex::new(y[0], y[1]);
        let n =
            f + i * w3t + tau * (u + omega3 * omega3) - 2.0 * i * tau * omega3 * f - tau * f * f;
        let df = n / (2.0 * tau * f.re);
        State::<4>::new(df.re, df.im, -1.0 / (2.0 * f.re), f.im / (2.0 * f.re))
    };
    let z0 = Complex::new(omega0.x, omega0.y);
    let (s_min, s0) = (-40.0f64, z0.norm_sqr().ln());
    let n = 200_000;
    let grid: Vec<f64> = (1..=n)
        .map(|j| s_min + (s0 - s_min) * j as f64 / n as f64)
        .collect();
    let mut stepper = Dop853::new(
        s_min,
        State::<4>::new(root.re, root.im, 0.0, 0.0),
        AdaptiveOptions::new(1e-13, 1e-16).unwrap(),
    )
    .unwrap();
    let path = solve(&mut stepper, &rhs, &grid).unwrap();
    let top_state = path.last().unwrap();
    let (elapsed_top, phase_top) = (top_state[2], top_state[3]);
    // t(s) = elapsed(s0) − elapsed(s), decreasing in s: find s with t(s) = time.
    times
        .iter()
        .map(|&time| {
            let j = path
                .iter()
                .position(|y| elapsed_top - y[2] <= time)
                .expect("time within range");
            let (ta, tb) = (elapsed_top - path[j - 1][2], elapsed_top - path[j][2]);
            let w = (time - ta) / (tb - ta);
            let s = grid[j - 1] + (grid[j] - grid[j - 1]) * w;
            let phase = path[j - 1][3] + (path[j][3] - path[j - 1][3]) * w - phase_top;
            z0 / z0.norm() * (0.5 * s).exp() * (i * phase).exp()
        })
        .collect()
}
