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

mod names;
mod range;

pub use names::{
    Choice, DIPOLES, DipoleKind, FORCES, FRAMES, FrameName, MODELS, ModelAsk, POTENTIALS, Tier,
    find, names,
};
pub use range::{Bound, Range};

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

pub use crate::output::flag_of;

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
/// The methods `plot` takes: all but `forward`, the last, which only the
/// full model takes (a plot draws the truncated and the reduced model).
const PLOT_METHOD_NAMES: &[&str] = MethodChoice::NAMES
    .split_at(MethodChoice::NAMES.len() - 1)
    .0;

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
        R::Names(PLOT_METHOD_NAMES), D::Name("exact")),
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

    /// `plot` offers every method but the full model's `forward`.
    #[test]
    fn plot_takes_every_method_but_forward() {
        let Range::Names(names) = key(Command::Plot, "solve", "method").range else {
            panic!("plot's method is a name");
        };
        let mut all = names.to_vec();
        assert!(!all.contains(&"forward"));
        all.push("forward");
        assert_eq!(all, MethodChoice::NAMES);
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

    use crate::output::{Entry, Knob};

    const KNOBS: [Knob; 17] = [
        Knob::Rtol,
        Knob::TEnd,
        Knob::Omega,
        Knob::Dipole,
        Knob::Step,
        Knob::MethodExact,
        Knob::MethodAdaptive,
        Knob::MethodAuto,
        Knob::ModelReduced,
        Knob::Tau0,
        Knob::R0,
        Knob::ForceLl,
        Knob::ForceAl,
        Knob::ShellTau0,
        Knob::Delay,
        Knob::Times,
        Knob::Rate,
    ];

    /// Advice names a key of the table, with a value the key takes, and in
    /// the words of the entry point: a flag never in a scene's advice, a
    /// section never on the command line.
    #[test]
    fn each_knob_is_a_key_of_the_table_named_as_its_entry_point_names_it() {
        for knob in KNOBS {
            let (section, key, value) = knob.key();
            let spec = specs()
                .iter()
                .find(|s| s.section == section && s.key == key)
                .unwrap_or_else(|| panic!("{knob:?}: no [{section}] {key} in the table"));
            if let (Some(v), Range::Names(names)) = (value, spec.range) {
                assert!(names.contains(&v), "{knob:?}: {key} takes no {v}");
            }
            let flag = Entry::CommandLine.name(knob);
            let scene = Entry::Scene.name(knob);
            assert!(
                flag.starts_with(&spec.flag()) && !flag.contains('['),
                "{flag}"
            );
            assert!(
                scene.starts_with(&format!("[{section}] {key}")) && !scene.contains("--"),
                "{scene}"
            );
        }
    }
}
