//! `spintop run SCENE`: one scene file, answered by the lightest model that is
//! right, printed under the matching command's JSON contract plus `scene`,
//! `chosen` and `warnings` (and, for a real particle, `units`).
//!
//! SCENE is a path, or the name of a catalogue scene (`spintop scenes` lists
//! them; they are compiled into the binary, so the names work from any
//! directory). A file on disk wins over a catalogue name.

use super::gate::Gate;
use super::{CliError, Format, bad};
use clap::Args;
use spintop::scene::answer::answer;
use spintop::scene::{Kind, Scene, catalogue};
use std::io::Write;
use std::path::Path;

/// The raw arguments of `run`.
#[derive(Debug, Args)]
#[command(
    after_help = "SCENE is a scene file (TOML) or the name of a catalogue scene; `spintop scenes` lists \
                  the catalogue. The output is that of the matching command (simulate, balance, orbit, \
                  shell, stability) plus `chosen`: the method used and why.\n\
                  Example: spintop run figure-2 --format json"
)]
pub struct RunArgs {
    /// A scene file, or the name of a catalogue scene.
    #[arg(value_name = "SCENE")]
    scene: String,
    /// Output format (stability scenes print table or json).
    #[arg(long, value_parser = super::values::format(), default_value = "table")]
    format: Format,
}

/// Read and validate a scene: the file `arg`, or the catalogue scene of that name.
pub fn load(arg: &str) -> Result<Scene, CliError> {
    let path = Path::new(arg);
    // Anything at that path (a file, a folder, a device, a dangling or looping
    // link) is what was meant: read it or say why not.
    if path.symlink_metadata().is_ok() {
        let text = super::read_text_file(path, "scene file", 1 << 20)?;
        return spintop::scene::parse(&text, arg).map_err(|e| bad(e.to_string()));
    }
    if let Some(entry) = catalogue::find(arg) {
        return entry.scene().map_err(|e| bad(e.to_string()));
    }
    Err(bad(format!(
        "{arg}: no such scene file, and no catalogue scene of that name; expected a path to a .toml file or one of the names `spintop scenes` lists"
    )))
}

/// Load, run and print a scene.
pub(crate) fn execute(
    args: RunArgs,
    out: &mut Gate<'_>,
    err: &mut impl Write,
) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    if args.format == Format::Csv && scene.kind() == Kind::Stability {
        return Err(bad(format!(
            "{}: a stability scene prints --format table or json, not csv",
            scene.file
        )));
    }
    let report = answer(&scene)?;
    // CSV has no room for comments: the warnings go to stderr.
    if args.format == Format::Csv {
        for w in &report.warnings {
            writeln!(err, "spintop: warning: {w}")?;
        }
    }
    out.emit(&report, args.format)
}
