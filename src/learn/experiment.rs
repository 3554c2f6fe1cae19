//! A chapter's experiments: inline code `` `spintop: ratio=1.5 method=rk4` ``
//! in its Markdown (the web book shows it as the settings to try, the text
//! around it is the caption), each a change to the chapter's own scene that
//! `x` applies.

use crate::live::settings::WARPS;
use crate::live::{Refusal, Settings, Top};
use spintop::math::Real;
use spintop::numbers::parse_number;
use spintop::sim::MethodChoice;

/// Why an experiment comment does not parse or apply.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExperimentError {
    /// A word that is not `key=value`.
    #[error("`{0}` is not key=value")]
    NotKeyValue(String),
    /// A value that is not a number.
    #[error("{0}")]
    Number(String),
    /// `omega` without three numbers.
    #[error("omega takes three numbers, got `{0}`")]
    Omega(String),
    /// A method the core does not name.
    #[error("method `{0}`: use one of {names}", names = MethodChoice::NAMES.join(", "))]
    Method(String),
    /// A warp the live view does not offer.
    #[error("warp {0} is not one of the live view's warps")]
    Warp(Real),
    /// `log` neither on nor off.
    #[error("log takes on or off, got `{0}`")]
    Log(String),
    /// A key experiments do not have.
    #[error("unknown key `{0}` (ratio, omega, method, warp, log)")]
    Key(String),
    /// A ratio for a general top.
    #[error("this scene is a general top: ratio does not apply")]
    RatioOfGeneral,
    /// The live models refused the settings.
    #[error(transparent)]
    Refused(#[from] Refusal),
}

/// One experiment, parsed from the book's `` `spintop: ratio=1.5 method=rk4` ``.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Experiment {
    /// I₃/I₁.
    pub ratio: Option<Real>,
    /// Ω₀.
    pub omega: Option<[Real; 3]>,
    /// The method.
    pub method: Option<MethodChoice>,
    /// τ per second, one of [`WARPS`].
    pub warp: Option<Real>,
    /// Log time axis.
    pub log_time: Option<bool>,
}

impl Experiment {
    /// Parses `key=value` words; unknown keys or bad values are an error (a
    /// test runs this over every experiment in the book).
    pub fn parse(text: &str) -> Result<Self, ExperimentError> {
        let mut e = Experiment::default();
        let settings = text.split_once('|').map_or(text, |(s, _)| s);
        for word in settings.split_whitespace() {
            let Some((k, v)) = word.split_once('=') else {
                return Err(ExperimentError::NotKeyValue(word.into()));
            };
            let number = |v: &str| parse_number(v).map_err(ExperimentError::Number);
            match k {
                "ratio" => e.ratio = Some(number(v)?),
                "omega" => {
                    let parts = v.split(',').map(number).collect::<Result<Vec<_>, _>>()?;
                    let [a, b, c] = parts[..] else {
                        return Err(ExperimentError::Omega(v.into()));
                    };
                    e.omega = Some([a, b, c]);
                }
                "method" => {
                    e.method = Some(
                        MethodChoice::from_name(v)
                            .ok_or_else(|| ExperimentError::Method(v.into()))?,
                    );
                }
                "warp" => {
                    let w = number(v)?;
                    if !WARPS.contains(&w) {
                        return Err(ExperimentError::Warp(w));
                    }
                    e.warp = Some(w);
                }
                "log" => {
                    e.log_time = Some(match v {
                        "on" | "true" => true,
                        "off" | "false" => false,
                        other => return Err(ExperimentError::Log(other.into())),
                    })
                }
                other => return Err(ExperimentError::Key(other.into())),
            }
        }
        Ok(e)
    }

    /// The settings this experiment makes of `base` (the chapter's own: an
    /// experiment never inherits an earlier one's changes).
    pub fn apply(&self, base: &Settings) -> Result<Settings, ExperimentError> {
        let omega = self.omega.unwrap_or(base.omega0());
        let method = self.method.unwrap_or(base.method());
        let warp = self.warp.unwrap_or(base.warp());
        Ok(match base.top() {
            Top::General(top) => {
                if self.ratio.is_some() {
                    return Err(ExperimentError::RatioOfGeneral);
                }
                Settings::general(*top, omega, method, warp)?
            }
            Top::Full(top) => Settings::full(self.ratio.unwrap_or(top.ratio()), omega, warp)?,
            Top::Symmetric(top) => {
                Settings::new(self.ratio.unwrap_or(top.ratio()), omega, method, warp)?
            }
        })
    }
}
