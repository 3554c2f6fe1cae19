//! The live terminal UI: the truncated and the reduced top, side by side, or
//! a general (asymmetric) top under the truncated ALE (3.3) in one column.
//!
//! A thin shell over [`crate::sim`]: every number on the screen is read from a
//! [`crate::sim::Sample`] or from the core's closed forms; nothing here redoes
//! physics. The pieces follow the house style:
//!
//! | module | what it holds |
//! |---|---|
//! | [`app`] | the state: [`app::App`] (the simulations of one [`app::Top`], the view, the mode) and the one [`app::App::apply`] that changes it |
//! | [`event`] | keys → [`event::Command`] values, and the terminal loop that turns wall-clock time into model steps |
//! | [`view`] | the layout; drawing only reads the state |
//! | [`widgets`] | the charts, the hodograph, the top in space, the live numbers |
//! | [`theme`] | every colour and style, in one place |
//! | [`learn`] | `spintop learn`: the book's chapters beside their live scenes |

pub mod app;
pub mod event;
pub mod learn;
pub mod signals;
pub mod theme;
pub mod view;
pub mod widgets;

pub use app::{App, Settings};
pub use event::{Command, command_for};
