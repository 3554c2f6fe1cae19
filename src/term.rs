//! What both full-screen shells need of the terminal (the live view and
//! `spintop learn`), below both of them: they never import each other.
//!
//! | module | what it holds |
//! |---|---|
//! | [`session`] | the terminal: checked, set up, the one loop of both views, restored |
//! | [`signals`] | the signals that end a session, turned into a flag; Ctrl-Z's stop and resume |
//! | [`theme`] | every colour and style, in one place |
//! | [`cells`] | lines that fit: header cells and footer keys that shorten or leave whole |
//! | [`popup`] | a box of text over the screen that scrolls |

pub mod cells;
pub mod popup;
pub mod session;
pub mod signals;
pub mod theme;
