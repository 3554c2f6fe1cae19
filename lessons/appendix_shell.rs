//! Lesson for the Appendix: the charge as a small shell, a delay equation.
//!
//! Run it: `cargo run --release --example appendix_shell`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::physics::central::abraham_lorentz_oscillator_roots;
use spintop::physics::shell::ShellModel;
use spintop::plot::{Series, chart};
use spintop::sim::shell::{History, ShellSample, ShellSolver, default_steps_per_delay, run_shell};
use std::io::{self, Write};

fn run_al(tau0: f64, delta: f64, times: &[f64]) -> Vec<ShellSample> {
    let model = ShellModel::new(tau0, delta).expect("valid parameters");
    run_shell(
        model,
        History::abraham_lorentz(tau0),
        default_steps_per_delay(delta),
        times,
    )
    .expect("finite")
}

fn dz(s: &ShellSample) -> f64 {
    s.z_minus_z_al[0].hypot(s.z_minus_z_al[1])
}

/// Print the lesson to `out`: its six parts in order.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(out, "Appendix: the charge as a small shell")?;
    writeln!(
        out,
        "Units: m = m0 + m_em = 1, k = 1; m0 Z''(t) + Z(t) = -m_em Z''(t - delay), m_em = tau0/delay\n"
    )?;
    regimes(out)?;
    exact_mode(out)?;
    // Parts 3 and 4 read the same runs: tau0 = 1e-3, up to t = 20, three delays.
    let (tau0, t) = (1e-3, 20.0);
    let deltas = [0.1, 0.03, 0.01];
    convergence(out, tau0, t, &deltas)?;
    balance(out, tau0, t, &deltas)?;
    growth(out)?;
    formal_limit(out)
}

/// Part 1: the three regimes, read off the characteristic roots.
fn regimes(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: regimes
    writeln!(out, "1. Three regimes, read off the characteristic roots")?;
    writeln!(
        out,
        "     tau0    delay        m0      m_em  regime                max Re s   ln(m_em/|m0|)/delay"
    )?;
    for (tau0, delta) in [
        (1e-3, 0.1),
        (0.049, 0.1),
        (0.04997, 0.1),
        (0.06, 0.1),
        (1e-3, 5e-4),
    ] {
        let m = ShellModel::new(tau0, delta).expect("valid");
        let max_re = m
            .roots(16)
            .iter()
            .map(|s| s.re)
            .fold(f64::NEG_INFINITY, f64::max);
        writeln!(
            out,
            "  {tau0:>7} {delta:>8} {:>9.4} {:>9.4}  {:<20} {max_re:>10.4} {:>21.4}",
            m.m0(),
            m.m_em(),
            m.regime().name(),
            m.chain_rate()
        )?;
    }
    let m = ShellModel::new(0.04997, 0.1).expect("valid");
    writeln!(
        out,
        "  tau0 = 0.04997: m0 - m_em = {:.4} > 0, yet unstable: it is below delay^2/pi^2 = {:.5}",
        m.m0() - m.m_em(),
        m.stability_threshold()
    )?;
    // ANCHOR_END: regimes
    Ok(())
}

/// Part 2: an exact mode as history stays exact.
fn exact_mode(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: exact_mode
    writeln!(
        out,
        "\n2. An exact mode e^(st) as history stays exact (tau0 = 1e-3, delay = 0.1)"
    )?;
    let m = ShellModel::new(1e-3, 0.1).expect("valid");
    let s = m.root_near_al().expect("root");
    let s_al = abraham_lorentz_oscillator_roots(1e-3).0;
    writeln!(
        out,
        "  root near AL: s = {:.10} + {:.10} i, |P(s)| = {:.1e}",
        s.re,
        s.im,
        m.characteristic(s).norm()
    )?;
    writeln!(
        out,
        "  s - s_AL = {:.3e} + {:.4e} i   (i tau0 delta/4 = {:.4e} i)",
        (s - s_al).re,
        (s - s_al).im,
        1e-3 * 0.1 / 4.0
    )?;
    let sample =
        run_shell(m, History::mode(s), default_steps_per_delay(0.1), &[20.0]).expect("finite")[0];
    let exact = (s * 20.0).exp();
    let err = (sample.z[0] - exact.re).hypot(sample.z[1] - exact.im);
    writeln!(
        out,
        "  solver vs e^(st) at t = 20: |error| = {}",
        if err < 1e-10 {
            "below 1e-10"
        } else {
            "TOO LARGE"
        }
    )?;
    // ANCHOR_END: exact_mode
    Ok(())
}

