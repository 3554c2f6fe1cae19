//! Row 4 of the stability suite: a free asymmetric top (τ = 0, I = (1, 2, 3))
//! over long times.
//!
//! A torque-free body keeps its energy, its |L| and its lab-frame angular
//! momentum O L (paper (3.2) with no torque). These tests pin down what the
//! row claims about keeping them up to t = 10⁴: RK4 at a fixed step and DP5 at
//! a fixed tolerance drift, their energy and |L| errors growing linearly in t
//! (log-log slope within 0.8..1.2), while the Strang and Yoshida-4 splittings at
//! the same step keep the energy error bounded (the error at 10⁴ is within a
//! small factor of the error at 10²) and |L| and the lab L to rounding
//! (≲ 8ε√steps). The splittings' orders, measured against DOP853, are 2 and 4.
//! The references are the invariants at t = 0, never earlier output.

use spintop::stability::long_run::{Drift, Measurement, STEP, TIMES, log_log_slope, measure};
use std::sync::OnceLock;

fn measurement() -> &'static Measurement {
    static M: OnceLock<Measurement> = OnceLock::new();
    M.get_or_init(|| measure().expect("row 4 runs"))
}

fn grows_linearly(d: &Drift) {
    for (what, slope) in [("energy", d.energy_slope), ("|L|", d.l_norm_slope)] {
        assert!(
            (0.8..=1.2).contains(&slope),
            "{:?}: {what} error slope {slope} ({:?}, {:?})",
            d.method,
            d.energy_error,
            d.l_norm_error
        );
    }
    // Linear growth over two decades: a factor of about 100, not a bounded error.
    assert!(
        d.energy_ratio() > 30.0,
        "{:?}: {:?}",
        d.method,
        d.energy_error
    );
    // The lab L drifts too (its error at 10² still holds an oscillating part,
    // so only growth is asserted).
    assert!(d.l_lab_error[2] > 5.0 * d.l_lab_error[0], "{:?}", d.method);
    assert!(!d.conserves());
}

#[test]
fn sec3_free_top_rk4_and_dp5_energy_and_l_errors_grow_linearly_in_t() {
    let m = measurement();
    grows_linearly(&m.rk4);
    grows_linearly(&m.dopri5);
}

#[test]
fn sec3_free_top_strang_and_yoshida_keep_the_energy_error_bounded() {
    let m = measurement();
    for d in [&m.strang, &m.yoshida4] {
        assert!(
            d.energy_ratio() < 1.5,
            "{:?}: energy error {:?} grows",
            d.method,
            d.energy_error
        );
        assert!(d.energy_slope.abs() < 0.1, "{:?}", d.method);
        // Bounded, and of the size the order predicts: Strang's O(h²) error is
        // far above Yoshida's O(h⁴) one at the same step.
        assert!(d.energy_error[2] > 0.0);
    }
    assert!(m.strang.energy_error[2] > 100.0 * m.yoshida4.energy_error[2]);
}

#[test]
fn eq_3_2_splittings_keep_l_norm_and_lab_l_to_rounding() {
    let m = measurement();
    for d in [&m.strang, &m.yoshida4] {
        let bound = 8.0 * f64::EPSILON * (d.stats.steps as f64).sqrt();
        assert!(bound < 1e-12);
        for i in 0..TIMES.len() {
            assert!(
                d.l_norm_error[i] <= bound,
                "{:?}: {:?}",
                d.method,
                d.l_norm_error
            );
            assert!(
                d.l_lab_error[i] <= bound,
                "{:?}: {:?}",
                d.method,
                d.l_lab_error
            );
        }
        assert!(d.conserves());
    }
    // The explicit methods are many orders of magnitude away from that.
    assert!(m.rk4.l_lab_error[2] > 1e4 * m.strang.l_lab_error[2]);
    assert!(m.dopri5.l_lab_error[2] > 1e4 * m.strang.l_lab_error[2]);
}

#[test]
fn splitting_orders_are_2_and_4() {
    let m = measurement();
    assert!((m.strang_order - 2.0).abs() < 0.1, "{}", m.strang_order);
    assert!(
        (m.yoshida4_order - 4.0).abs() < 0.15,
        "{}",
        m.yoshida4_order
    );
}

/// Work: t = 10⁴ at h = 0.05 is 200 000 steps; a Strang step is 5 axis
/// rotations, a Yoshida-4 step 13 (three Strang steps, merged where adjacent
/// rotations share an axis); an RK4 step 4 evaluations.
#[test]
fn work_counts_follow_from_the_step() {
    let m = measurement();
    let steps = (TIMES[2] / STEP).round() as u64;
    assert_eq!(m.strang.stats.steps, steps);
    assert_eq!(m.strang.stats.rhs_evals, 5 * steps);
    assert_eq!(m.yoshida4.stats.steps, steps);
    assert_eq!(m.yoshida4.stats.rhs_evals, 13 * steps);
    assert_eq!(m.rk4.stats.rhs_evals, 4 * m.rk4.stats.steps);
    assert!((steps..steps + 4).contains(&m.rk4.stats.steps));
    assert!(m.dopri5.stats.steps > 0 && m.dopri5.stats.rejected < m.dopri5.stats.steps);
}

#[test]
fn row_4_shows_the_explicit_methods_failing_and_the_splittings_holding() {
    let row = measurement().row();
    assert_eq!(row.number, 4);
    assert!(row.holds(), "{row:#?}");
    assert_eq!(row.naive.len(), 2);
    assert_eq!(row.fix.len(), 2);
    assert!(row.naive.iter().all(|o| !o.ok));
    assert!(row.fix.iter().all(|o| o.ok));
    assert!(row.notes.iter().any(|n| n.contains("Yoshida-4")));
}

#[test]
fn log_log_slope_recovers_power_laws() {
    let t = [1e2, 1e3, 1e4];
    assert!((log_log_slope(&t, &[3e-9, 3e-8, 3e-7]) - 1.0).abs() < 1e-12);
    assert!(log_log_slope(&t, &[5e-6, 5e-6, 5e-6]).abs() < 1e-12);
    assert!((log_log_slope(&t, &[1.0, 1e-2, 1e-4]) + 2.0).abs() < 1e-12);
}
