//! The book a student's copy carries, read where the copy is: every chapter
//! of an exported copy resolves its `{{#include}}`s to the same text as the
//! repository's (the assignments page rewritten for the copy, the commands
//! as a copy runs them: `spintop_course::export::copy_chapter`), and
//! `spintop learn` run in a copy whose clone was deleted and which was then
//! moved reads the copy's chapters, with their code, and keeps its place in
//! the copy's `target/`.

use super::{names_nothing_outside, repo, scratch};
use spintop_app::learn::chapters;
use spintop_app::learn::markdown::resolve_includes;
use spintop_app::learn::progress::{Keeper, Progress};
use std::path::Path;
use std::process::{Command, Output};

/// What an include that does not resolve leaves in the text.
const NOT_FOUND: &str = "(not found: ";

/// The chapters `SUMMARY.md` in `book` lists (file names).
fn files(book: &Path) -> Vec<String> {
    let summary = std::fs::read_to_string(book.join("SUMMARY.md")).unwrap();
    chapters(&summary).into_iter().map(|c| c.file).collect()
}

/// The chapter `file` of `book` as the reader reads it: includes resolved.
fn resolved(book: &Path, file: &str) -> String {
    let text = std::fs::read_to_string(book.join(file)).unwrap();
    resolve_includes(&text, book)
}

#[test]
fn every_chapter_of_an_exported_copy_reads_as_the_repositorys() {
    let root = scratch("book-copy");
    let copy = root.join("copy");
    spintop_course::export(repo(), &copy).unwrap();
    let (ours, theirs) = (repo().join("book/src"), copy.join("book/src"));
    let listed = files(&ours);
    assert_eq!(files(&theirs), listed);
    assert!(listed.len() >= 20, "{listed:?}");
    let mut includes = 0;
    for file in &listed {
        let text = std::fs::read_to_string(ours.join(file)).unwrap();
        includes += text.matches("{{#include ").count();
        let (mine, copied) = (resolved(&ours, file), resolved(&theirs, file));
        assert!(!mine.contains(NOT_FOUND), "{file} in the repository");
        assert!(!copied.contains(NOT_FOUND), "{file} in the copy: {copied}");
        if file != "assignments.md" {
            // As the repository's, its commands as a copy runs them.
            let expected =
                resolve_includes(&spintop_course::export::copy_chapter(file, &text), &ours);
            assert_eq!(copied, expected, "{file}");
        }
    }
    assert!(includes >= 50, "{includes} includes");
    // The copy's assignments page is the one it carries beside the book.
    assert_eq!(
        std::fs::read_to_string(theirs.join("assignments.md")).unwrap(),
        std::fs::read_to_string(copy.join("book/assignments.md")).unwrap()
    );
    // The reader in the copy shows §4.1's commands as the copy runs them,
    // and the repository's example as the repository's.
    let reader = spintop_app::learn::Learn::open(&theirs, Some("4.1")).unwrap();
    let shown = reader.chapter_text(80);
    let shown = shown.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(shown.contains("spintop figure 1") && !shown.contains("cargo run --release -- "));
    assert!(
        shown.contains("(in spintop's repository) cargo run --release --example"),
        "{shown}"
    );
    // Not what only the HTML book needs; no reference solution anywhere.
    assert!(!theirs.join("katex").exists());
    assert!(!copy.join("lessons/src").exists());
    names_nothing_outside(&copy, &[repo().display().to_string()]);
    std::fs::remove_dir_all(&root).unwrap();
}

/// `spintop learn ARGS` run in `dir`, as a student runs it there (no test
/// override of the progress file).
fn learn_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .arg("learn")
        .args(args)
        .current_dir(dir)
        .env_remove("SPINTOP_LEARN_PROGRESS")
        .env_remove("CARGO_TARGET_DIR")
        .output()
        .unwrap()
}

fn stdout_of(out: &Output, what: &str) -> String {
    assert!(
        out.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

#[test]
#[ignore = "end-to-end: exports a copy from a scratch clone of the repository, deletes the clone, runs the binary in the moved copy"]
fn learn_in_a_moved_copy_reads_the_copys_book_with_its_code_and_keeps_its_place_there() {
    let root = scratch("book-moved");
    let (exported, clone) = super::export_from_a_deleted_clone(&root);
    let copy = root.join("elsewhere").join("course");
    std::fs::create_dir_all(copy.parent().unwrap()).unwrap();
    std::fs::rename(&exported, &copy).unwrap();
    let outside = [
        repo().display().to_string(),
        clone.display().to_string(),
        exported.display().to_string(),
    ];
    names_nothing_outside(&copy, &outside);
    // The binary still knows where it was built (this repository, whose book
    // is whole): only text that is in the copy alone proves the copy's book
    // is read. A chapter's title, its text, and the lesson code it includes.
    let edit = |rel: &str, from: &str, to: &str| {
        let path = copy.join(rel);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(from), "{rel} no longer says {from:?}");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    };
    let title = "[The asymmetric top as this copy holds it]";
    edit(
        "book/src/SUMMARY.md",
        "[Beyond the paper: the asymmetric top]",
        title,
    );
    let words = "Words that only the moved copy's chapter holds.";
    edit(
        "book/src/asymmetric-top.md",
        "\nSection 3 of the paper",
        &format!("\n{words}\n\nSection 3 of the paper"),
    );
    let code = "let only_in_the_copy = 1; // in the copy's lessons/";
    edit(
        "lessons/asymmetric_top.rs",
        "// ANCHOR: energy_rise\n",
        &format!("// ANCHOR: energy_rise\n    {code}\n"),
    );
    // The place kept in the copy's target/, as the reader leaves it there.
    let place = copy.join("target/spintop-learn.json");
    let left = Progress {
        opened: vec!["asymmetric-top.md".into()],
        last: Some("asymmetric-top.md".into()),
        ..Progress::default()
    };
    Keeper::new(place.clone(), Progress::default())
        .save(&left)
        .unwrap();
    let inside = copy.join("src");
    let list = stdout_of(&learn_in(&inside, &["--list"]), "learn --list");
    let first = list.lines().next().unwrap();
    assert!(first.contains(" 1 opened"), "{first}");
    assert!(
        first.contains(&format!("the book at {}", copy.join("book/src").display())),
        "{first}"
    );
    let row = list
        .lines()
        .find(|l| l.contains(&title[1..title.len() - 1]));
    assert!(row.is_some_and(|r| r.contains('✓')), "{list}");
    let chapter = stdout_of(
        &learn_in(&inside, &["--chapter", "as this copy holds it", "--list"]),
        "learn --chapter … --list",
    );
    assert!(chapter.contains(words), "{chapter}");
    assert!(chapter.contains(code), "{chapter}");
    assert!(chapter.contains("let top = chapter_top(1.0);"), "{chapter}");
    assert!(!chapter.contains(NOT_FOUND), "{chapter}");
    for (what, text) in [("--list", &list), ("--chapter", &chapter)] {
        for path in &outside {
            assert!(!text.contains(path.as_str()), "{what} names {path}");
        }
    }
    let reset = stdout_of(&learn_in(&inside, &["--reset"]), "learn --reset");
    assert!(
        reset.contains(&format!("progress forgotten ({})", place.display())),
        "{reset}"
    );
    assert!(!place.exists());
    std::fs::remove_dir_all(&root).unwrap();
}
