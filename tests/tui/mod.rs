//! The live view and `spintop learn`: keys, screens drawn headless, the
//! reader against `less`, and the real binary under tmux (the end-to-end
//! tier: `tmux`, `term_e2e`).

mod keys;
mod learn;
mod live_view;
mod overlays;
mod reader;
mod screens;
mod student;
mod term_e2e;
mod tmux;
