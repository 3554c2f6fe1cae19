//! Lesson for Section 2: two laws for the loss of angular momentum.
//!
//! Run it: `cargo run --release --example ch2_balance_laws`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::integrate::{AdaptiveOptions, Dop853, solve};
use spintop::math::State;
use spintop::physics::balance::{PlanarLoop, PrecessingDipole, balance_at, period_average};
use spintop::physics::central::{
    ChargeInField, Potential, Vec2, abraham_lorentz_oscillator_roots, abraham_lorentz_rhs,
    bohr_collapse_time_seconds, coulomb_circular_radius, electron_tau0_seconds,
    landau_lifshitz_oscillator_root, oscillator_mode, pos_vel,
};
use spintop::plot::{Series, chart};
use spintop::sim::orbit::{Force, OrbitConfig, run_orbit};
use std::io::{self, Write};

/// Print the lesson to `out`: its four parts in order.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(out, "Section 2: two laws for the loss of angular momentum")?;
    writeln!(
        out,
        "Units: kappa = 2/(3c^3) = 1 for dipoles; m = k = 1 for orbits\n"
    )?;
    precessing_dipole(out)?;
    planar_loop(out)?;
    coulomb_collapse(out)?;
    oscillator_roots(out)?;
    runaway(out)
}

/// Part 1: a dipole in regular precession, where the Schott term's rate
/// averages to zero in the lab but not along the dipole.
fn precessing_dipole(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: precessing
    // A rigid dipole on a cone (theta = 0.5, omega = 1): a top in regular precession.
    let (theta, omega) = (0.5_f64, 1.0_f64);
    let top = PrecessingDipole::new(theta, omega).expect("valid cone and rate");
    let avg = period_average(&top).expect("periodic");
    writeln!(
        out,
        "1. Precessing dipole, theta = {theta}, omega = {omega}"
    )?;
    writeln!(
        out,
        "       t   dL_S/dt (lab x, y, z)                 n . dL_S/dt"
    )?;
    for t in [0.0, 1.0, 2.0, 3.0] {
        let b = balance_at(&top, t);
        let r = b.schott_rate;
        writeln!(
            out,
            "  {t:>6.2}   ({:>8.5}, {:>8.5}, {:>8.5})   {:>12.8}",
            r.x,
            r.y,
            r.z + 0.0,
            b.schott_rate_axial
        )?;
    }
    let w3s2c = omega.powi(3) * theta.sin().powi(2) * theta.cos();
    writeln!(
        out,
        "  period average: |<dL_S/dt>| = {:.1e} in the lab, but <n . dL_S/dt> = {:.8}",
        avg.schott_rate.norm(),
        avg.schott_rate_axial
    )?;
    writeln!(
        out,
        "  closed form omega^3 sin^2(theta) cos(theta)            = {w3s2c:.8}"
    )?;
    writeln!(
        out,
        "  along the dipole: (2.1) gives {:.8}, the torque (2.2) gives {:.1e}\n",
        avg.larmor_axial, avg.torque_axial
    )?;
    // ANCHOR_END: precessing
    Ok(())
}

/// Part 2: a planar loop, where the two laws agree on the period average only.
fn planar_loop(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: loop
    // The loop d = (cos t, b sin t + eps sin 2t, 0): the laws agree on average only.
    let (b, eps) = (0.5, 0.2);
    let lp = PlanarLoop::new(b, eps).expect("finite parameters");
    writeln!(
        out,
        "2. Planar loop, b = {b}, eps = {eps} (all vectors along z)"
    )?;
    writeln!(out, "       t      (2.1)      (2.2)   dL_S/dt")?;
    for k in 0..=4 {
        let t = k as f64 * std::f64::consts::FRAC_PI_4;
        let s = balance_at(&lp, t);
        writeln!(
            out,
            "  {t:>6.3} {:>10.5} {:>10.5} {:>9.5}",
            s.larmor.z, s.torque.z, s.schott_rate.z
        )?;
    }
    let avg = period_average(&lp).expect("periodic");
    writeln!(
        out,
        "  period average: (2.1) {:.12}, (2.2) {:.12}, dL_S/dt {:.1e}\n",
        avg.larmor.z, avg.torque.z, avg.schott_rate.z
    )?;
    // ANCHOR_END: loop
    Ok(())
}

