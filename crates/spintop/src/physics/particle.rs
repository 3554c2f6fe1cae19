//! A real particle: shape, size, density and dipole moment in laboratory
//! units, turned into the paper's units, and the milestones of its spin-down.
//!
//! The paper's introduction (§1) points at nanoparticles in optical traps spun
//! to GHz, with dipole moments of 10³–10⁷ debye. Its equations are written in
//! units where τ = 2d²/(3I₁c³) = 1 and I₁ = 1 (§4, after (4.4)); this module
//! computes τ in seconds in Gaussian units, so every time of the closed forms
//! can be read in seconds or years.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `radius_cm`, `length_cm` | a, h | sphere or cylinder radius, cylinder length | cm |
//! | `density_g_cm3` | ρ | mass density | g/cm³ |
//! | `dipole_esu_cm` | d | permanent dipole, along the symmetry axis (4.1) | statC·cm |
//! | `i1`, `i3` | I₁, I₃ | principal moments about a diameter and the axis | g·cm² |
//! | `tau_s` | τ | 2d²/(3I₁c³), the time unit of §4 | s |
//!
//! Moments of a homogeneous body of mass M: a sphere has I₁ = I₃ = (2/5)Ma²
//! (so I₃/I₁ = 1); a cylinder has I₃ = Ma²/2 and I₁ = M(3a² + h²)/12, so
//! I₃/I₁ = 6a²/(3a² + h²), which lies in (0, 2) as a rigid body's must.

use super::general_top::GeneralTop;
use super::symmetric_top::{
    SymmetricTop, precession_tilt, reduced_time_to_factor, truncated_time_to_factor,
};
use super::{ParamError, finite};
use crate::math::{Real, Vec3};
use serde::Serialize;

/// The speed of light in cm/s (exact by the definition of the metre).
pub const SPEED_OF_LIGHT_CM_S: Real = 2.997_924_58e10;

/// One debye in statC·cm (Gaussian units), exact by definition.
pub const DEBYE_ESU_CM: Real = 1e-18;

/// One debye in C·m (= 10⁻²¹/c C·m with c in m/s).
pub const DEBYE_C_M: Real = 3.335_640_951_981_52e-30;

/// Seconds in one Julian year (365.25 days), the year of astronomy.
pub const SECONDS_PER_YEAR: Real = 31_557_600.0;

/// The shape of a homogeneous particle; its symmetry axis carries the dipole.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Shape {
    /// A ball of radius a: I₃/I₁ = 1.
    Sphere,
    /// A solid cylinder of radius a and length h along its axis.
    Cylinder,
}

impl Shape {
    /// `sphere` or `cylinder`.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere => "sphere",
            Shape::Cylinder => "cylinder",
        }
    }
}

/// A homogeneous sphere or cylinder with a permanent dipole on its axis, in
/// Gaussian units. Built only through [`Particle::new`], so every size is
/// positive and finite and its I₃/I₁ is a rigid body's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle {
    shape: Shape,
    radius_cm: Real,
    length_cm: Real,
    density_g_cm3: Real,
    dipole_esu_cm: Real,
    /// The paper's symmetric top of its I₃/I₁, built (and so checked) once.
    top: SymmetricTop,
}

/// I₃/I₁ of a homogeneous sphere (1) or cylinder of radius a and length h
/// (6a²/(3a² + h²)).
fn shape_ratio(shape: Shape, radius_cm: Real, length_cm: Real) -> Real {
    match shape {
        Shape::Sphere => 1.0,
        Shape::Cylinder => {
            let (a2, h2) = (radius_cm.powi(2), length_cm.powi(2));
            6.0 * a2 / (3.0 * a2 + h2)
        }
    }
}

fn positive(name: &'static str, value: Real) -> Result<Real, ParamError> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ParamError::OutOfRange {
            name,
            value,
            range: "positive",
        })
    }
}

