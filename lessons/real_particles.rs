//! Lesson for the chapter "Real particles": a silica nanosphere spun to a GHz,
//! with 10³ to 10⁷ debye, in seconds and years.
//!
//! Run it: `cargo run --release --example real_particles`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::numbers;
use spintop::output::Format;
use spintop::physics::particle::{
    DEBYE_ESU_CM, Milestones, Particle, SECONDS_PER_YEAR, SPEED_OF_LIGHT_CM_S, Shape,
};
use spintop::scene::answer::answer;
use spintop::scene::catalogue::find;
use spintop::scene::write::write_report;
use std::io::{self, Write};

fn years(tau_units: Option<f64>, tau_s: f64) -> String {
    match tau_units {
        Some(t) => format!("{} yr", numbers::exponent(t * tau_s / SECONDS_PER_YEAR, 4)),
        None => "never".to_string(),
    }
}

/// Print the lesson to `out`.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "Real particles: a silica sphere, radius 50 nm, 2200 kg/m^3, spun to 1 GHz"
    )?;
    writeln!(
        out,
        "at 45 deg from its dipole, in Gaussian units (cm, g, s, statC)\n"
    )?;

    // ANCHOR: particle
    let sphere = |debye: f64| {
        Particle::new(Shape::Sphere, 50e-7, 0.0, 2.2, debye * DEBYE_ESU_CM).expect("positive sizes")
    };
    let p = sphere(1e3);
    let (i1, i3) = p.moments_g_cm2();
    // ANCHOR_END: particle
    writeln!(
        out,
        "mass      M  = (4/3) pi a^3 rho = {} g",
        numbers::exponent(p.mass_g(), 4)
    )?;
    writeln!(
        out,
        "moments   I1 = I3 = (2/5) M a^2 = {i1} g cm^2 (I3/I1 = {})",
        i3 / i1,
        i1 = numbers::exponent(i1, 4)
    )?;
    writeln!(
        out,
        "light     c^3 = {} cm^3/s^3\n",
        numbers::exponent(SPEED_OF_LIGHT_CM_S.powi(3), 4)
    )?;

    writeln!(
        out,
        "{:>8} {:>12} {:>11} {:>16} {:>16} {:>16}",
        "d [D]", "tau [s]", "tau Omega", "|Omega|/2 trunc", "tilt e-fold red", "tilt < 1 deg red"
    )?;
    for debye in [1e3, 1e4, 1e5, 1e6, 1e7] {
        // ANCHOR: milestones
        let p = sphere(debye);
        let tau_s = p.tau_seconds();
        let omega0 = p.omega0_per_tau(1e9, 45f64.to_radians());
        let m = Milestones::new(&p.top(), &omega0, 1f64.to_radians());
        // ANCHOR_END: milestones
        writeln!(
            out,
            "{debye:>8} {tau_s:>12} {:>11} {:>16} {:>16} {:>16}",
            numbers::exponent(omega0.norm(), 3),
            years(m.truncated_half_spin, tau_s),
            years(m.reduced_tilt_decay, tau_s),
            years(m.reduced_upright, tau_s),
            debye = numbers::exponent(debye, 0),
            tau_s = numbers::exponent(tau_s, 4)
        )?;
    }
    writeln!(
        out,
        "\nEvery time scales as 1/d^2. The reduced model never halves |Omega|: the spin"
    )?;
    writeln!(
        out,
        "about the dipole, Omega3 = |Omega0| cos 45 deg, is kept for ever.\n"
    )?;

    writeln!(out, "$ spintop run nanoparticle-1e7-debye")?;
    let scene = find("nanoparticle-1e7-debye")
        .expect("in the catalogue")
        .scene()
        .expect("the catalogue parses");
    let report = answer(&scene).map_err(|e| io::Error::other(e.to_string()))?;
    let mut text = Vec::new();
    write_report(&mut text, &report, Format::Table)?;
    out.write_all(&text)
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
