//! Searching the book as `less` searches a file: `/` forward and Ctrl-R
//! backward from where the reader is, `n` on in the same direction and `N`
//! back, case-insensitive; a word not in the rest of this chapter is looked
//! for in the next chapters (the previous ones, backward), round the whole
//! book, and the status says where it was found.

use super::markdown;
use ratatui::text::Line;
use std::ops::Range;

/// A search and what it found in the chapter shown: (line, byte range in
/// the line's text).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Search {
    /// The word searched for.
    pub query: String,
    /// Its direction: forward (`/`), or backward (Ctrl-R).
    pub forward: bool,
    /// Every match in the chapter shown, in reading order.
    pub matches: Vec<(usize, Range<usize>)>,
    /// The match last shown, if it is in this chapter.
    pub at: Option<usize>,
}

/// The longest search typed.
pub const LONGEST: usize = 64;

/// Every match of `query` (case-insensitive) in `lines`.
pub fn find(lines: &[Line], query: &str) -> Vec<(usize, Range<usize>)> {
    let needle = query.to_lowercase();
    if needle.is_empty() {
        return Vec::new();
    }
    let mut matches = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        let lower = text.to_lowercase();
        // Lower-casing keeps byte offsets for the text this book holds
        // (ASCII and Greek letters of the same length); where it would
        // not, the match is skipped rather than misplaced.
        if lower.len() != text.len() {
            continue;
        }
        let mut from = 0;
        while let Some(at) = lower[from..].find(&needle) {
            let start = from + at;
            matches.push((i, start..start + needle.len()));
            from = start + needle.len().max(1);
        }
    }
    matches
}

/// The width other chapters are rendered at to be searched: wide, so that
/// few phrases break across lines.
const SEARCH_WIDTH: u16 = 200;

/// The plain text of every chapter, rendered once (library source folded or
/// whole) to be searched across the book.
#[derive(Debug, Default)]
pub struct Texts {
    unfolded: bool,
    chapters: Vec<Option<String>>,
}

impl Texts {
    /// Whether chapter `i` (its `source`) holds `query`, case-insensitive.
    pub fn holds(
        &mut self,
        i: usize,
        source: impl FnOnce() -> String,
        unfolded: bool,
        query: &str,
    ) -> bool {
        if self.unfolded != unfolded {
            self.chapters.clear();
            self.unfolded = unfolded;
        }
        if self.chapters.len() <= i {
            self.chapters.resize(i + 1, None);
        }
        let text = self.chapters[i].get_or_insert_with(|| {
            let rendered = markdown::render_with(
                &source(),
                SEARCH_WIDTH,
                &markdown::Options {
                    unfold: unfolded,
                    figures_later: true,
                    images: None,
                },
            );
            markdown::plain(&rendered.lines).to_lowercase()
        });
        text.contains(&query.to_lowercase())
    }
}