impl Particle {
    /// Validate the sizes (the length is ignored for a sphere).
    pub fn new(
        shape: Shape,
        radius_cm: Real,
        length_cm: Real,
        density_g_cm3: Real,
        dipole_esu_cm: Real,
    ) -> Result<Self, ParamError> {
        positive("radius", radius_cm)?;
        if shape == Shape::Cylinder {
            positive("length", length_cm)?;
        }
        positive("density", density_g_cm3)?;
        positive("dipole", dipole_esu_cm)?;
        let length_cm = if shape == Shape::Cylinder {
            length_cm
        } else {
            0.0
        };
        let ratio = shape_ratio(shape, radius_cm, length_cm);
        // NOTE: a cylinder 150 decades longer than wide has I₃/I₁ = 6a²/(3a²
        // + h²) below the smallest double: refused here, as a parameter.
        let top = SymmetricTop::new(ratio, 1.0).map_err(|_| ParamError::OutOfRange {
            name: "I3/I1 of the shape",
            value: ratio,
            range: "in (0, 2], which a double cannot hold when the length and the radius differ by some 150 decades or more",
        })?;
        Ok(Self {
            shape,
            radius_cm,
            length_cm,
            density_g_cm3,
            dipole_esu_cm,
            top,
        })
    }

    /// The shape.
    pub fn shape(&self) -> Shape {
        self.shape
    }

    /// The radius a, in cm.
    pub fn radius_cm(&self) -> Real {
        self.radius_cm
    }

    /// The cylinder's length h, in cm (0 for a sphere).
    pub fn length_cm(&self) -> Real {
        self.length_cm
    }

    /// The density ρ, in g/cm³.
    pub fn density_g_cm3(&self) -> Real {
        self.density_g_cm3
    }

    /// The dipole d, in statC·cm.
    pub fn dipole_esu_cm(&self) -> Real {
        self.dipole_esu_cm
    }

    /// The volume, in cm³.
    pub fn volume_cm3(&self) -> Real {
        let a = self.radius_cm;
        match self.shape {
            Shape::Sphere => 4.0 / 3.0 * std::f64::consts::PI * a.powi(3),
            Shape::Cylinder => std::f64::consts::PI * a * a * self.length_cm,
        }
    }

    /// The mass M, in g.
    pub fn mass_g(&self) -> Real {
        self.density_g_cm3 * self.volume_cm3()
    }

    /// The principal moments (I₁, I₃) about a diameter and about the axis, in g·cm².
    pub fn moments_g_cm2(&self) -> (Real, Real) {
        let (m, a, h) = (self.mass_g(), self.radius_cm, self.length_cm);
        match self.shape {
            Shape::Sphere => {
                let i = 0.4 * m * a * a;
                (i, i)
            }
            Shape::Cylinder => (m * (3.0 * a * a + h * h) / 12.0, 0.5 * m * a * a),
        }
    }

    /// I₃/I₁: 1 for a sphere, 6a²/(3a² + h²) for a cylinder.
    pub fn ratio(&self) -> Real {
        shape_ratio(self.shape, self.radius_cm, self.length_cm)
    }

    // ANCHOR: tau_seconds
    /// τ in seconds, Gaussian units.
    ///
    /// Paper: Eq. (4.4) (the definition of τ that follows it).
    ///
    /// ```text
    /// τ = 2d² / (3 I₁ c³)
    /// ```
    pub fn tau_seconds(&self) -> Real {
        let (i1, _) = self.moments_g_cm2();
        let d = self.dipole_esu_cm;
        2.0 * d * d / (3.0 * i1 * SPEED_OF_LIGHT_CM_S.powi(3))
    }
    // ANCHOR_END: tau_seconds

    /// The particle as the paper's symmetric top (I₁ = 1, τ = 1 units).
    pub fn top(&self) -> SymmetricTop {
        self.top
    }

    /// The body rate Ω₀, in 1/τ, of a particle spinning at `spin_hz` turns per
    /// second about an axis at `tilt` radians from its symmetry axis (in the
    /// body's 2–3 plane, as the paper's Ω₁₀ = 0).
    pub fn omega0_per_tau(&self, spin_hz: Real, tilt: Real) -> Vec3 {
        let w = 2.0 * std::f64::consts::PI * spin_hz * self.tau_seconds();
        Vec3::new(0.0, w * tilt.sin(), w * tilt.cos())
    }
}

