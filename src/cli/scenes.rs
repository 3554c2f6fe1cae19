//! `spintop scenes`: the catalogue of `crates/spintop/scenes/`, one line per scene.
//!
//! The files are compiled into the binary (see [`spintop::scene::catalogue`]),
//! so the list and `spintop run NAME` work from any directory.

use super::CliError;
use super::gate::Gate;
use clap::Args;
use spintop::scene::catalogue::CATALOGUE;
use std::io::Write;

/// The raw arguments of `scenes` (none).
#[derive(Debug, Args)]
#[command(
    after_help = "Run one with `spintop run NAME`, or open a top scene live with `spintop tui NAME`.\n\
                  Example: spintop scenes, then spintop run nanoparticle-1e7-debye"
)]
pub struct ScenesArgs {}

/// Print the catalogue: name, kind, the first sentence of the description.
pub(crate) fn execute(_args: ScenesArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    for entry in CATALOGUE {
        // NOTE: the catalogue is tested to parse; a failure here is a build
        // from an edited tree, reported rather than skipped.
        let scene = entry
            .scene()
            .map_err(|e| CliError::BadInput(e.to_string()))?;
        writeln!(
            out,
            "{:<24} {:<10} {}",
            scene.name,
            scene.kind().name(),
            scene.summary()
        )?;
    }
    Ok(())
}
