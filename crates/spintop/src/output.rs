//! What each question of the command line answers, below every shell: the
//! validated request, the computation, the JSON contract and its table and
//! CSV forms, for `simulate`, `balance`, `orbit` and `shell`.
//!
//! The scene engine ([`crate::scene::answer`]) answers a scene file with the
//! same computations and prints the same contracts; the command line only
//! turns arguments into the requests here. A run that cannot be answered is a
//! [`Failure`]: bad input, or a run that stopped, each one line that carries
//! the time and what to try.

use crate::integrate::IntegrateError;
use crate::sim::cost::{Cheaper, TooCostly};
use crate::sim::{MethodChoice, Model, SimError};
use serde::Serialize;
use std::io::{self, Write};
use thiserror::Error;

pub mod balance;
pub mod check;
pub mod orbit;
pub mod shell;
pub mod simulate;

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Aligned columns for reading.
    Table,
    /// Comma-separated values with a header row, full precision.
    Csv,
    /// One JSON object (the documented contract).
    Json,
}

impl Format {
    /// Every format, in the order of [`Format::NAMES`].
    pub const ALL: [Format; 3] = [Format::Table, Format::Csv, Format::Json];

    /// The names the user types (`--format NAME`), in the order of [`Format::ALL`].
    pub const NAMES: [&'static str; 3] = ["table", "csv", "json"];

    /// The name the user types.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The format of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
    }

    /// One line on the format, as `--help` lists it.
    pub fn help(self) -> &'static str {
        match self {
            Format::Table => "Aligned columns for reading",
            Format::Csv => "Comma-separated values with a header row, full precision",
            Format::Json => "One JSON object (the documented contract)",
        }
    }
}

/// A run that stopped before it gave everything that was asked for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stop {
    /// One line in the output itself: `# stopped: LINE` after a table or a
    /// CSV file, `"stopped": "LINE"` in the JSON object.
    pub line: String,
    /// The one line the command line prints on stderr as it exits with code
    /// 3: when, why, and what to try.
    pub message: String,
}

/// What a command answers, as every format writes it: its `Serialize` form
/// is the JSON contract (and what [`check::first_non_finite`] checks), its
/// [`Output::write_text`] the table and the CSV.
pub trait Output: Serialize {
    /// The table or the CSV (JSON is written from the `Serialize` form).
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()>;
    /// Set when the run stopped before it gave all that was asked.
    fn stopped(&self) -> Option<Stop> {
        None
    }
    /// What to try when a number of the output came out NaN or infinite,
    /// naming the settings as `entry` names them.
    fn advice(&self, entry: Entry) -> String;
}

/// A JSON object with a `"stopped"` line after its own fields when its run
/// stopped early.
#[derive(Serialize)]
struct WithStop<'a, T: ?Sized> {
    #[serde(flatten)]
    value: &'a T,
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped: Option<&'a str>,
}

/// Write `value` in `format`, the one way every output is written: JSON
/// whole, with `"stopped"` when the run stopped early, or the table or CSV
/// followed by a `# stopped: …` line. It does not check the numbers: the
/// command line's gate checks them with [`check::first_non_finite`] first.
pub fn write<T: Output + ?Sized>(out: &mut dyn Write, value: &T, format: Format) -> io::Result<()> {
    let stop = value.stopped();
    match format {
        Format::Json => {
            // NOTE: written as it is walked, never built whole first: a
            // million samples took 2.2 GB as a `serde_json::Value`.
            let json = WithStop {
                value,
                stopped: stop.as_ref().map(|s| s.line.as_str()),
            };
            serde_json::to_writer(&mut *out, &json)?;
            writeln!(out)
        }
        Format::Table | Format::Csv => {
            value.write_text(out, format)?;
            match &stop {
                Some(stop) => writeln!(out, "# stopped: {}", stop.line),
                None => Ok(()),
            }
        }
    }
}

/// Why a question got no answer, in one line.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum Failure {
    /// Malformed or unphysical input, or a run refused before it starts.
    #[error("{0}")]
    BadInput(String),
    /// A run stopped for a numerical or modelling reason; the message carries
    /// the time and what to try.
    #[error("{0}")]
    Stopped(String),
}

