//! # spintop
//!
//! The free rotation of a polarized spinning top under radiation reaction, after
//! A. Duviryak, "On the free rotation of a polarized spinning-top as a test of the
//! correct radiation reaction torque". Every equation of the paper that the crate
//! uses is cited in its doc comment as `Paper: Eq. (N.M).`
//!
//! - [`math`]: scalar, vector and rotation types; SO(3) helpers.
//! - [`physics`]: the paper, one module per concept (pure: no I/O, no clock).
//! - [`integrate`]: RK4, Dormand–Prince 5(4) and DOP853 over one small trait.
//! - [`sim`]: a model plus a method, stepped and sampled (pure).
//! - [`cli`]: the `spintop` command line, a thin shell over [`sim`].
//! - [`tui`]: the live terminal view, another thin shell over [`sim`].
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod cli;
pub mod integrate;
pub mod math;
pub mod physics;
pub mod sim;
pub mod tui;
