//! The `spintop` binary: everything lives in the library's [`spintop_app::cli`].

use std::io::{self, BufWriter};
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut stdout = BufWriter::new(io::stdout().lock());
    let mut stderr = io::stderr().lock();
    spintop_app::cli::run(std::env::args_os(), &mut stdout, &mut stderr)
}
