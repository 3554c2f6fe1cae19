//! The `spintop` binary: everything lives in the library's [`spintop_app::cli`].

use std::io::{self, BufWriter};
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut stdout = BufWriter::new(io::stdout().lock());
    // Not locked for the whole run: a progress bar (`course grade`) writes
    // to stderr from other threads, and would wait for the lock for ever.
    let mut stderr = io::stderr();
    spintop_app::cli::run(std::env::args_os(), &mut stdout, &mut stderr)
}