/// One atomic mass unit times one square ångström, in g·cm² (CODATA 2018:
/// 1 u = 1.660 539 066 60 × 10⁻²⁴ g, 1 Å = 10⁻⁸ cm).
pub const AMU_A2_G_CM2: Real = 1.660_539_066_60e-40;

/// κ = 2/(3c³) in s³/cm³, the constant of (2.1) in Gaussian units.
pub fn kappa_gaussian() -> Real {
    2.0 / (3.0 * SPEED_OF_LIGHT_CM_S.powi(3))
}

/// What an asymmetric real particle is made of.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RigidShape {
    /// A molecule, given by its principal moments (amu·Å², as spectroscopy
    /// tables list them).
    Molecule {
        /// I_A, I_B, I_C in amu·Å², in the body axes 1, 2, 3.
        moments_amu_a2: [Real; 3],
    },
    /// A homogeneous ellipsoid with semi-axes a₁, a₂, a₃ along the body axes:
    /// I₁ = M(a₂² + a₃²)/5 and cyclically, M = (4/3)π a₁a₂a₃ ρ.
    Ellipsoid {
        /// a₁, a₂, a₃ in nm.
        semi_axes_nm: [Real; 3],
        /// ρ in kg/m³.
        density_kg_m3: Real,
    },
}

/// An asymmetric rigid particle with a permanent dipole anywhere in the body,
/// in Gaussian units, and the κ = 1 units of the general top it becomes.
///
/// The general ALE (3.3) is I Ω̇ + Ω × IΩ = κ × (terms quadratic in D, cubic
/// in Ω). Measuring moments in I_min, the dipole in |D| and time in
/// τ_f = κ|D|²/I_min (the fast time) turns it into the κ = 1 form with
/// min I = 1 and |d| = 1, so that τ_f = 1 there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidParticle {
    shape: RigidShape,
    inertia_g_cm2: Vec3,
    dipole_esu_cm: Vec3,
    /// Its κ = 1 top, built (and so checked) once.
    top: GeneralTop,
}

impl RigidParticle {
    /// Validate the shape (positive sizes, moments that a rigid body can
    /// have) and a non-zero dipole (`dipole_debye`, body frame).
    pub fn new(shape: RigidShape, dipole_debye: [Real; 3]) -> Result<Self, ParamError> {
        let inertia = match shape {
            RigidShape::Molecule { moments_amu_a2 } => {
                for (name, m) in ["I_A", "I_B", "I_C"].into_iter().zip(moments_amu_a2) {
                    positive(name, m)?;
                }
                Vec3::from(moments_amu_a2) * AMU_A2_G_CM2
            }
            RigidShape::Ellipsoid {
                semi_axes_nm,
                density_kg_m3,
            } => {
                for (name, a) in ["a1", "a2", "a3"].into_iter().zip(semi_axes_nm) {
                    positive(name, a)?;
                }
                positive("density", density_kg_m3)?;
                let [a1, a2, a3] = semi_axes_nm.map(|a| a * 1e-7);
                let mass = 4.0 / 3.0 * std::f64::consts::PI * a1 * a2 * a3 * density_kg_m3 * 1e-3;
                Vec3::new(a2 * a2 + a3 * a3, a3 * a3 + a1 * a1, a1 * a1 + a2 * a2) * (mass / 5.0)
            }
        };
        // The moments must be a rigid body's (triangle inequalities), checked
        // in the same relative form as the general top's.
        super::check_principal_moments(&(inertia / inertia.max()))?;
        for (name, d) in ["D1", "D2", "D3"].into_iter().zip(dipole_debye) {
            finite(name, d)?;
        }
        let dipole = Vec3::from(dipole_debye) * DEBYE_ESU_CM;
        if dipole == Vec3::zeros() {
            return Err(ParamError::ZeroDipole);
        }
        // The κ = 1 top: moments over min I, dipole over |D|, checked as any
        // general top is (a |D| that overflows a double is refused here).
        let top = GeneralTop::new(inertia / inertia.min(), dipole / dipole.norm())?;
        Ok(Self {
            shape,
            inertia_g_cm2: inertia,
            dipole_esu_cm: dipole,
            top,
        })
    }

