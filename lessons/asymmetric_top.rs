//! Lesson for the asymmetric top: what changes when I₁ ≠ I₂ ≠ I₃, beyond the
//! paper's Section 4. The reduced ALE for any top, checked against
//! (4.12)–(4.14); the polhode of the free motion; the energy of the truncated
//! model (3.3), which is not monotone; how far the truncated (O(τ)) and the
//! reduced (O(τ²)) models stand from the physical solution of (3.4); and the
//! end states the two laws predict.
//!
//! Run it: `cargo run --release --example asymmetric_top`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::math::{Real, Vec3, least_squares_slope};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::rigid_body::energy;
use spintop::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs};
use spintop::plot::panels::{Panel, panels_svg};
use spintop::plot::{Series, chart};
use spintop::sim::physical::general::{fast_time, general_physical_solution};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
use std::io::{self, Write};

/// The chapter's top: I = (1, 2, 2.5), d = (1, 0.5, 0.2), κ = 1.
fn chapter_top(scale: Real) -> GeneralTop {
    GeneralTop::new(Vec3::new(1.0, 2.0, 2.5), Vec3::new(1.0, 0.5, 0.2) * scale)
        .expect("a rigid body with a dipole")
}

/// Ω at `times` for a model of the general top, by DOP853 at rtol 1e-12.
fn omega_at(model: Model, omega0: Vec3, times: &[Real]) -> Vec<Vec3> {
    let initial = InitialState::new(omega0, EulerAngles::new(0.0, 0.0, 0.0)).expect("finite");
    let options = MethodOptions::default()
        .with_rtol(1e-12)
        .expect("a valid tolerance");
    let last = times.last().copied();
    let mut sim = Simulation::new(model, MethodChoice::Auto, options, initial, last)
        .expect("the run is cheap");
    times
        .iter()
        .map(|&t| sim.advance_to(t).expect("smooth").omega_vec())
        .collect()
}

/// Print the lesson to `out`: its parts in order.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(out, "The asymmetric top: beyond Section 4\n")?;
    reduced_check(out)?;
    // Every part after the first starts the top at the same Omega0.
    let omega0 = Vec3::new(0.3, -0.2, 0.1);
    polhode(out, omega0)?;
    energy_rise(out, omega0)?;
    orders(out, omega0)?;
    end_states(out, omega0)
}

/// The reduced ALE of any top, on a symmetric one, against (4.12)-(4.14).
fn reduced_check(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: reduced_check
    // The reduced ALE of any top, on a symmetric one (I1 = I2 = 1, d on the
    // axis, so tau = d^2): it must be (4.12)-(4.14).
    let symmetric = GeneralTop::new(Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 0.5)).unwrap();
    let paper = SymmetricTop::new(0.4, 0.25).unwrap();
    let omega = Vec3::new(0.3, -0.1, 0.7);
    let gap = (symmetric.reduced_ale_rhs(&omega) - reduced_ale_rhs(&paper, &omega)).norm();
    // ANCHOR_END: reduced_check
    writeln!(
        out,
        "reduced ALE for any top vs (4.12)-(4.14), I = (1, 1, 0.4), d = (0, 0, 0.5): |difference| = {gap:.1e}"
    )?;
    Ok(())
}

/// The free top (a dipole a million times smaller): its polhode, the curve
/// Omega draws in the body, lies where the energy and |L|^2 ellipsoids meet.
fn polhode(out: &mut dyn Write, omega0: Vec3) -> io::Result<()> {
    let free = chapter_top(1e-6);
    let times: Vec<Real> = (0..=600).map(|k| k as Real * 0.1).collect();
    let path = omega_at(Model::General(free), omega0, &times);
    let i = free.inertia();
    let (e0, l0) = (energy(&i, &omega0), i.component_mul(&omega0).norm());
    let drift = path
        .iter()
        .map(|w| {
            ((energy(&i, w) - e0) / e0)
                .abs()
                .max((i.component_mul(w).norm() - l0).abs() / l0)
        })
        .fold(0.0, Real::max);
    writeln!(
        out,
        "\nfree top, I = (1, 2, 2.5), Omega0 = (0.3, -0.2, 0.1): E and |L| kept to {drift:.0e} over t = 60"
    )?;
    let polhode: Vec<(f64, f64)> = path.iter().map(|w| (w.y, w.z)).collect();
    write!(
        out,
        "{}",
        chart(
            "polhode of the free top: (Omega2, Omega3) in the body, a closed loop about axis 1",
            &[Series::line("Omega3 against Omega2", polhode)],
            (-0.25, 0.25),
            80,
            24
        )
    )?;
    Ok(())
}