/// Part 3: the shell converges to Abraham-Lorentz at `t` as the delay
/// shrinks through `deltas` (Z at order 1, L at order 2).
fn convergence(out: &mut dyn Write, tau0: f64, t: f64, deltas: &[f64]) -> io::Result<()> {
    // ANCHOR: convergence
    writeln!(
        out,
        "\n3. Convergence to Abraham-Lorentz at t = {t}, tau0 = {tau0}"
    )?;
    writeln!(
        out,
        "   delay   |Z - Z_AL|   tau0*delay*t/4   |L - L_AL|   2tL(tau0 d^2/12 - 3tau0^2 d/4)   order Z   order L"
    )?;
    let mut prev: Option<(f64, f64, f64)> = None;
    for &d in deltas {
        let s = run_al(tau0, d, &[t])[0];
        let (ez, el) = (dz(&s), (s.l - s.l_al).abs());
        let predicted = 2.0 * t * s.l_al * (tau0 * d * d / 12.0 - 0.75 * tau0 * tau0 * d);
        let orders = prev.map_or(String::new(), |(d0, ez0, el0)| {
            let k = (d0 / d).ln();
            format!("{:>9.3} {:>9.3}", (ez0 / ez).ln() / k, (el0 / el).ln() / k)
        });
        writeln!(
            out,
            "  {d:>6} {ez:>12.4e} {:>16.4e} {el:>12.4e} {:>32.4e} {orders}",
            tau0 * d * t / 4.0,
            predicted.abs()
        )?;
        prev = Some((d, ez, el));
    }
    let l2: Vec<f64> = [0.1, 0.01]
        .iter()
        .map(|&d| {
            let s = run_al(1e-5, d, &[t])[0];
            (s.l - s.l_al).abs()
        })
        .collect();
    writeln!(
        out,
        "  with tau0 = 1e-5 (delay >> 9 tau0 throughout): order of L from 0.1 to 0.01 = {:.3}",
        (l2[0] / l2[1]).log10()
    )?;
    let mut z_pts = Vec::new();
    let mut l_pts = Vec::new();
    for k in 0..=12 {
        let d = 10f64.powf(-2.0 + k as f64 / 8.0);
        let s = run_al(tau0, d, &[t])[0];
        z_pts.push((d.log10(), dz(&s).log10()));
        l_pts.push((d.log10(), (s.l - s.l_al).abs().log10()));
    }
    write!(
        out,
        "{}",
        chart(
            "log10 error at t = 20 against log10 delay",
            &[
                Series::dots("|Z - Z_AL|, slope 1", z_pts),
                Series::dots("|L - L_AL|, slope 2", l_pts),
            ],
            (-2.0, -0.5),
            100,
            40,
        )
    )?;
    // ANCHOR_END: convergence
    Ok(())
}

