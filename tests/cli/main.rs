//! The `spintop` command line, run as a user runs it: one module per subcommand.
//! (One test binary for all of them: each file under tests/ is a binary to link.)

#[path = "../support/mod.rs"]
mod support;

mod bad_input;
mod balance;
mod bench;
mod gate;
mod orbit;
mod plot;
mod run;
mod shell;
mod simulate;
