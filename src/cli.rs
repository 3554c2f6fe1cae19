//! The `spintop` command line: a thin shell over [`spintop::sim`].
//!
//! Raw arguments are parsed by clap, then validated into the objects the core
//! runs on ([`spintop::output::simulate::SimulateConfig`]), then run; every failure becomes one line on
//! stderr and an exit code:
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success |
//! | 2 | bad input: malformed or unphysical arguments |
//! | 3 | numerical failure: the run was stopped, with the time and what to try |
//! | 4 | could not grade: the machine refused a grading (no cargo, a broken toolchain, crates missing offline, a folder it may not write), with what to do |

use clap::{Parser, Subcommand};
use spintop::math::Real;
pub(crate) use spintop::numbers::parse_number;
use spintop::output::Failure;
pub use spintop::output::Format;
use spintop::scene::Refusal;
use spintop::sim::SimError;
use std::ffi::OsString;
use std::io::{self, Write};
use std::process::ExitCode;

pub mod balance;
pub mod bench;
pub mod book;
pub mod course;
pub mod figure;
pub mod gate;
pub mod learn;
pub mod orbit;
pub mod plot;
pub mod run;
pub mod scenes;
pub mod shell;
pub mod simulate;
pub mod stability;
pub mod tui;
pub mod values;

/// Exit code for bad input.
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit code for a numerical failure.
pub const EXIT_NUMERICAL: u8 = 3;
/// Exit code for a grading the machine did not allow (`spintop course`):
/// nothing was judged of the student's code.
pub const EXIT_CANNOT_GRADE: u8 = 4;

/// The command line.
#[derive(Debug, Parser)]
#[command(
    name = "spintop",
    version,
    about = "The polarized spinning top of Duviryak's paper: the truncated and the reduced \
             radiation-reaction models, runnable and tested.",
    after_help = "Units: time in tau = 2d^2/(3 I1 c^3), rates in 1/tau, I1 = 1 (symmetric models); \
                  kappa = 2/(3c^3) = 1 (general model).\n\n\
                  Exit codes: 0 success; 1 the output could not be written; 2 bad input (a flag, a value, \
                  a file, or a run refused before it starts because it would cost too much); 3 a numerical \
                  failure (runaway, stiffness, step underflow, a non-finite result), reported with its time; \
                  4 `spintop course` could not grade (no cargo, a broken toolchain, crates missing offline, \
                  a folder it may not write: said with what to do; or, for `course grade`, a copy not fully \
                  graded); 128+N the live view or `learn` was stopped by signal N (the terminal is restored)."
)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Integrate or evaluate one model and print samples (table, CSV or JSON).
    #[command(after_help = simulate::after_help())]
    Simulate(simulate::SimulateArgs),
    /// Section 2: the two balance laws (2.1), (2.2) and the Schott term (2.4) for a dipole trajectory.
    Balance(balance::BalanceArgs),
    /// Section 2: a charge in a Coulomb or oscillator field under radiation reaction (2.5)-(2.9).
    Orbit(orbit::OrbitArgs),
    /// Appendix: the charge as a small shell, a delay equation (A.1)-(A.3), and where it breaks.
    Shell(shell::ShellArgs),
    /// The live view: truncated and reduced models side by side (also `spintop` alone).
    Tui(tui::TuiArgs),
    /// Print the curves of the live view as text charts (for pipes and the book).
    Plot(plot::PlotArgs),
    /// Where natural methods fail, beside what spintop does instead: six measured rows.
    Stability(stability::StabilityArgs),
    /// Answer one scene file (or catalogue scene) with the lightest model that is right.
    Run(run::RunArgs),
    /// List the catalogue of scenes, one line each.
    Scenes(scenes::ScenesArgs),
    /// Work against precision: every method's error against its cost, as charts, a table and CSV/JSON.
    Bench(bench::BenchArgs),
    /// The paper's Figures 1 and 2 as text charts, and as SVG with --svg FILE.
    Figure(figure::FigureArgs),
    /// Study in the terminal: the book's chapters, each beside its live scene.
    Learn(learn::LearnArgs),
    /// The course: every assignment with its state, the progress and what to do next.
    Course(course::CourseArgs),
    /// Serve the book on 127.0.0.1, where ▶ runs each snippet against this spintop.
    Book(book::BookArgs),
}

/// A comma-separated list of times (a newtype, so clap takes it as one value).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TimeList(pub(crate) Vec<Real>);

/// Times as typed (their rule is the core's, [`spintop::sim::times::check_times`],
/// applied where a scene's `[solve] times` is).
pub(crate) fn parse_times(s: &str) -> Result<TimeList, values::ValueError> {
    values::reals(s).map(TimeList)
}

