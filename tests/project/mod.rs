//! The project as a whole: the book's ties to the code, and the direction of imports between the core and the shells.

mod architecture;
mod book;
mod readme;
mod sizes;