/// Where a question came from, so that advice names what can be changed
/// there: a flag on the command line, a key in a scene file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Entry {
    /// `spintop simulate`, `plot`, `orbit`, …: flags.
    #[default]
    CommandLine,
    /// `spintop run SCENE`: the scene's keys.
    Scene,
}

/// A setting that advice can point at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Knob {
    /// The tolerance.
    Rtol,
    /// The last output time.
    TEnd,
    /// The initial body rate.
    Omega,
    /// A general top's dipole.
    Dipole,
    /// RK4's step.
    Step,
    /// The closed forms.
    MethodExact,
    /// An adaptive method.
    MethodAdaptive,
    /// The method that chooses (the full model's physical solution).
    MethodAuto,
    /// The reduced model.
    ModelReduced,
    /// The orbit's radiation time.
    Tau0,
    /// The orbit's starting radius.
    R0,
    /// The orbit's force law.
    ForceLl,
    /// The orbit's physical solution of (2.5).
    ForceAl,
    /// The shell's radiation time.
    ShellTau0,
    /// The shell's delay r0/c.
    Delay,
    /// The output times.
    Times,
    /// The rate of a balance's dipole.
    Rate,
}

impl Knob {
    /// The key of the table it is (section, key), and the value advice
    /// names with it, if any (`method` `"exact"`).
    pub fn key(self) -> (&'static str, &'static str, Option<&'static str>) {
        match self {
            Knob::Rtol => ("solve", "rtol", None),
            Knob::TEnd => ("solve", "t_end", None),
            Knob::Omega => ("top", "omega", None),
            Knob::Dipole => ("top", "dipole", None),
            Knob::Step => ("solve", "step", None),
            Knob::MethodExact => ("solve", "method", Some("exact")),
            Knob::MethodAdaptive => ("solve", "method", Some("dop853")),
            Knob::MethodAuto => ("solve", "method", Some("auto")),
            Knob::ModelReduced => ("top", "model", Some("reduced")),
            Knob::Tau0 => ("orbit", "tau0", None),
            Knob::R0 => ("orbit", "r0", None),
            Knob::ForceLl => ("orbit", "force", Some("ll")),
            Knob::ForceAl => ("orbit", "force", Some("al")),
            Knob::ShellTau0 => ("shell", "tau0", None),
            Knob::Delay => ("shell", "delay", None),
            Knob::Times => ("solve", "times", None),
            Knob::Rate => ("balance", "rate", None),
        }
    }
}

/// The long flag of a key: `--t-end` for `t_end` (the one rule; the scene
/// table's flags are these).
pub fn flag_of(key: &str) -> String {
    format!("--{}", key.replace('_', "-"))
}

impl Entry {
    /// How a user names `knob` at this entry point, by the one rule of
    /// [`flag_of`]: the flag on the command line
    /// (`--method exact`), the key in a scene file (`[solve] method =
    /// "exact"`). Advice is one template with this name filled in.
    pub fn name(self, knob: Knob) -> String {
        let (section, key, value) = knob.key();
        match (self, value) {
            (Entry::CommandLine, None) => flag_of(key),
            (Entry::CommandLine, Some(v)) => {
                format!("{} {v}", flag_of(key))
            }
            (Entry::Scene, None) => format!("[{section}] {key}"),
            (Entry::Scene, Some(v)) => format!("[{section}] {key} = \"{v}\""),
        }
    }
}

/// The cheaper way of a refusal over the step budget, naming the settings
/// as `entry` spells them.
pub fn cheaper(c: Cheaper, entry: Entry) -> String {
    let k = |knob| entry.name(knob);
    match c {
        Cheaper::ClosedForms => format!(
            "the closed forms ({} or {}) answer any time at once",
            k(Knob::MethodAuto),
            k(Knob::MethodExact)
        ),
        Cheaper::Exact => format!(
            "the closed forms ({}) take no steps at all",
            k(Knob::MethodExact)
        ),
        Cheaper::EarlierTime => "ask for an earlier last time".into(),
        Cheaper::EarlierOrOmegaAlone => match entry {
            Entry::CommandLine => "ask for an earlier last time; a scene file (`spintop run`) answers Omega alone from the closed form at any time".into(),
            Entry::Scene => "ask for an earlier last time".into(),
        },
    }
}

