//! # spintop-app
//!
//! The `spintop` application: the shells over the core crate [`spintop`].
//!
//! - [`cli`]: the `spintop` command line (raw arguments, then validation into
//!   the core's structures, then a run and an exit code).
//! - [`tui`]: the live terminal view and the terminal reader of the book.
//!
//! The course runner ([`spintop_course`]) and the book server
//! ([`spintop_server`]) are crates below this one; the physics, the
//! integrators, the models and the scenes are the core's. This library exists
//! so that the tests drive the shells in process; nothing imports it.
#![forbid(unsafe_code)]

pub mod cli;
pub mod tui;
