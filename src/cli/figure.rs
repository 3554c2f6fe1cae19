//! `spintop figure 1|2 [--svg FILE]`: the paper's Figures 1 and 2, and
//! `spintop figure NAME --svg FILE`: one of the book's diagrams.
//!
//! Prints the figure as text charts; with `--svg FILE` also writes it as an
//! SVG document. The points come from [`spintop::figure`], the drawing from
//! [`spintop::plot::figure`]; the diagrams from [`spintop::plot::diagram`], which
//! projects spintop's own vectors. A name that is neither 1, 2 nor a diagram,
//! or a file that cannot be written, is bad input: one line on stderr, exit
//! code 2, and nothing on stdout.

use super::gate::Gate;
use super::{CliError, bad};
use clap::Args;
use spintop::figure::{Figure, FigureNumber};
use spintop::plot::diagram;
use spintop::plot::figure::{ascii, svg};
use std::io::Write;
use std::path::PathBuf;

/// The raw arguments of `figure`.
#[derive(Debug, Args)]
#[command(
    after_help = "Figure 1 is the truncated model (no Schott term), Figure 2 the reduced model \
                  (Schott term kept); both with I3/I1 = 2/5 and Omega0 = (0, 0.1, 0.2) in 1/tau.\n\
                  Examples: spintop figure 2; spintop figure 1 --svg figure-1.svg; \
                  spintop figure euler-angles --svg euler-angles.svg"
)]
pub struct FigureArgs {
    /// Which figure: 1 (truncated model) or 2 (reduced model), or the name of
    /// one of the book's diagrams (top-axes-dipole, euler-angles,
    /// precession-cone, free-top-cones, shell-model).
    #[arg(value_name = "N")]
    number: String,
    /// Also write the figure as SVG to FILE.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
}

/// Validate, compute, write the SVG (if asked), then print the text charts.
pub(crate) fn execute(args: FigureArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    if let Some(d) = diagram::by_name(args.number.trim()) {
        if let Some(path) = &args.svg {
            std::fs::write(path, &d.svg)
                .map_err(|e| bad(format!("cannot write the SVG to {}: {e}", path.display())))?;
        }
        writeln!(out, "{}: {}", d.name, d.title)?;
        if let Some(path) = &args.svg {
            writeln!(out, "SVG written to {}", path.display())?;
        }
        return Ok(());
    }
    let number = FigureNumber::parse(&args.number).map_err(|e| {
        bad(format!(
            "{e}; the book's diagrams are {}",
            diagram::NAMES.join(", ")
        ))
    })?;
    let figure = Figure::new(number).map_err(|e| bad(e.to_string()))?;
    // NOTE: the file is written before anything is printed, so a path that
    // cannot be written leaves stdout empty and the error is the only output.
    if let Some(path) = &args.svg {
        std::fs::write(path, svg(&figure))
            .map_err(|e| bad(format!("cannot write the SVG to {}: {e}", path.display())))?;
    }
    write!(out, "{}", ascii(&figure))?;
    if let Some(path) = &args.svg {
        writeln!(out, "\nSVG written to {}", path.display())?;
    }
    Ok(())
}
