//! A simulation: one model of the top, one method, stepped and sampled.
//!
//! Pure like the physics: no clock, no I/O. The same inputs give the same bits,
//! so the CLI, the TUI and the tests all see identical numbers.
//!
//! The lightest adequate path is used (`MethodChoice::Auto`):
//!
//! | model | Ω(t) | orientation O(t) |
//! |---|---|---|
//! | truncated (4.2)–(4.4) | closed form (4.7) | closed form, Rot(n_L, |L₀|ϑ)·O₀·R_z(Ω̃₃₀ϑ) |
//! | reduced (4.12)–(4.14) | closed form (4.15)–(4.16) | O = Q·R_z(Ω̃₃t): the precession exact, Q by DOP853 on SO(3), driven by the closed form |
//! | general (3.3) | DOP853, or the Taylor method at rtol ≤ [`TAYLOR_AUTO_RTOL`] | the same method, in the same state (the Taylor method carries a unit quaternion) |
//!
//! | module | what it holds |
//! |---|---|
//! | `model` | [`Model`]: which equation of motion |
//! | `method` | [`MethodChoice`], [`Method`], [`MethodOptions`]: how it is stepped |
//! | `state` | [`InitialState`], [`Sample`], [`SimError`] |
//! | `stepping` | the steppers: Runge–Kutta on SO(3), the Taylor method |
//! | `simulation` | [`Simulation`]: a model and a method, advanced to each time |

pub mod accuracy;
pub mod claim;
pub mod cost;
pub mod measured;
mod method;
mod model;
pub mod orbit;
pub mod physical;
pub mod regime;
pub mod secular;
pub mod shell;
mod simulation;
pub mod split;
mod state;
mod stepping;
pub mod times;

pub use method::{
    MIN_RTOL, Method, MethodChoice, MethodOptions, MethodRefused, OptionsError, TAYLOR_AUTO_RTOL,
    auto_integrator,
};
pub use model::Model;
pub use simulation::Simulation;
pub use state::{InitialState, MAX_RATE, Sample, SimError, check_rate};
