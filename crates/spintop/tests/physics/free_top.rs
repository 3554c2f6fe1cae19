//! The free asymmetric top in closed form (Jacobi's elliptic functions,
//! `physics::free_top`) against an independent method: Euler's equations
//! integrated by DOP853 from the same point, over the polhode and over many
//! periods. (Here rather than beside the closed form: the physics does not
//! import the integrators.)

use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::{Real, State, Vec3};
use spintop::physics::free_top::Polhode;

/// The closed form against Euler's equations integrated by DOP853 from
/// the same point: both families, an elongated and a flat top.
#[test]
fn the_polhode_is_the_free_motion_of_euler_equations() {
    for (inertia, omega0) in [
        (Vec3::new(1.0, 1.5, 2.0), Vec3::new(0.3, 0.0, 1.0)), // round c
        (Vec3::new(2.0, 1.5, 1.0), Vec3::new(0.2, 0.0, 1.0)), // c is axis 0
        (Vec3::new(1.0, 1.5, 2.0), Vec3::new(1.0, 0.0, 0.4)), // round a
        (Vec3::new(0.6, 1.15, 1.75), Vec3::new(0.5, 0.0, -0.7)),
    ] {
        let p = Polhode::through(&inertia, &omega0);
        // The closed form starts where the sn component is zero, with
        // positive cn and dn: flip signs of the data to match it.
        let start = p.omega_at(0.0);
        let flip = Vec3::new(
            omega0[0].signum() * start[0].signum(),
            1.0,
            omega0[2].signum() * start[2].signum(),
        );
        assert!(
            (start.component_mul(&flip) - omega0).norm() < 1e-12,
            "{start} vs {omega0}"
        );
        let rhs = |_t: Real, y: &State<3>| -> State<3> {
            let w = Vec3::new(y[0], y[1], y[2]);
            -(w.cross(&inertia.component_mul(&w))).component_div(&inertia)
        };
        let times: Vec<Real> = (1..=40).map(|k| k as Real * 0.37).collect();
        let mut s = Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-13, 1e-15).unwrap()).unwrap();
        let got = solve(&mut s, &rhs, &times).unwrap();
        // Which way round the polhode the data go is the sign of λ.
        let err = |dir: Real| {
            times
                .iter()
                .zip(&got)
                .map(|(&t, y)| (p.omega_at(dir * t).component_mul(&flip) - y).norm())
                .fold(0.0, Real::max)
        };
        let e = err(1.0).min(err(-1.0));
        assert!(e < 1e-10, "{inertia} {omega0}: {e:e}");
        // And the period: Ω returns to its start after 4K/λ.
        let back = {
            let mut s =
                Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-13, 1e-15).unwrap()).unwrap();
            solve(&mut s, &rhs, &[p.period()]).unwrap()[0]
        };
        assert!((back - omega0).norm() < 1e-10, "period {}", p.period());
    }
}

/// The average over one period equals the average over a long DOP853
/// run (many periods, ends trimmed to whole periods).
#[test]
fn period_averages_match_a_long_run() {
    let inertia = Vec3::new(1.0, 1.5, 2.0);
    let omega0 = Vec3::new(0.6, 0.1, 0.8);
    let f = |w: &Vec3| [w.x * w.x * w.y * w.y, w.z.powi(4), (w.x * w.z).powi(2)];
    let p = Polhode::through(&inertia, &omega0);
    let (avg, n) = p.average(f, 1e-13);
    assert!(n <= 256, "{n} points");
    let periods = 50.0;
    let t_end = periods * p.period();
    let steps = 200_000;
    let rhs = |_t: Real, y: &State<3>| -> State<3> {
        let w = Vec3::new(y[0], y[1], y[2]);
        -(w.cross(&inertia.component_mul(&w))).component_div(&inertia)
    };
    let times: Vec<Real> = (0..=steps)
        .map(|k| t_end * k as Real / steps as Real)
        .collect();
    let mut s = Dop853::new(0.0, omega0, AdaptiveOptions::new(1e-12, 1e-14).unwrap()).unwrap();
    let ys = solve(&mut s, &rhs, &times).unwrap();
    let mut long = [0.0; 3];
    for (k, y) in ys.iter().enumerate() {
        let w = Vec3::new(y[0], y[1], y[2]);
        let weight = if k == 0 || k == steps { 0.5 } else { 1.0 };
        for (l, v) in long.iter_mut().zip(f(&w)) {
            *l += weight * v / steps as Real;
        }
    }
    for (a, b) in avg.iter().zip(long) {
        assert!((a - b).abs() < 1e-8 * a.abs().max(1e-3), "{a} vs {b}");
    }
}
