//! The README is a front door: short, and every command it shows still runs.
//! The commands that compute are run here and must succeed with output; the
//! live ones (the view, `learn`) must get as far as asking for a terminal and
//! be run in one by `tests/tui/tmux.rs`; the book server and the course,
//! which build and run cargo, by `.ci/run`. The capture of the live view is
//! the live view's own snapshot (`tests/tui/snapshots/`), so a change of the
//! screen that is accepted there must be copied here.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).expect("README.md")
}

/// Every command the README shows: the lines of its `sh` blocks (comments
/// dropped) and the `spintop …` examples of its tables, as arguments of
/// `spintop` (`cargo run --release -- ARGS` and `spintop ARGS` alike; `None`
/// for `cargo test` and its end-to-end tier `cargo test -- --ignored`, the
/// suite itself, which `.ci/run` runs).
fn commands(text: &str) -> Vec<(String, Option<Vec<String>>)> {
    let mut found = Vec::new();
    let mut in_sh = false;
    for line in text.lines() {
        if line.starts_with("```") {
            in_sh = line.trim() == "```sh";
            continue;
        }
        let mut shown: Vec<String> = Vec::new();
        if in_sh {
            let command = line.split(" #").next().unwrap_or(line).trim();
            if !command.is_empty() {
                shown.push(command.to_string());
            }
        } else if line.starts_with('|') {
            for cell in line.split('|') {
                let cell = cell.trim();
                if let Some(inner) = cell
                    .strip_prefix("`spintop ")
                    .and_then(|c| c.strip_suffix('`'))
                {
                    shown.push(format!("spintop {inner}"));
                }
            }
        }
        for command in shown {
            let args = if command == "cargo test" || command == "cargo test -- --ignored" {
                None
            } else if let Some(rest) = command.strip_prefix("cargo run --release --") {
                Some(rest.split_whitespace().map(String::from).collect())
            } else if command == "cargo run --release" {
                Some(Vec::new())
            } else if let Some(rest) = command.strip_prefix("spintop") {
                Some(rest.split_whitespace().map(String::from).collect())
            } else {
                panic!(
                    "the README shows `{command}`, which no test runs: show a spintop command, or run it in a test"
                );
            };
            found.push((command, args));
        }
    }
    found
}

/// Commands that need a real terminal (they stop at the terminal check when
/// piped), and the launch of them in `tests/tui/tmux.rs`.
fn live(args: &[String]) -> Option<&'static str> {
    match args.first().map(String::as_str) {
        None => Some("launch(\"plain\", \"\")"),
        Some("tui") => Some("\"tui "),
        Some("learn") if !args.iter().any(|a| a == "--list") => Some("\"learn "),
        _ => None,
    }
}

/// Commands that build and run cargo or serve for ever, and the step of
/// `.ci/run` that runs them.
fn run_by_ci(args: &[String]) -> Option<&'static str> {
    match args {
        [one] if one == "book" => Some("-- book --self-test"),
        [one] if one == "course" => Some("--quiet -- course)"),
        _ => None,
    }
}

fn spintop(args: &[String], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("spintop runs")
}

#[test]
fn readme_is_a_front_door_under_250_lines() {
    let text = readme();
    let n = text.lines().count();
    assert!(
        n <= 250,
        "README.md has {n} lines; measurements go to benches/README.md, reference to --help and the book"
    );
    for section in [
        "## Two commands",
        "## Three ways in",
        "## The commands",
        "## Where the rest lives",
    ] {
        assert!(text.contains(section), "README.md lacks {section}");
    }
    // The measurements live in benches/README.md, current figures first.
    let benches =
        std::fs::read_to_string(root().join("benches/README.md")).expect("benches/README.md");
    let current = benches.find("## Current figures").expect("current figures");
    let history = benches.find("## History").expect("their history");
    assert!(current < history);
}

#[test]
fn readme_capture_is_the_live_views_own_snapshot() {
    let text = readme();
    let marker = "<!-- capture: ";
    let at = text.find(marker).expect("a capture of the live view");
    let snapshot = text[at + marker.len()..].split(" -->").next().unwrap();
    let shown: Vec<&str> = text[at..]
        .split("```text\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .expect("the capture's text block")
        .lines()
        .collect();
    let snap = std::fs::read_to_string(root().join(snapshot)).expect("the snapshot file");
    let body = snap
        .splitn(3, "---\n")
        .nth(2)
        .expect("an insta snapshot body");
    let screen: Vec<String> = body
        .lines()
        .filter(|l| !l.is_empty())
        .map(|l| serde_json::from_str::<String>(l).expect("a quoted screen line"))
        .collect();
    assert_eq!(
        shown, screen,
        "the README's capture differs from {snapshot}: copy the snapshot's lines into README.md"
    );
}

#[test]
fn every_command_the_readme_shows_is_run() {
    let text = readme();
    let shown = commands(&text);
    assert!(shown.len() >= 15, "{shown:?}");
    let tmux = std::fs::read_to_string(root().join("tests/tui/tmux.rs")).unwrap();
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    for (command, args) in shown {
        let Some(args) = args else { continue };
        if let Some(launch) = live(&args) {
            let out = spintop(&args, &root());
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{command}: {stderr}");
            assert!(stderr.contains("needs a terminal"), "{command}: {stderr}");
            assert!(
                tmux.contains(launch),
                "{command}: tests/tui/tmux.rs does not run it ({launch})"
            );
        } else if let Some(step) = run_by_ci(&args) {
            assert!(
                ci.contains(step),
                "{command}: .ci/run does not run it ({step:?})"
            );
        } else {
            let out = spintop(&args, &root());
            assert!(
                out.status.success(),
                "{command}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(!out.stdout.is_empty(), "{command} printed nothing");
        }
    }
}

#[test]
fn the_readme_check_refuses_a_command_it_cannot_run() {
    let result = std::panic::catch_unwind(|| commands("```sh\nmdbook serve book\n```\n"));
    assert!(result.is_err());
    let shown = commands(
        "```sh\ncargo run --release -- figure 2   # Figure 2\ncargo test\n```\n| a | `spintop scenes` |\n",
    );
    assert_eq!(shown.len(), 3);
    assert_eq!(
        shown[0].1,
        Some(vec!["figure".to_string(), "2".to_string()])
    );
    assert_eq!(shown[1].1, None);
    assert_eq!(shown[2].1, Some(vec!["scenes".to_string()]));
}

/// The README sends a reader to `spintop CMD --help` for "every option of a
/// command with examples": every command's help has one.
#[test]
fn every_commands_help_gives_an_example() {
    let without: Vec<String> = crate::support::commands()
        .into_iter()
        .filter(|c| {
            let out = crate::support::spintop(&[c.as_str(), "--help"]);
            !String::from_utf8_lossy(&out.stdout).contains("Example")
        })
        .collect();
    assert!(
        without.is_empty(),
        "`spintop CMD --help` gives no example for: {}",
        without.join(", ")
    );
}