/// The truncated model (3.3) gains energy for a while: its power changes sign.
fn energy_rise(out: &mut dyn Write, omega0: Vec3) -> io::Result<()> {
    // ANCHOR: energy_rise
    // The truncated model (3.3) of the chapter's top: its power dE/dt =
    // Omega . I dOmega/dt has no fixed sign.
    let top = chapter_top(1.0);
    let i = top.inertia();
    let times: Vec<Real> = (0..=4000).map(|k| k as Real * 0.01).collect();
    let path = omega_at(Model::General(top), omega0, &times);
    let power: Vec<(f64, f64)> = times
        .iter()
        .zip(&path)
        .map(|(&t, w)| (t, w.dot(&i.component_mul(&top.truncated_ale_rhs(w)))))
        .collect();
    let rising: Vec<f64> = power.iter().filter(|p| p.1 > 0.0).map(|p| p.0).collect();
    // ANCHOR_END: energy_rise
    let (first, last) = (rising.first().copied(), rising.last().copied());
    let e_at = |t: Real| energy(&i, &path[(t / 0.01).round() as usize]);
    writeln!(
        out,
        "\ntruncated model (3.3), d = (1, 0.5, 0.2): dE/dt > 0 on {} of 4001 samples, first at t = {:.2}, last at t = {:.2}",
        rising.len(),
        first.unwrap_or(Real::NAN),
        last.unwrap_or(Real::NAN)
    )?;
    writeln!(
        out,
        "  E(10.90) = {:.9}, E(11.00) = {:.9}: a rise of {:.2e}",
        e_at(10.9),
        e_at(11.0),
        e_at(11.0) - e_at(10.9)
    )?;
    write!(
        out,
        "{}",
        chart(
            "power dE/dt of the truncated asymmetric top (3.3), t from 9 to 16: it crosses zero",
            &[
                Series::line(
                    "dE/dt",
                    power
                        .iter()
                        .filter(|p| (9.0..=16.0).contains(&p.0))
                        .copied()
                        .collect()
                ),
                Series::line("0", vec![(9.0, 0.0), (16.0, 0.0)]),
            ],
            (9.0, 16.0),
            100,
            24
        )
    )?;
    Ok(())
}

/// How far the truncated and the reduced models stand from the physical
/// solution of (3.4): O(tau) and O(tau^2).
fn orders(out: &mut dyn Write, omega0: Vec3) -> io::Result<()> {
    // ANCHOR: orders
    // How far the truncated (3.3) and the reduced models stand from the
    // physical solution of (3.4) as tau_f = |d|^2 / min I shrinks (d scaled).
    let times: Vec<Real> = (1..=20).map(|k| k as Real).collect();
    let mut rows = Vec::new();
    for tau in [0.01, 0.02, 0.04, 0.08] {
        let top = chapter_top((tau / 1.29_f64).sqrt());
        let physical = general_physical_solution(&top, &omega0, &times, 1e-12)
            .expect("the shoot converges")
            .omega;
        let gap = |other: Vec<Vec3>| {
            other
                .iter()
                .zip(&physical)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, Real::max)
        };
        let truncated = gap(omega_at(Model::General(top), omega0, &times));
        let reduced = gap(omega_at(Model::GeneralReduced(top), omega0, &times));
        rows.push((fast_time(&top), truncated, reduced));
    }
    let slope = |pick: fn(&(Real, Real, Real)) -> Real| {
        least_squares_slope(rows.iter().map(|r| (r.0.ln(), pick(r).ln())))
    };
    // ANCHOR_END: orders
    writeln!(
        out,
        "\nmax |Omega - Omega_physical| over t = 1..20, Omega0 = (0.3, -0.2, 0.1):"
    )?;
    writeln!(out, "  tau_f      truncated (3.3)   reduced")?;
    for (tau, truncated, reduced) in &rows {
        writeln!(out, "  {tau:<8.3} {truncated:<17.3e} {reduced:.3e}")?;
    }
    writeln!(
        out,
        "  log-log slopes: truncated {:.2} (O(tau)), reduced {:.2} (O(tau^2))",
        slope(|r| r.1),
        slope(|r| r.2)
    )?;
    Ok(())
}

