//! The book stays true to the code.
//!
//! mdBook renders a missing `{{#include file:anchor}}` as an empty block with no
//! error, so these tests are the only guard: every chapter in SUMMARY.md exists
//! and is compiled as a doctest, every included file and anchor exists, and the
//! program output shown in each chapter is what the lesson program prints now.
//!
//! The same holds for the SVG figures: the book's `figures/figure-N.svg` are
//! what `spintop figure N --svg FILE` draws now.
//!
//! After a deliberate change to a lesson or a figure, refresh the book's copies
//! with `UPDATE_BOOK=1 cargo test -p spintop-app --test app project::`, and review the diff.

mod diagrams;
mod figures;
mod lessons;
mod math;
mod snippets;
mod symbols;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn book_src() -> PathBuf {
    root().join("book/src")
}

/// Chapter files linked from SUMMARY.md (drafts, `[Title]()`, have no file).
fn summary_chapters() -> Vec<String> {
    let summary = fs::read_to_string(book_src().join("SUMMARY.md")).expect("SUMMARY.md");
    summary
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .filter(|link| !link.is_empty())
        .map(str::to_string)
        .collect()
}

/// Compare a lesson's output with the copy the book shows; `None` when fresh.
fn stale(name: &str, output: &str, shown: &Path) -> Option<String> {
    let shown_text = fs::read_to_string(shown).unwrap_or_default();
    if shown_text == output {
        return None;
    }
    let line = shown_text
        .lines()
        .zip(output.lines())
        .position(|(a, b)| a != b)
        .map_or_else(|| "its length".to_string(), |i| format!("line {}", i + 1));
    Some(format!(
        "the book's copy of `{name}` output ({}) is stale at {line}; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::",
        shown.display()
    ))
}

/// A figure the book embeds is what code draws now: `fresh` is written to
/// `book/src/NAME` under `UPDATE_BOOK=1`, must equal the file otherwise, and
/// `chapter` must embed it. Returns the chapter's text.
fn figure_is_current(name: &str, fresh: &str, chapter: &str, drawn_by: &str) -> String {
    let shown = book_src().join(name);
    if std::env::var_os("UPDATE_BOOK").is_some() {
        fs::write(&shown, fresh).unwrap();
    }
    assert!(
        fs::read_to_string(&shown).unwrap_or_default() == fresh,
        "the book's {name} is not what {drawn_by} draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::"
    );
    let text = fs::read_to_string(book_src().join(chapter)).unwrap();
    assert!(
        text.contains(&format!("]({name})")),
        "{chapter} embeds {name}"
    );
    text
}

#[test]
fn book_every_summary_chapter_exists_and_is_compiled_as_a_doctest() {
    // The core doctests the chapters; the course's chapters, whose snippets
    // use the graders and the course runner, are doctested by spintop-course.
    let lib = [
        "crates/spintop/src/lib.rs",
        "crates/spintop-course/src/lib.rs",
    ]
    .map(|f| fs::read_to_string(root().join(f)).unwrap())
    .concat();
    let chapters = summary_chapters();
    assert!(chapters.len() >= 4, "{chapters:?}");
    for chapter in &chapters {
        assert!(
            book_src().join(chapter).is_file(),
            "SUMMARY.md lists {chapter}, which is missing"
        );
        let include = format!("include_str!(\"../../../book/src/{chapter}\")");
        assert!(
            lib.contains(&include),
            "crates/spintop/src/lib.rs does not doctest {chapter}: add {include}"
        );
    }
    // And no chapter file sits outside SUMMARY.md, unseen.
    let listed: BTreeSet<&str> = chapters.iter().map(String::as_str).collect();
    for entry in fs::read_dir(book_src()).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".md") && name != "SUMMARY.md" {
            assert!(
                listed.contains(name.as_str()),
                "{name} is not in SUMMARY.md"
            );
        }
    }
}
