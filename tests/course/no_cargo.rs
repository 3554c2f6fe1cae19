//! A grading that the machine does not allow (no cargo on `PATH`, a
//! rustup with no toolchain chosen, crates missing from cargo's cache
//! offline) is an error of the grading, said in one line with what to do
//! and exit 4 (could not grade), never "does not compile" blamed on the
//! student's code.

use super::{export_linked, scratch};
use std::path::Path;
use std::process::Command;

/// `spintop course --course COPY` with `env` set (and `CARGO` unset, as in
/// a student's shell): (exit code, stdout, stderr).
fn grade_with(copy: &Path, env: &[(&str, &std::ffi::OsStr)]) -> (Option<i32>, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_spintop"));
    cmd.arg("course")
        .arg("--course")
        .arg(copy)
        .env_remove("CARGO");
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// What every one of them says: a failure of the grading, exit 4, nothing
/// blamed on the code, and `words` (cargo's own, the advice).
fn says_it_could_not_grade(got: &(Option<i32>, String, String), words: &[&str]) {
    let (code, stdout, stderr) = got;
    assert_eq!(*code, Some(4), "{stdout}\n{stderr}");
    assert!(stderr.contains("the grading could not run"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    for w in words {
        assert!(stderr.contains(w), "{w:?} in {stderr}");
    }
    for text in [stdout, stderr] {
        assert!(!text.contains("does not compile"), "{text}");
        assert!(!text.contains("next: fix"), "{text}");
        assert!(!text.contains("Cargo.toml:1"), "{text}");
    }
}

/// The code is documented where a user looks, beside 2 and 3, which it
/// is not.
#[test]
fn could_not_grade_has_its_own_documented_exit_code() {
    assert_eq!(spintop_app::cli::EXIT_CANNOT_GRADE, 4);
    assert_ne!(
        spintop_app::cli::EXIT_CANNOT_GRADE,
        spintop_app::cli::EXIT_BAD_INPUT
    );
    assert_ne!(
        spintop_app::cli::EXIT_CANNOT_GRADE,
        spintop_app::cli::EXIT_NUMERICAL
    );
    for args in [&["course", "--help"][..], &["--help"][..]] {
        let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
            .args(args)
            .output()
            .unwrap();
        let help = String::from_utf8_lossy(&out.stdout)
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        assert!(
            help.contains("4 could not grade")
                || help.contains("4 `spintop course` could not grade"),
            "{args:?}: {help}"
        );
        assert!(help.contains("2 bad input"), "{args:?}: {help}");
    }
}

#[test]
#[ignore = "end-to-end: grades a copy with no cargo, a toolchain that refuses, and no crates offline"]
fn a_grading_the_machine_refuses_is_an_error_of_the_grading_not_of_the_code() {
    let dir = scratch("no-cargo");
    let copy = dir.join("copy");
    export_linked(&copy);
    // The student's PATH without cargo's folder; spintop found by its path.
    let got = grade_with(&copy, &[("PATH", "/usr/bin:/bin".as_ref())]);
    says_it_could_not_grade(&got, &["cargo was not found", "/usr/bin:/bin", "rustup.rs"]);
    // A cargo that is rustup's proxy with no default toolchain.
    let fake = dir.join("rustup-bin");
    std::fs::create_dir_all(&fake).unwrap();
    let cargo = fake.join("cargo");
    std::fs::write(
        &cargo,
        "#!/bin/sh\necho \"error: rustup could not choose a version of cargo to run, because one wasn't specified explicitly, and no default is configured.\" >&2\necho \"help: run 'rustup default stable' to download the latest stable release of Rust and set it as your default toolchain.\" >&2\nexit 1\n",
    )
    .unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let path =
        std::env::join_paths([fake.as_path(), Path::new("/usr/bin"), Path::new("/bin")]).unwrap();
    let got = grade_with(&copy, &[("PATH", path.as_os_str())]);
    says_it_could_not_grade(
        &got,
        &[
            "rustup could not choose a version of cargo",
            "rustup default stable",
        ],
    );
    // The real cargo, offline (as grading always is) with an empty cache.
    let empty = dir.join("empty-cargo-home");
    std::fs::create_dir_all(&empty).unwrap();
    let got = grade_with(&copy, &[("CARGO_HOME", empty.as_os_str())]);
    says_it_could_not_grade(&got, &["cargo fetch", "error: "]);
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
