//! The raw shape of a scene file, as TOML gives it: every key optional and
//! spanned, unknown keys refused by serde. [`super::parse`] turns this into a
//! validated [`super::Scene`], reporting missing keys and bad values with the
//! line they sit on.

use crate::math::Real;
use serde::Deserialize;
use toml::Spanned;

/// An optional key with the byte range of its value in the file.
pub(super) type Key<T> = Option<Spanned<T>>;

/// A key holding exactly `N` numbers: serde's arrays would take the first
/// `N` of a longer list and drop the rest without a word.
fn exact<'de, D, const N: usize>(d: D) -> Result<Key<[Real; N]>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    use serde::de::Error;
    let Some(list) = Option::<Spanned<Vec<Real>>>::deserialize(d)? else {
        return Ok(None);
    };
    let span = list.span();
    let values = list.into_inner();
    let n = values.len();
    <[Real; N]>::try_from(values)
        .map(|a| Some(Spanned::new(span, a)))
        .map_err(|_| D::Error::custom(format!("expected {N} numbers, got {n}")))
}

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
    #[serde(default, deserialize_with = "exact")]
    pub inertia: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
    pub dipole: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
    pub omega: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
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
    #[serde(default, deserialize_with = "exact")]
    pub charges: Key<[Real; 2]>,
    #[serde(default, deserialize_with = "exact")]
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
    #[serde(default, deserialize_with = "exact")]
    pub moments_amu_a2: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
    pub semi_axes_nm: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
    pub dipole_vector_debye: Key<[Real; 3]>,
    #[serde(default, deserialize_with = "exact")]
    pub omega_hz: Key<[Real; 3]>,
}
