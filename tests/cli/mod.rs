//! The `spintop` command line, run as a user runs it: one module per subcommand.

mod bad_input;
mod balance;
mod bench;
mod entry;
mod entry_advice;
mod entry_sweep;
mod figure;
mod gate;
mod learn;
mod lost_orientation;
mod orbit;
mod plot;
mod run;
mod shell;
mod simulate;
mod stability;
