//! The raw shape of a scene file, as TOML gives it: every key optional and
//! spanned, unknown keys refused by serde. [`super::parse`] turns this into a
//! validated [`super::Scene`], reporting missing keys and bad values with the
//! line they sit on.

use crate::math::Real;
use serde::Deserialize;
use toml::Spanned;

/// An optional key with the byte range of its value in the file.
pub(super) type Key<T> = Option<Spanned<T>>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFile {
    pub scene: Key<RawScene>,
    pub top: Key<RawTop>,
    pub balance: Key<RawBalance>,
    pub orbit: Key<RawOrbit>,
    pub shell: Key<RawShell>,
    pub stability: Key<RawStability>,
    pub solve: Key<RawSolve>,
    pub units: Key<RawUnits>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub name: Key<String>,
    pub kind: Key<String>,
    pub description: Key<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTop {
    pub model: Key<String>,
    pub ratio: Key<Real>,
    pub inertia: Key<[Real; 3]>,
    pub dipole: Key<[Real; 3]>,
    pub omega: Key<[Real; 3]>,
    pub euler: Key<[Real; 3]>,
    pub frame: Key<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBalance {
    pub dipole: Key<String>,
    pub cone: Key<Real>,
    pub rate: Key<Real>,
    pub b: Key<Real>,
    pub eps: Key<Real>,
    pub charges: Key<[Real; 2]>,
    pub masses: Key<[Real; 2]>,
    pub length: Key<Real>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOrbit {
    pub potential: Key<String>,
    pub tau0: Key<Real>,
    pub force: Key<String>,
    pub r0: Key<Real>,
    pub eccentricity: Key<Real>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShell {
    pub tau0: Key<Real>,
    pub delay: Key<Real>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawStability {
    pub row: Key<i64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSolve {
    pub method: Key<String>,
    pub rtol: Key<Real>,
    pub step: Key<Real>,
    pub times: Key<Vec<Real>>,
    pub t_end: Key<Real>,
    pub samples: Key<i64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawUnits {
    pub shape: Key<String>,
    pub radius_nm: Key<Real>,
    pub length_nm: Key<Real>,
    pub density_kg_m3: Key<Real>,
    pub dipole_debye: Key<Real>,
    pub spin_hz: Key<Real>,
    pub spin_tilt_deg: Key<Real>,
    pub upright_deg: Key<Real>,
    pub time_unit: Key<String>,
}
