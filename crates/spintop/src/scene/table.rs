//! The one table of what a question takes: each key of a scene file, the
//! flag that stands for it on the command line, the names it accepts, its
//! default and its range. A scene file and the flags of `simulate`,
//! `balance`, `orbit`, `shell` and `plot` are read by the same code from
//! this table ([`super::parse`], [`super::request`]); the command line's
//! `--help` writes its ranges and defaults from it; nothing restates them.
//!
//! Where a constructor of the core checks a value (`SymmetricTop::new`,
//! `MethodOptions::with_rtol`, …) the range here says what it accepts (a
//! test holds the two together at each bound); where none does (`t_end`,
//! `samples`, a chart's size) the range here is the check.
//!
//! | code name | meaning |
//! |---|---|
//! | [`Choice`] | a name a key takes, what it stands for, its help line |
//! | [`MODELS`], [`POTENTIALS`], [`FORCES`], [`DIPOLES`], [`FRAMES`] | the names of `model`, `potential`, `force`, `[balance] dipole`, `frame` |
//! | [`Spec`] | one key: its section, flag, help, range and default |
//! | [`Range`], [`Bound`] | what a value must be |
//! | [`Command`] | the command (or kind of scene) a key belongs to |

use crate::math::Real;
use crate::numbers::fmt_value;
use crate::physics::central::{ChargeInField, Potential};
use crate::physics::symmetric_top::{FIGURE_OMEGA0, FIGURE_RATIO};
use crate::sim::orbit::{Force, MAX_ORBIT_RTOL, OrbitConfig};
use crate::sim::times::MAX_SAMPLES;
use crate::sim::{MAX_RATE, MIN_RTOL, MethodChoice, MethodOptions};

// ------------------------------------------------------------------ names

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

// ------------------------------------------------------------------ keys

/// The command, or kind of scene, a key belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `simulate`, and a scene of kind `top`.
    Simulate,
    /// `balance`, and a scene of kind `balance`.
    Balance,
    /// `orbit`, and a scene of kind `orbit`.
    Orbit,
    /// `shell`, and a scene of kind `shell`.
    Shell,
    /// `plot` (the keys of a top it shares are [`Command::Simulate`]'s).
    Plot,
}

/// One end of a range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// No end.
    None,
    /// The end, excluded.
    Open(Real),
    /// The end, included.
    Closed(Real),
}

/// What a value must be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// Any finite number (or numbers).
    Finite,
    /// A number between two ends.
    Between(Bound, Bound),
    /// A number (or vector) that is not zero.
    NonZero,
    /// Numbers, each at most this in size.
    EachAtMost(Real),
    /// Numbers, each positive.
    EachPositive,
    /// The principal moments of a rigid body.
    RigidBody,
    /// A whole number from the first to the second.
    Count(usize, usize),
    /// Output times: finite, and when `forward` also >= 0 and non-decreasing.
    Times {
        /// Whether the times step forward from 0.
        forward: bool,
    },
    /// One of these names.
    Names(&'static [&'static str]),
}

/// A number in a range, as written (`pi` for π).
fn bound_text(x: Real) -> String {
    if x == std::f64::consts::PI {
        "pi".to_string()
    } else {
        fmt_value(x)
    }
}

impl Range {
    /// True when the number `x` lies in the range (names and lists: always).
    pub fn contains(&self, x: Real) -> bool {
        match *self {
            Range::Finite => x.is_finite(),
            Range::Between(lo, hi) => {
                let above = match lo {
                    Bound::None => true,
                    Bound::Open(a) => x > a,
                    Bound::Closed(a) => x >= a,
                };
                let below = match hi {
                    Bound::None => true,
                    Bound::Open(b) => x < b,
                    Bound::Closed(b) => x <= b,
                };
                x.is_finite() && above && below
            }
            Range::NonZero => x.is_finite() && x != 0.0,
            Range::EachAtMost(m) => x.abs() <= m,
            Range::EachPositive => x > 0.0 && x.is_finite(),
            Range::Count(lo, hi) => x >= lo as Real && x <= hi as Real && x.fract() == 0.0,
            Range::RigidBody | Range::Times { .. } | Range::Names(_) => true,
        }
    }

