//! A real particle in `[units]`: a sphere or a cylinder (a symmetric top with
//! its dipole on the axis, answered in τ units) or an ellipsoid or a molecule
//! (an asymmetric top, answered in units where κ = 1), and the unit the
//! output's times are shown in. Sizes in nm, density in kg/m³, dipoles in
//! debye, rates in Hz; the particle itself works in Gaussian units.

use super::format::{At, Key, RawUnits};
use super::keys::{Ctx, Refusal, choice, finite_array, missing, not_here, num_in};
use crate::math::Real;
use crate::physics::particle::{
    DEBYE_ESU_CM, Particle, RigidParticle, RigidShape, SECONDS_PER_YEAR, Shape,
};

/// A time unit for the output of a real particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeUnit {
    /// Seconds.
    Second,
    /// Minutes.
    Minute,
    /// Hours.
    Hour,
    /// Days.
    Day,
    /// Julian years, 365.25 days.
    Year,
}

/// The names of the time units, in the order of [`TimeUnit`].
pub const TIME_UNITS: [&str; 5] = ["s", "min", "h", "d", "yr"];

impl TimeUnit {
    /// `s`, `min`, `h`, `d` or `yr`.
    pub fn name(&self) -> &'static str {
        TIME_UNITS[*self as usize]
    }

    /// Seconds per unit.
    pub fn seconds(&self) -> Real {
        match self {
            TimeUnit::Second => 1.0,
            TimeUnit::Minute => 60.0,
            TimeUnit::Hour => 3600.0,
            TimeUnit::Day => 86_400.0,
            TimeUnit::Year => SECONDS_PER_YEAR,
        }
    }
}

/// The `[units]` of a top: a real particle and how to show times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RealUnits {
    /// The particle.
    pub particle: Particle,
    /// Its spin rate, turns per second.
    pub spin_hz: Real,
    /// The angle between Ω₀ and the symmetry axis, in degrees.
    pub spin_tilt_deg: Real,
    /// The tilt counted as upright, in degrees.
    pub upright_deg: Real,
    /// The unit of `[solve]` times and of the output.
    pub time_unit: TimeUnit,
}

impl RealUnits {
    /// τ in seconds.
    pub fn tau_seconds(&self) -> Real {
        self.particle.tau_seconds()
    }

    /// How many τ make one output time unit.
    pub fn tau_per_unit(&self) -> Real {
        self.time_unit.seconds() / self.tau_seconds()
    }
}

/// The `[units]` of an asymmetric real particle (an ellipsoid or a
/// molecule): the particle, its body-frame rates and how to show times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralUnits {
    /// The particle.
    pub particle: RigidParticle,
    /// Body-frame rates Ω₀/2π, turns per second.
    pub omega_hz: [Real; 3],
    /// The unit of `[solve]` times and of the output.
    pub time_unit: TimeUnit,
}

impl GeneralUnits {
    /// τ_f = κ|D|²/min I in seconds, the time unit of its κ = 1 top.
    pub fn fast_time_seconds(&self) -> Real {
        self.particle.fast_time_seconds()
    }

    /// How many τ_f make one output time unit.
    pub fn u_per_unit(&self) -> Real {
        self.time_unit.seconds() / self.fast_time_seconds()
    }
}

/// The shapes of `[units] shape`.
pub const SHAPES: [&str; 4] = ["sphere", "cylinder", "ellipsoid", "molecule"];
/// The shapes of `[units]` that make an asymmetric top.
pub const GENERAL_SHAPES: [&str; 2] = ["ellipsoid", "molecule"];

