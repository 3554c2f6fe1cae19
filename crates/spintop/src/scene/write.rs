//! A scene's answer written as `spintop run` prints it: the JSON object
//! whole, or the matching command's table and CSV with the scene's header,
//! its choice and warnings, and a real particle's report in comment lines.

use super::answer::{
    Answer, OmegaOnlyOutput, PhysicalReport, Report, RigidReport, SecularOutput, Span, TopRun,
};
use crate::math::{Real, Vec3};
use crate::numbers::{cell, csv, short, significant, table};
use crate::output::{Format, Output, Stop, write_aligned};
use crate::physics::particle::RigidShape;
use std::io::{self, Write};

/// "after T unit (T s, T tau)", or "never".
fn when(what: &str, span: &Option<Span>, unit: &str) -> String {
    match span {
        Some(s) => format!(
            "{what} after {} {unit} ({} s, {} tau)",
            significant(s.unit),
            significant(s.seconds),
            significant(s.tau)
        ),
        None => format!("never {what}"),
    }
}

fn write_physical(out: &mut dyn Write, p: &PhysicalReport) -> io::Result<()> {
    let size = match p.length_nm {
        Some(l) => format!("radius {} nm, length {} nm", short(p.radius_nm), short(l)),
        None => format!("radius {} nm", short(p.radius_nm)),
    };
    writeln!(
        out,
        "# particle: {} of {size}, density {} kg/m^3: mass {} kg, I1 = {} kg m^2, I3/I1 = {}",
        p.shape,
        short(p.density_kg_m3),
        significant(p.mass_kg),
        significant(p.i1_kg_m2),
        significant(p.ratio)
    )?;
    writeln!(
        out,
        "# dipole {} D along the axis; {}",
        short(p.dipole_debye),
        p.conversion
    )?;
    writeln!(
        out,
        "# spin {} Hz at {} deg from the axis: tau |Omega0| = {}; 1 {} = {} s = {} tau",
        short(p.spin_hz),
        short(p.spin_tilt_deg),
        significant(p.tau_omega),
        p.time_unit,
        short(p.seconds_per_unit),
        significant(p.tau_per_unit)
    )?;
    let m = &p.milestones;
    let u = p.time_unit;
    writeln!(
        out,
        "# truncated model: |Omega| {}; the tilt stays {} deg, so it never stands upright",
        when("halves", &m.truncated_half_spin, u),
        significant(m.truncated_tilt_deg)
    )?;
    writeln!(
        out,
        "# reduced model: |Omega| {}; the spin about the axis stays {} Hz",
        when("halves", &m.reduced_half_spin, u),
        significant(m.reduced_final_spin_hz)
    )?;
    let decay = match &m.reduced_tilt_decay {
        Some(s) => format!("e-folds in {} {u}", significant(s.unit)),
        None => "never decays".to_string(),
    };
    writeln!(
        out,
        "# reduced model: the tilt {decay}, and {}",
        when(
            &format!("falls below {} deg", short(m.upright_deg)),
            &m.reduced_upright,
            u
        )
    )
}

