//! Searching the book as `less` searches a file: `/` forward and Ctrl-R
//! backward from where the reader is, `n` on in the same direction and `N`
//! back, case-insensitive; a word not in the rest of this chapter is looked
//! for in the next chapters (the previous ones, backward), round the whole
//! book, and the status says where it was found.

use super::markdown;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, mpsc};

/// A match: each part of it as drawn, (line, byte range in the line's
/// text); more than one part when the text's wrap splits the phrase.
#[derive(Debug, Clone, PartialEq)]
pub struct Match(pub Vec<(usize, Range<usize>)>);

impl Match {
    /// The line it starts on.
    pub fn line(&self) -> usize {
        self.0.first().map_or(0, |p| p.0)
    }
}

/// A search and what it found in the chapter shown.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Search {
    /// The word searched for.
    pub query: String,
    /// Its direction: forward (`/`), or backward (Ctrl-R).
    pub forward: bool,
    /// Every match in the chapter shown, in reading order.
    pub matches: Vec<Match>,
    /// The match last shown, if it is in this chapter.
    pub at: Option<usize>,
}

/// The longest search typed.
pub const LONGEST: usize = 64;

/// A stretch of text as written (a paragraph, a line of code), before the
/// width wrapped it: its text, and where each drawn line of it is, (line,
/// its bytes in `text`, where they start in the line's own text).
struct Unwrapped {
    text: String,
    lines: Vec<(usize, Range<usize>, usize)>,
}

/// The rendered lines joined back where the width wrapped them, as `less`
/// searches a file's lines and not the screen's rows.
fn unwrapped(rendered: &markdown::Rendered) -> Vec<Unwrapped> {
    let mut out: Vec<Unwrapped> = Vec::new();
    let mut wraps = rendered.wraps.iter().peekable();
    for (i, line) in rendered.lines.iter().enumerate() {
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        while wraps.next_if(|w| w.0 < i).is_some() {}
        match (wraps.next_if(|w| w.0 == i), out.last_mut()) {
            (Some(&(_, prefix, joint)), Some(last)) if prefix <= text.len() => {
                last.text.push_str(joint);
                let start = last.text.len();
                last.text.push_str(&text[prefix..]);
                last.lines.push((i, start..last.text.len(), prefix));
            }
            _ => out.push(Unwrapped {
                lines: vec![(i, 0..text.len(), 0)],
                text,
            }),
        }
    }
    out
}

/// The text of `rendered` as searched: its wraps undone, lower-cased.
pub fn searched(rendered: &markdown::Rendered) -> String {
    let texts: Vec<String> = unwrapped(rendered).into_iter().map(|u| u.text).collect();
    texts.join("\n").to_lowercase()
}

/// Every match of `query` (case-insensitive) in `rendered`, a phrase the
/// wrap splits included (then in two parts).
pub fn find(rendered: &markdown::Rendered, query: &str) -> Vec<Match> {
    let needle = query.to_lowercase();
    if needle.is_empty() {
        return Vec::new();
    }
    let mut matches = Vec::new();
    for u in unwrapped(rendered) {
        let lower = u.text.to_lowercase();
        // Lower-casing keeps byte offsets for the text this book holds
        // (ASCII and Greek letters of the same length); where it would
        // not, the match is skipped rather than misplaced.
        if lower.len() != u.text.len() {
            continue;
        }
        let mut from = 0;
        while let Some(at) = lower[from..].find(&needle) {
            let start = from + at;
            matches.push(Match(parts(&u, start..start + needle.len())));
            from = start + needle.len().max(1);
        }
    }
    matches
}

/// The drawn parts of the bytes `range` of an unwrapped text.
fn parts(u: &Unwrapped, range: Range<usize>) -> Vec<(usize, Range<usize>)> {
    let mut out = Vec::new();
    for (line, bytes, own) in &u.lines {
        let (a, b) = (range.start.max(bytes.start), range.end.min(bytes.end));
        if a < b {
            out.push((*line, own + a - bytes.start..own + b - bytes.start));
        }
    }
    out
}

/// The width other chapters are rendered at to be searched: wide, so that
/// few phrases break across lines.
const SEARCH_WIDTH: u16 = 200;

/// The plain text of every chapter, rendered once (library source folded or
/// whole) to be searched across the book. The folded texts are made in the
/// background from the start ([`Texts::warm`]), so that the first search
/// across the book does not wait for 25 chapters to render.
#[derive(Debug, Default)]
pub struct Texts {
    unfolded: bool,
    chapters: Vec<Option<String>>,
    /// The folded texts of every chapter, being made in the background.
    warming: Option<mpsc::Receiver<Vec<String>>>,
    /// Set when the texts are no longer wanted: the background stops.
    stop: Arc<AtomicBool>,
}

impl Drop for Texts {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

/// A chapter's text as searched: rendered wide, plain, lower-cased.
fn searched_text(source: &str, unfolded: bool) -> String {
    let rendered = markdown::render_with(
        source,
        SEARCH_WIDTH,
        &markdown::Options {
            unfold: unfolded,
            figures_later: true,
            images: None,
            plain: false,
        },
    );
    searched(&rendered)
}

/// A chapter's Markdown source, its includes resolved (empty when it
/// cannot be read).
pub fn chapter_source(path: &Path, book: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    markdown::resolve_includes(&text, path.parent().unwrap_or(book))
}

impl Texts {
    /// Texts whose folded chapters (`paths`) are made on another thread
    /// from now on.
    pub fn warm(paths: Vec<PathBuf>, book: PathBuf) -> Self {
        let (tx, rx) = mpsc::channel();
        let stop = Arc::new(AtomicBool::new(false));
        let stopped = Arc::clone(&stop);
        let spawned = std::thread::Builder::new()
            .name("search-texts".into())
            .spawn(move || {
                let mut texts = Vec::with_capacity(paths.len());
                for p in &paths {
                    if stopped.load(Ordering::Relaxed) {
                        return;
                    }
                    texts.push(searched_text(&chapter_source(p, &book), false));
                }
                let _ = tx.send(texts);
            });
        Self {
            unfolded: false,
            chapters: Vec::new(),
            warming: spawned.ok().map(|_| rx),
            stop,
        }
    }

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
        if !unfolded && let Some(rx) = self.warming.take() {
            // Made in the background since the start: ready, or soon.
            if let Ok(texts) = rx.recv() {
                self.chapters = texts.into_iter().map(Some).collect();
            }
        }
        if self.chapters.len() <= i {
            self.chapters.resize(i + 1, None);
        }
        let text = self.chapters[i].get_or_insert_with(|| searched_text(&source(), unfolded));
        text.contains(&query.to_lowercase())
    }
}
