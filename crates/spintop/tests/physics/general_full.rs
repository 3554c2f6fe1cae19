//! The physical (non-runaway) solution of the full ALE (3.4) for any top,
//! `general_physical_solution`, checked three independent ways:
//! (a) it satisfies (3.4) in integrated form along the computed solution,
//! with Ω̇ the manifold's own rate and no difference quotient of the output;
//! (b) for I₁ = I₂ and d on the axis it is the symmetric top's physical
//! solution (backward shooting on one amplitude, a different code path);
//! (c) as τ → 0 it meets the reduced general model with an error ∝ τ², while
//! the truncated model (3.3) stays O(τ) away.

use spintop::math::{Real, Vec3};
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::physical::general::{
    fast_time, general_integrate_forward, general_physical_solution, near_manifold,
};
use spintop::sim::physical::physical_solution;

/// The asymmetric top of the book's chapter.
fn asymmetric(scale: Real) -> GeneralTop {
    GeneralTop::new(Vec3::new(1.0, 2.0, 2.5), Vec3::new(1.0, 0.5, 0.2) * scale).unwrap()
}

fn grid(t_end: Real, h: Real) -> Vec<Real> {
    let n = (t_end / h).round() as usize;
    (0..=n).map(|i| i as Real * h).collect()
}

/// Composite Simpson's rule of equally spaced vectors (an even number of panels).
fn simpson(values: &[Vec3], h: Real) -> Vec3 {
    let n = values.len() - 1;
    assert!(n.is_multiple_of(2));
    let mut sum = values[0] + values[n];
    for (i, v) in values.iter().enumerate().take(n).skip(1) {
        sum += v * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * (h / 3.0)
}

/// (a) (3.4), I Ω̇ + Ω × IΩ = d × {d × (Ω²Ω − Ω̈) + (d·Ω̇)Ω + 2(d·Ω)Ω̇},
/// integrated over [t_a, t_b]: the Ω̈ term integrates to the jump of Ω̇, and
/// Ω̇ is the W the slow manifold gives at each time. Also Ω(t_b) − Ω(t_a) =
/// ∫Ω̇ dt. Both residuals are compared with the size of the terms.
#[test]
fn eq_3_4_general_physical_solution_satisfies_the_equation_in_integrated_form() {
    let top = asymmetric(0.3);
    let omega0 = Vec3::new(0.3, -0.2, 0.1);
    let h = 0.005;
    let times = grid(20.0, h);
    let sol = general_physical_solution(&top, &omega0, &times, 1e-12).unwrap();
    let (i, d) = (top.inertia(), top.dipole());
    let per_time = |k: usize| {
        let (om, w) = (sol.omega[k], sol.omega_dot[k]);
        let torque =
            d.cross(&(d.cross(&(om.norm_squared() * om)) + d.dot(&w) * om + 2.0 * d.dot(&om) * w));
        om.cross(&i.component_mul(&om)) - torque
    };
    let mut worst: Real = 0.0;
    for (a, b) in [(0, 400), (400, 2000), (1000, 4000)] {
        let inner: Vec<Vec3> = (a..=b).map(per_time).collect();
        let jump = sol.omega_dot[b] - sol.omega_dot[a];
        let residual = i.component_mul(&(sol.omega[b] - sol.omega[a]))
            + simpson(&inner, h)
            + d.cross(&d.cross(&jump));
        let size = i.component_mul(&(sol.omega[b] - sol.omega[a])).norm();
        worst = worst.max(residual.norm() / size);
        let w_int = simpson(&sol.omega_dot[a..=b], h);
        let kin = (sol.omega[b] - sol.omega[a] - w_int).norm() / size;
        assert!(
            kin < 1e-8,
            "[{a}, {b}]: Omega jump vs integral of W: {kin:e}"
        );
    }
    println!("integrated residual of (3.4): {worst:e} (relative)");
    assert!(worst < 1e-8, "relative residual of (3.4) {worst:e}");
    // The first-order part of (3.4), along d: d·(IΩ̇ + Ω × IΩ) = 0.
    for k in (0..times.len()).step_by(97) {
        let (om, w) = (sol.omega[k], sol.omega_dot[k]);
        let c = d.dot(&(i.component_mul(&w) + om.cross(&i.component_mul(&om))));
        assert!(c.abs() < 1e-10, "constraint at t = {}: {c:e}", times[k]);
    }
}

/// (b) A symmetric top (I₁ = I₂ = 1, d on the axis, τ = d²) through the general
/// 3-D shoot gives the symmetric physical solution (a 1-D shoot with the phase
/// fixed by symmetry) to 1e-9.
#[test]
fn eq_3_4_general_physical_solution_for_i1_eq_i2_is_the_symmetric_one() {
    for (tau, omega0) in [
        (1.0, Vec3::new(0.0, 0.1, 0.2)),
        (0.2, Vec3::new(0.3, -0.4, 0.5)),
    ] {
        let general = GeneralTop::new(
            Vec3::new(1.0, 1.0, 0.4),
            Vec3::new(0.0, 0.0, Real::sqrt(tau)),
        )
        .unwrap();
        let symmetric = SymmetricTop::new(0.4, tau).unwrap();
        let times = [0.0, 1.0, 10.0, 50.0, 100.0];
        let g = general_physical_solution(&general, &omega0, &times, 1e-12).unwrap();
        let s = physical_solution(&symmetric, &omega0, &times, 1e-12).unwrap();
        for (k, t) in times.iter().enumerate() {
            let z = s.z[k];
            let expected = Vec3::new(z.re, z.im, omega0.z);
            let err = (g.omega[k] - expected).norm();
            println!(
                "tau = {tau}, t = {}: general vs symmetric physical {err:e}",
                times[k]
            );
            assert!(
                err < 1e-9,
                "tau = {tau}, t = {t}: {:?} vs {expected:?} ({err:e})",
                g.omega[k]
            );
            let v = s.z_dot[k];
            let err = (g.omega_dot[k] - Vec3::new(v.re, v.im, 0.0)).norm();
            assert!(err < 1e-9, "tau = {tau}, t = {t}: rate off by {err:e}");
        }
    }
}

/// Max |Ω_a − Ω_b| over the samples.
fn max_gap(a: &[Vec3], b: &[Vec3]) -> Real {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, Real::max)
}

