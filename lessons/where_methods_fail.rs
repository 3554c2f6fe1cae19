//! Lesson for the chapter "Where methods fail": the six rows of the stability
//! suite, each with the naive method beside spintop's, and charts of the
//! failures.
//!
//! Run it: `cargo run --release --example where_methods_fail`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::integrate::{AdaptiveOptions, Composition, Dop853, Rk4, Splitting, Stepper, solve};
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::free_top::{FreeRigidBody, RigidBodyState};
use spintop::physics::full_ale::symmetric_full_ale_rhs;
use spintop::physics::shell::ShellModel;
use spintop::physics::symmetric_top::{
    FIGURE_OMEGA0, SymmetricTop, reduced_ale_rhs, reduced_amplitude,
};
use spintop::plot::{Series, chart};
use spintop::sim::physical::physical_solution;
use spintop::sim::shell::{History, default_steps_per_delay, run_shell};
use spintop::stability;
use std::io::{self, Write};

fn row(out: &mut dyn Write, n: u8) -> io::Result<()> {
    match stability::row(n) {
        Ok(row) => write!(out, "{row}"),
        Err(e) => writeln!(out, "{e}"),
    }
}

/// log10 |z(t)| of (3.4) integrated forward from the reduced slope, with no
/// monitor, against the physical solution and the reduced model.
fn runaway_chart() -> String {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::from(FIGURE_OMEGA0);
    let times: Vec<f64> = (0..=80).map(|i| 0.1 * i as f64).collect();
    // ANCHOR: forward
    let slope = reduced_ale_rhs(&top, &omega0);
    let y0 = State::<4>::new(omega0.x, omega0.y, slope.x, slope.y);
    let rhs = |_t: f64, y: &State<4>| symmetric_full_ale_rhs(&top, omega0.z, y);
    let opts = AdaptiveOptions::new(1e-10, 1e-14).expect("valid tolerances");
    let mut stepper = Dop853::new(0.0, y0, opts).expect("a finite start");
    let forward = solve(&mut stepper, &rhs, &times).expect("finite to t = 8");
    // ANCHOR_END: forward
    let physical = physical_solution(&top, &omega0, &times, 1e-10).expect("the shoot converges");
    let log = |x: f64| x.log10();
    let series = [
        Series::line(
            "forward (3.4)",
            times
                .iter()
                .zip(&forward)
                .map(|(&t, y)| (t, log(y[0].hypot(y[1]))))
                .collect(),
        ),
        Series::dots(
            "physical (backward)",
            times
                .iter()
                .zip(&physical.z)
                .map(|(&t, z)| (t, log(z.norm())))
                .collect(),
        ),
        Series::line(
            "reduced (4.16)",
            times
                .iter()
                .map(|&t| (t, log(0.1 * reduced_amplitude(&top, &omega0, t))))
                .collect(),
        ),
    ];
    chart(
        "log10 |Omega_perp| against t (tau = 1)",
        &series,
        (0.0, 8.0),
        120,
        48,
    )
}

/// Row 3: log10 of the steps each method takes against log10 S.
fn stiffness_chart() -> String {
    let Ok(m) = stability::stiffness::measure() else {
        return "row 3 did not run".into();
    };
    let pts = |runs: Vec<(f64, u64)>| -> Vec<(f64, f64)> {
        runs.iter()
            .map(|&(s, n)| (s.log10(), (n as f64).log10()))
            .collect()
    };
    chart(
        "log10 steps over t in [0, 10] against log10 S (Omega0 = S (0, 0.1, 0.2))",
        &[
            Series::line(
                "DP5, rtol 1e-6",
                pts(m.dp5.iter().map(|r| (r.s, r.stats.steps)).collect()),
            ),
            Series::line(
                "Radau IIA 5",
                pts(m
                    .radau5
                    .iter()
                    .map(|r| (r.run.s, r.run.stats.steps))
                    .collect()),
            ),
            Series::line(
                "exact splitting",
                pts(m.splitting.iter().map(|r| (r.s, r.stats.steps)).collect()),
            ),
        ],
        (0.0, 3.0),
        120,
        40,
    )
}

