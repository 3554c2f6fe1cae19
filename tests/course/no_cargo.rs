//! A grading that cannot run (no cargo on `PATH`) is an error of the
//! grading, said in one line with exit 3, never "does not compile" blamed on
//! the student's code.

use super::{export_linked, scratch};
use std::process::Command;

#[test]
#[ignore = "end-to-end: grades a copy with no cargo on PATH"]
fn a_grading_without_cargo_is_an_error_of_the_grading_not_of_the_code() {
    let dir = scratch("no-cargo");
    let copy = dir.join("copy");
    export_linked(&copy);
    // The student's PATH without cargo's folder; spintop found by its path.
    let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .arg("course")
        .arg("--course")
        .arg(&copy)
        .env("PATH", "/usr/bin:/bin")
        .env_remove("CARGO")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stdout}\n{stderr}");
    assert!(stderr.contains("the grading could not run"), "{stderr}");
    assert!(stderr.contains("cargo"), "{stderr}");
    for text in [&stdout, &stderr] {
        assert!(!text.contains("does not compile"), "{text}");
        assert!(!text.contains("next: fix"), "{text}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The source rule refuses a copy as a whole (its files are built together,
/// so one file's `std::fs` reaches every assignment): the words say so, and
/// an untouched stub is "copy refused", not "failing".
#[test]
#[ignore = "end-to-end: grades a copy"]
fn a_copy_refused_by_the_source_rule_says_the_rule_is_per_copy() {
    let dir = scratch("per-copy");
    let copy = dir.join("copy");
    export_linked(&copy);
    let file = std::fs::read_dir(copy.join("src"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "rs") && !p.ends_with("lib.rs"))
        .unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &file,
        format!("{text}\n#[allow(unused_imports)]\nuse std::fs;\n"),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .arg("course")
        .arg("--course")
        .arg(&copy)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let rows = stdout
        .lines()
        .filter(|l| l.ends_with("copy refused"))
        .count();
    assert_eq!(rows, spintop_course::COURSE.len(), "{stdout}");
    assert!(!stdout.lines().any(|l| l.ends_with("failing")), "{stdout}");
    assert!(stdout.contains("the rule is per copy"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}