/// Integrate Ω̇ = f(Ω) with a fine RK4 (an independent integrator) to the times.
fn rk4(f: impl Fn(&Vec3) -> Vec3, omega0: Vec3, times: &[Real], h: Real) -> Vec<Vec3> {
    let mut out = Vec::new();
    let (mut t, mut y) = (0.0, omega0);
    for &target in times {
        while t < target - 1e-12 {
            let s = h.min(target - t);
            let k1 = f(&y);
            let k2 = f(&(y + k1 * (s / 2.0)));
            let k3 = f(&(y + k2 * (s / 2.0)));
            let k4 = f(&(y + k3 * s));
            y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (s / 6.0);
            t += s;
        }
        out.push(y);
    }
    out
}

/// (c) As τ → 0 (the dipole scaled down), the physical solution and the reduced
/// general model part by O(τ²): the log-log slope over four values of τ is 2.
/// The truncated model (3.3) stays O(τ) away (slope 1).
#[test]
fn eq_3_4_general_physical_solution_approaches_the_reduced_model_like_tau_squared() {
    let omega0 = Vec3::new(0.3, -0.2, 0.1);
    let times: Vec<Real> = (1..=20).map(|k| k as Real).collect();
    let mut reduced_pts = Vec::new();
    let mut truncated_pts = Vec::new();
    for tau in [0.01, 0.02, 0.04, 0.08] {
        // τ_f = |d|²/min I = |d|² here (min I = 1).
        let top = asymmetric((tau / 1.29_f64).sqrt());
        assert!((fast_time(&top) - tau).abs() < 1e-12);
        let phys = general_physical_solution(&top, &omega0, &times, 1e-12).unwrap();
        let red = rk4(|w| top.reduced_ale_rhs(w), omega0, &times, 1e-3);
        let tru = rk4(|w| top.truncated_ale_rhs(w), omega0, &times, 1e-3);
        reduced_pts.push((tau.ln(), max_gap(&phys.omega, &red).ln()));
        truncated_pts.push((tau.ln(), max_gap(&phys.omega, &tru).ln()));
    }
    let slope = spintop::math::least_squares_slope(reduced_pts.iter().copied());
    let slope_truncated = spintop::math::least_squares_slope(truncated_pts.iter().copied());
    println!(
        "physical vs reduced: slope {slope:.3}; physical vs truncated (3.3): slope {slope_truncated:.3}"
    );
    assert!(
        (slope - 2.0).abs() < 0.15,
        "physical vs reduced: log-log slope {slope:.3} (expected 2)"
    );
    assert!(
        (slope_truncated - 1.0).abs() < 0.15,
        "physical vs truncated: slope {slope_truncated:.3} (expected 1)"
    );
}

