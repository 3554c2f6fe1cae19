//! The book server's request parser fed arbitrary bytes (`parsers`). The
//! attacks on the running server (`spintop book`, its supervisor and its
//! snippets) are the application's tests (`tests/book`), since they run the
//! `spintop` binary that launches and supervises each snippet.

mod parsers;
