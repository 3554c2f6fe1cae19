//! `spintop learn` in a student's copy, in a real terminal (tmux, 80×24):
//! run from a folder inside the copy it shows the copy's own chapter (text
//! that only the copy holds) and, on `q`, keeps the reader's place in the
//! copy's `target/`, not the repository's; a copy that carries no book (an
//! older export) reads the repository's, and the screen says so.

use super::tmux::{exit_status, launch_sized};
use crate::course::{repo, scratch};
use std::time::Duration;

#[test]
#[ignore = "end-to-end: tmux"]
fn learn_in_a_copy_shows_the_copys_chapter_and_keeps_the_place_in_the_copy() {
    let root = scratch("learn-copy-tmux");
    let copy = root.join("course");
    spintop_course::export(repo(), &copy).unwrap();
    let chapter = copy.join("book/src/asymmetric-top.md");
    let text = std::fs::read_to_string(&chapter).unwrap();
    let (from, mark) = ("What you will learn here.", "Copy-only words.");
    assert!(text.contains(from));
    std::fs::write(&chapter, text.replacen(from, mark, 1)).unwrap();
    // Started in the copy's src/, with no test override of the progress file.
    let env = format!(
        "cd '{}' && env -u SPINTOP_LEARN_PROGRESS",
        copy.join("src").display()
    );
    let args = "learn --chapter asymmetric-top --no-grading";
    let Some(tmux) = launch_sized("copy", &env, args, (80, 24)) else {
        return;
    };
    let long = Duration::from_secs(20);
    tmux.wait_for("the copy's words", long, |s| s.contains(mark));
    tmux.keys("q");
    assert_eq!(exit_status(&tmux, long), "0");
    let place = copy.join("target/spintop-learn.json");
    let kept =
        std::fs::read_to_string(&place).unwrap_or_else(|e| panic!("{}: {e}", place.display()));
    let kept: serde_json::Value = serde_json::from_str(&kept).unwrap();
    assert_eq!(kept["last"], "asymmetric-top.md", "{kept}");
    drop(tmux);
    // A copy exported before copies carried the book: the repository's is
    // read, and the screen says so (its place kept aside, not in the
    // repository's target/, which is a reader's own).
    std::fs::remove_dir_all(copy.join("book/src")).unwrap();
    let aside = root.join("progress.json");
    let env = format!(
        "cd '{}' && SPINTOP_LEARN_PROGRESS='{}'",
        copy.join("src").display(),
        aside.display()
    );
    let Some(tmux) = launch_sized("copy-older", &env, args, (80, 24)) else {
        return;
    };
    let screen = tmux.wait_for("whose book", long, |s| {
        s.contains("reading the repository's book")
    });
    assert!(!screen.contains(mark), "{screen}");
    tmux.keys("q");
    assert_eq!(exit_status(&tmux, long), "0");
    assert!(aside.is_file());
    drop(tmux);
    std::fs::remove_dir_all(&root).unwrap();
}