/// A failure of the command line, mapped to one line and an exit code.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Malformed or unphysical input.
    #[error("{0}")]
    BadInput(String),
    /// A question's flags refused by the core, in the words a scene's keys get.
    #[error(transparent)]
    Refused(#[from] Refusal),
    /// A run stopped for a numerical or modelling reason; the message carries
    /// the time and what to try.
    #[error("{0}")]
    Stopped(String),
    /// A grading the machine did not allow (cargo missing or refusing, a
    /// folder it may not write): the message says what and what to do.
    #[error("{0}")]
    CannotGrade(String),
    /// Writing the output failed.
    #[error("cannot write output: {0}")]
    Io(io::Error),
    /// A file the command keeps (the reader's place) could not be written:
    /// the message names it and the system's reason.
    #[error("{0}")]
    NotSaved(String),
    /// A terminal session was ended by a signal (the terminal was restored):
    /// its number and name.
    #[error("stopped by {1}; the terminal is restored")]
    Signal(i32, String),
}

impl CliError {
    /// The exit code.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::BadInput(_) | CliError::Refused(_) => EXIT_BAD_INPUT,
            CliError::Stopped(_) => EXIT_NUMERICAL,
            CliError::CannotGrade(_) => EXIT_CANNOT_GRADE,
            CliError::Io(_) | CliError::NotSaved(_) => 1,
            // As a shell reports a process a signal stopped: 128 + its number.
            CliError::Signal(n, _) => u8::try_from(128 + n).unwrap_or(EXIT_NUMERICAL),
        }
    }

    /// The one-line message.
    pub fn message(&self) -> String {
        self.to_string()
    }
}

impl From<SimError> for CliError {
    fn from(e: SimError) -> Self {
        CliError::from(Failure::from(e))
    }
}

impl From<Failure> for CliError {
    fn from(e: Failure) -> Self {
        match e {
            Failure::BadInput(msg) => CliError::BadInput(msg),
            Failure::Stopped(msg) => CliError::Stopped(msg),
        }
    }
}

/// A simulation's failure, with advice for the model and the method in use
/// (see [`spintop::output::sim_failure`]).
pub(crate) fn sim_failure(
    e: SimError,
    model: &spintop::sim::Model,
    choice: spintop::sim::MethodChoice,
) -> CliError {
    CliError::from(spintop::output::sim_failure(
        e,
        model,
        choice,
        spintop::output::Entry::CommandLine,
    ))
}

pub(crate) fn bad(msg: impl Into<String>) -> CliError {
    CliError::BadInput(msg.into())
}

impl From<io::Error> for CliError {
    fn from(e: io::Error) -> Self {
        // The gate's refusal of a non-finite number in prose is a numerical
        // failure (exit 3), not a failed write.
        if let Some(refusal) = e
            .get_ref()
            .filter(|inner| inner.is::<gate::NonFiniteText>())
        {
            return CliError::Stopped(refusal.to_string());
        }
        CliError::Io(e)
    }
}

/// Reads a text file given on the command line, refusing what is not one: a
/// folder, a FIFO, a device (`/dev/zero` never ends), a symlink loop, or a
/// file over `max_bytes` (checked before and while reading, so nothing
/// unbounded is read). `what` names the file in the message ("scene file").
pub(crate) fn read_text_file(
    path: &std::path::Path,
    what: &str,
    max_bytes: u64,
) -> Result<String, CliError> {
    use std::io::Read;
    let shown = path.display();
    let meta = std::fs::metadata(path)
        .map_err(|e| bad(format!("{shown}: cannot read the {what}: {e}")))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file (a device, FIFO or socket)"
        };
        return Err(bad(format!(
            "{shown}: the {what} is {kind}; give the path of a text file"
        )));
    }
    if meta.len() > max_bytes {
        return Err(bad(format!(
            "{shown}: the {what} has {} bytes, more than the {max_bytes} allowed",
            meta.len()
        )));
    }
    let file = std::fs::File::open(path)
        .map_err(|e| bad(format!("{shown}: cannot read the {what}: {e}")))?;
    let mut bytes = Vec::new();
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| bad(format!("{shown}: cannot read the {what}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(bad(format!(
            "{shown}: the {what} is longer than the {max_bytes} bytes allowed"
        )));
    }
    String::from_utf8(bytes).map_err(|_| bad(format!("{shown}: the {what} is not UTF-8 text")))
}

/// A name a flag does not take, in the words a scene's key gets for it
/// (`--model xml is not known; expected one of truncated, …`), with clap's
/// suggestion when it has one.
fn unknown_name(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if e.kind() != ErrorKind::InvalidValue {
        return None;
    }
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let flag = text(ContextKind::InvalidArg)?;
    let flag = flag.split_whitespace().next()?.to_string();
    let value = text(ContextKind::InvalidValue)?;
    let Some(ContextValue::Strings(names)) = e.get(ContextKind::ValidValue) else {
        return None;
    };
    if names.is_empty() {
        // A path (clap refuses an empty one, with no list of names to offer).
        return value
            .is_empty()
            .then(|| format!("{flag}: the path is empty"));
    }
    let value = if value.is_empty() {
        "''".to_string()
    } else {
        value
    };
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut message = spintop::scene::request::not_known(&format!("{flag} {value}"), &names);
    if let Some(near) = suggested(e).filter(|_| names.len() > 1) {
        message = format!("{message} (a similar one: {near})");
    }
    Some(message)
}

