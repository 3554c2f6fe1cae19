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
    // read, and the screen says so; the place is still the copy's own (it
    // was the repository's, so a copy read and wrote another's place).
    std::fs::remove_dir_all(copy.join("book/src")).unwrap();
    std::fs::remove_file(&place).unwrap();
    let env = format!(
        "cd '{}' && env -u SPINTOP_LEARN_PROGRESS",
        copy.join("src").display()
    );
    let args = "learn --chapter asymmetric-top --no-grading";
    let Some(tmux) = launch_sized("copy-older", &env, args, (80, 24)) else {
        return;
    };
    let screen = tmux.wait_for("whose book", long, |s| {
        s.contains("reading the repository's book")
    });
    assert!(!screen.contains(mark), "{screen}");
    tmux.keys("q");
    assert_eq!(exit_status(&tmux, long), "0");
    let kept: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&place).expect("the copy's own place"))
            .unwrap();
    assert_eq!(kept["last"], "asymmetric-top.md", "{kept}");
    drop(tmux);
    std::fs::remove_dir_all(&root).unwrap();
}

/// Whether this test can be another user: root, with `setpriv`.
fn can_be_nobody() -> bool {
    let root = std::process::Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.trim_ascii() == b"0");
    let setpriv = std::process::Command::new("setpriv")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    root && setpriv
}

/// As another user in a course that user may not write (a copy root owns),
/// `spintop learn` reads on and says what could not be written, whose the
/// folder is and what still works: the reader's place on the status line,
/// the grading in the course panel; `q` ends with exit 1 and the place's
/// file named.
#[test]
#[ignore = "end-to-end: tmux, as another uid (root and setpriv)"]
fn learn_as_another_user_in_a_read_only_copy_says_what_it_cannot_write() {
    if !can_be_nobody() {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "learn as another user: SKIPPED, it needs root and setpriv to become nobody"
        );
        return;
    }
    // A path as short as a student's (/home/alice/course): the status
    // line holds three rows.
    let root = std::env::temp_dir().join(format!("sp-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let copy = root.join("course");
    spintop_course::export(repo(), &copy).unwrap();
    let env = format!(
        "cd '{}' && setpriv --reuid=65534 --regid=65534 --clear-groups env -u SPINTOP_LEARN_PROGRESS HOME=/nonexistent",
        copy.display()
    );
    let Some(tmux) = launch_sized("nobody", &env, "learn", (80, 24)) else {
        return;
    };
    let long = Duration::from_secs(30);
    // The screen's words, its wrapped lines joined (the panel's border out).
    let flat = |s: &str| {
        s.replace('│', " ")
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
    };
    let place = copy.join("target/spintop-learn.json");
    let screen = tmux.wait_for("the place's refusal", long, |s| {
        flat(s).contains("(uid 65534)")
    });
    let said = flat(&screen);
    for words in [
        format!("could not be saved to {}", place.display()),
        "its folder course/ is root's (mode 755), not writable by nobody (uid 65534)".to_string(),
        "(reading goes on)".to_string(),
    ] {
        assert!(
            said.contains(&words),
            "{words:?}:
{screen}"
        );
    }
    assert!(!said.contains("os error 13"), "{screen}");
    tmux.keys("a");
    let screen = tmux.wait_for("the grading's refusal", long, |s| {
        flat(s).contains("the grader builds in")
    });
    let said = flat(&screen);
    assert!(
        said.contains("cp -r") && said.contains("reading the book"),
        "{screen}"
    );
    tmux.keys("Escape");
    // (Escape and q at once read as Alt-q.)
    tmux.wait_for("the panel closed", long, |s| !s.contains("╭ course"));
    tmux.keys("q");
    assert_eq!(exit_status(&tmux, long), "1");
    assert!(!place.exists());
    drop(tmux);
    // The command line as nobody: could not grade (exit 4), saying why; a
    // hint is shown though its rung cannot be kept (exit 1).
    let as_nobody = |args: &[&str]| {
        std::process::Command::new("setpriv")
            .args(["--reuid=65534", "--regid=65534", "--clear-groups"])
            .arg(env!("CARGO_BIN_EXE_spintop"))
            .args(args)
            .current_dir(&copy)
            .env("HOME", "/nonexistent")
            .output()
            .unwrap()
    };
    let out = as_nobody(&["course"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(4), "{stderr}");
    assert!(
        stderr.contains("its folder course/ is root's") && stderr.contains("cp -r"),
        "{stderr}"
    );
    let out = as_nobody(&["course", "hint", "larmor_rate"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("hint 1 of 3"));
    assert!(
        stderr.contains("target/spintop-course.json") && stderr.contains("not writable by nobody"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&root).unwrap();
}
