//! `spintop learn` and `spintop course export` as a user runs them: what
//! they say about a progress file that cannot be read, a chapter asked for
//! by a word many chapters hold, and the paths they name.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("spintop-cli-learn-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `spintop learn ARGS` with its place kept in `progress`.
fn learn(progress: &std::path::Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .arg("learn")
        .args(args)
        .env("SPINTOP_LEARN_PROGRESS", progress)
        .output()
        .unwrap()
}

/// A progress file that is not one is said (its path, why), set aside as
/// `.bad` with its bytes, and the reader starts afresh; the next run is
/// quiet (nothing left to complain of).
#[test]
fn an_unreadable_progress_file_is_said_and_kept_aside() {
    let dir = scratch("bad");
    let path = dir.join("spintop-learn.json");
    std::fs::write(&path, "{garbage\n").unwrap();
    let out = learn(&path, &["--no-grading", "--list"]);
    let said = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{said}");
    let first = said.lines().next().unwrap_or_default();
    assert!(
        first.contains(&path.display().to_string())
            && first.contains("could not be read")
            && first.contains("spintop-learn.json.bad"),
        "{said}"
    );
    assert_eq!(
        std::fs::read(dir.join("spintop-learn.json.bad")).unwrap(),
        b"{garbage\n"
    );
    let again = learn(&path, &["--no-grading", "--list"]);
    assert!(!String::from_utf8_lossy(&again.stdout).contains("could not be read"));
    let _ = std::fs::remove_dir_all(&dir);
}