pub(super) fn real_units(ctx: &Ctx, u: &RawUnits, header: &At) -> Result<RealUnits, Refusal> {
    let s = "units";
    let (shape, _) = choice(ctx, s, "shape", &u.shape, &SHAPES)?
        .ok_or_else(|| missing(ctx, header, s, "shape", "sphere or cylinder"))?;
    let shape = if shape == 0 {
        Shape::Sphere
    } else {
        Shape::Cylinder
    };
    let positive = |key: &str, v: &Key<Real>, what: &str| -> Result<Real, Refusal> {
        num_in(ctx, s, key, v, |x| x > 0.0, &format!("a positive {what}"))?
            .map(|(x, _)| x)
            .ok_or_else(|| missing(ctx, header, s, key, &format!("a positive {what}")))
    };
    let radius_nm = positive("radius_nm", &u.radius_nm, "radius in nanometres")?;
    let length_nm = match shape {
        Shape::Sphere => {
            not_here(
                ctx,
                &u.length_nm,
                s,
                "length_nm",
                "belongs to shape = \"cylinder\"; a sphere has only radius_nm",
            )?;
            0.0
        }
        Shape::Cylinder => positive("length_nm", &u.length_nm, "cylinder length in nanometres")?,
    };
    let density = positive("density_kg_m3", &u.density_kg_m3, "density in kg/m^3")?;
    let debye = positive("dipole_debye", &u.dipole_debye, "dipole moment in debye")?;
    let spin_hz = positive("spin_hz", &u.spin_hz, "spin rate in turns per second")?;
    let spin_tilt_deg = num_in(
        ctx,
        s,
        "spin_tilt_deg",
        &u.spin_tilt_deg,
        |x| (0.0..=180.0).contains(&x),
        "an angle in [0, 180] degrees between the spin and the symmetry axis",
    )?
    .map_or(45.0, |(x, _)| x);
    let upright_deg = num_in(
        ctx,
        s,
        "upright_deg",
        &u.upright_deg,
        |x| x > 0.0 && x < 90.0,
        "an angle in (0, 90) degrees",
    )?
    .map_or(1.0, |(x, _)| x);
    let time_unit = time_unit(ctx, u)?;
    let asymmetric_only = "belongs to shape = \"ellipsoid\" or \"molecule\"";
    not_here(ctx, &u.moments_amu_a2, s, "moments_amu_a2", asymmetric_only)?;
    not_here(ctx, &u.semi_axes_nm, s, "semi_axes_nm", asymmetric_only)?;
    not_here(
        ctx,
        &u.dipole_vector_debye,
        s,
        "dipole_vector_debye",
        &format!(
            "{asymmetric_only}; a sphere's or cylinder's dipole lies on its axis: dipole_debye"
        ),
    )?;
    not_here(
        ctx,
        &u.omega_hz,
        s,
        "omega_hz",
        &format!("{asymmetric_only}; a sphere or cylinder gives spin_hz and spin_tilt_deg"),
    )?;
    // NOTE: nm → cm is 1e-7, kg/m³ → g/cm³ is 1e-3: the particle works in Gaussian units.
    let particle = Particle::new(
        shape,
        radius_nm * 1e-7,
        length_nm * 1e-7,
        density * 1e-3,
        debye * DEBYE_ESU_CM,
    )
    .map_err(|e| ctx.at(header, format!("[units] {e}")))?;
    time_scale_fits(ctx, header, "tau", particle.tau_seconds())?;
    let per_tau = particle.omega0_per_tau(spin_hz, 0.0).norm();
    rate_fits(
        ctx,
        u.spin_hz.as_ref().map_or(header.clone(), |v| v.at.clone()),
        (
            &format!("spin_hz = {}", crate::numbers::short(spin_hz)),
            "tau",
            particle.tau_seconds(),
        ),
        per_tau,
    )?;
    Ok(RealUnits {
        particle,
        spin_hz,
        spin_tilt_deg,
        upright_deg,
        time_unit,
    })
}

/// A particle's time scale in seconds must be a positive, finite double.
pub(super) fn time_scale_fits(
    ctx: &Ctx,
    header: &At,
    name: &str,
    seconds: Real,
) -> Result<(), Refusal> {
    if seconds > 0.0 && seconds.is_finite() {
        Ok(())
    } else {
        Err(ctx.at(header, format!("[units] give {name} = {} s, which a double cannot hold; expected sizes and a dipole of laboratory scale", crate::numbers::fmt_value(seconds))))
    }
}

