//! The live view and `spintop learn`: keys, screens drawn headless, the
//! reader against `less`, and the real binary under tmux (the end-to-end
//! tier: `tmux`, `term_e2e`, `copy`: `learn` in a student's copy).

mod copy;
mod keys;
mod learn;
mod live_fit;
mod live_front;
mod live_messages;
mod live_scenes;
mod live_view;
mod overlays;
mod reader;
mod reader_nav;
mod reader_wrap;
mod screens;
mod student;
mod term_e2e;
mod tmux;
