//! Lesson for the paper's Figures 1 and 2: both figures as text charts.
//!
//! Run it: `cargo run --release --example figures`
//! (the same charts as `spintop figure 1` and `spintop figure 2`; add
//! `--svg FILE` to the command for the vector version).
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::figure::{Figure, FigureNumber};
use spintop::plot::figure::ascii;
use std::io::{self, Write};

/// Print the lesson to `out`.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    for (i, number) in [FigureNumber::One, FigureNumber::Two]
        .into_iter()
        .enumerate()
    {
        if i > 0 {
            writeln!(out, "\n{}\n", "=".repeat(100))?;
        }
        // ANCHOR: figure_points
        let figure = Figure::new(number).map_err(io::Error::other)?;
        // ANCHOR_END: figure_points
        write!(out, "{}", ascii(&figure))?;
    }
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