    /// The interval, in the notation `(0, 2]`, `>= 0`, `> 0`.
    fn interval(lo: Bound, hi: Bound) -> String {
        match (lo, hi) {
            (Bound::None, Bound::None) => String::new(),
            (lo, Bound::None) => match lo {
                Bound::Open(a) => format!("> {}", bound_text(a)),
                Bound::Closed(a) => format!(">= {}", bound_text(a)),
                Bound::None => unreachable!("matched above"),
            },
            (Bound::None, Bound::Open(b)) => format!("< {}", bound_text(b)),
            (Bound::None, Bound::Closed(b)) => format!("<= {}", bound_text(b)),
            (lo, hi) => {
                let end = |b: Bound, open: char, closed: char| match b {
                    Bound::Open(x) => (open, x),
                    Bound::Closed(x) => (closed, x),
                    Bound::None => (open, Real::INFINITY),
                };
                let (open, a) = end(lo, '(', '[');
                let (close, b) = end(hi, ')', ']');
                format!("in {open}{}, {}{close}", bound_text(a), bound_text(b))
            }
        }
    }

    /// What a message expects, for a value described by `noun` ("a time"):
    /// `a time >= 0`, `a positive step in units of tau`, `one of a, b`.
    pub fn expected(&self, noun: &str) -> String {
        match self {
            Range::Finite => noun.to_string(),
            Range::Between(Bound::Open(a), Bound::None) if *a == 0.0 => {
                let bare = noun
                    .strip_prefix("an ")
                    .or_else(|| noun.strip_prefix("a "))
                    .unwrap_or(noun);
                format!("a positive {bare}")
            }
            Range::Between(lo, hi) => format!("{noun} {}", Self::interval(*lo, *hi)),
            Range::NonZero => format!("{noun}, not zero"),
            Range::EachAtMost(m) => format!("{noun}, each at most {} in size", bound_text(*m)),
            Range::EachPositive => format!("{noun}, each positive"),
            Range::RigidBody => {
                format!("{noun}: positive, each at most the sum of the other two")
            }
            Range::Count(lo, hi) => format!("a whole number from {lo} to {hi}"),
            Range::Times { forward: true } => "finite times >= 0, in increasing order".into(),
            Range::Times { forward: false } => "finite numbers".into(),
            Range::Names(names) => format!("one of {}", names.join(", ")),
        }
    }

    /// The range as a flag's help line ends: `in (0, 2]`, `>= 0`; empty for
    /// what says itself (any number, a name clap lists).
    pub fn short(&self) -> String {
        match self {
            Range::Finite | Range::Names(_) => String::new(),
            Range::Between(lo, hi) => Self::interval(*lo, *hi),
            Range::NonZero => "not zero".into(),
            Range::EachAtMost(m) => format!("each at most {} in size", bound_text(*m)),
            Range::EachPositive => "each positive".into(),
            Range::RigidBody => "positive, each at most the sum of the other two".into(),
            Range::Count(lo, hi) => format!("{lo} to {hi}"),
            Range::Times { forward: true } => ">= 0 and non-decreasing".into(),
            Range::Times { forward: false } => String::new(),
        }
    }

    /// The range with the flag in it, for a command's summary of ranges:
    /// `0 < --ratio <= 2`, `each --omega component at most 1e100`; `None`
    /// for what has no range to state.
    pub fn with_flag(&self, flag: &str) -> Option<String> {
        let side = |b: Bound, before: bool| match (b, before) {
            (Bound::Open(x), true) => Some(format!("{} < ", bound_text(x))),
            (Bound::Closed(x), true) => Some(format!("{} <= ", bound_text(x))),
            (Bound::Open(x), false) => Some(format!(" < {}", bound_text(x))),
            (Bound::Closed(x), false) => Some(format!(" <= {}", bound_text(x))),
            (Bound::None, _) => None,
        };
        match self {
            Range::Finite | Range::Names(_) | Range::Times { forward: false } => None,
            Range::Between(lo, Bound::None) => {
                Some(format!("{flag} {}", Self::interval(*lo, Bound::None)))
            }
            Range::Between(lo, hi) => Some(format!(
                "{}{flag}{}",
                side(*lo, true).unwrap_or_default(),
                side(*hi, false).unwrap_or_default()
            )),
            Range::NonZero => Some(format!("{flag} not zero")),
            Range::EachAtMost(m) => {
                Some(format!("each {flag} component at most {}", bound_text(*m)))
            }
            Range::EachPositive => Some(format!("each of {flag} positive")),
            Range::RigidBody => Some(format!(
                "{flag} positive and a rigid body (each at most the sum of the other two)"
            )),
            Range::Count(lo, hi) => Some(format!("{flag} from {lo} to {hi}")),
            Range::Times { forward: true } => Some(format!("{flag} >= 0 and non-decreasing")),
        }
    }
}

