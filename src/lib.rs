//! # spintop-app
//!
//! The `spintop` application: the shells over the core crate [`spintop`].
//!
//! - [`cli`]: the `spintop` command line (raw arguments, then validation into
//!   the core's structures, then a run and an exit code). It launches the
//!   two full-screen shells:
//! - [`tui`]: the live view, and
//! - [`learn`]: the terminal reader of the book, each chapter beside its
//!   scene, with the course graded beside it.
//!
//! What those two share sits below both: [`live`], the live models as both
//! draw them, and [`term`], the terminal (its loop, signals, theme). The
//! course runner ([`spintop_course`]) and the book server
//! ([`spintop_server`]) are crates below this one; the physics, the
//! integrators, the models and the scenes are the core's. This library exists
//! so that the tests drive the shells in process; nothing imports it.
#![forbid(unsafe_code)]

pub mod cli;
pub mod learn;
pub mod live;
pub mod term;
pub mod tui;
