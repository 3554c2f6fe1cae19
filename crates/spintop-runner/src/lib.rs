//! What a student's runner and spintop's graders share, and nothing more.
//!
//! `spintop course` and `spintop course grade` never run a student's code in
//! the process that holds the reference answers: the graders (in the
//! `spintop` binary) compute the expected values, and the student's
//! functions run in a **runner**, a separate program linked with the
//! student's crate and this crate only, which answers one call per line:
//!
//! ```text
//! grader → runner:  larmor_rate 0.1 -0.3 …          (the name, the arguments' numbers)
//! runner → grader:  \x1e ok 0.25 1e-3 -0.5           (the answer's numbers)
//!                   \x1e panic not yet implemented   (the function panicked)
//! ```
//!
//! - [`wire`]: an assignment's arguments and answers as numbers, exactly
//!   (every `f64` is printed so that it parses back to the same bits);
//! - [`fields`]: the right-hand sides a step assignment (`rk4_step`,
//!   `dp5_step`) is given, chosen by name and parameters: test problems,
//!   never an assignment's answer;
//! - [`serve`] and [`dispatch!`]: the runner's loop and its table of the
//!   course's 22 functions.
//!
//! Nothing here computes an answer, so a runner that reads its own memory
//! (safe Rust can, through rust-lang/rust#25860) finds no reference to call.

#![forbid(unsafe_code)]

pub mod fields;
mod serve;
pub mod wire;

pub use serve::{ASSIGNMENTS, HELLO, MARK, Reply, answer, parse_reply, request, serve};
pub use spintop::assignment::{C, Jet, Mat3, Real, State, Vec3};
