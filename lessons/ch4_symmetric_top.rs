//! Lesson for Section 4: the axially symmetric top, truncated against reduced.
//!
//! Run it: `cargo run --release --example ch4_symmetric_top`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::integrate::{AdaptiveOptions, Dop853, Stepper, solve};
use spintop::math::{State, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::symmetric_top::{
    SymmetricTop, precession_tilt, printed_tilt_4_11, reduced_ale_rhs, reduced_closed_form,
    reduced_decay_time, truncated_ale_rhs, truncated_closed_form, truncated_orientation,
};
use spintop::plot::{Series, chart};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
use std::io::{self, Write};

/// Each model's Ω by DOP853 at the sample times: truncated, then reduced.
type Sampled = Vec<Vec<Vec3>>;

/// Print the lesson to `out`: its parts in order.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    writeln!(out, "Section 4: the symmetric top of the paper's figures")?;
    writeln!(
        out,
        "I3/I1 = 0.4, Omega0 = (0, 0.1, 0.2) in units of 1/tau\n"
    )?;
    let (times, sampled) = closed_form_vs_integration(out, top, omega0)?;
    omega_perp_table(out, top, omega0, &times, &sampled)?;
    omega_charts(out, top, omega0, &times, &sampled)?;
    erratum_4_11(out, top, omega0)?;
    tilt_and_end_states(out, top, omega0)
}

/// Both models' Ω integrated by DOP853 against their closed forms; returns
/// the sample times and the integrated Ω at them.
fn closed_form_vs_integration(
    out: &mut dyn Write,
    top: SymmetricTop,
    omega0: Vec3,
) -> io::Result<(Vec<f64>, Sampled)> {
    // ANCHOR: closed_form_vs_integration
    // Integrate each model's Omega with DOP853 and compare with its closed form.
    let times: Vec<f64> = (1..=200).map(|i| 5.0 * i as f64).collect();
    type Rhs = fn(&SymmetricTop, &Vec3) -> Vec3;
    type ClosedForm = fn(&SymmetricTop, &Vec3, f64) -> Vec3;
    let models: [(&str, Rhs, ClosedForm); 2] = [
        (
            "truncated (4.2)-(4.4) vs (4.7)",
            truncated_ale_rhs,
            truncated_closed_form,
        ),
        (
            "reduced (4.12)-(4.14) vs (4.15)-(4.16)",
            reduced_ale_rhs,
            reduced_closed_form,
        ),
    ];
    let mut sampled = Vec::new();
    for (name, rhs, closed) in models {
        let f = |_t: f64, y: &State<3>| rhs(&top, y);
        let opts = AdaptiveOptions::new(1e-12, 1e-20).expect("valid tolerances");
        let mut dop853 = Dop853::new(0.0, omega0, opts).expect("valid start");
        let numeric = solve(&mut dop853, &f, &times).expect("smooth problem");
        let worst = numeric
            .iter()
            .zip(&times)
            .map(|(y, &t)| (y - closed(&top, &omega0, t)).norm() / closed(&top, &omega0, t).norm())
            .fold(0.0, f64::max);
        writeln!(
            out,
            "{name}: DOP853 at rtol 1e-12 over 200 times up to t = 1000: max relative error below 1e{}, {} RHS evaluations",
            worst.log10().ceil(),
            dop853.stats().rhs_evals
        )?;
        sampled.push(numeric);
    }
    // ANCHOR_END: closed_form_vs_integration
    Ok((times, sampled))
}