/// The end states: with d along a principal axis, the Schott term spares
/// the spin about d; with d off the axes, both laws drain the energy.
fn end_states(out: &mut dyn Write, omega0: Vec3) -> io::Result<()> {
    let i = chapter_top(1.0).inertia();
    let e0 = energy(&i, &omega0);
    writeln!(
        out,
        "\nenergy left at t = 1000 (E0 = {e0:.4}), I = (1, 2, 2.5), Omega0 = (0.3, -0.2, 0.1):"
    )?;
    for (what, d) in [
        ("d = (0, 0, 0.5), along axis 3", Vec3::new(0.0, 0.0, 0.5)),
        ("d = (1, 0.5, 0.2), off the axes", Vec3::new(1.0, 0.5, 0.2)),
    ] {
        let top = GeneralTop::new(Vec3::new(1.0, 2.0, 2.5), d).unwrap();
        let end = |model| {
            let w = omega_at(model, omega0, &[1000.0])[0];
            (energy(&i, &w), w)
        };
        let (et, _) = end(Model::General(top));
        let (er, wr) = end(Model::GeneralReduced(top));
        let along = wr.dot(&d).abs() / (wr.norm() * d.norm());
        writeln!(
            out,
            "  {what}: truncated {et:.3e}, reduced {er:.3e} (its Omega makes |cos| = {along:.4} with d)"
        )?;
    }
    Ok(())
}

/// The book's figure `figures/asymmetric-energy.svg`: the energy of the
/// chapter's top under (3.3) over t = 0..40, and its power on t = 9..16,
/// where it crosses zero.
#[allow(dead_code)]
pub fn energy_figure() -> String {
    let top = chapter_top(1.0);
    let i = top.inertia();
    let omega0 = Vec3::new(0.3, -0.2, 0.1);
    let times: Vec<Real> = (0..=4000).map(|k| k as Real * 0.01).collect();
    let path = omega_at(Model::General(top), omega0, &times);
    let energy_curve = times
        .iter()
        .zip(&path)
        .step_by(10)
        .map(|(&t, w)| (t, energy(&i, w)))
        .collect();
    let power = times
        .iter()
        .zip(&path)
        .filter(|(t, _)| (9.0..=16.0).contains(*t))
        .map(|(&t, w)| (t, w.dot(&i.component_mul(&top.truncated_ale_rhs(w)))))
        .collect();
    panels_svg(
        "The truncated ALE (3.3), I = (1, 2, 2.5), d = (1, 0.5, 0.2), \u{3a9}\u{2080} = (0.3, -0.2, 0.1), \u{3ba} = 1",
        &[
            Panel {
                caption: "(a) energy E(t): falling on the whole".into(),
                x_label: "t [u]".into(),
                y_label: "E".into(),
                curves: vec![("E".into(), energy_curve)],
            },
            Panel {
                caption: "(b) its power dE/dt: positive from t = 10.8 to 14.1".into(),
                x_label: "t [u]".into(),
                y_label: "dE/dt".into(),
                curves: vec![
                    ("dE/dt".into(), power),
                    ("0".into(), vec![(9.0, 0.0), (16.0, 0.0)]),
                ],
            },
        ],
    )
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