/// A run over the step budget, in the one wording
/// ([`crate::sim::cost::over_budget`]) with the cheaper way in the words of
/// `entry`.
pub fn too_costly(e: &TooCostly, entry: Entry) -> String {
    format!("{e}; {}", cheaper(e.estimate.cheaper, entry))
}

impl From<SimError> for Failure {
    fn from(e: SimError) -> Self {
        Failure::of(e, Entry::CommandLine)
    }
}

impl Failure {
    /// A simulation's failure, with advice in the words of `entry`.
    pub fn of(e: SimError, entry: Entry) -> Self {
        use crate::sim::physical::PhysicalError as P;
        let k = |knob| entry.name(knob);
        match e {
            SimError::Integrate(IntegrateError::InvalidOption(msg)) => Failure::BadInput(msg),
            SimError::Integrate(e) => numerical(&e, entry),
            SimError::NonFiniteSample(t) => numerical(&IntegrateError::NonFinite { t }, entry),
            SimError::Physical(P::Integrate(e)) => numerical(&e, entry),
            // NOTE: the symmetric top's shoot brackets at every spin (its
            // guess decays at linear theory's rate), and the general top's
            // converges once its horizon is cut into segments; a shoot that
            // still fails is not helped by any setting known.
            SimError::Physical(e @ P::NoConvergence(_)) => Failure::Stopped(format!(
                "{e}; no setting is known to help here (the horizon is already cut into segments, and a looser {} only changes the digits): please report the inputs",
                k(Knob::Rtol)
            )),
            SimError::Physical(e @ P::NotSeparated { .. }) => Failure::Stopped(format!(
                "{e}; a smaller {} or {}, or {}, avoids it",
                k(Knob::Omega),
                k(Knob::Dipole),
                k(Knob::ModelReduced)
            )),
            SimError::TooCostly(c) => Failure::BadInput(too_costly(&c, entry)),
            other => Failure::BadInput(other.to_string()),
        }
    }
}

/// An integrator's failure with general advice.
fn numerical(e: &IntegrateError, entry: Entry) -> Failure {
    Failure::Stopped(format!("{e}; {}", advice(e, entry)))
}

/// What to try after a numerical failure.
fn advice(e: &IntegrateError, entry: Entry) -> String {
    let k = |knob| entry.name(knob);
    match e {
        IntegrateError::NonFinite { .. } => format!(
            "the step is too large for this problem: try a smaller {}, or an adaptive method ({})",
            k(Knob::Step),
            k(Knob::MethodAdaptive)
        ),
        IntegrateError::StepSizeUnderflow { .. } => format!(
            "the problem is too stiff or singular here: try {} where a closed form exists, a looser {}, or a smaller {}",
            k(Knob::MethodExact),
            k(Knob::Rtol),
            k(Knob::Omega)
        ),
        IntegrateError::TooManySteps { .. } => format!(
            "the run needs too many steps: shorten {}, loosen {}, enlarge {}, or use {}",
            k(Knob::TEnd),
            k(Knob::Rtol),
            k(Knob::Step),
            k(Knob::MethodExact)
        ),
        IntegrateError::NoConvergence { .. } => format!(
            "the implicit method's Newton iteration failed: try a smaller {} or an adaptive method",
            k(Knob::Step)
        ),
        IntegrateError::InvalidOption(_) => "check the method options".into(),
    }
}