    /// What it is made of.
    pub fn shape(&self) -> RigidShape {
        self.shape
    }

    /// Principal moments, g·cm².
    pub fn inertia_g_cm2(&self) -> Vec3 {
        self.inertia_g_cm2
    }

    /// The body-frame dipole, statC·cm.
    pub fn dipole_esu_cm(&self) -> Vec3 {
        self.dipole_esu_cm
    }

    /// τ_f = κ|D|²/min I in seconds: the time unit of its κ = 1 top.
    pub fn fast_time_seconds(&self) -> Real {
        kappa_gaussian() * self.dipole_esu_cm.norm_squared() / self.inertia_g_cm2.min()
    }

    /// The general top in κ = 1 units: moments over min I, dipole over |D|.
    pub fn top(&self) -> GeneralTop {
        self.top
    }

    /// Ω₀ in the top's units from body-frame rates in turns per second.
    pub fn omega0(&self, omega_hz: [Real; 3]) -> Vec3 {
        Vec3::from(omega_hz) * (2.0 * std::f64::consts::PI * self.fast_time_seconds())
    }
}

/// What the closed forms say about how long a symmetric top takes to slow
/// down and to stand upright, in units of τ. `None` means never.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Milestones {
    /// Truncated model: |Ω| halves (every component falls as 1/R(t)).
    pub truncated_half_spin: Option<Real>,
    /// Truncated model: the constant tilt between axis and L, in radians
    /// (corrected (4.11)); the top never stands upright.
    pub truncated_tilt: Real,
    /// Reduced model: |Ω| halves; never when Ω₃ ≥ |Ω₀|/2, since Ω₃ is kept.
    pub reduced_half_spin: Option<Real>,
    /// Reduced model: the final spin rate |Ω₃|, in 1/τ.
    pub reduced_final_spin: Real,
    /// Reduced model: σ = I₁²/(I₃²Ω₃²τ), the late e-folding time of Ω⊥ and of the tilt.
    pub reduced_tilt_decay: Option<Real>,
    /// Reduced model: the tilt between axis and L falls below `upright_angle`.
    pub reduced_upright: Option<Real>,
    /// The tilt counted as upright, in radians.
    pub upright_angle: Real,
}

fn finite_time(t: Real) -> Option<Real> {
    t.is_finite().then_some(t)
}

