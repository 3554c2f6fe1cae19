//! Lesson for the chapter "Where methods fail": the six rows of the stability
//! suite, each with the naive method beside spintop's, and charts of the
//! failures.
//!
//! Run it: `cargo run --release --example where_methods_fail`
//!
//! The book shows this program's output; `tests/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::{State, Vec3};
use spintop::physics::full_ale::symmetric_full_ale_rhs;
use spintop::physics::shell::ShellModel;
use spintop::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs, reduced_amplitude};
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
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
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