/// Forward, (3.4) of the same top runs away from the reduced model's slope:
/// the monitor stops it within a few τ_f and measures a growth rate of order
/// 1/τ_f; from the physical solution's own state it stays put far longer.
#[test]
fn eq_3_4_general_forward_integration_runs_away() {
    let top = asymmetric(0.3);
    let tau_f = fast_time(&top);
    let omega0 = Vec3::new(0.3, -0.2, 0.1);
    let run = general_integrate_forward(&top, near_manifold(&top, &omega0), 200.0 * tau_f, 1e-10)
        .unwrap();
    let r = run.runaway.expect("a runaway");
    assert!(r.t < 40.0 * tau_f, "detected at {}", r.t);
    assert!(
        r.growth_rate * tau_f > 0.5 && r.growth_rate * tau_f < 5.0,
        "rate {}",
        r.growth_rate * tau_f
    );
    let phys = general_physical_solution(&top, &omega0, &[0.0], 1e-13).unwrap();
    let mut y = near_manifold(&top, &omega0);
    y.fixed_rows_mut::<3>(3).copy_from(&phys.omega_dot[0]);
    let run = general_integrate_forward(&top, y, 200.0 * tau_f, 1e-13).unwrap();
    let later = run.runaway.map_or(Real::INFINITY, |r| r.t);
    assert!(
        later > r.t + 10.0 * tau_f,
        "from the manifold: {later} vs {}",
        r.t
    );
}

/// The live view runs the full models open-ended: the physical solution is
/// tabulated 50 fast times ahead and extended from the state at the end of
/// each chunk. Through several chunks it agrees with one run over the whole
/// horizon (Ω and the orientation), for the general and the symmetric top.
#[test]
fn eq_3_4_open_ended_physical_runs_continue_chunk_by_chunk() {
    use spintop::physics::euler_angles::EulerAngles;
    use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
    let initial =
        InitialState::new(Vec3::new(0.3, -0.2, 0.1), EulerAngles::new(0.1, 0.4, 0.2)).unwrap();
    let options = MethodOptions::default()
        .with_rtol(1e-12)
        .expect("a valid tolerance");
    let models = [
        Model::GeneralFull(asymmetric(0.3)),
        Model::Full(SymmetricTop::new(0.4, 0.05).unwrap()),
    ];
    for model in models {
        let times: Vec<Real> = (1..=30).map(|k| k as Real * 0.5).collect();
        let t_last = *times.last().unwrap();
        let mut whole =
            Simulation::new(model, MethodChoice::Auto, options, initial, Some(t_last)).unwrap();
        let mut open = Simulation::new(model, MethodChoice::Auto, options, initial, None).unwrap();
        for &t in &times {
            let a = *whole.advance_to(t).unwrap();
            let b = *open.advance_to(t).unwrap();
            let dw = (a.omega_vec() - b.omega_vec()).norm();
            let dr = (a.rotation_matrix() - b.rotation_matrix()).norm();
            assert!(
                dw < 1e-9 && dr < 1e-8,
                "{} at t = {t}: omega {dw:e}, rotation {dr:e}",
                model.name()
            );
        }
    }
}

/// Shot at a loose rtol, the table `auto` reads the physical solution from
/// stays within rtol of the tight solution over many segments. Each segment's
/// output pass stops at every table time and its Newton shots only at the
/// segment's start, so the pass began off the previous segment's end by the
/// shots' own error, and the jumps added up: 2.3e-2 of |Ω₀| at rtol 1e-2,
/// 1.8e-6 at rtol 1e-6, by t = 300.
#[test]
fn eq_3_4_general_physical_table_stays_within_rtol_at_a_loose_rtol() {
    use spintop::sim::physical::general::general_physical_table;
    let top = GeneralTop::new(Vec3::new(1.0, 1.2, 0.5), Vec3::new(0.2, 0.0, 0.3)).unwrap();
    let omega0 = Vec3::new(0.5, 0.05, 0.02);
    let (tight, _) = general_physical_table(&top, &omega0, 300.0, 1e-12, 1.0).unwrap();
    for rtol in [1e-2, 1e-4, 1e-6] {
        let (table, _) = general_physical_table(&top, &omega0, 300.0, rtol, 1.0).unwrap();
        let worst = (0..=300)
            .map(|t| (table.omega_at(t as Real) - tight.omega_at(t as Real)).norm())
            .fold(0.0, Real::max)
            / omega0.norm();
        assert!(worst <= rtol, "rtol {rtol:e}: off by {worst:e} of |Omega0|");
        assert!((table.omega_at(0.0) - omega0).norm() <= 1e-3 * rtol * omega0.norm());
    }
}
