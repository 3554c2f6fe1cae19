//! The live view: keys, screens drawn headless, and the real binary under tmux.
//! (One test binary for all of them: each file under tests/ is a binary to link.)

#[path = "../support/mod.rs"]
mod support;

mod keys;
mod learn;
mod screens;
mod tmux;
