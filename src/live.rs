//! The live models, as both full-screen shells show them: the live view
//! (`spintop tui`) shows every column full screen, and `spintop learn`
//! shows the columns a chapter is about beside its text.
//!
//! A thin shell over [`spintop::sim`]: every number on the screen is read
//! from a [`spintop::sim::Sample`] or from the core's closed forms; nothing
//! here redoes physics. The pieces follow the house style:
//!
//! | module | what it holds |
//! |---|---|
//! | [`app`] | the state: [`App`] (what it shows of each model, the view, the mode), its [`Command`]s and the one [`App::apply`] that changes it |
//! | [`settings`] | the parameters the models start from, validated, and the live cost check |
//! | [`layout`] | the top shown, and so its columns: which model and method each runs |
//! | [`columns`] | one model as the screen shows it: its latest sample and its history |
//! | [`stepper`] | the models, stepped tick by tick on a thread of their own (or inline, for tests) |
//! | [`draw`] | one model's column, drawn; the clock's status |
//! | [`widgets`] | the charts, the hodograph, the top in space, the live numbers |
//! | [`entry`] | a number typed into the Ω₀ field: refused with its reason, never changed |
//! | [`help`] | what the help says: the keys, the panels, every row of numbers |
//! | [`refusal`] | why a setting is refused, in one line for the user |

pub mod app;
pub mod columns;
pub mod draw;
pub mod entry;
pub mod help;
pub mod layout;
pub mod refusal;
pub mod settings;
pub mod stepper;
pub mod widgets;

pub use app::{App, Command, Mode};
pub use layout::Top;
pub use refusal::Refusal;
pub use settings::Settings;
