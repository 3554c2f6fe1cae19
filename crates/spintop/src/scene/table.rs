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
use std::sync::LazyLock;

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
#[derive(Clone, Debug, PartialEq)]
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
    Names(Vec<&'static str>),
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
#[derive(Clone, Debug, PartialEq)]
pub enum DefaultValue {
    /// None: the key is required, or its absence means something.
    None,
    /// A number.
    Number(Real),
    /// Numbers.
    Numbers(Vec<Real>),
    /// A whole number.
    Count(usize),
    /// A name.
    Name(&'static str),
}

impl DefaultValue {
    /// As a flag takes it (`0.4`, `0,0.1,0.2`, `ll`); `None` when there is none.
    pub fn text(&self) -> Option<String> {
        match self {
            DefaultValue::None => None,
            DefaultValue::Number(x) => Some(fmt_value(*x)),
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
#[derive(Clone, Debug, PartialEq)]
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

fn spec(
    command: Command,
    (section, key): (&'static str, &'static str),
    (noun, help, value_name): (&'static str, &'static str, &'static str),
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

/// The time a top runs to when a scene or `simulate` gives no times, in τ.
pub const TOP_T_END: Real = 100.0;
/// How many evenly spaced times `t_end` stands for without `samples`.
pub const SAMPLES: usize = 11;

fn top_keys() -> Vec<Spec> {
    use Command::Simulate as S;
    let methods = MethodOptions::default();
    vec![
        spec(
            S,
            ("top", "model"),
            ("a model", "Which equations of motion", "MODEL"),
            Range::Names(names(&MODELS)),
            DefaultValue::None,
        ),
        spec(
            S,
            ("top", "ratio"),
            ("I3/I1", "I3/I1 of the symmetric models", "RATIO"),
            Range::Between(Bound::Open(0.0), Bound::Closed(2.0)),
            DefaultValue::Number(FIGURE_RATIO),
        ),
        spec(
            S,
            ("top", "inertia"),
            (
                "three principal moments",
                "Principal moments of an asymmetric top (kappa = 1 units)",
                "I1,I2,I3",
            ),
            Range::RigidBody,
            DefaultValue::None,
        ),
        spec(
            S,
            ("top", "dipole"),
            (
                "three numbers, the body-frame dipole",
                "Body-frame dipole of an asymmetric top (kappa = 1 units)",
                "D1,D2,D3",
            ),
            Range::NonZero,
            DefaultValue::None,
        ),
        spec(
            S,
            ("top", "omega"),
            (
                "three body-frame rates in 1/tau",
                "Initial body angular velocity, in 1/tau",
                "W1,W2,W3",
            ),
            Range::EachAtMost(MAX_RATE),
            DefaultValue::Numbers(FIGURE_OMEGA0.to_vec()),
        ),
        spec(
            S,
            ("top", "euler"),
            (
                "three z-x-z Euler angles in radians",
                "Initial orientation as z-x-z Euler angles, radians",
                "PHI,THETA,PSI",
            ),
            Range::Finite,
            DefaultValue::Numbers(vec![0.0; 3]),
        ),
        spec(
            S,
            ("top", "frame"),
            ("a frame", "Lab z along L0 instead of Euler angles", "FRAME"),
            Range::Names(names(&FRAMES)),
            DefaultValue::None,
        ),
        spec(
            S,
            ("solve", "method"),
            ("a method", "Numerical method", "METHOD"),
            Range::Names(MethodChoice::NAMES.to_vec()),
            DefaultValue::Name(MethodChoice::Auto.name()),
        ),
        spec(
            S,
            ("solve", "rtol"),
            (
                "a relative tolerance",
                "Relative tolerance of the adaptive methods",
                "RTOL",
            ),
            Range::Between(Bound::Closed(MIN_RTOL), Bound::Open(1.0)),
            DefaultValue::Number(methods.rtol()),
        ),
        spec(
            S,
            ("solve", "step"),
            ("a step in units of tau", "Step size of RK4, in tau", "STEP"),
            Range::Between(Bound::Open(0.0), Bound::None),
            DefaultValue::Number(methods.step()),
        ),
    ]
}

/// The times of `[solve]`, read the same way by every command: `times`, or
/// `t_end` with `samples`.
fn times_keys(command: Command, forward: bool, t_end: DefaultValue) -> Vec<Spec> {
    let (noun, help) = if forward {
        ("output times", "Output times, comma-separated")
    } else {
        (
            "sample times",
            "Sample times, comma-separated (any finite values)",
        )
    };
    vec![
        spec(
            command,
            ("solve", "times"),
            (noun, help, "T1,T2,..."),
            Range::Times { forward },
            DefaultValue::None,
        ),
        spec(
            command,
            ("solve", "t_end"),
            (
                "a time",
                "Last output time (with samples, evenly spaced times from 0)",
                "T_END",
            ),
            Range::Between(Bound::Closed(0.0), Bound::None),
            t_end,
        ),
        spec(
            command,
            ("solve", "samples"),
            (
                "a count",
                "Number of evenly spaced output times from 0 to t_end",
                "SAMPLES",
            ),
            Range::Count(1, MAX_SAMPLES),
            DefaultValue::Count(SAMPLES),
        ),
    ]
}

fn other_keys() -> Vec<Spec> {
    use Command::{Balance as B, Orbit as O, Plot as P, Shell as H};
    let positive = || Range::Between(Bound::Open(0.0), Bound::None);
    vec![
        spec(
            B,
            ("balance", "dipole"),
            ("a dipole trajectory", "Which dipole trajectory", "DIPOLE"),
            Range::Names(names(&DIPOLES)),
            DefaultValue::None,
        ),
        spec(
            B,
            ("balance", "cone"),
            (
                "a cone angle",
                "Cone half-angle theta of the precessing dipole, radians",
                "CONE",
            ),
            Range::Between(Bound::Closed(0.0), Bound::Closed(std::f64::consts::PI)),
            DefaultValue::Number(0.5),
        ),
        spec(
            B,
            ("balance", "rate"),
            (
                "a rate",
                "Rate omega of the precessing dipole or the dumbbell",
                "RATE",
            ),
            Range::NonZero,
            DefaultValue::Number(1.0),
        ),
        spec(
            B,
            ("balance", "b"),
            ("a number", "Loop parameter b", "B"),
            Range::Finite,
            DefaultValue::Number(0.5),
        ),
        spec(
            B,
            ("balance", "eps"),
            ("a number", "Loop parameter eps, the second harmonic", "EPS"),
            Range::Finite,
            DefaultValue::Number(0.2),
        ),
        spec(
            B,
            ("balance", "charges"),
            (
                "two charges",
                "Dumbbell charges q1,q2 (kappa = 1 units)",
                "Q1,Q2",
            ),
            Range::Finite,
            DefaultValue::Numbers(vec![1.0, -1.0]),
        ),
        spec(
            B,
            ("balance", "masses"),
            ("two masses", "Dumbbell masses m1,m2", "M1,M2"),
            Range::EachPositive,
            DefaultValue::Numbers(vec![1.0, 1.0]),
        ),
        spec(
            B,
            ("balance", "length"),
            ("a length", "Dumbbell rod length", "LENGTH"),
            positive(),
            DefaultValue::Number(1.0),
        ),
        spec(
            O,
            ("orbit", "potential"),
            ("a potential", "The central potential", "POTENTIAL"),
            Range::Names(names(&POTENTIALS)),
            DefaultValue::None,
        ),
        spec(
            O,
            ("orbit", "tau0"),
            ("tau0 = 2q^2/(3mc^3)", "tau0 = 2q^2/(3mc^3)", "TAU0"),
            positive(),
            DefaultValue::None,
        ),
        spec(
            O,
            ("orbit", "force"),
            ("a force", "The equation of motion", "FORCE"),
            Range::Names(names(&FORCES)),
            DefaultValue::Name(FORCES[0].name),
        ),
        spec(
            O,
            ("orbit", "r0"),
            ("a radius", "Starting radius", "R0"),
            positive(),
            DefaultValue::Number(1.0),
        ),
        spec(
            O,
            ("orbit", "eccentricity"),
            ("an eccentricity", "Eccentricity of the starting orbit", "E"),
            Range::Between(Bound::Closed(0.0), Bound::Open(1.0)),
            DefaultValue::Number(0.0),
        ),
        spec(
            O,
            ("solve", "rtol"),
            (
                "a relative tolerance",
                "Relative tolerance of the integrations",
                "RTOL",
            ),
            Range::Between(Bound::Closed(MIN_RTOL), Bound::Closed(MAX_ORBIT_RTOL)),
            orbit_rtol(),
        ),
        spec(
            H,
            ("shell", "tau0"),
            ("tau0 = 2q^2/(3mc^3)", "tau0 = 2q^2/(3mc^3)", "TAU0"),
            positive(),
            DefaultValue::None,
        ),
        spec(
            H,
            ("shell", "delay"),
            (
                "a delay r0/c, different from tau0",
                "The delay r0/c, different from tau0",
                "DELAY",
            ),
            positive(),
            DefaultValue::None,
        ),
        spec(
            P,
            ("solve", "method"),
            ("a method", "Numerical method", "METHOD"),
            Range::Names(MethodChoice::NAMES.to_vec()),
            DefaultValue::Name(MethodChoice::Exact.name()),
        ),
        spec(
            P,
            ("plot", "t_end"),
            (
                "a last time of a chart",
                "Last time of the plot, in tau",
                "T_END",
            ),
            positive(),
            DefaultValue::Number(PLOT_T_END),
        ),
        spec(
            P,
            ("plot", "width"),
            (
                "a width in characters",
                "Width of each chart, in characters",
                "WIDTH",
            ),
            Range::Count(16, 500),
            DefaultValue::Count(60),
        ),
        spec(
            P,
            ("plot", "height"),
            (
                "a height in lines",
                "Height of each chart, in lines",
                "HEIGHT",
            ),
            Range::Count(2, 200),
            DefaultValue::Count(10),
        ),
    ]
}

/// The tolerance an orbit is integrated at unless `rtol` says otherwise: the
/// one [`OrbitConfig::new`] sets.
fn orbit_rtol() -> DefaultValue {
    ChargeInField::new(Potential::Coulomb, 1e-3)
        .and_then(|c| OrbitConfig::new(c, 1.0, 0.0, Force::LandauLifshitz))
        .map_or(DefaultValue::None, |c| DefaultValue::Number(c.rtol))
}

/// The time a chart of `plot` ends at, in τ.
pub const PLOT_T_END: Real = 500.0;

static SPECS: LazyLock<Vec<Spec>> = LazyLock::new(|| {
    let mut all = top_keys();
    all.extend(times_keys(
        Command::Simulate,
        true,
        DefaultValue::Number(TOP_T_END),
    ));
    all.extend(other_keys());
    all.extend(times_keys(Command::Balance, false, DefaultValue::None));
    all.extend(times_keys(Command::Orbit, true, DefaultValue::None));
    all.extend(times_keys(Command::Shell, true, DefaultValue::None));
    all
});

/// Every key, by command.
pub fn specs() -> &'static [Spec] {
    &SPECS
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
