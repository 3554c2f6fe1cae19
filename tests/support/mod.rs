//! Helpers shared by the tests that run the real `spintop` binary.
//! (`tests/support/mod.rs` rather than `tests/support.rs`, so that Cargo does
//! not build it as a test target of its own.)

#![allow(dead_code)]

use serde_json::Value;
use std::process::{Command, Output};

/// Run `spintop` with `args` and capture everything.
pub fn spintop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Run `spintop SUBCOMMAND ARGS --format json`, require success, parse the object.
pub fn json(subcommand: &str, args: &[&str]) -> Value {
    let mut all = vec![subcommand];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--format", "json"]);
    let out = spintop(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}
