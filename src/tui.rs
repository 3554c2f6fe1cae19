//! The live terminal UI: the truncated and the reduced top side by side, the
//! full ALE's physical solution beside its runaway, or a general
//! (asymmetric) top's three models; and `spintop learn`, the book beside
//! each chapter's own scene.
//!
//! A thin shell over [`spintop::sim`]: every number on the screen is read from a
//! [`spintop::sim::Sample`] or from the core's closed forms; nothing here redoes
//! physics. The pieces follow the house style:
//!
//! | module | what it holds |
//! |---|---|
//! | [`app`] | the live view's state: [`app::App`] (what it shows of each model, the view, the mode), its [`app::Command`]s and the one [`app::App::apply`] that changes it |
//! | [`stepper`] | the models, stepped tick by tick on a thread of their own (or inline, for tests) |
//! | [`event`] | terminal events → [`app::Command`] values |
//! | [`view`] | the live view's layout; drawing only reads the state |
//! | [`widgets`] | the charts, the hodograph, the top in space, the live numbers |
//! | [`theme`] | every colour and style, in one place |
//! | [`session`] | the terminal: checked, set up, the one loop of both views, restored |
//! | [`signals`] | the signals that end a session, turned into a flag |
//! | [`learn`] | `spintop learn`: the book's chapters beside their live scenes |

pub mod app;
pub mod event;
pub mod learn;
pub mod session;
pub mod signals;
pub mod stepper;
pub mod theme;
pub mod view;
pub mod widgets;

pub use app::{App, Command, Settings};
pub use event::command_for;
