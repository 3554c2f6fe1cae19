//! A real particle's report beside a scene's answer: its inputs in SI and
//! CGS units, the conversion to τ units, and its milestones in seconds.

use super::RealUnits;
use crate::math::Real;
use crate::numbers::{fmt_value, worked};
use crate::physics::particle::{DEBYE_ESU_CM, Milestones, SPEED_OF_LIGHT_CM_S};
use serde::Serialize;

/// A real particle's inputs, the conversion to τ units, and its milestones.
#[derive(Clone, Debug, Serialize)]
pub struct PhysicalReport {
    /// `sphere` or `cylinder`.
    pub shape: &'static str,
    /// Radius, nm.
    pub radius_nm: Real,
    /// Cylinder length, nm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_nm: Option<Real>,
    /// Density, kg/m³.
    pub density_kg_m3: Real,
    /// Mass, kg.
    pub mass_kg: Real,
    /// I₁, kg·m².
    pub i1_kg_m2: Real,
    /// I₃, kg·m².
    pub i3_kg_m2: Real,
    /// I₃/I₁.
    pub ratio: Real,
    /// Dipole, debye.
    pub dipole_debye: Real,
    /// Dipole, statC·cm.
    pub dipole_esu_cm: Real,
    /// Spin rate, Hz.
    pub spin_hz: Real,
    /// Angle between Ω₀ and the symmetry axis, degrees.
    pub spin_tilt_deg: Real,
    /// τ = 2d²/(3I₁c³), in seconds.
    pub tau_s: Real,
    /// The conversion, written out with the numbers.
    pub conversion: String,
    /// τ|Ω₀|, the size of the radiation effect per radian.
    pub tau_omega: Real,
    /// The output time unit.
    pub time_unit: &'static str,
    /// Seconds per output time unit.
    pub seconds_per_unit: Real,
    /// τ per output time unit.
    pub tau_per_unit: Real,
    /// The milestones, from the closed forms of both models.
    pub milestones: MilestoneTimes,
}

/// A time in three units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Span {
    /// In units of τ.
    pub tau: Real,
    /// In seconds.
    pub seconds: Real,
    /// In the scene's time unit.
    pub unit: Real,
}

/// [`Milestones`] in seconds and in the scene's unit; `null` means never.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MilestoneTimes {
    /// Truncated model: |Ω| halves.
    pub truncated_half_spin: Option<Span>,
    /// Truncated model: the constant tilt between axis and L, degrees.
    pub truncated_tilt_deg: Real,
    /// Reduced model: |Ω| halves.
    pub reduced_half_spin: Option<Span>,
    /// Reduced model: the final spin rate |Ω₃|/2π, Hz.
    pub reduced_final_spin_hz: Real,
    /// Reduced model: σ, the late e-folding time of Ω⊥ and of the tilt.
    pub reduced_tilt_decay: Option<Span>,
    /// Reduced model: the tilt falls below `upright_deg`.
    pub reduced_upright: Option<Span>,
    /// The tilt counted as upright, degrees.
    pub upright_deg: Real,
}

/// The physical report of a `[units]` scene.
pub fn physical_report(units: &RealUnits) -> PhysicalReport {
    let p = &units.particle;
    let tau_s = units.tau_seconds();
    let (i1, i3) = p.moments_g_cm2();
    let omega0 = p.omega0_per_tau(units.spin_hz, units.spin_tilt_deg.to_radians());
    let m = Milestones::new(&p.top(), &omega0, units.upright_deg.to_radians());
    let per_unit = units.time_unit.seconds();
    let span = |t: Option<Real>| {
        t.map(|tau| Span {
            tau,
            seconds: tau * tau_s,
            unit: tau * tau_s / per_unit,
        })
    };
    let d = p.dipole_esu_cm();
    PhysicalReport {
        shape: p.shape().name(),
        radius_nm: p.radius_cm() * 1e7,
        length_nm: (p.length_cm() > 0.0).then(|| p.length_cm() * 1e7),
        density_kg_m3: p.density_g_cm3() * 1e3,
        mass_kg: p.mass_g() * 1e-3,
        i1_kg_m2: i1 * 1e-7,
        i3_kg_m2: i3 * 1e-7,
        ratio: p.ratio(),
        dipole_debye: d / DEBYE_ESU_CM,
        dipole_esu_cm: d,
        spin_hz: units.spin_hz,
        spin_tilt_deg: units.spin_tilt_deg,
        tau_s,
        conversion: format!(
            "tau = 2 d^2/(3 I1 c^3) = 2 ({} statC cm)^2 / (3 x {} g cm^2 x ({} cm/s)^3) = {} s (Gaussian units)",
            worked(d),
            worked(i1),
            fmt_value(SPEED_OF_LIGHT_CM_S),
            worked(tau_s)
        ),
        tau_omega: omega0.norm(),
        time_unit: units.time_unit.name(),
        seconds_per_unit: per_unit,
        tau_per_unit: units.tau_per_unit(),
        milestones: MilestoneTimes {
            truncated_half_spin: span(m.truncated_half_spin),
            truncated_tilt_deg: m.truncated_tilt.to_degrees(),
            reduced_half_spin: span(m.reduced_half_spin),
            reduced_final_spin_hz: m.reduced_final_spin / tau_s / (2.0 * std::f64::consts::PI),
            reduced_tilt_decay: span(m.reduced_tilt_decay),
            reduced_upright: span(m.reduced_upright),
            upright_deg: units.upright_deg,
        },
    }
}
