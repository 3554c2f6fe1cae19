//! The raw shape of a question, as a scene file's TOML gives it or as a
//! command's flags fill it: every key optional and marked with where it came
//! from, unknown keys refused by serde. [`super::parse`] (a file) and
//! [`super::request`] (flags) turn these into validated questions by the same
//! code, reporting missing keys and bad values at the file's line or at the
//! flag.

use crate::math::Real;
use serde::{Deserialize, Deserializer};
use std::ops::Range;
use toml::Spanned;

/// Where a value came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum At {
    /// The byte range of its text in a scene file.
    Text(Range<usize>),
    /// A flag of the command line (the message names the flag).
    Flag,
}

/// A value as given, and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Given<T> {
    /// The value.
    pub value: T,
    /// Where it was given.
    pub at: At,
}

impl<T> Given<T> {
    /// A value given by a flag.
    pub fn flag(value: T) -> Self {
        Self {
            value,
            at: At::Flag,
        }
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Given<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let spanned = Spanned::<T>::deserialize(d)?;
        Ok(Self {
            at: At::Text(spanned.span()),
            value: spanned.into_inner(),
        })
    }
}

/// An optional key, with where it was given.
pub type Key<T> = Option<Given<T>>;

/// A key holding exactly `N` numbers: serde's arrays would take the first
/// `N` of a longer list and drop the rest without a word.
fn exact<'de, D, const N: usize>(d: D) -> Result<Key<[Real; N]>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    use serde::de::Error;
    let Some(list) = Option::<Given<Vec<Real>>>::deserialize(d)? else {
        return Ok(None);
    };
    let n = list.value.len();
    let at = list.at;
    <[Real; N]>::try_from(list.value)
        .map(|value| Some(Given { value, at }))
        .map_err(|_| D::Error::custom(format!("expected {N} numbers, got {n}")))
}

/// A scene file: its sections.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFile {
    /// `[scene]`: name, kind, description.
    pub scene: Key<RawScene>,
    /// `[top]`: a top (`simulate`, `plot`).
    pub top: Key<RawTop>,
    /// `[balance]`: a dipole trajectory (`balance`).
    pub balance: Key<RawBalance>,
    /// `[orbit]`: a charge in a central field (`orbit`).
    pub orbit: Key<RawOrbit>,
    /// `[shell]`: the charge as a shell (`shell`).
    pub shell: Key<RawShell>,
    /// `[stability]`: a row of the stability suite.
    pub stability: Key<RawStability>,
    /// `[solve]`: the times, and the method where the kind takes one.
    pub solve: Key<RawSolve>,
    /// `[units]`: a real particle.
    pub units: Key<RawUnits>,
}

/// `[scene]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// Lower-case letters, digits and dashes.
    pub name: Key<String>,
    /// `top`, `balance`, `orbit`, `shell` or `stability`.
    pub kind: Key<String>,
    /// What the scene asks.
    pub description: Key<String>,
}

/// `[top]`, or the flags of `simulate` and `plot` (see [`super::table`]).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTop {
    /// A name of [`super::table::MODELS`].
    pub model: Key<String>,
    /// I₃/I₁ of a symmetric top.
    pub ratio: Key<Real>,
    /// The principal moments of an asymmetric top.
    #[serde(default, deserialize_with = "exact")]
    pub inertia: Key<[Real; 3]>,
    /// The body-frame dipole of an asymmetric top.
    #[serde(default, deserialize_with = "exact")]
    pub dipole: Key<[Real; 3]>,
    /// Ω₀ in the body frame.
    #[serde(default, deserialize_with = "exact")]
    pub omega: Key<[Real; 3]>,
    /// The z-x-z Euler angles of O(0).
    #[serde(default, deserialize_with = "exact")]
    pub euler: Key<[Real; 3]>,
    /// `paper`: lab z along L₀.
    pub frame: Key<String>,
}

/// `[balance]`, or the flags of `balance`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBalance {
    /// A name of [`super::table::DIPOLES`].
    pub dipole: Key<String>,
    /// The cone half-angle of the precessing dipole.
    pub cone: Key<Real>,
    /// The rate of the precessing dipole or the dumbbell.
    pub rate: Key<Real>,
    /// The loop's b.
    pub b: Key<Real>,
    /// The loop's ε.
    pub eps: Key<Real>,
    /// The dumbbell's charges.
    #[serde(default, deserialize_with = "exact")]
    pub charges: Key<[Real; 2]>,
    /// The dumbbell's masses.
    #[serde(default, deserialize_with = "exact")]
    pub masses: Key<[Real; 2]>,
    /// The dumbbell's rod length.
    pub length: Key<Real>,
}

/// `[orbit]`, or the flags of `orbit`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOrbit {
    /// A name of [`super::table::POTENTIALS`].
    pub potential: Key<String>,
    /// τ₀ = 2q²/(3mc³).
    pub tau0: Key<Real>,
    /// A name of [`super::table::FORCES`].
    pub force: Key<String>,
    /// The starting radius.
    pub r0: Key<Real>,
    /// The eccentricity.
    pub eccentricity: Key<Real>,
}

/// `[shell]`, or the flags of `shell`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawShell {
    /// τ₀ = 2q²/(3mc³).
    pub tau0: Key<Real>,
    /// The delay r₀/c.
    pub delay: Key<Real>,
}

/// `[stability]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStability {
    /// The row, 1 to 6.
    pub row: Key<i64>,
}

/// `[solve]`, or the flags of the times and the method.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSolve {
    /// A name of [`crate::sim::MethodChoice::NAMES`].
    pub method: Key<String>,
    /// The relative tolerance.
    pub rtol: Key<Real>,
    /// The fixed step of RK4.
    pub step: Key<Real>,
    /// The output times.
    pub times: Key<Vec<Real>>,
    /// The last output time (with `samples`).
    pub t_end: Key<Real>,
    /// How many evenly spaced times from 0 to `t_end`.
    pub samples: Key<i64>,
}

/// `[units]`: a real particle (scenes only).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawUnits {
    /// A name of [`super::SHAPES`].
    pub shape: Key<String>,
    /// A sphere's or cylinder's radius, nm.
    pub radius_nm: Key<Real>,
    /// A cylinder's length, nm.
    pub length_nm: Key<Real>,
    /// Density, kg/m³.
    pub density_kg_m3: Key<Real>,
    /// A sphere's or cylinder's dipole, debye.
    pub dipole_debye: Key<Real>,
    /// A sphere's or cylinder's spin, Hz.
    pub spin_hz: Key<Real>,
    /// The angle between the spin and the axis, degrees.
    pub spin_tilt_deg: Key<Real>,
    /// The tilt counted as upright, degrees.
    pub upright_deg: Key<Real>,
    /// A name of [`super::TIME_UNITS`].
    pub time_unit: Key<String>,
    /// A molecule's principal moments, amu Å².
    #[serde(default, deserialize_with = "exact")]
    pub moments_amu_a2: Key<[Real; 3]>,
    /// An ellipsoid's semi-axes, nm.
    #[serde(default, deserialize_with = "exact")]
    pub semi_axes_nm: Key<[Real; 3]>,
    /// An asymmetric particle's body-frame dipole, debye.
    #[serde(default, deserialize_with = "exact")]
    pub dipole_vector_debye: Key<[Real; 3]>,
    /// An asymmetric particle's body-frame rates, Hz.
    #[serde(default, deserialize_with = "exact")]
    pub omega_hz: Key<[Real; 3]>,
}