/// Row 4: log10 of the largest relative energy error of a free asymmetric top
/// over [0, t], against t (the row's measure, at 2000 times).
fn long_run_chart() -> String {
    let inertia = Vec3::new(1.0, 2.0, 3.0);
    let l0 = Vec3::new(1.0, 1.0, 0.9);
    let (h, t_end, samples) = (0.05, 1e4, 2000);
    let body = FreeRigidBody::new(inertia).expect("valid moments");
    let e0 = body.energy(&l0);
    let times: Vec<f64> = (1..=samples)
        .map(|i| t_end * i as f64 / samples as f64)
        .collect();
    let rel = |e: f64| (e - e0).abs() / e0;
    // Running maximum, drawn on a log scale.
    let envelope = |errors: Vec<f64>| -> Vec<(f64, f64)> {
        let mut worst: f64 = 1e-17;
        times
            .iter()
            .zip(errors)
            .map(|(&t, e)| {
                worst = worst.max(e);
                (t, worst.log10())
            })
            .collect()
    };
    // ANCHOR: euler_equations
    // Euler's equations for L in the body frame: L' = L x Omega, Omega = I^-1 L.
    let rhs = |_t: f64, l: &State<3>| l.cross(&l.component_div(&inertia));
    // ANCHOR_END: euler_equations
    let mut rk4 = Rk4::new(0.0, l0, h).expect("valid step");
    let rk4_curve = envelope(
        times
            .iter()
            .map(|&t| {
                while rk4.t() < t {
                    rk4.step(&rhs, t).expect("finite");
                }
                rel(body.energy(rk4.y()))
            })
            .collect(),
    );
    let split_curve = |composition| -> Vec<(f64, f64)> {
        let start = RigidBodyState {
            l_body: l0,
            rotation: Mat3::identity(),
        };
        let mut split = Splitting::new(body, composition, 0.0, start, h).expect("valid step");
        envelope(
            times
                .iter()
                .map(|&t| {
                    split.advance_to(t).expect("finite");
                    rel(body.energy(&split.state().l_body))
                })
                .collect(),
        )
    };
    chart(
        "log10 max |E - E0|/E0 over [0, t] against t, free top I = (1, 2, 3), h = 0.05",
        &[
            Series::line("RK4", rk4_curve),
            Series::line("Strang", split_curve(Composition::Strang)),
            Series::line("Yoshida-4", split_curve(Composition::Yoshida4)),
        ],
        (0.0, t_end),
        120,
        40,
    )
}

/// log10 |Z − Z_AL| of (A.1): the small shell against a larger one.
fn delay_chart() -> String {
    let times: Vec<f64> = (0..=280).map(|i| 0.025 * i as f64).collect();
    let curve = |tau0: f64| -> Vec<(f64, f64)> {
        let model = ShellModel::new(tau0, 0.1).expect("valid shell");
        run_shell(
            model,
            History::abraham_lorentz(tau0),
            default_steps_per_delay(0.1),
            &times,
        )
        .expect("finite to t = 7")
        .iter()
        .filter(|s| s.t > 0.0)
        .map(|s| {
            (
                s.t,
                s.z_minus_z_al[0]
                    .hypot(s.z_minus_z_al[1])
                    .max(1e-300)
                    .log10(),
            )
        })
        .collect()
    };
    chart(
        "log10 |Z - Z_AL| against t, delay 0.1",
        &[
            Series::line("tau0 = 0.06: m0 < m_em", curve(0.06)),
            Series::line("tau0 = 0.001: m0 > m_em", curve(0.001)),
        ],
        (0.0, 7.0),
        120,
        40,
    )
}

/// Print the lesson to `out`.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "Where methods fail: six rows, the naive method beside spintop's\n"
    )?;
    row(out, 1)?;
    writeln!(out)?;
    writeln!(out, "{}", runaway_chart())?;
    row(out, 2)?;
    writeln!(out)?;
    row(out, 3)?;
    writeln!(out)?;
    writeln!(out, "{}", stiffness_chart())?;
    row(out, 4)?;
    writeln!(out)?;
    writeln!(out, "{}", long_run_chart())?;
    row(out, 5)?;
    writeln!(out)?;
    row(out, 6)?;
    writeln!(out)?;
    writeln!(out, "{}", delay_chart())?;
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
