//! The project as a whole: the book's ties to the code, and the direction of imports between the core and the shells.
//! (One test binary for all of them: each file under tests/ is a binary to link.)

#[path = "../support/mod.rs"]
mod support;

mod architecture;
mod book;
mod readme;
