//! Lesson for "Speed against accuracy": what each method pays for its accuracy.
//!
//! Run it: `cargo run --release --example speed_accuracy`
//!
//! Everything here is counted, not timed, so the output is the same on every
//! machine and the book can show it (`tests/project/book.rs` checks that it does).
//! `spintop bench` measures the wall time of the same runs.

use spintop::integrate::{AdaptiveOptions, Dop853, Stepper, solve};
use spintop::math::{Real, State, Vec3};
use spintop::numbers;
use spintop::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs, reduced_closed_form};
use spintop::workprecision::report::{self, CostAxis, cost_at};
use spintop::workprecision::{
    Method, Plan, Problem, ProblemKind, Row, Solver, Spintop, Target, sweep,
};
use std::io::{self, Write};

/// Print the lesson to `out`.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "Speed against accuracy: the reduced model (4.12)-(4.14)"
    )?;
    writeln!(
        out,
        "I3/I1 = 0.4, Omega0 = (0, 0.1, 0.2)/tau, 200 output points t = 1..200 tau\n"
    )?;

    // ANCHOR: sweep
    // Every spintop method on the reduced problem, over thirteen decades of
    // tolerance and seven halvings of the RK4 step, counted but not timed.
    let problem = Problem::new(ProblemKind::Reduced).expect("the stored reference");
    let entries: Vec<Spintop> = [
        Method::ClosedForm,
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
        Method::Taylor,
    ]
    .into_iter()
    .map(|method| Spintop {
        method,
        target: Target::Omega,
    })
    .collect();
    let solvers: Vec<&dyn Solver> = entries.iter().map(|s| s as &dyn Solver).collect();
    let plan = Plan {
        rtols: (3..=15).map(|k| (10.0 as Real).powi(-k)).collect(),
        steps: (0..=6).map(|k| (0.5 as Real).powi(k)).collect(),
        timing: None,
    };
    let rows = sweep(&[problem], &solvers, &plan, None);
    // ANCHOR_END: sweep
    if let Some(chart) = report::chart(&rows, "reduced", CostAxis::Evals, 120, 60) {
        write!(out, "{chart}")?;
    }

    // ANCHOR: cost_at_matched_error
    // The right-hand-side evaluations each method needs for a given error,
    // read off its curve; and how steeply its error falls with more work.
    // (The Taylor method evaluates no right-hand side: its count is the
    // arithmetic of its recurrences, p(p+1)/2 evaluations' worth a step.)
    writeln!(
        out,
        "\nRHS evaluations needed for a max relative error of Omega of"
    )?;
    writeln!(
        out,
        "{:<8} {:>9} {:>9} {:>9} {:>9}   slope of log(error) against log(evaluations)",
        "method", "1e-6", "1e-9", "1e-12", "1e-14"
    )?;
    for method in ["rk4", "dopri5", "dop853", "taylor"] {
        let points = evals_and_errors(&rows, method);
        let need = |e: Real| cost_at(&points, e).map_or("-".to_string(), |n| numbers::fixed(n, 0));
        writeln!(
            out,
            "{method:<8} {:>9} {:>9} {:>9} {:>9}   {}",
            need(1e-6),
            need(1e-9),
            need(1e-12),
            need(1e-14),
            numbers::fixed(slope(&points), 1)
        )?;
    }
    // ANCHOR_END: cost_at_matched_error
    let closed = rows.iter().find(|r| r.method == "closed-form");
    if let Some(Row {
        omega_error: Some(e),
        ..
    }) = closed
    {
        writeln!(
            out,
            "closed form: 0 evaluations, error {e} against the 40-digit reference (rounding)",
            e = numbers::exponent(*e, 1)
        )?;
    }

    digits(out, &rows)?;
    stiffness(out)
}

/// (evaluations, error) of one method's rows.
fn evals_and_errors(rows: &[Row], method: &str) -> Vec<(Real, Real)> {
    rows.iter()
        .filter(|r| r.method == method)
        .filter_map(|r| Some((r.rhs_evals? as Real, r.omega_error?)))
        .collect()
}