// ANCHOR: milestones
impl Milestones {
    /// The milestones of a top started at Ω₀ (I₁ = 1, τ units).
    ///
    /// Paper: Eq. (4.6), Eq. (4.11), Eq. (4.16).
    ///
    /// ```text
    /// truncated: |Ω| = |Ω₀|/R(t)       ⇒ halves at t = 3/(2τΩ⊥₀²)
    /// reduced:   |Ω|² = Ω⊥₀²Φ² + Ω₃²   ⇒ halves when Φ² = (|Ω₀|²/4 − Ω₃²)/Ω⊥₀²
    ///            tan(tilt) = Ω⊥/|k|    ⇒ upright when Φ = |k| tan(angle)/Ω⊥₀
    /// ```
    pub fn new(top: &SymmetricTop, omega0: &Vec3, upright_angle: Real) -> Self {
        let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
        let w0 = u0.sqrt();
        let k = (top.ratio() * omega0.z).abs();
        let quarter = 0.25 * (u0 + omega0.z * omega0.z) - omega0.z * omega0.z;
        let reduced_half_spin = (quarter > 0.0)
            .then(|| reduced_time_to_factor(top, omega0, (quarter / u0).sqrt()))
            .and_then(finite_time);
        let reduced_upright = if w0 <= k * upright_angle.tan() {
            Some(0.0)
        } else if k == 0.0 {
            None
        } else {
            finite_time(reduced_time_to_factor(
                top,
                omega0,
                k * upright_angle.tan() / w0,
            ))
        };
        Self {
            truncated_half_spin: finite_time(truncated_time_to_factor(top, w0, 0.5)),
            truncated_tilt: precession_tilt(top, omega0),
            reduced_half_spin,
            reduced_final_spin: omega0.z.abs(),
            reduced_tilt_decay: (k > 0.0 && top.tau() > 0.0).then(|| 1.0 / (k * k * top.tau())),
            reduced_upright,
            upright_angle,
        }
    }
}
// ANCHOR_END: milestones

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn silica_sphere(debye: Real) -> Particle {
        Particle::new(Shape::Sphere, 50e-7, 0.0, 2.2, debye * DEBYE_ESU_CM).unwrap()
    }

    /// The same τ from the SI form μ₀d²/(6πcI₁), an independent route through
    /// other constants (μ₀ = 4π × 10⁻⁷ to the precision used here).
    #[test]
    fn tau_in_gaussian_units_equals_the_si_form() {
        let p = silica_sphere(1e3);
        let (i1_cgs, _) = p.moments_g_cm2();
        let i1_si = i1_cgs * 1e-7;
        let d_si = 1e3 * DEBYE_C_M;
        let mu0 = 4e-7 * std::f64::consts::PI;
        let tau_si = mu0 * d_si * d_si / (6.0 * std::f64::consts::PI * 299_792_458.0 * i1_si);
        assert_relative_eq!(p.tau_seconds(), tau_si, max_relative = 1e-9);
    }

    #[test]
    fn cylinder_moments_follow_the_textbook_formulas() {
        let p = Particle::new(Shape::Cylinder, 1.0, 2.0, 1.0, 1.0).unwrap();
        let m = std::f64::consts::PI * 2.0;
        let (i1, i3) = p.moments_g_cm2();
        assert_relative_eq!(i3, m / 2.0, max_relative = 1e-15);
        assert_relative_eq!(i1, m * 7.0 / 12.0, max_relative = 1e-15);
        assert_relative_eq!(p.ratio(), i3 / i1, max_relative = 1e-15);
        // A flat disc approaches the limit I₃ = 2I₁ but never passes it.
        let disc = Particle::new(Shape::Cylinder, 1.0, 1e-3, 1.0, 1.0).unwrap();
        assert!(disc.ratio() < 2.0 && disc.ratio() > 1.999_99);
        assert!(SymmetricTop::new(disc.ratio(), 1.0).is_ok());
    }

    #[test]
    fn sizes_must_be_positive_and_finite() {
        assert!(Particle::new(Shape::Sphere, -1.0, 0.0, 1.0, 1.0).is_err());
        assert!(Particle::new(Shape::Cylinder, 1.0, 0.0, 1.0, 1.0).is_err());
        assert!(Particle::new(Shape::Sphere, 1.0, 0.0, Real::NAN, 1.0).is_err());
        assert!(Particle::new(Shape::Sphere, 1.0, 0.0, 1.0, 0.0).is_err());
        assert!(Particle::new(Shape::Sphere, 1.0, 0.0, 1.0, 1.0).is_ok());
    }

    /// A top that starts upright is upright at once; one without spin about its
    /// axis never stands up; one mostly spun about its axis never halves its rate.
    #[test]
    fn milestones_edge_cases() {
        let top = SymmetricTop::figure();
        let m = Milestones::new(&top, &Vec3::new(0.0, 1e-6, 0.2), 1e-2);
        assert_eq!(m.reduced_upright, Some(0.0));
        let m = Milestones::new(&top, &Vec3::new(0.0, 0.1, 0.0), 1e-2);
        assert_eq!(m.reduced_upright, None);
        assert_eq!(m.reduced_tilt_decay, None);
        let m = Milestones::new(&top, &Vec3::new(0.0, 0.1, 0.2), 1e-2);
        assert_eq!(m.reduced_half_spin, None);
        assert_relative_eq!(m.truncated_half_spin.unwrap(), 150.0, max_relative = 1e-14);
        assert_relative_eq!(m.reduced_tilt_decay.unwrap(), 156.25, max_relative = 1e-14);
    }
}
