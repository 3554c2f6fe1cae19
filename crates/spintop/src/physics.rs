//! The paper's physics, one module per concept. Pure: no I/O, no clock, no
//! printing; the same input gives the same bits.
//!
//! | module | paper | what it holds |
//! |---|---|---|
//! | [`balance`] | §2, (2.1)–(2.4) | the Larmor-like law, the torque law and the Schott angular momentum of any dipole trajectory |
//! | [`radiation`] | §1–§2, (2.1) | the dipole's fields, the energy and angular momentum they carry through a sphere, Larmor's power |
//! | [`central`] | §2, (2.5)–(2.9) | a charge in a Coulomb or oscillator potential: Abraham–Lorentz, Landau–Lifshitz, collapse, runaways |
//! | [`rigid_body`] | §3, (3.1)–(3.2) | kinematics, `Ω̇ = F(Ω)` models, observables E, L, tilt |
//! | [`euler_angles`] | (3.5), (4.8) | z-x-z Euler angles and their rates |
//! | [`general_top`] | (3.3) | the truncated ALE for any principal moments and dipole |
//! | [`symmetric_top`] | §4, (4.1)–(4.18) | truncated and reduced ALE of the axially symmetric top, closed forms |
//! | [`full_ale`] | (3.4) | the full ALE with its Schott term, as first-order systems |
//! | [`shell`] | Appendix, (A.1)–(A.3) | the charge as a small shell: a neutral delay equation, its roots and balance |
//! | [`particle`] | §1, (4.4), (4.6), (4.16) | a real sphere or cylinder in Gaussian units: τ in seconds, spin-down and upright times |
//!
//! Units: κ = 2/(3c³) = 1 for the general top; τ = 2d²/(3I₁c³) = 1 and I₁ = 1 for
//! the symmetric top (so times are in units of τ and rates in units of 1/τ).

use crate::math::Real;
use thiserror::Error;

pub mod balance;
pub mod central;
pub mod euler_angles;
pub mod free_top;
pub mod full_ale;
pub mod general_top;
pub mod particle;
pub mod radiation;
pub mod rigid_body;
pub mod shell;
pub mod symmetric_top;

/// A physical parameter that was refused when a model was built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ParamError {
    /// An input that must be a finite number was not.
    #[error("{name} must be a finite number, got {value}")]
    NotFinite {
        /// Which input.
        name: &'static str,
        /// Its value.
        value: Real,
    },
    /// The symmetric top's I₃/I₁ lies outside (0, 2].
    #[error(
        "I3/I1 = {} is not a rigid body: the moments must be positive and obey I3 <= I1 + I2 = 2 I1, so 0 < I3/I1 <= 2",
        crate::numbers::fmt_value(*.0)
    )]
    RatioOutOfRange(Real),
    /// A principal moment is not positive.
    #[error("principal moment I{index} = {} must be positive", crate::numbers::fmt_value(*value))]
    MomentNotPositive {
        /// 1, 2 or 3.
        index: usize,
        /// Its value.
        value: Real,
    },
    /// The principal moments break a triangle inequality.
    #[error(
        "moments ({}, {}, {}) are not a rigid body: each must be at most the sum of the other two",
        crate::numbers::fmt_value(*.0),
        crate::numbers::fmt_value(*.1),
        crate::numbers::fmt_value(*.2)
    )]
    TriangleInequality(Real, Real, Real),
    /// The dipole is zero, so there is no radiation and no model to study.
    #[error("the dipole must be non-zero (a top without a dipole does not radiate)")]
    ZeroDipole,
    /// τ is negative.
    #[error("tau must be >= 0, got {}", crate::numbers::fmt_value(*.0))]
    NegativeTau(Real),
    /// A parameter lies outside its allowed range (Section 2's models).
    #[error("{name} = {} is out of range: it must be {range}", crate::numbers::fmt_value(*value))]
    OutOfRange {
        /// Which input.
        name: &'static str,
        /// Its value.
        value: Real,
        /// The allowed range, in words.
        range: &'static str,
    },
}

/// Refuse a non-finite input, naming it.
pub(crate) fn finite(name: &'static str, value: Real) -> Result<Real, ParamError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ParamError::NotFinite { name, value })
    }
}

/// Refuse principal moments that no rigid body has: each finite and positive,
/// and each at most the sum of the other two (the triangle inequality).
///
/// NOTE: a tiny relative slack lets the flat limit I₃ = I₁ + I₂ (a disc)
/// through when it is written with rounded decimals.
pub(crate) fn check_principal_moments(inertia: &crate::math::Vec3) -> Result<(), ParamError> {
    for (i, name) in ["I1", "I2", "I3"].into_iter().enumerate() {
        finite(name, inertia[i])?;
        if inertia[i] <= 0.0 {
            return Err(ParamError::MomentNotPositive {
                index: i + 1,
                value: inertia[i],
            });
        }
    }
    let (a, b, c) = (inertia.x, inertia.y, inertia.z);
    let slack = 1e-12 * (a + b + c);
    if a > b + c + slack || b > a + c + slack || c > a + b + slack {
        return Err(ParamError::TriangleInequality(a, b, c));
    }
    Ok(())
}