/// A key's default.
#[derive(Clone, Copy, Debug)]
pub enum DefaultValue {
    /// None: the key is required, or its absence means something.
    None,
    /// A number.
    Number(Real),
    /// A number another part of the core holds (a tolerance `MethodOptions`
    /// starts from).
    Of(fn() -> Real),
    /// Numbers.
    Numbers(&'static [Real]),
    /// A whole number.
    Count(usize),
    /// A name.
    Name(&'static str),
}

impl DefaultValue {
    /// The number, where the default is one.
    pub fn number(&self) -> Option<Real> {
        match self {
            DefaultValue::Number(x) => Some(*x),
            DefaultValue::Of(f) => Some(f()),
            _ => None,
        }
    }

    /// As a flag takes it (`0.4`, `0,0.1,0.2`, `ll`); `None` when there is none.
    pub fn text(&self) -> Option<String> {
        match self {
            DefaultValue::None => None,
            DefaultValue::Number(_) | DefaultValue::Of(_) => self.number().map(fmt_value),
            DefaultValue::Numbers(v) => Some(
                v.iter()
                    .map(|x| fmt_value(*x))
                    .collect::<Vec<_>>()
                    .join(","),
            ),
            DefaultValue::Count(n) => Some(n.to_string()),
            DefaultValue::Name(s) => Some(s.to_string()),
        }
    }
}

/// One key of a scene file and the flag that stands for it.
#[derive(Clone, Copy, Debug)]
pub struct Spec {
    /// The command it belongs to.
    pub command: Command,
    /// Its section in a scene file (`top`, `solve`, …).
    pub section: &'static str,
    /// The key (`t_end`); the flag is the key with `-` for `_` (`--t-end`).
    pub key: &'static str,
    /// What the value is, for messages: "a time", "I3/I1".
    pub noun: &'static str,
    /// The flag's help line, without range and default.
    pub help: &'static str,
    /// The flag's value name in `--help` (`W1,W2,W3`).
    pub value_name: &'static str,
    /// What the value must be.
    pub range: Range,
    /// Its default.
    pub default: DefaultValue,
}

impl Spec {
    /// The long flag, with its dashes: `--t-end`.
    pub fn flag(&self) -> String {
        flag_of(self.key)
    }

    /// What a message expects: `a time >= 0`.
    pub fn expected(&self) -> String {
        self.range.expected(self.noun)
    }

    /// The flag's help line: what it is, its range, its default.
    pub fn help_line(&self) -> String {
        let mut line = self.help.to_string();
        let range = self.range.short();
        if !range.is_empty() {
            line = format!("{line}, {range}");
        }
        if let Some(d) = self.default.text() {
            line = format!("{line} [default: {d}]");
        }
        line
    }
}

/// The long flag of a key: `--t-end` for `t_end`.
pub fn flag_of(key: &str) -> String {
    format!("--{}", key.replace('_', "-"))
}

/// The names of a table of names, as a constant.
const fn names_of<T: Copy, const N: usize>(table: &[Choice<T>; N]) -> [&'static str; N] {
    let mut names = [""; N];
    let mut i = 0;
    while i < N {
        names[i] = table[i].name;
        i += 1;
    }
    names
}

const MODEL_NAMES: [&str; MODELS.len()] = names_of(&MODELS);
const POTENTIAL_NAMES: [&str; POTENTIALS.len()] = names_of(&POTENTIALS);
const FORCE_NAMES: [&str; FORCES.len()] = names_of(&FORCES);
const DIPOLE_NAMES: [&str; DIPOLES.len()] = names_of(&DIPOLES);
const FRAME_NAMES: [&str; FRAMES.len()] = names_of(&FRAMES);

/// The time a top runs to when a scene or `simulate` gives no times, in τ.
pub const TOP_T_END: Real = 100.0;
/// How many evenly spaced times `t_end` stands for without `samples`.
pub const SAMPLES: usize = 11;
/// The time a chart of `plot` ends at, in τ.
pub const PLOT_T_END: Real = 500.0;

/// The tolerance of the adaptive methods unless `rtol` says otherwise.
fn method_rtol() -> Real {
    MethodOptions::default().rtol()
}

/// The step of RK4 unless `step` says otherwise.
fn method_step() -> Real {
    MethodOptions::default().step()
}

/// The tolerance an orbit is integrated at unless `rtol` says otherwise: the
/// one [`OrbitConfig::new`] sets.
fn orbit_rtol() -> Real {
    ChargeInField::new(Potential::Coulomb, 1e-3)
        .and_then(|c| OrbitConfig::new(c, 1.0, 0.0, Force::LandauLifshitz))
        .map_or(MIN_RTOL, |c| c.rtol)
}

/// A row of the table.
#[allow(clippy::too_many_arguments)]
const fn row(
    command: Command,
    section: &'static str,
    key: &'static str,
    noun: &'static str,
    help: &'static str,
    value_name: &'static str,
    range: Range,
    default: DefaultValue,
) -> Spec {
    Spec {
        command,
        section,
        key,
        noun,
        help,
        value_name,
        range,
        default,
    }
}

use Command::{Balance as B, Orbit as O, Plot as P, Shell as H, Simulate as S};
use DefaultValue as D;
use Range as R;
const POSITIVE: Range = R::Between(Bound::Open(0.0), Bound::None);
const NOT_NEGATIVE: Range = R::Between(Bound::Closed(0.0), Bound::None);
const FORWARD: Range = R::Times { forward: true };
const TIME: &str = "a time";
const T_END_HELP: &str = "Last output time (with samples, evenly spaced times from 0)";
const SAMPLES_HELP: &str = "Number of evenly spaced output times from 0 to t_end";
const TIMES_HELP: &str = "Output times, comma-separated";
const TAU0: &str = "tau0 = 2q^2/(3mc^3)";

/// Every key of every command: section, key, what its value is, the flag's
/// help line and value name, its range and its default.
#[rustfmt::skip]
pub const SPECS: &[Spec] = &[
    // simulate, and a scene of kind top: [top]
    row(S, "top", "model", "a model", "Which equations of motion", "MODEL",
        R::Names(&MODEL_NAMES), D::None),
    row(S, "top", "ratio", "I3/I1", "I3/I1 of the symmetric models", "RATIO",
        R::Between(Bound::Open(0.0), Bound::Closed(2.0)), D::Number(FIGURE_RATIO)),
    row(S, "top", "inertia", "three principal moments",
        "Principal moments of an asymmetric top (kappa = 1 units)", "I1,I2,I3",
        R::RigidBody, D::None),
    row(S, "top", "dipole", "three numbers, the body-frame dipole",
        "Body-frame dipole of an asymmetric top (kappa = 1 units)", "D1,D2,D3",
        R::NonZero, D::None),
    row(S, "top", "omega", "three body-frame rates in 1/tau",
        "Initial body angular velocity, in 1/tau", "W1,W2,W3",
        R::EachAtMost(MAX_RATE), D::Numbers(&FIGURE_OMEGA0)),
    row(S, "top", "euler", "three z-x-z Euler angles in radians",
        "Initial orientation as z-x-z Euler angles, radians", "PHI,THETA,PSI",
        R::Finite, D::Numbers(&[0.0; 3])),
    row(S, "top", "frame", "a frame", "Lab z along L0 instead of Euler angles", "FRAME",
        R::Names(&FRAME_NAMES), D::None),
    // [solve]
    row(S, "solve", "method", "a method", "Numerical method", "METHOD",
        R::Names(&MethodChoice::NAMES), D::Name("auto")),
    row(S, "solve", "rtol", "a relative tolerance", "Relative tolerance of the adaptive methods",
        "RTOL", R::Between(Bound::Closed(MIN_RTOL), Bound::Open(1.0)), D::Of(method_rtol)),
    row(S, "solve", "step", "a step in units of tau", "Step size of RK4, in tau", "STEP",
        POSITIVE, D::Of(method_step)),
    row(S, "solve", "times", "output times", TIMES_HELP, "T1,T2,...", FORWARD, D::None),
    row(S, "solve", "t_end", TIME, T_END_HELP, "T_END", NOT_NEGATIVE, D::Number(TOP_T_END)),
    row(S, "solve", "samples", "a count", SAMPLES_HELP, "SAMPLES",
        R::Count(1, MAX_SAMPLES), D::Count(SAMPLES)),
    // balance: [balance] and [solve]
    row(B, "balance", "dipole", "a dipole trajectory", "Which dipole trajectory", "DIPOLE",
        R::Names(&DIPOLE_NAMES), D::None),
    row(B, "balance", "cone", "a cone angle",
        "Cone half-angle theta of the precessing dipole, radians", "CONE",
        R::Between(Bound::Closed(0.0), Bound::Closed(std::f64::consts::PI)), D::Number(0.5)),
    row(B, "balance", "rate", "a rate", "Rate omega of the precessing dipole or the dumbbell",
        "RATE", R::NonZero, D::Number(1.0)),
    row(B, "balance", "b", "a number", "Loop parameter b", "B", R::Finite, D::Number(0.5)),
    row(B, "balance", "eps", "a number", "Loop parameter eps, the second harmonic", "EPS",
        R::Finite, D::Number(0.2)),
    row(B, "balance", "charges", "two charges", "Dumbbell charges q1,q2 (kappa = 1 units)",
        "Q1,Q2", R::Finite, D::Numbers(&[1.0, -1.0])),
    row(B, "balance", "masses", "two masses", "Dumbbell masses m1,m2", "M1,M2",
        R::EachPositive, D::Numbers(&[1.0, 1.0])),
    row(B, "balance", "length", "a length", "Dumbbell rod length", "LENGTH",
        POSITIVE, D::Number(1.0)),
    row(B, "solve", "times", "sample times", "Sample times, comma-separated (any finite values)",
        "T1,T2,...", R::Times { forward: false }, D::None),
    row(B, "solve", "t_end", TIME, T_END_HELP, "T_END", NOT_NEGATIVE, D::None),
    row(B, "solve", "samples", "a count", SAMPLES_HELP, "SAMPLES",
        R::Count(1, MAX_SAMPLES), D::Count(SAMPLES)),
    // orbit: [orbit] and [solve]
    row(O, "orbit", "potential", "a potential", "The central potential", "POTENTIAL",
        R::Names(&POTENTIAL_NAMES), D::None),
    row(O, "orbit", "tau0", TAU0, TAU0, "TAU0", POSITIVE, D::None),
    row(O, "orbit", "force", "a force", "The equation of motion", "FORCE",
        R::Names(&FORCE_NAMES), D::Name(FORCE_NAMES[0])),
    row(O, "orbit", "r0", "a radius", "Starting radius", "R0", POSITIVE, D::Number(1.0)),
    row(O, "orbit", "eccentricity", "an eccentricity", "Eccentricity of the starting orbit", "E",
        R::Between(Bound::Closed(0.0), Bound::Open(1.0)), D::Number(0.0)),
    row(O, "solve", "rtol", "a relative tolerance", "Relative tolerance of the integrations",
        "RTOL", R::Between(Bound::Closed(MIN_RTOL), Bound::Closed(MAX_ORBIT_RTOL)),
        D::Of(orbit_rtol)),
    row(O, "solve", "times", "output times", TIMES_HELP, "T1,T2,...", FORWARD, D::None),
    row(O, "solve", "t_end", TIME, T_END_HELP, "T_END", NOT_NEGATIVE, D::None),
    row(O, "solve", "samples", "a count", SAMPLES_HELP, "SAMPLES",
        R::Count(1, MAX_SAMPLES), D::Count(SAMPLES)),
    // shell: [shell] and [solve]
    row(H, "shell", "tau0", TAU0, TAU0, "TAU0", POSITIVE, D::None),
    row(H, "shell", "delay", "a delay r0/c, different from tau0",
        "The delay r0/c, different from tau0", "DELAY", POSITIVE, D::None),
    row(H, "solve", "times", "output times", TIMES_HELP, "T1,T2,...", FORWARD, D::None),
    row(H, "solve", "t_end", TIME, T_END_HELP, "T_END", NOT_NEGATIVE, D::None),
    row(H, "solve", "samples", "a count", SAMPLES_HELP, "SAMPLES",
        R::Count(1, MAX_SAMPLES), D::Count(SAMPLES)),
    // plot: its own keys (it shares [top] ratio and omega with simulate)
    row(P, "solve", "method", "a method", "Numerical method", "METHOD",
        R::Names(&MethodChoice::NAMES), D::Name("exact")),
    row(P, "plot", "t_end", "a last time of a chart", "Last time of the plot, in tau", "T_END",
        POSITIVE, D::Number(PLOT_T_END)),
    row(P, "plot", "width", "a width in characters", "Width of each chart, in characters",
        "WIDTH", R::Count(16, 500), D::Count(60)),
    row(P, "plot", "height", "a height in lines", "Height of each chart, in lines", "HEIGHT",
        R::Count(2, 200), D::Count(10)),
];

/// Every key, by command.
pub fn specs() -> &'static [Spec] {
    SPECS
}

/// The keys of a command, in the table's order.
pub fn keys_of(command: Command) -> impl Iterator<Item = &'static Spec> {
    specs().iter().filter(move |s| s.command == command)
}

