//! `spintop stability`: the six rows of the stability suite, each the naive
//! method that fails beside the method spintop uses, with measured numbers.

use super::gate::Gate;
use super::{CliError, bad};
use clap::{Args, ValueEnum};
use serde::Serialize;
use spintop::output::{Format, Output};
use spintop::stability::{Row, RowError, all_rows};
use std::io::{self, Write};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum StabilityFormat {
    /// One block per row, for reading.
    Table,
    /// One JSON object: {"rows": [...]}.
    Json,
}

/// The raw arguments of `stability`.
#[derive(Debug, Args)]
#[command(
    after_help = "Rows: 1 full ALE (3.4) runaway, 2 Euler angles at the pole, \
                        3 stiffness, 4 long runs without radiation, 5 closed forms at \
                        realistic tau, 6 the appendix delay equation.\n\
                        Example: spintop stability --row 5"
)]
pub struct StabilityArgs {
    /// Run only this row (1-6); all rows by default.
    #[arg(long)]
    row: Option<u8>,
    /// Output format.
    #[arg(long, value_enum, default_value = "table")]
    format: StabilityFormat,
}

/// The rows measured, the `stability --format json` contract.
#[derive(Serialize)]
struct Report {
    rows: Vec<Row>,
}

impl Output for Report {
    /// One block per row, for reading (there is no CSV form).
    fn write_text(&self, out: &mut dyn Write, _format: Format) -> io::Result<()> {
        for (i, row) in self.rows.iter().enumerate() {
            if i > 0 {
                writeln!(out)?;
            }
            write!(out, "{row}")?;
        }
        Ok(())
    }

    fn advice(&self, _entry: spintop::output::Entry) -> String {
        "a row's measurement overflowed; run that row alone with --row to see it".into()
    }
}

/// Run and print `stability`.
pub(crate) fn execute(args: StabilityArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let rows: Vec<Result<Row, RowError>> = match args.row {
        None => all_rows(),
        Some(n @ 1..=6) => vec![spintop::stability::row(n)],
        Some(n) => return Err(bad(format!("--row must be 1 to 6, got {n}"))),
    };
    let mut done = Vec::with_capacity(rows.len());
    for row in rows {
        done.push(row.map_err(|e| CliError::Stopped(e.to_string()))?);
    }
    let format = match args.format {
        StabilityFormat::Table => Format::Table,
        StabilityFormat::Json => Format::Json,
    };
    out.emit(&Report { rows: done }, format)
}
