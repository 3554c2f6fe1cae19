//! The direction of imports inside a crate, read from the sources: what
//! the compiler cannot see. Between crates the manifests hold the layers
//! (`crates/spintop` → `spintop-runner` → `spintop-grading` → `spintop-course`,
//! `spintop-server` → the application), and cargo refuses a circle; inside
//! one crate any module may name any other, so this test holds the order:
//!
//! ```text
//! the core (crates/spintop):
//!   math, numbers → physics → integrate → sim
//!     → {assignment, figure, output, plot, scene, stability, workprecision}
//! the application (src/):
//!   term → live → cli, tui, learn side by side (the command line launches
//!   the live view and the reader; they never import each other)
//! ```
//!
//! A module may use what lies in a lower layer, a service the neighbours
//! listed in its rules, and a shell no other shell (the command line
//! launches the live view from the files in its rules' launchers). Every
//! path into the crate counts: `use` trees over
//! several lines and nested braces, `super::` chains (resolved against the
//! file's module and any inline `mod` it sits in), `self::`, and fully
//! qualified `crate::…` paths in code (spaces round `::` too), a path in an
//! attribute's string (`#[serde(with = "crate::…")]`), and the use of a
//! `#[macro_export]` macro (an import of the module that defines it).
//! Comments, doc links and other string literals do not. The forms it
//! cannot follow are refused outright: an alias of the crate, a glob of its
//! root, a re-export in the crate root, `#[path]` and `include!`. Among the top-level modules, and among the files of one module (say
//! `integrate/dopri5.rs` and `integrate/explicit.rs`), no two may import each
//! other, directly or round a longer circle.
//!
//! A new import that breaks a rule fails here with the file, the line and the
//! rule; `the_checker_fails_on_each_kind_of_wrong_import` and
//! `the_checker_sees_imports_in_every_disguise` show each kind caught (on a
//! scratch tree under the rules the crate had as one package, which hold
//! every kind of module at once).

mod inner;
mod manifests;
mod reader;
mod rules;
mod self_tests;

use reader::{module_of, rust_files};
use rules::{CRATES, violations};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn imports_follow_the_layers_and_run_in_no_circle() {
    let bad: Vec<String> = CRATES
        .iter()
        .flat_map(|(dir, rules)| {
            violations(&root().join(dir), rules)
                .into_iter()
                .map(move |v| format!("{dir}/{v}"))
        })
        .collect();
    assert!(
        bad.is_empty(),
        "imports that break the order:\n{}",
        bad.join("\n")
    );
}

#[test]
fn every_top_level_module_is_placed_in_a_layer_on_purpose() {
    for (dir, rules) in CRATES {
        let root = root().join(dir);
        let mut files = Vec::new();
        rust_files(&root.join("src"), &mut files);
        let mut modules: Vec<String> = files
            .iter()
            .map(|f| module_of(&root, f))
            .filter(|m| m.first().is_some_and(|f| f != "bin"))
            .filter_map(|m| m.first().cloned())
            .collect();
        modules.sort();
        modules.dedup();
        let mut placed: Vec<String> = rules.layers.iter().map(|(m, _)| m.to_string()).collect();
        placed.sort();
        assert_eq!(
            modules, placed,
            "{dir}: a top-level module was added or removed: place it in the crate's rules (and its neighbours if a module of its layer uses it)"
        );
    }
}

/// Issue 30: the scene engine is split by concept, each file under about 600
/// lines (`scene.rs` was 1.8k lines holding every concept; auto's model
/// choice grew `plan.rs` to 888 before it moved to `choose.rs`).
#[test]
fn scene_files_are_split_by_concept_under_600_lines() {
    let mut files = vec![root().join("crates/spintop/src/scene.rs")];
    rust_files(&root().join("crates/spintop/src/scene"), &mut files);
    assert!(files.len() > 5, "the scene engine's files: {files:?}");
    let long: Vec<String> = files
        .iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(f)
                .expect("a scene file")
                .lines()
                .count();
            (n > 600).then(|| format!("{} has {n} lines", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "split these by concept: {long:?}");
}
