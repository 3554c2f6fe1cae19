//! Helpers shared by the tests that run the real `spintop` binary.
//! Each test binary includes it with `#[path = "../support/mod.rs"] mod support;`
//! (a folder without `main.rs`, so Cargo does not build it as a test target).

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