/// Part 4: the angular momentum balance (A.2)-(A.3) at `t`, for each delay.
fn balance(out: &mut dyn Write, tau0: f64, t: f64, deltas: &[f64]) -> io::Result<()> {
    // ANCHOR: balance
    writeln!(
        out,
        "\n4. The balance (A.2)-(A.3) at t = {t}, tau0 = {tau0}"
    )?;
    writeln!(
        out,
        "   delay     J - J(0)   exact flux - (J - J(0))   paper's (A.2) - (J - J(0))        L - J     tau0 dL/dt"
    )?;
    for &d in deltas {
        let s = run_al(tau0, d, &[t])[0];
        writeln!(
            out,
            "  {d:>6} {:>12.8} {:>25} {:>28.3e} {:>12.5e} {:>14.5e}",
            s.j_change,
            if (s.flux_exact - s.j_change).abs() < 1e-10 {
                "below 1e-10"
            } else {
                "TOO LARGE"
            },
            s.flux_paper - s.j_change,
            s.l_minus_j,
            s.l_schott
        )?;
    }
    // ANCHOR_END: balance
    Ok(())
}

/// Part 5: an unstable shell, its growth measured against the predicted rate.
fn growth(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: growth
    let (tau0, delta) = (0.06, 0.1);
    let m = ShellModel::new(tau0, delta).expect("valid");
    writeln!(
        out,
        "\n5. Growing oscillation: tau0 = {tau0}, delay = {delta}, m0 = {:.2}, m_em = {:.2}",
        m.m0(),
        m.m_em()
    )?;
    let mut solver = ShellSolver::new(m, History::abraham_lorentz(tau0), 64).expect("solver");
    let first = solver.jump();
    for _ in 0..20 {
        solver.advance().expect("finite");
    }
    let ratio = (solver.jump().norm() / first.norm()).powf(1.0 / 20.0);
    writeln!(
        out,
        "  jump of Z'' at t = n delay: |ratio| per delay = {ratio:.12} (m_em/m0 = {:.12})",
        m.m_em() / m.m0()
    )?;
    let peak = |a: f64| {
        let times: Vec<f64> = (0..=400).map(|k| a + k as f64 / 400.0).collect();
        run_al(tau0, delta, &times)
            .iter()
            .map(dz)
            .fold(0.0, f64::max)
    };
    let measured = (peak(6.0) / peak(2.0)).ln() / 4.0;
    let predicted = (m.m_em() / m.m0()).ln() / delta;
    writeln!(
        out,
        "  |Z - Z_AL| grows at {measured:.4} per unit time; ln(m_em/m0)/delay = {predicted:.4} ({:+.2}%), lowest root {:.4}",
        100.0 * (measured / predicted - 1.0),
        m.growth_rate().expect("unstable")
    )?;
    let pts: Vec<(f64, f64)> = run_al(
        tau0,
        delta,
        &(0..=300).map(|k| k as f64 / 50.0).collect::<Vec<_>>(),
    )
    .iter()
    .map(|s| (s.t, dz(s).log10()))
    .collect();
    write!(
        out,
        "{}",
        chart(
            "log10 |Z - Z_AL| against t (slope 4.08/ln 10 = 1.77)",
            &[Series::line("tau0 = 0.06, delay = 0.1", pts)],
            (0.0, 6.0),
            100,
            32,
        )
    )?;
    // ANCHOR_END: growth
    Ok(())
}

/// Part 6: m held fixed while the shell shrinks: the runaway comes back.
fn formal_limit(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: formal_limit
    writeln!(
        out,
        "\n6. Holding m fixed while the shell shrinks (tau0 = 1e-3)"
    )?;
    writeln!(
        out,
        "     delay           m0   regime        largest Re s   (AL runaway 1/tau0 + ... = {:.4})",
        abraham_lorentz_oscillator_roots(1e-3).1
    )?;
    for delta in [0.1, 0.01, 0.0015, 5e-4, 1e-5, 1e-7] {
        let m = ShellModel::new(1e-3, delta).expect("valid");
        let rate = m
            .growth_rate()
            .map_or("-".to_string(), |r| format!("{r:.4}"));
        writeln!(
            out,
            "  {delta:>8} {:>12.1} {:<20} {rate:>14}",
            m.m0(),
            m.regime().name()
        )?;
    }
    // ANCHOR_END: formal_limit
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