/// A simulation's failure, with advice that applies to the model and the
/// method in use, in the words of `entry`: it names only options that exist
/// for them and are not already chosen (no "method exact" for a model
/// without a closed form or a run already exact, no step for an adaptive
/// method).
pub fn sim_failure(e: SimError, model: &Model, choice: MethodChoice, entry: Entry) -> Failure {
    use crate::sim::MethodChoice as M;
    let k = |knob| entry.name(knob);
    let integrate = match &e {
        SimError::Integrate(ie) if !matches!(ie, IntegrateError::InvalidOption(_)) => ie.clone(),
        SimError::NonFiniteSample(t) => IntegrateError::NonFinite { t: *t },
        SimError::Physical(crate::sim::physical::PhysicalError::Integrate(ie)) => ie.clone(),
        _ => return Failure::of(e, entry),
    };
    let closed = model.has_closed_form();
    let full = model.is_full();
    // The closed forms ran: nothing stepped, so only the time or the inputs
    // can have overflowed.
    let closed_form_run = matches!(
        model.method(choice, &crate::sim::MethodOptions::default()),
        Ok(crate::sim::Method::ClosedForm | crate::sim::Method::ClosedFormDop853)
    );
    // A general top's numbers are in kappa = 1 units, and its dipole is an
    // input that can overflow too.
    let inputs = if matches!(
        model,
        Model::General(_) | Model::GeneralReduced(_) | Model::GeneralFull(_)
    ) {
        format!(
            "a smaller {} or {} (kappa = 1 units)",
            k(Knob::Omega),
            k(Knob::Dipole)
        )
    } else {
        format!("a smaller {} (in units of 1/tau)", k(Knob::Omega))
    };
    let exact = if closed && matches!(choice, M::Rk4 | M::Dopri5 | M::Dop853) {
        format!(
            ", or {} (the closed forms take no steps)",
            k(Knob::MethodExact)
        )
    } else {
        String::new()
    };
    let (omega, rtol, t_end, step) = (k(Knob::Omega), k(Knob::Rtol), k(Knob::TEnd), k(Knob::Step));
    let advice: String = match (&integrate, choice) {
        (IntegrateError::NonFinite { .. }, M::Rk4) => {
            format!(
                "RK4's fixed step is too large for these rates (its stability limit is about 2.8 over the largest decay rate): use a smaller {step}, or an adaptive method ({}){exact}",
                k(Knob::MethodAdaptive)
            )
        }
        (IntegrateError::NonFinite { .. }, _) if closed_form_run => format!(
            "the closed forms overflow a double at this time: ask for earlier times, or use {inputs}"
        ),
        (IntegrateError::NonFinite { .. }, _) if full => format!(
            "the full ALE's solution left the range of a double: use {inputs} or a shorter {t_end}, or compare {}",
            k(Knob::ModelReduced)
        ),
        (IntegrateError::NonFinite { .. }, _) => {
            format!("the rates overflow a double: use {inputs}{exact}")
        }
        (IntegrateError::StepSizeUnderflow { .. }, _) => {
            if closed && choice != M::Exact && choice != M::Auto {
                format!(
                    "the problem is stiff or singular here: {} takes no steps; else use a smaller {omega}",
                    k(Knob::MethodExact)
                )
            } else {
                format!(
                    "the problem is stiff or singular here: use a smaller {omega} or a looser {rtol}"
                )
            }
        }
        (IntegrateError::TooManySteps { .. }, M::Rk4) => {
            format!("use a larger {step} (if RK4 stays stable) or a shorter {t_end}{exact}")
        }
        (IntegrateError::TooManySteps { .. }, _) => {
            format!("use a looser {rtol} or a shorter {t_end}{exact}")
        }
        (IntegrateError::NoConvergence { .. }, _) => format!(
            "the implicit method's Newton iteration failed: use an adaptive method or a smaller {omega}"
        ),
        (IntegrateError::InvalidOption(_), _) => "check the method options".into(),
    };
    Failure::Stopped(format!("{integrate}; {advice}"))
}

/// One row of an aligned table: every cell right-aligned in `width` columns.
pub fn write_aligned<S: std::fmt::Display>(
    out: &mut (impl Write + ?Sized),
    cells: impl IntoIterator<Item = S>,
    width: usize,
) -> io::Result<()> {
    for c in cells {
        // A cell as wide as its column still gets a space before it, so that
        // columns never run together.
        let c = c.to_string();
        if c.chars().count() >= width {
            write!(out, " {c}")?;
        } else {
            write!(out, "{c:>width$}")?;
        }
    }
    writeln!(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failure's advice from a scene names no flag; from the command line,
    /// no section.
    #[test]
    fn advice_names_keys_in_a_scene_and_flags_on_the_command_line() {
        let e = IntegrateError::TooManySteps {
            t: 1.0,
            max_steps: 10,
        };
        let (Failure::Stopped(scene), Failure::Stopped(flags)) = (
            numerical(&e, Entry::Scene),
            numerical(&e, Entry::CommandLine),
        ) else {
            panic!("a numerical failure is a stop");
        };
        assert!(
            !scene.contains("--") && scene.contains("[solve] rtol"),
            "{scene}"
        );
        assert!(!flags.contains('[') && flags.contains("--rtol"), "{flags}");
    }
}
