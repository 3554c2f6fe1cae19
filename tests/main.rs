//! The application's tests, in one binary (each file under tests/ would be
//! a binary to link): the command line run as a user runs it (`cli`), the
//! live view and the terminal reader (`tui`), the book server attacked as
//! `spintop book` runs it (`book`), the course graded as `spintop course`
//! grades it (`course`), and the project as a whole
//! (`project`: the book's ties to the code, the README, the layers).

mod support;

mod book;
mod cli;
mod course;
mod project;
mod tui;
