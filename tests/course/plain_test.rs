//! A student's plain `cargo test` in an exported copy reports every
//! assignment: a failing chapter hides none of the others (cargo stops at
//! the first test program that fails, and a copy used to have one per
//! chapter, so the appendix's failures hid Section 2's results), one
//! chapter still runs alone, and `spintop course` grades the copy the same.

use super::{export_linked, scratch, solution, spintop, target, write_function};
use spintop_course::COURSE;
use std::process::Command;

#[test]
#[ignore = "end-to-end: builds and runs a copy's tests"]
fn a_plain_cargo_test_in_a_copy_reports_every_assignment() {
    let dir = scratch("plain-test").join("copy");
    export_linked(&dir);
    write_function(&dir, "ch2", "larmor_rate", &solution("ch2", "larmor_rate"));
    let cargo = |args: &[&str]| {
        Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
            .current_dir(&dir)
            .args(args)
            .env("CARGO_TARGET_DIR", target())
            .env_remove("SPINTOP_SEED")
            .output()
            .unwrap()
    };
    let out = cargo(&["test", "--offline"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success(), "21 stubs fail");
    for a in COURSE.iter() {
        let line = |verdict: &str| format!("test {}::{} ... {verdict}", a.binary, a.test);
        let (ok, failed) = (
            stdout.contains(&line("ok")),
            stdout.contains(&line("FAILED")),
        );
        assert!(ok != failed, "{} is reported once:\n{stdout}", a.test);
        assert_eq!(ok, a.function == "larmor_rate", "{}:\n{stdout}", a.test);
    }
    assert!(
        stdout.contains(&format!("1 passed; {} failed", COURSE.len() - 1)),
        "{stdout}"
    );
    // One chapter alone, as the README and the reports name it.
    let one = cargo(&["test", "--offline", "--test", "ch2", "eq_2_1_larmor_rate"]);
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    // And `spintop course` grades the copy as cargo does.
    let graded = spintop(&["course", "--course", dir.to_str().unwrap()]);
    let said = String::from_utf8_lossy(&graded.stdout);
    assert_eq!(graded.status.code(), Some(0), "{said}");
    assert!(
        said.starts_with(&format!("spintop course: 1 of {} passing", COURSE.len())),
        "{said}"
    );
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}
