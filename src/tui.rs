//! The live view (`spintop tui`, and `spintop` alone): the truncated and the
//! reduced top side by side, the full ALE's physical solution beside its
//! runaway, or a general (asymmetric) top's three models, full screen.
//!
//! The models and their columns are [`crate::live`]'s (`spintop learn`
//! shows them beside its chapters too); the terminal, its loop and its
//! restoring are [`crate::term`]'s. What is the live view's own:
//!
//! | module | what it holds |
//! |---|---|
//! | [`event`] | terminal events → [`crate::live::Command`] values |
//! | [`view`] | the full-screen layout: header, columns, footer, help; drawing only reads the state |

pub mod event;
pub mod view;

use crate::live::App;
use crate::term::session::{LoopReport, Session};
use std::time::Duration;

/// Runs the live view on `app` in the terminal until it quits, a signal
/// arrives, or `limit` has passed (the benchmark); the terminal is restored
/// whichever way it ends.
pub fn run(app: &mut App, limit: Option<Duration>) -> std::io::Result<LoopReport> {
    Session::start()?.run(app, limit)
}