/// Ω⊥ at five times: each closed form beside its DOP853 value.
fn omega_perp_table(
    out: &mut dyn Write,
    top: SymmetricTop,
    omega0: Vec3,
    times: &[f64],
    sampled: &Sampled,
) -> io::Result<()> {
    writeln!(
        out,
        "\nOmega_perp: closed form against DOP853 (the dots in the chart below sit on the lines)"
    )?;
    writeln!(
        out,
        "{:>6} {:>18} {:>18} {:>18} {:>18}",
        "t", "truncated (4.6)", "DOP853", "reduced (4.16)", "DOP853"
    )?;
    for i in [19, 59, 99, 139, 199] {
        let t = times[i];
        writeln!(
            out,
            "{t:>6} {:>18.10e} {:>18.10e} {:>18.10e} {:>18.10e}",
            truncated_closed_form(&top, &omega0, t).xy().norm(),
            sampled[0][i].xy().norm(),
            reduced_closed_form(&top, &omega0, t).xy().norm(),
            sampled[1][i].xy().norm(),
        )?;
    }
    Ok(())
}

/// Ω⊥(t), Ω₃(t) and the truncated Ω₁(t): closed forms drawn as lines, DOP853 as dots.
fn omega_charts(
    out: &mut dyn Write,
    top: SymmetricTop,
    omega0: Vec3,
    times: &[f64],
    sampled: &Sampled,
) -> io::Result<()> {
    let grid: Vec<f64> = (0..=400).map(|i| 2.5 * i as f64).collect();
    let curve = |f: &dyn Fn(f64) -> f64| grid.iter().map(|&t| (t, f(t))).collect::<Vec<_>>();
    writeln!(out)?;
    write!(
        out,
        "{}",
        chart(
            "Omega_perp(t), 0 <= t <= 1000: closed forms (4.6) and (4.16) against DOP853",
            &[
                Series::line(
                    "truncated, ~ 1/sqrt(t)",
                    curve(&|t| truncated_closed_form(&top, &omega0, t).xy().norm())
                ),
                Series::line(
                    "reduced, ~ exp(-t/sigma)",
                    curve(&|t| reduced_closed_form(&top, &omega0, t).xy().norm())
                ),
                Series::dots("DOP853, both models", {
                    let every = |ys: &Vec<Vec3>| {
                        ys.iter()
                            .zip(times)
                            .step_by(8)
                            .map(|(y, &t)| (t, y.xy().norm()))
                            .collect::<Vec<_>>()
                    };
                    [every(&sampled[0]), every(&sampled[1])].concat()
                }),
            ],
            (0.0, 1000.0),
            120,
            40,
        )
    )?;
    writeln!(out)?;
    write!(
        out,
        "{}",
        chart(
            "Omega_3(t): the truncated spin decays as 1/R(t), the reduced one is constant (4.14)",
            &[
                Series::line(
                    "truncated",
                    curve(&|t| truncated_closed_form(&top, &omega0, t).z)
                ),
                Series::line(
                    "reduced",
                    curve(&|t| reduced_closed_form(&top, &omega0, t).z)
                ),
            ],
            (0.0, 1000.0),
            120,
            32,
        )
    )?;
    writeln!(out)?;
    let early: Vec<f64> = (0..=300).map(|i| 0.5 * i as f64).collect();
    write!(
        out,
        "{}",
        chart(
            "Omega_1(t) of the truncated model, 0 <= t <= 150: closed form and DOP853 samples",
            &[
                Series::line(
                    "closed form (4.7)",
                    early
                        .iter()
                        .map(|&t| (t, truncated_closed_form(&top, &omega0, t).x))
                        .collect()
                ),
                Series::dots("DOP853", {
                    let f = |_t: f64, y: &State<3>| truncated_ale_rhs(&top, y);
                    let ts: Vec<f64> = (1..=30).map(|i| 5.0 * i as f64).collect();
                    let opts = AdaptiveOptions::new(1e-10, 1e-20).expect("valid tolerances");
                    let mut s = Dop853::new(0.0, omega0, opts).expect("valid start");
                    let ys = solve(&mut s, &f, &ts).expect("smooth problem");
                    ts.iter().zip(ys).map(|(&t, y)| (t, y.x)).collect()
                }),
            ],
            (0.0, 150.0),
            120,
            32,
        )
    )?;
    Ok(())
}