/// The key `key` of `section` for `command`.
///
/// # Panics
/// When the table has no such key: a call names a key of the table.
pub fn key(command: Command, section: &str, key: &str) -> &'static Spec {
    specs()
        .iter()
        .find(|s| s.command == command && s.section == section && s.key == key)
        .unwrap_or_else(|| panic!("the table has no [{section}] {key} for {command:?}"))
}

/// A command's ranges in one paragraph for its `--help`, from the table:
/// `0 < --ratio <= 2; each --omega component at most 1e100; …`.
pub fn ranges_help(command: Command) -> String {
    keys_of(command)
        .filter_map(|s| s.range.with_flag(&s.flag()))
        .collect::<Vec<_>>()
        .join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::request::{self, Given, RawBalance, RawOrbit, RawShell, RawSolve, RawTop};

    /// Whether the flags of `spec`'s command, a valid question but for
    /// `spec`'s key set to `x`, are accepted.
    fn accepts(spec: &Spec, x: Real) -> bool {
        let g = |v: Real| Some(Given::flag(v));
        let name = |s: &str| Some(Given::flag(s.to_string()));
        let mut solve = RawSolve {
            t_end: g(1.0),
            ..RawSolve::default()
        };
        match (spec.section, spec.key) {
            ("solve", "rtol") if spec.command == Command::Simulate => solve.rtol = g(x),
            ("solve", "rtol") => solve.rtol = g(x),
            ("solve", "step") => {
                solve.method = name("rk4");
                solve.step = g(x);
            }
            ("solve", "t_end") => solve.t_end = g(x),
            ("solve", "samples") => solve.samples = Some(Given::flag(x as i64)),
            _ => {}
        }
        match spec.command {
            Command::Simulate => {
                let mut top = RawTop {
                    model: name("truncated"),
                    ..RawTop::default()
                };
                match spec.key {
                    "ratio" => top.ratio = g(x),
                    "omega" => top.omega = Some(Given::flag([x, 0.0, 0.0])),
                    "dipole" => {
                        top.inertia = Some(Given::flag([1.0, 2.0, 2.5]));
                        top.dipole = Some(Given::flag([0.0, 0.0, x]));
                    }
                    _ => {}
                }
                request::top(&top, &solve).is_ok()
            }
            Command::Balance => {
                let mut raw = RawBalance {
                    dipole: name("precessing"),
                    ..RawBalance::default()
                };
                match spec.key {
                    "cone" => raw.cone = g(x),
                    "rate" => raw.rate = g(x),
                    "masses" | "length" => {
                        raw.dipole = name("dumbbell");
                        if spec.key == "length" {
                            raw.length = g(x);
                        } else {
                            raw.masses = Some(Given::flag([1.0, x]));
                        }
                    }
                    _ => {}
                }
                request::balance(&raw, &solve).is_ok()
            }
            Command::Orbit => {
                let mut raw = RawOrbit {
                    potential: name("harmonic"),
                    tau0: g(1e-3),
                    ..RawOrbit::default()
                };
                match spec.key {
                    "tau0" => raw.tau0 = g(x),
                    "r0" => raw.r0 = g(x),
                    "eccentricity" => raw.eccentricity = g(x),
                    _ => {}
                }
                request::orbit(&raw, &solve).is_ok()
            }
            Command::Shell => {
                let mut raw = RawShell {
                    tau0: g(1e-3),
                    delay: g(0.03),
                };
                match spec.key {
                    "tau0" => raw.tau0 = g(x),
                    "delay" => raw.delay = g(x),
                    _ => {}
                }
                request::shell(&raw, &solve).is_ok()
            }
            Command::Plot => spec.range.contains(x),
        }
    }

    /// Values at each end of a range, with whether the range holds them:
    /// the end itself and the double just beyond it.
    fn probes(range: &Range) -> Vec<(Real, bool)> {
        let mut out = Vec::new();
        match *range {
            Range::Between(lo, hi) => {
                match lo {
                    Bound::Open(a) => out.extend([(a, false), (a.next_up(), true)]),
                    Bound::Closed(a) => out.extend([(a, true), (a.next_down(), false)]),
                    Bound::None => {}
                }
                match hi {
                    Bound::Open(b) => out.extend([(b, false), (b.next_down(), true)]),
                    Bound::Closed(b) => out.extend([(b, true), (b.next_up(), false)]),
                    Bound::None => {}
                }
            }
            Range::NonZero | Range::EachPositive => out.extend([(0.0, false), (1.0, true)]),
            Range::EachAtMost(m) => out.extend([(m, true), (m.next_up(), false)]),
            Range::Count(lo, hi) => out.extend([
                (lo as Real, true),
                (lo as Real - 1.0, false),
                (hi as Real, true),
                (hi as Real + 1.0, false),
            ]),
            _ => {}
        }
        out
    }

    /// The ranges `--help` states are the ones the checks enforce: at each
    /// end of each key's range, the value the range holds is accepted and
    /// the double beyond it refused, by the validation a flag goes through.
    #[test]
    fn each_range_in_the_table_is_what_the_checks_enforce() {
        let mut wrong = Vec::new();
        let mut probed = 0;
        for spec in SPECS {
            for (x, held) in probes(&spec.range) {
                probed += 1;
                if accepts(spec, x) != held {
                    wrong.push(format!(
                        "{:?} [{}] {} = {x:e}: the table says {}",
                        spec.command,
                        spec.section,
                        spec.key,
                        if held { "in range" } else { "out of range" }
                    ));
                }
            }
        }
        assert!(probed > 40, "{probed}");
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    }

    /// Every name a table of names lists maps back to what it stands for,
    /// and the core's own names agree (`Potential::name`, `Force::name`).
    #[test]
    fn names_are_the_cores_names() {
        for c in POTENTIALS {
            assert_eq!(find(&POTENTIALS, c.name), Some(c.value));
            assert_eq!(c.value.name(), c.name);
        }
        for c in FORCES {
            assert_eq!(c.value.name(), c.name);
        }
        for spec in SPECS {
            if let (Range::Names(names), DefaultValue::Name(d)) = (spec.range, spec.default) {
                assert!(
                    names.contains(&d),
                    "{:?} {}: default {d}",
                    spec.command,
                    spec.key
                );
            }
        }
    }

    #[test]
    fn ranges_read_as_written() {
        let ratio = key(Command::Simulate, "top", "ratio");
        assert_eq!(ratio.range.short(), "in (0, 2]");
        assert_eq!(
            ratio.range.with_flag("--ratio").unwrap(),
            "0 < --ratio <= 2"
        );
        assert_eq!(
            ratio.help_line(),
            "I3/I1 of the symmetric models, in (0, 2] [default: 0.4]"
        );
        let rtol = key(Command::Simulate, "solve", "rtol");
        assert_eq!(
            rtol.range.with_flag("--rtol").unwrap(),
            "1e-14 <= --rtol < 1"
        );
        assert_eq!(rtol.default.text().unwrap(), "1e-10");
        let step = key(Command::Simulate, "solve", "step");
        assert_eq!(step.expected(), "a positive step in units of tau");
        let cone = key(Command::Balance, "balance", "cone");
        assert_eq!(cone.range.short(), "in [0, pi]");
        assert!(ranges_help(Command::Simulate).contains("each --omega component at most 1e100"));
    }
}