/// What one more digit costs: DOP853's price per digit is fixed by its
/// order, the Taylor method's falls as its order rises with the digits.
fn digits(out: &mut dyn Write, rows: &[Row]) -> io::Result<()> {
    // ANCHOR: digits
    // Going down the ladder of tolerances, the work of each row over the
    // row before, per decade of error gained: the price of one more digit.
    writeln!(
        out,
        "\nThe price of one more digit: work ratio per tenfold smaller error, row to row"
    )?;
    writeln!(
        out,
        "{:>7} | {:>6} {:>6} {:>9} {:>9} {:>6} | {:>6} {:>9} {:>9} {:>6}",
        "rtol", "order", "steps", "evals", "error", "digit", "steps", "evals", "error", "digit"
    )?;
    writeln!(
        out,
        "{:>7} | {:^40} | {:^33}",
        "", "Taylor (order grows with the digits)", "DOP853 (order 8)"
    )?;
    let of = |method: &str| -> Vec<&Row> { rows.iter().filter(|r| r.method == method).collect() };
    let (taylor, dop853) = (of("taylor"), of("dop853"));
    let per_digit = |a: &Row, b: &Row| -> Option<Real> {
        let work = b.rhs_evals? as Real / a.rhs_evals? as Real;
        let gained = (a.omega_error? / b.omega_error?).log10();
        (gained > 0.3).then(|| work.powf(1.0 / gained))
    };
    let show = |x: Option<Real>| x.map_or("-".to_string(), |v| numbers::fixed(v, 2));
    for i in 0..taylor.len().min(dop853.len()) {
        let (t, d) = (taylor[i], dop853[i]);
        let rtol = t.value.unwrap_or(Real::NAN);
        let order = spintop::integrate::taylor::taylor_order(rtol);
        let (tp, dp) = if i > 0 {
            (per_digit(taylor[i - 1], t), per_digit(dop853[i - 1], d))
        } else {
            (None, None)
        };
        writeln!(
            out,
            "{rtol:>7} | {order:>6} {:>6} {:>9} {:>9} {:>6} | {:>6} {:>9} {:>9} {:>6}",
            t.steps.unwrap_or(0),
            t.rhs_evals.unwrap_or(0),
            numbers::exponent(t.omega_error.unwrap_or(Real::NAN), 1),
            show(tp),
            d.steps.unwrap_or(0),
            d.rhs_evals.unwrap_or(0),
            numbers::exponent(d.omega_error.unwrap_or(Real::NAN), 1),
            show(dp),
            rtol = numbers::exponent(rtol, 0)
        )?;
    }
    // ANCHOR_END: digits
    Ok(())
}

/// Least-squares slope of log10(error) against log10(cost), over the points
/// with error between 1e-13 and 1e-4 (the straight part of the curve).
fn slope(points: &[(Real, Real)]) -> Real {
    spintop::math::least_squares_slope(
        points
            .iter()
            .filter(|(_, e)| (1e-13..1e-4).contains(e))
            .map(|(c, e)| (c.log10(), e.log10())),
    )
}

/// DOP853 on a stiff reduced top: a fast spin makes the damping rate of Ω⊥
/// large, Ω⊥ is gone within a few τ, and yet the steps stay short for ever.
fn stiffness(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: stiffness
    // Spin 50 times faster: the damping rate of Omega_perp is
    // tau*((I3/I1)^2*Omega3^2 + Omega_perp^2) = 16/tau, and Omega_perp turns
    // at (1 - I3/I1)*Omega3 = 6/tau. After t = 3 tau Omega_perp is below 1e-21:
    // Omega is constant, a single step could cover any time span.
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.0, 0.1, 10.0);
    let f = |_t: Real, y: &State<3>| reduced_ale_rhs(&top, y);
    let lambda = (16.0_f64.powi(2) + 6.0_f64.powi(2)).sqrt(); // |eigenvalue| of the Omega_perp equation
    writeln!(
        out,
        "\nStiffness: the reduced top with Omega0 = (0, 0.1, 10)/tau, DOP853"
    )?;
    writeln!(
        out,
        "{:>6} {:>7} {:>8} {:>6} {:>9} {:>15}  max error against the closed form",
        "T", "rtol", "evals", "steps", "rejected", "mean h|lambda|"
    )?;
    for (t_end, rtol) in [
        (50.0, 1e-6),
        (100.0, 1e-6),
        (200.0, 1e-6),
        (200.0, 1e-3),
        (200.0, 1e-9),
    ] {
        let opts = AdaptiveOptions::new(rtol, 1e-6 * rtol * omega0.norm()).expect("valid");
        let mut dop853 = Dop853::new(0.0, omega0, opts).expect("a start");
        let times: Vec<Real> = (1..=50).map(|i| t_end * i as Real / 50.0).collect();
        let ys = solve(&mut dop853, &f, &times).expect("DOP853 stays stable");
        let error = ys
            .iter()
            .zip(&times)
            .map(|(y, &t)| {
                let exact = reduced_closed_form(&top, &omega0, t);
                (y - exact).norm() / exact.norm()
            })
            .fold(0.0, Real::max);
        let s = dop853.stats();
        writeln!(
            out,
            "{t_end:>6} {rtol:>7} {:>8} {:>6} {:>9} {:>15}  {error}",
            s.rhs_evals,
            s.steps,
            s.rejected,
            numbers::fixed(t_end / s.steps as Real * lambda, 2),
            rtol = numbers::exponent(rtol, 0),
            error = numbers::exponent(error, 1)
        )?;
    }
    // ANCHOR_END: stiffness
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