/// A number too large for a double, in the words a scene's key gets
/// (`--b: 1e400 overflows f64 …`).
fn overflow(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    use std::error::Error;
    let values::ValueError::Overflow(number) = e.source()?.downcast_ref()? else {
        return None;
    };
    let Some(ContextValue::String(arg)) = e.get(ContextKind::InvalidArg) else {
        return None;
    };
    let flag = arg.split_whitespace().next()?;
    Some(spintop::scene::request::overflows(flag, number))
}

/// clap's suggestion of a similar name, if any.
fn suggested(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    match e.get(ContextKind::SuggestedValue)? {
        ContextValue::String(s) => Some(s.clone()),
        ContextValue::Strings(v) if !v.is_empty() => Some(v.join(", ")),
        _ => None,
    }
}

/// clap's report on one line: a name a flag does not take in the core's
/// words (the names it takes listed, as a scene's key gets them), or the
/// error, the missing arguments, the possible values and the tip ("a similar
/// argument exists") without the usage block, with a pointer to `--help`.
fn clap_message(e: &clap::Error) -> String {
    if let Some(message) = unknown_name(e).or_else(|| overflow(e)) {
        return message;
    }
    format!("{} (see --help)", clap_report(e))
}

/// clap's own report on one line, without the usage block.
fn clap_report(e: &clap::Error) -> String {
    let rendered = e.render().to_string();
    let mut parts: Vec<String> = Vec::new();
    for line in rendered.lines() {
        let t = line.trim();
        if t.starts_with("Usage:") || t.starts_with("For more information") {
            break;
        }
        if t.is_empty() {
            continue;
        }
        parts.push(t.strip_prefix("error: ").unwrap_or(t).to_string());
    }
    let mut message = String::new();
    // After "…not provided:" the parts are a list of arguments.
    let mut listing = false;
    for part in parts {
        if message.is_empty() {
            listing = part.ends_with(':');
            message = part;
        } else if part.starts_with('[') {
            message = format!("{message} {part}");
        } else if listing && !part.starts_with("tip:") {
            let sep = if message.ends_with(':') { " " } else { ", " };
            message = format!("{message}{sep}{part}");
        } else {
            listing = false;
            message = format!("{message}; {part}");
        }
    }
    if message.is_empty() {
        "invalid arguments".to_string()
    } else {
        message
    }
}

/// Parse, validate, run and print; returns the process exit code.
pub fn run<I, T>(args: I, stdout: &mut impl Write, stderr: &mut impl Write) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    ExitCode::from(run_code(args, stdout, stderr))
}

/// [`run`], with the exit code as a number: what the tests read when they
/// run the command line in their own process.
pub fn run_code<I, T>(args: I, stdout: &mut impl Write, stderr: &mut impl Write) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                // The help is output like any other: a write that fails (a
                // full disk) is said, as the commands' are; a closed pipe is not.
                return match write!(stdout, "{e}").and_then(|()| stdout.flush()) {
                    Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
                        let e = CliError::from(e);
                        let _ = writeln!(stderr, "spintop: error: {}", e.message());
                        e.exit_code()
                    }
                    _ => 0,
                };
            }
            let _ = writeln!(stderr, "spintop: error: {}", clap_message(&e));
            return EXIT_BAD_INPUT;
        }
    };
    // Every command writes its output through the gate, and only through it.
    let mut gate = gate::Gate::new(stdout);
    let out = &mut gate;
    let result = match cli.command {
        // No subcommand opens the live view, the program's main job.
        None => tui::execute(tui::TuiArgs::default(), out),
        Some(Command::Simulate(args)) => simulate::execute(args, out, stderr),
        Some(Command::Balance(args)) => balance::execute(args, out),
        Some(Command::Orbit(args)) => orbit::execute(args, out),
        Some(Command::Shell(args)) => shell::execute(args, out, stderr),
        Some(Command::Tui(args)) => tui::execute(args, out),
        Some(Command::Plot(args)) => plot::execute(args, out),
        Some(Command::Stability(args)) => stability::execute(args, out),
        Some(Command::Run(args)) => run::execute(args, out, stderr),
        Some(Command::Scenes(args)) => scenes::execute(args, out),
        Some(Command::Bench(args)) => bench::execute(args, out),
        Some(Command::Figure(args)) => figure::execute(args, out),
        Some(Command::Learn(args)) => learn::execute(args, out),
        Some(Command::Course(args)) => course::execute(args, out),
        Some(Command::Book(args)) => book::execute(args, out),
    };
    match result.and_then(|()| gate.flush().map_err(CliError::from)) {
        Ok(()) => 0,
        // A closed pipe (`spintop … | head`) is the reader's choice, not an error.
        Err(CliError::Io(e)) if e.kind() == io::ErrorKind::BrokenPipe => 0,
        Err(e) => {
            let _ = writeln!(stderr, "spintop: error: {}", e.message());
            e.exit_code()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}