/// A rate given in hertz must not vanish in the model's unit of time: one
/// below the smallest normal double there became 0, and the top was run at
/// rest ("the tilt stays 0 deg", "a steady spin about a principal axis")
/// against the scene's own rates. `key` names the rates (as given), `unit` and
/// `seconds` the unit of time; `in_units` is the largest rate in it.
fn rate_fits(
    ctx: &Ctx,
    at: At,
    (key, unit, seconds): (&str, &str, Real),
    in_units: Real,
) -> Result<(), Refusal> {
    if in_units >= Real::MIN_POSITIVE {
        return Ok(());
    }
    Err(ctx.at(
        &at,
        format!(
            "[units] {key} is {} in the model's unit of time, {unit} = {} s, below what a double holds; expected faster rates",
            crate::numbers::short(in_units),
            crate::numbers::worked(seconds)
        ),
    ))
}

/// The time unit of `[units] time_unit` (seconds by default).
pub(super) fn time_unit(ctx: &Ctx, u: &RawUnits) -> Result<TimeUnit, Refusal> {
    Ok(
        choice(ctx, "units", "time_unit", &u.time_unit, &TIME_UNITS)?.map_or(
            TimeUnit::Second,
            |(i, _)| {
                [
                    TimeUnit::Second,
                    TimeUnit::Minute,
                    TimeUnit::Hour,
                    TimeUnit::Day,
                    TimeUnit::Year,
                ][i]
            },
        ),
    )
}

/// `[units]` of an ellipsoid or a molecule.
pub(super) fn rigid_units(ctx: &Ctx, u: &RawUnits, header: &At) -> Result<GeneralUnits, Refusal> {
    let s = "units";
    let (shape, _) = choice(ctx, s, "shape", &u.shape, &SHAPES)?
        .ok_or_else(|| missing(ctx, header, s, "shape", "ellipsoid or molecule"))?;
    if !GENERAL_SHAPES.contains(&SHAPES[shape]) {
        return Err(ctx.at(header, format!("[units] shape = \"{}\" is a symmetric top with its dipole on the axis; an asymmetric top (inertia and dipole, or model = \"general\") takes shape = \"ellipsoid\" or \"molecule\"", SHAPES[shape])));
    }
    refuse_symmetric_keys(ctx, u)?;
    let shape = if SHAPES[shape] == "ellipsoid" {
        ellipsoid(ctx, u, header)?
    } else {
        molecule(ctx, u, header)?
    };
    let dipole = three(
        ctx,
        header,
        ("dipole_vector_debye", &u.dipole_vector_debye),
        "three numbers, the body-frame dipole in debye",
    )?;
    let omega_hz = three(
        ctx,
        header,
        ("omega_hz", &u.omega_hz),
        "three body-frame rates in turns per second",
    )?;
    if omega_hz.iter().any(|x| x.abs() > 1e30) {
        return Err(ctx.at(
            header,
            "[units] omega_hz is out of range; expected each rate at most 1e30 Hz",
        ));
    }
    let particle =
        RigidParticle::new(shape, dipole).map_err(|e| ctx.at(header, format!("[units] {e}")))?;
    time_scale_fits(ctx, header, "tau_f", particle.fast_time_seconds())?;
    if omega_hz.iter().any(|&f| f != 0.0) {
        rate_fits(
            ctx,
            u.omega_hz.as_ref().map_or(header.clone(), |v| v.at.clone()),
            ("omega_hz", "tau_f", particle.fast_time_seconds()),
            particle.omega0(omega_hz).amax(),
        )?;
    }
    Ok(GeneralUnits {
        particle,
        omega_hz,
        time_unit: time_unit(ctx, u)?,
    })
}

/// Three finite numbers a key of `[units]` must give.
fn three(
    ctx: &Ctx,
    header: &At,
    (key, v): (&str, &Key<[Real; 3]>),
    what: &str,
) -> Result<[Real; 3], Refusal> {
    finite_array(ctx, "units", key, v, what)?
        .map(|(x, _)| x)
        .ok_or_else(|| missing(ctx, header, "units", key, what))
}