fn write_omega_only(
    out: &mut dyn Write,
    o: &OmegaOnlyOutput,
    units: Option<&PhysicalReport>,
    format: Format,
) -> io::Result<()> {
    match format {
        Format::Json => unreachable!("JSON is written whole"),
        Format::Csv => {
            let unit_col = units.map_or(String::new(), |u| format!("t_{},", u.time_unit));
            writeln!(
                out,
                "t,{unit_col}omega1,omega2,omega3,omega_perp,energy,l1,l2,l3,tilt"
            )?;
            for s in &o.samples {
                let mut row = vec![s.t];
                row.extend(s.t_unit);
                row.extend(s.omega);
                row.extend([s.omega_perp, s.energy]);
                row.extend(s.l_body);
                row.push(s.tilt);
                write_csv_row(out, &row)?;
            }
            Ok(())
        }
        Format::Table => {
            write_method_line(out, o.model, o.method, o.method_detail)?;
            writeln!(
                out,
                "# work: {} rhs evaluations, {} steps",
                o.stats.rhs_evals, o.stats.steps
            )?;
            writeln!(out, "# orientation skipped: {}", o.orientation_skipped)?;
            match units {
                Some(u) => {
                    let hz = |w: Real| w / u.tau_s / (2.0 * std::f64::consts::PI);
                    let e0 = o.samples.first().map_or(1.0, |s| s.energy);
                    let head = [
                        format!("t [{}]", u.time_unit),
                        "f [Hz]".into(),
                        "f_perp [Hz]".into(),
                        "f3 [Hz]".into(),
                        "tilt [deg]".into(),
                        "E/E0".into(),
                    ];
                    write_aligned(out, head, 15)?;
                    for s in &o.samples {
                        let w = Vec3::from(s.omega);
                        let row = [
                            s.t_unit.unwrap_or(s.t),
                            hz(w.norm()),
                            hz(s.omega_perp),
                            hz(w.z),
                            s.tilt.to_degrees(),
                            if e0 > 0.0 { s.energy / e0 } else { 0.0 },
                        ];
                        write_aligned(out, row.iter().map(|x| cell(*x)), 15)?;
                    }
                }
                None => {
                    let head = [
                        "t",
                        "omega1",
                        "omega2",
                        "omega3",
                        "omega_perp",
                        "energy",
                        "|L|",
                        "tilt",
                    ];
                    write_aligned(out, head, 14)?;
                    for s in &o.samples {
                        let l = Vec3::from(s.l_body).norm();
                        let row = [
                            s.t,
                            s.omega[0],
                            s.omega[1],
                            s.omega[2],
                            s.omega_perp,
                            s.energy,
                            l,
                            s.tilt,
                        ];
                        write_aligned(out, row.iter().map(|x| table(*x)), 14)?;
                    }
                }
            }
            Ok(())
        }
    }
}

/// One CSV line of numbers, lossless.
fn write_csv_row(out: &mut dyn Write, row: &[Real]) -> io::Result<()> {
    let cells: Vec<String> = row.iter().map(|x| csv(*x)).collect();
    writeln!(out, "{}", cells.join(","))
}

/// The table's `# MODEL model; method: …` line.
fn write_method_line(
    out: &mut dyn Write,
    model: &str,
    method: &str,
    detail: &str,
) -> io::Result<()> {
    writeln!(out, "# {model} model; method: {method} ({detail})")
}

fn write_rigid(out: &mut dyn Write, p: &RigidReport) -> io::Result<()> {
    let v = |x: [Real; 3]| {
        format!(
            "({}, {}, {})",
            significant(x[0]),
            significant(x[1]),
            significant(x[2])
        )
    };
    let what = match p.shape {
        RigidShape::Molecule { moments_amu_a2 } => {
            format!(
                "molecule with principal moments {} amu A^2",
                v(moments_amu_a2)
            )
        }
        RigidShape::Ellipsoid {
            semi_axes_nm,
            density_kg_m3,
        } => format!(
            "ellipsoid with semi-axes {} nm, density {} kg/m^3",
            v(semi_axes_nm),
            short(density_kg_m3)
        ),
    };
    writeln!(
        out,
        "# particle: {what}: I = {} kg m^2; dipole {} D in the body frame",
        v(p.inertia_kg_m2),
        v(p.dipole_debye)
    )?;
    writeln!(out, "# {}", p.conversion)?;
    writeln!(
        out,
        "# rates {} Hz in the body frame: tau_f |Omega0| = {}; 1 {} = {} s = {} u (u = tau_f, the unit where kappa = 1)",
        v(p.omega_hz),
        significant(p.share_per_radian),
        p.time_unit,
        short(p.seconds_per_unit),
        significant(p.u_per_unit)
    )
}

