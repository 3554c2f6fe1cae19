//! `spintop stability` and the delay equation's warning, run as a user runs them.

use crate::support;

/// Row 6 of the stability suite as `spintop shell` meets it: a shell smaller
/// than its own electromagnetic mass grows, and the warning comes before any
/// output (the growth itself is tested in the core's numerics tests).
#[test]
fn eq_a_1_row_6_a_growing_shell_is_warned_before_any_output() {
    let out = support::spintop(&["shell", "--tau0", "0.06", "--delay", "0.1", "--times", "1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("spintop: warning:"), "{err}");
}

/// `spintop stability` prints every requested row and refuses a bad one.
#[test]
fn cli_stability_prints_rows_and_refuses_bad_input() {
    let v = support::json("stability", &["--row", "5"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0]["number"], 5);
    assert!(
        rows[0]["naive"]
            .as_array()
            .unwrap()
            .iter()
            .all(|o| o["ok"] == false)
    );
    let out = support::spintop(&["stability", "--row", "6"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with("Row 6:") && text.contains("[holds]"),
        "{text}"
    );
    for bad in [["--row", "7"], ["--row", "x"], ["--format", "yaml"]] {
        let mut args = vec!["stability"];
        args.extend_from_slice(&bad);
        let out = support::spintop(&args);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}