/// Refuse the keys of a sphere or a cylinder in an asymmetric particle's `[units]`.
fn refuse_symmetric_keys(ctx: &Ctx, u: &RawUnits) -> Result<(), Refusal> {
    let s = "units";
    let symmetric_only = "belongs to shape = \"sphere\" or \"cylinder\"";
    not_here(
        ctx,
        &u.radius_nm,
        s,
        "radius_nm",
        &format!("{symmetric_only}; an ellipsoid has semi_axes_nm, a molecule moments_amu_a2"),
    )?;
    not_here(ctx, &u.length_nm, s, "length_nm", symmetric_only)?;
    not_here(
        ctx,
        &u.dipole_debye,
        s,
        "dipole_debye",
        &format!(
            "{symmetric_only}, whose dipole lies on the axis; give dipole_vector_debye = [D1, D2, D3]"
        ),
    )?;
    not_here(
        ctx,
        &u.spin_hz,
        s,
        "spin_hz",
        &format!("{symmetric_only}; give omega_hz = [f1, f2, f3], the body-frame rates"),
    )?;
    not_here(
        ctx,
        &u.spin_tilt_deg,
        s,
        "spin_tilt_deg",
        &format!("{symmetric_only}; give omega_hz = [f1, f2, f3]"),
    )?;
    not_here(ctx, &u.upright_deg, s, "upright_deg", symmetric_only)
}

/// An ellipsoid: its semi-axes and density.
fn ellipsoid(ctx: &Ctx, u: &RawUnits, header: &At) -> Result<RigidShape, Refusal> {
    let s = "units";
    not_here(
        ctx,
        &u.moments_amu_a2,
        s,
        "moments_amu_a2",
        "belongs to shape = \"molecule\"; an ellipsoid's moments follow from semi_axes_nm and density_kg_m3",
    )?;
    let density = num_in(
        ctx,
        s,
        "density_kg_m3",
        &u.density_kg_m3,
        |x| x > 0.0,
        "a positive density in kg/m^3",
    )?
    .map(|(x, _)| x)
    .ok_or_else(|| {
        missing(
            ctx,
            header,
            s,
            "density_kg_m3",
            "a positive density in kg/m^3",
        )
    })?;
    Ok(RigidShape::Ellipsoid {
        semi_axes_nm: three(
            ctx,
            header,
            ("semi_axes_nm", &u.semi_axes_nm),
            "three positive semi-axes in nm, along the body axes",
        )?,
        density_kg_m3: density,
    })
}

/// A molecule: its rigid principal moments.
fn molecule(ctx: &Ctx, u: &RawUnits, header: &At) -> Result<RigidShape, Refusal> {
    let s = "units";
    let belongs = "belongs to shape = \"ellipsoid\"; a molecule gives moments_amu_a2";
    not_here(ctx, &u.semi_axes_nm, s, "semi_axes_nm", belongs)?;
    not_here(ctx, &u.density_kg_m3, s, "density_kg_m3", belongs)?;
    let m = three(
        ctx,
        header,
        ("moments_amu_a2", &u.moments_amu_a2),
        "three principal moments in amu A^2",
    )?;
    for (k, &mk) in m.iter().enumerate() {
        // NOTE: the other two summed, not the total less this one, which
        // cancels to 0 beside a moment of 1e300.
        let others = m[(k + 1) % 3] + m[(k + 2) % 3];
        if mk > others * (1.0 + 1e-12) {
            let at = u
                .moments_amu_a2
                .as_ref()
                .map_or(header.clone(), |v| v.at.clone());
            return Err(ctx.at(&at, format!("[units] moments_amu_a2: I{} = {} exceeds the sum of the other two, {}, by {} amu A^2, which no rigid body does; measured moments carry the inertia defect of vibration, so give the rigid ones (I_C = I_A + I_B for a planar molecule)", k + 1, crate::numbers::short(mk), crate::numbers::short(others), crate::numbers::sci(Some(mk - others)))));
        }
    }
    Ok(RigidShape::Molecule { moments_amu_a2: m })
}