fn write_secular(
    out: &mut dyn Write,
    o: &SecularOutput,
    units: Option<&RigidReport>,
    format: Format,
) -> io::Result<()> {
    let e0 = o.samples.first().map_or(1.0, |r| r.sample.energy);
    let l0 = o.samples.first().map_or(1.0, |r| r.sample.l_norm);
    let ratio = |x: Real, x0: Real| if x0 > 0.0 { x / x0 } else { 0.0 };
    match format {
        Format::Json => unreachable!("JSON is written whole"),
        Format::Csv => {
            let unit_col = units.map_or(String::new(), |u| format!("t_{},", u.time_unit));
            writeln!(out, "t,{unit_col}energy,l_norm,axis,period")?;
            for r in &o.samples {
                let s = &r.sample;
                let mut row = vec![s.t];
                row.extend(r.t_unit);
                row.extend([s.energy, s.l_norm, s.axis as Real]);
                let mut cells: Vec<String> = row.iter().map(|x| csv(*x)).collect();
                // No period (a rotation about an axis): an empty cell.
                cells.push(s.period.map_or(String::new(), csv));
                writeln!(out, "{}", cells.join(","))?;
            }
            Ok(())
        }
        Format::Table => {
            write_method_line(out, o.model, o.method, o.method_detail)?;
            writeln!(
                out,
                "# work: {} slow steps, {} period averages of at most {} points each",
                o.stats.steps, o.stats.rhs_evals, o.max_quadrature_points
            )?;
            writeln!(out, "# orientation skipped: {}", o.orientation_skipped)?;
            writeln!(out, "# error: {}", o.error.line())?;
            let (time_head, period_head, per) = match units {
                Some(u) => (
                    format!("t [{}]", u.time_unit),
                    "period [s]".to_string(),
                    u.fast_time_s,
                ),
                None => ("t".to_string(), "period".to_string(), 1.0),
            };
            write_aligned(
                out,
                [
                    time_head,
                    "E/E0".into(),
                    "|L|/|L0|".into(),
                    "round axis".into(),
                    period_head,
                ],
                15,
            )?;
            for r in &o.samples {
                let s = &r.sample;
                let row = [
                    cell(r.t_unit.unwrap_or(s.t)),
                    cell(ratio(s.energy, e0)),
                    cell(ratio(s.l_norm, l0)),
                    s.axis.to_string(),
                    s.period.map_or("none".to_string(), |p| cell(p * per)),
                ];
                write_aligned(out, row, 15)?;
            }
            Ok(())
        }
    }
}

/// Write a report in the requested format (see [`crate::output::write`]).
pub fn write_report(out: &mut dyn Write, report: &Report, format: Format) -> io::Result<()> {
    crate::output::write(out, report, format)
}

impl Output for Report {
    /// The scene's header, its choice and warnings and a real particle's
    /// report as comment lines, then the matching command's table or CSV.
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()> {
        let report = self;
        if format == Format::Json {
            return crate::output::write(out, report, format);
        }
        if format == Format::Table {
            let s = &report.scene;
            writeln!(
                out,
                "# scene {} ({}, kind {}): {}",
                s.name, s.file, s.kind, s.description
            )?;
            writeln!(
                out,
                "# chosen: {}: {}",
                report.chosen.method, report.chosen.reason
            )?;
            for w in &report.warnings {
                writeln!(out, "# warning: {w}")?;
            }
        }
        match &report.answer {
            Answer::Top(top) => {
                if format == Format::Table
                    && let Some(u) = &top.units
                {
                    write_physical(out, u)?;
                }
                if format == Format::Table
                    && let Some(u) = &top.rigid_units
                {
                    write_rigid(out, u)?;
                }
                match &top.run {
                    TopRun::Full(o) => o.write_text(out, format),
                    TopRun::OmegaOnly(o) => write_omega_only(out, o, top.units.as_ref(), format),
                    TopRun::Secular(o) => write_secular(out, o, top.rigid_units.as_ref(), format),
                }
            }
            Answer::Balance(o) => o.write_text(out, format),
            Answer::Orbit(o) => o.write_text(out, format),
            Answer::Shell(o) => o.write_text(out, format),
            Answer::Stability(a) => {
                for row in &a.rows {
                    write!(out, "{row}")?;
                }
                Ok(())
            }
        }
    }

    /// A forward run of the full ALE or of (2.5) that ran away.
    fn stopped(&self) -> Option<Stop> {
        match &self.answer {
            Answer::Top(top) => match &top.run {
                TopRun::Full(o) => o.stopped(),
                TopRun::OmegaOnly(_) | TopRun::Secular(_) => None,
            },
            Answer::Orbit(o) => o.stopped(),
            Answer::Balance(_) | Answer::Shell(_) | Answer::Stability(_) => None,
        }
    }

    fn advice(&self) -> &'static str {
        "ask for smaller rates or earlier times"
    }
}
