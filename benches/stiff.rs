//! Radau IIA 5 on two classic stiff problems, Van der Pol with μ = 1000 and
//! Robertson's chemical kinetics: the work it does (Jacobian evaluations, LU
//! decompositions, steps, rejections, right-hand-side evaluations), its error
//! against a reference run at rtol 1e-13, and the median wall time of a solve.
//!
//! `cargo bench -p spintop-benches --bench stiff` prints one line per problem and tolerance.
//! The problems (Hairer & Wanner, *Solving ODEs II*, Sec. IV.10), each with
//! its exact Jacobian: Van der Pol y₁' = y₂, y₂' = μ(1 − y₁²)y₂ − y₁,
//! y(0) = (2, 0), t ∈ [0, 3000] (a relaxation period is (3 − 2 ln 2)μ ≈ 1614);
//! Robertson y₁' = −0.04y₁ + 10⁴y₂y₃, y₃' = 3·10⁷y₂², y₂' = −y₁' − y₃',
//! y(0) = (1, 0, 0), t ∈ [0, 10¹¹], absolute tolerance 10⁻⁶ of rtol.

use nalgebra::SMatrix;
use spintop::integrate::{AdaptiveOptions, Radau5, Rhs, Stepper};
use spintop::math::State;
use spintop::numbers;
use std::time::Instant;

struct VanDerPol {
    mu: f64,
}

impl Rhs<2> for VanDerPol {
    fn eval(&self, _t: f64, y: &State<2>) -> State<2> {
        State::<2>::new(y[1], self.mu * (1.0 - y[0] * y[0]) * y[1] - y[0])
    }
    fn jacobian(&self, _t: f64, y: &State<2>) -> SMatrix<f64, 2, 2> {
        SMatrix::<f64, 2, 2>::new(
            0.0,
            1.0,
            -2.0 * self.mu * y[0] * y[1] - 1.0,
            self.mu * (1.0 - y[0] * y[0]),
        )
    }
}

struct Robertson;

impl Rhs<3> for Robertson {
    fn eval(&self, _t: f64, y: &State<3>) -> State<3> {
        let a = -0.04 * y[0] + 1e4 * y[1] * y[2];
        let c = 3e7 * y[1] * y[1];
        State::<3>::new(a, -a - c, c)
    }
    fn jacobian(&self, _t: f64, y: &State<3>) -> SMatrix<f64, 3, 3> {
        SMatrix::<f64, 3, 3>::new(
            -0.04,
            1e4 * y[2],
            1e4 * y[1],
            0.04,
            -1e4 * y[2] - 6e7 * y[1],
            -1e4 * y[1],
            0.0,
            6e7 * y[1],
            0.0,
        )
    }
}

/// Solve to `t_end`; the end state, the counts and the time of one solve.
fn solve<const N: usize, R: Rhs<N>>(
    rhs: &R,
    y0: State<N>,
    t_end: f64,
    rtol: f64,
    atol: f64,
) -> (State<N>, [u64; 5]) {
    let opts = AdaptiveOptions::new(rtol, atol).expect("valid tolerances");
    let mut s = Radau5::new(0.0, y0, opts).expect("valid start");
    while s.t() < t_end {
        s.step(rhs, t_end).expect("Radau5 solves it");
    }
    let st = s.stats();
    (
        *s.y(),
        [
            s.jacobian_evals(),
            s.lu_decompositions(),
            st.steps,
            st.rejected,
            st.rhs_evals,
        ],
    )
}

fn report<const N: usize, R: Rhs<N>>(name: &str, rhs: &R, y0: State<N>, t_end: f64, atol_rel: f64) {
    let reference = solve(rhs, y0, t_end, 1e-13, 1e-13 * atol_rel).0;
    for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
        let (y, counts) = solve(rhs, y0, t_end, rtol, rtol * atol_rel);
        let err = (0..N)
            .map(|i| ((y[i] - reference[i]) / (reference[i].abs() + atol_rel)).abs())
            .fold(0.0, f64::max);
        let mut times = Vec::new();
        for _ in 0..7 {
            let start = Instant::now();
            std::hint::black_box(solve(rhs, y0, t_end, rtol, rtol * atol_rel));
            times.push(start.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        let [jac, lu, steps, rejected, evals] = counts;
        println!(
            "{name:<22} rtol {rtol}: jacobians {jac:>5} ({:>3}% of steps)  LUs {lu:>5}  steps {steps:>5}  rejected {rejected:>4}  f evals {evals:>6}  error {err}  time {} µs",
            numbers::fixed(100.0 * jac as f64 / steps as f64, 0),
            numbers::fixed(times[3] * 1e6, 0),
            rtol = numbers::exponent(rtol, 0),
            err = numbers::exponent(err, 1)
        );
    }
}

fn main() {
    // Van der Pol, mu = 1000, over one relaxation period and a half (t = 3000).
    report(
        "Van der Pol mu = 1000",
        &VanDerPol { mu: 1000.0 },
        State::<2>::new(2.0, 0.0),
        3000.0,
        1.0,
    );
    // Robertson over [0, 1e11]: y2 stays below 4e-5, so the absolute
    // tolerance is small, 1e-6 of rtol.
    report(
        "Robertson",
        &Robertson,
        State::<3>::new(1.0, 0.0, 0.0),
        1e11,
        1e-6,
    );
}
