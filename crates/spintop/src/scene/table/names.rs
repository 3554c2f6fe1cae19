//! The names a key takes (`[top] model`, `[orbit] potential`, …), what each
//! stands for, and its line in `--help`.

use crate::physics::central::Potential;
use crate::sim::orbit::Force;

/// A name a key takes, what it stands for, and the line `--help` shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice<T: 'static> {
    /// The name the user writes.
    pub name: &'static str,
    /// What it stands for.
    pub value: T,
    /// One line for `--help`.
    pub help: &'static str,
}

/// The value of `name` in `table`.
pub fn find<T: Copy>(table: &[Choice<T>], name: &str) -> Option<T> {
    table.iter().find(|c| c.name == name).map(|c| c.value)
}

/// The names of `table`, in order.
pub fn names<T>(table: &[Choice<T>]) -> Vec<&'static str> {
    table.iter().map(|c| c.name).collect()
}

/// Which of a top's three models: the lightest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tier {
    /// The truncated ALE: (4.2)–(4.4) for a symmetric top, (3.3) for any.
    Truncated,
    /// The reduced ALE: (4.12)–(4.14) for a symmetric top, (3.4) reduced for any.
    Reduced,
    /// The physical (non-runaway) solution of the full ALE (3.4).
    Physical,
}

impl Tier {
    /// The three tiers, lightest first.
    pub const ALL: [Tier; 3] = [Tier::Truncated, Tier::Reduced, Tier::Physical];

    /// Its place among a top's three models, lightest first.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// What a name of `[top] model` (and `--model`) asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelAsk {
    /// The tier; `None` for `auto`, which chooses.
    pub tier: Option<Tier>,
    /// True when the name itself says the top is asymmetric (`general`);
    /// otherwise `inertia` and `dipole` (or an asymmetric particle) say so.
    pub asymmetric: bool,
}

/// The names of `[top] model` and `--model`.
pub const MODELS: [Choice<ModelAsk>; 5] = [
    Choice {
        name: "truncated",
        value: ModelAsk {
            tier: Some(Tier::Truncated),
            asymmetric: false,
        },
        help: "Eqs. (4.2)-(4.4): the symmetric top without the Schott term; with inertia and dipole, (3.3) for any top",
    },
    Choice {
        name: "reduced",
        value: ModelAsk {
            tier: Some(Tier::Reduced),
            asymmetric: false,
        },
        help: "Eqs. (4.12)-(4.14): the symmetric top with the Schott term, reduced; with inertia and dipole, (3.4) reduced the same way for any top",
    },
    Choice {
        name: "general",
        value: ModelAsk {
            tier: Some(Tier::Truncated),
            asymmetric: true,
        },
        help: "Eq. (3.3): any top, given inertia and dipole",
    },
    Choice {
        name: "full",
        value: ModelAsk {
            tier: Some(Tier::Physical),
            asymmetric: false,
        },
        help: "Eq. (3.4): the full ALE, Schott term kept (its physical solution); with inertia and dipole, for any top",
    },
    Choice {
        name: "auto",
        value: ModelAsk {
            tier: None,
            asymmetric: false,
        },
        help: "The lightest of the three that answers within rtol, chosen before anything runs (scenes)",
    },
];

/// The names of `[orbit] potential` and `--potential`.
pub const POTENTIALS: [Choice<Potential>; 2] = [
    Choice {
        name: "coulomb",
        value: Potential::Coulomb,
        help: "V = -k/r",
    },
    Choice {
        name: "harmonic",
        value: Potential::Harmonic,
        help: "V = k r^2 / 2",
    },
];

/// The names of `[orbit] force` and `--force`.
pub const FORCES: [Choice<Force>; 3] = [
    Choice {
        name: "ll",
        value: Force::LandauLifshitz,
        help: "The Landau-Lifshitz reduction of (2.5)",
    },
    Choice {
        name: "al",
        value: Force::AbrahamLorentz,
        help: "The physical (non-runaway) solution of (2.5): exact roots (harmonic), backward integration (Coulomb)",
    },
    Choice {
        name: "al-forward",
        value: Force::AbrahamLorentzForward,
        help: "(2.5) integrated forward from the Newtonian acceleration: the runaway, detected and reported",
    },
];

/// A dipole trajectory of `balance`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DipoleKind {
    /// A rigid dipole on a cone.
    Precessing,
    /// The two-harmonic planar loop.
    Loop,
    /// A rigid rotating dumbbell.
    Dumbbell,
}

/// The names of `[balance] dipole` and `balance --dipole`.
pub const DIPOLES: [Choice<DipoleKind>; 3] = [
    Choice {
        name: "precessing",
        value: DipoleKind::Precessing,
        help: "A rigid unit dipole on a cone about z (cone, rate): a top in regular precession",
    },
    Choice {
        name: "loop",
        value: DipoleKind::Loop,
        help: "The planar loop d = (cos t, b sin t + eps sin 2t, 0) (b, eps)",
    },
    Choice {
        name: "dumbbell",
        value: DipoleKind::Dumbbell,
        help: "A rigid dumbbell spinning about an axis perpendicular to its rod (charges, masses, length, rate)",
    },
];

/// How the initial orientation is given when `euler` is not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameName {
    /// The paper's frame: lab z along L₀.
    Paper,
}

/// The names of `[top] frame`.
pub const FRAMES: [Choice<FrameName>; 1] = [Choice {
    name: "paper",
    value: FrameName::Paper,
    help: "Lab z along L0, as in (4.11) and the figures",
}];
