//! The catalogue: the scene files of `crates/spintop/scenes/`, compiled into the
//! binary so that `spintop scenes` and `spintop run NAME` work from any
//! directory. `tests/numerics/scenes.rs` checks that this list and the folder agree.

use super::{Scene, SceneError, parse};

/// One scene of the catalogue.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// The scene's name, which is its file name without `.toml`.
    pub name: &'static str,
    /// The file's text.
    pub text: &'static str,
}

impl Entry {
    /// Where the file lives in the repository: `crates/spintop/scenes/NAME.toml`.
    pub fn path(&self) -> String {
        format!("crates/spintop/scenes/{}.toml", self.name)
    }

    /// Parse it.
    pub fn scene(&self) -> Result<Scene, SceneError> {
        parse(self.text, &self.path())
    }
}

macro_rules! catalogue {
    ($($name:literal),* $(,)?) => {
        /// Every scene of `crates/spintop/scenes/`, in the order `spintop scenes` lists them.
        pub const CATALOGUE: &[Entry] = &[
            $(Entry {
                name: $name,
                text: include_str!(concat!("../../scenes/", $name, ".toml")),
            }),*
        ];
    };
}

catalogue![
    "figure-1",
    "figure-2",
    "erratum-1-instant-loss",
    "erratum-4-tilt",
    "erratum-5-generic-frame",
    "euler-pole",
    "reduced-strong-spin",
    "asymmetric-top",
    "full-ale-physical",
    "precessing-dipole",
    "coulomb-collapse",
    "appendix-convergence",
    "appendix-instability",
    "stability-row-1",
    "stability-row-2",
    "stability-row-3",
    "stability-row-4",
    "stability-row-5",
    "stability-row-6",
    "nanoparticle-1e3-debye",
    "nanoparticle-1e7-debye",
    "nanorod-cylinder",
    "formaldehyde-molecule",
    "nanoellipsoid-tumbling",
];

/// The catalogue entry called `name`.
pub fn find(name: &str) -> Option<&'static Entry> {
    CATALOGUE.iter().find(|e| e.name == name)
}