/// Part 3: the Coulomb collapse, integrated against its averaged closed form.
fn coulomb_collapse(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: collapse
    // Coulomb, circular start at r0 = 1, tau0 = 1e-3: Landau-Lifshitz integration
    // against the averaged closed form r^3 = r0^3 - 6 tau0 t.
    let tau0 = 1e-3;
    let charge = ChargeInField::new(Potential::Coulomb, tau0).expect("tau0 > 0");
    let config = OrbitConfig::new(charge, 1.0, 0.0, Force::LandauLifshitz).expect("valid orbit");
    let times: Vec<f64> = (0..=83).map(|i| 2.0 * i as f64).collect();
    let mut times_and_end = times.clone();
    times_and_end.push(166.6);
    let run = run_orbit(&config, &times_and_end).expect("the run stops before the collapse");
    writeln!(
        out,
        "3. Coulomb collapse, tau0 = {tau0}, r0 = 1 (t_c = r0^3/(6 tau0) = {:.4})",
        1.0 / (6.0 * tau0)
    )?;
    for c in run.first_crossing.as_ref().expect("Coulomb") {
        let (t, avg) = (c.t.expect("reached"), c.averaged.expect("circular"));
        writeln!(
            out,
            "  r = {:.1}: integration t = {t:.4}, closed form t = {avg:.4}, relative difference {:+.1e}",
            c.r,
            t / avg - 1.0
        )?;
    }
    let closed: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let t = 166.6 * i as f64 / 400.0;
            (t, coulomb_circular_radius(tau0, 1.0, t))
        })
        .collect();
    let integrated: Vec<(f64, f64)> = run.samples.iter().map(|s| (s.t, s.r)).collect();
    write!(
        out,
        "{}",
        chart(
            "r(t), Coulomb, tau0 = 1e-3",
            &[
                Series::line("closed form (r0^3 - 6 tau0 t)^(1/3)", closed),
                Series::dots("Landau-Lifshitz integration", integrated),
            ],
            (0.0, 166.6),
            100,
            28,
        )
    )?;
    writeln!(
        out,
        "  hydrogen from the Bohr radius: tau0 = {:.4e} s, t_c = a0^3/(4 r_e^2 c) = {:.4e} s\n",
        electron_tau0_seconds(),
        bohr_collapse_time_seconds()
    )?;
    // ANCHOR_END: collapse
    Ok(())
}

/// Part 4: the oscillator's characteristic roots under Abraham-Lorentz and
/// Landau-Lifshitz.
fn oscillator_roots(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: oscillator_roots
    writeln!(
        out,
        "4. Oscillator V = r^2/2: roots of tau0 s^3 - s^2 - 1 = 0 (AL) and s^2 + tau0 s + 1 = 0 (LL)"
    )?;
    writeln!(
        out,
        "     tau0   Im s_AL              Im s_LL              (s_AL - s_LL)/tau0^2     runaway root"
    )?;
    for tau0 in [1e-1, 1e-2, 1e-3] {
        let (s, s_run) = abraham_lorentz_oscillator_roots(tau0);
        let s_ll = landau_lifshitz_oscillator_root(tau0);
        let d = (s - s_ll) / (tau0 * tau0);
        writeln!(
            out,
            "  {tau0:>7.0e}   {:.15}   {:.15}   {:+.5} {:+.5} i   {s_run:.6}",
            s.im, s_ll.im, d.re, d.im
        )?;
    }
    // ANCHOR_END: oscillator_roots
    Ok(())
}

/// Part 4, continued: (2.5) runs away forward in time and is damped backward.
fn runaway(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: runaway
    let tau0 = 1e-2;
    let osc = ChargeInField::new(Potential::Harmonic, tau0).expect("tau0 > 0");
    let forward = OrbitConfig::new(osc, 1.0, 0.0, Force::AbrahamLorentzForward).expect("valid");
    let run = run_orbit(&forward, &[0.0, 1.0]).expect("the runaway is reported, not an error");
    let r = run.runaway.expect("forward integration runs away");
    writeln!(
        out,
        "\n  forward (2.5), tau0 = {tau0}, started with the Newtonian acceleration: runaway at t = {:.4} ({:.1} tau0),",
        r.t,
        r.t / tau0
    )?;
    writeln!(
        out,
        "  |a - F| growing at rate {:.3} against the real root {:.3}",
        r.growth_rate.expect("measured"),
        r.predicted_rate
    )?;
    // Backward from T = 5 with the same wrong (Newtonian) acceleration.
    let (s, _) = abraham_lorentz_oscillator_roots(tau0);
    let (x0, v0) = (Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0));
    let t_final = 5.0;
    let (xf, vf, _) = oscillator_mode(s, &x0, &v0, t_final);
    let y_final = State::<6>::new(xf.x, xf.y, vf.x, vf.y, -xf.x, -xf.y);
    let rhs = |_t: f64, y: &State<6>| abraham_lorentz_rhs(&osc, y);
    let opts = AdaptiveOptions::new(1e-12, 1e-15).expect("valid tolerances");
    writeln!(
        out,
        "  backward (2.5) from T = 5 with the Newtonian acceleration:"
    )?;
    writeln!(out, "       t   (T-t)/tau0   |a - a_physical(r, v)|")?;
    for t in [5.0, 4.98, 4.95, 4.9, 4.8, 4.0, 0.0] {
        // NOTE: one run per output time, so each value is at a step end: the
        // continuous extension between steps does not resolve the damped mode.
        let mut back = Dop853::new(t_final, y_final, opts).expect("valid start");
        let y = &solve(&mut back, &rhs, &[t]).expect("damped backward")[0];
        let (x, v) = pos_vel(y);
        let physical = oscillator_mode(s, &x, &v, 0.0).2;
        let off = (Vec2::new(y[4], y[5]) - physical).norm();
        writeln!(
            out,
            "  {t:>6.2} {:>12.1} {off:>24.3e}",
            (t_final - t) / tau0
        )?;
    }
    // ANCHOR_END: runaway
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