/// Erratum (4.11): the tilt of the particular solution, as printed and corrected.
fn erratum_4_11(out: &mut dyn Write, top: SymmetricTop, omega0: Vec3) -> io::Result<()> {
    // ANCHOR: erratum_4_11
    // The particular solution (4.11): L along lab z, so the tilt theta should stay fixed.
    let corrected = precession_tilt(&top, &omega0); // arctan(I1 Omega20 / (I3 Omega30))
    let printed = printed_tilt_4_11(&top, &omega0); // arctan(Omega20 / Omega3~0), as printed
    let theta_range = |theta0: f64| {
        let o0 = EulerAngles::new(0.0, theta0, 0.0).to_rotation();
        (0..=500)
            .map(|i| {
                let o = truncated_orientation(&top, &omega0, &o0, 2.0 * i as f64);
                EulerAngles::from_rotation(&o).theta
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), th| {
                (lo.min(th), hi.max(th))
            })
    };
    // ANCHOR_END: erratum_4_11
    writeln!(out, "\nErratum (4.11): the tilt of the particular solution")?;
    let (lo, hi) = theta_range(corrected);
    writeln!(
        out,
        "  corrected arctan(I1 W20/(I3 W30)) = {corrected:.4} rad: theta stays in [{lo:.4}, {hi:.4}]"
    )?;
    let (lo, hi) = theta_range(printed);
    writeln!(
        out,
        "  printed   arctan(W20/W3~0)       = {printed:.4} rad: theta wanders over [{lo:.4}, {hi:.4}]"
    )?;
    Ok(())
}

/// The tilt between the axis and L under both models, and where each ends.
fn tilt_and_end_states(out: &mut dyn Write, top: SymmetricTop, omega0: Vec3) -> io::Result<()> {
    writeln!(
        out,
        "\nThe tilt between the symmetry axis and L, started from (phi, theta, psi) = (0, 0, 0):"
    )?;
    writeln!(out, "{:>8} {:>12} {:>12}", "t", "truncated", "reduced")?;
    let initial = InitialState::new(omega0, EulerAngles::new(0.0, 0.0, 0.0)).expect("finite");
    let options = MethodOptions::default();
    let mut trunc = Simulation::new(
        Model::Truncated(top),
        MethodChoice::Auto,
        options,
        initial,
        None,
    )
    .expect("valid");
    let mut red = Simulation::new(
        Model::Reduced(top),
        MethodChoice::Auto,
        options,
        initial,
        None,
    )
    .expect("valid");
    for t in [0.0, 250.0, 500.0, 1000.0, 2000.0, 3000.0] {
        let a = trunc.advance_to(t).expect("closed form").tilt;
        let b = red.advance_to(t).expect("smooth").tilt;
        writeln!(out, "{t:>8} {a:>12.4e} {b:>12.4e}")?;
    }
    let sigma = reduced_decay_time(&top, omega0.z);
    writeln!(
        out,
        "  reduced decay time sigma = I1^2/(I3^2 Omega3^2 tau) = {sigma:.2}"
    )?;

    let a = *trunc.current();
    let b = *red.current();
    writeln!(out, "\nEnd states at t = 3000:")?;
    writeln!(
        out,
        "  truncated: E = {:.4e}, |L| = {:.4e}, still tilted by {:.4} rad and still slowing",
        a.energy,
        Vec3::from(a.l_lab).norm(),
        a.tilt
    )?;
    writeln!(
        out,
        "  reduced:   E = {:.6}, |L| = {:.6}: the top spins about its axis with E = I3 W3^2/2 = {:.6}, L = I3 W3 = {:.6}",
        b.energy,
        Vec3::from(b.l_lab).norm(),
        0.5 * 0.4 * 0.2f64.powi(2),
        0.4 * 0.2
    )?;
    writeln!(
        out,
        "  reduced, lab frame: theta = {:.4} rad, the angle between lab z and L, not 0 (erratum (4.18))",
        b.euler[1]
    )?;
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
