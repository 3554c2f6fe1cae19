//! The live view: keys, screens drawn headless, and the real binary under tmux.

mod keys;
mod learn;
mod screens;
mod tmux;
