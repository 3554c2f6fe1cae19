//! The book's runnable snippets name no crate but spintop (▶ builds them
//! beside spintop's own crates alone).

use super::{book_src, root};
use std::collections::BTreeSet;
use std::fs;

/// The crates `Cargo.toml` names as dependencies (the application's, not
/// the dev-dependencies; those of every target included), with `-` written
/// `_` as code names them, but the ones ▶'s scratch project depends on
/// (`spintop_server::SNIPPET_CRATES`).
fn dependency_crates() -> BTreeSet<String> {
    let manifest: toml::Table = fs::read_to_string(root().join("Cargo.toml"))
        .unwrap()
        .parse()
        .expect("Cargo.toml parses");
    let tables = |t: &toml::Table| -> Vec<toml::Table> {
        t.get("dependencies")
            .and_then(|d| d.as_table())
            .into_iter()
            .cloned()
            .collect()
    };
    let mut all = tables(&manifest);
    if let Some(targets) = manifest.get("target").and_then(|t| t.as_table()) {
        for target in targets.values().filter_map(|t| t.as_table()) {
            all.extend(tables(target));
        }
    }
    let snippet_crates: Vec<String> = spintop_server::SNIPPET_CRATES
        .iter()
        .map(|c| c.replace('-', "_"))
        .collect();
    all.iter()
        .flat_map(|d| d.keys())
        .map(|k| k.replace('-', "_"))
        .filter(|k| !snippet_crates.contains(k))
        .collect()
}

/// The crates a runnable Rust block of `chapter` names by path
/// (`name::…`) among `crates`; hidden lines (`# …`) included.
fn crates_named_by_snippets(chapter: &str, crates: &BTreeSet<String>) -> Vec<String> {
    let mut named = Vec::new();
    let mut in_block = false;
    for line in chapter.lines() {
        let fence = line.trim_start();
        if fence.starts_with("```") {
            in_block = !in_block && (fence == "```rust" || fence == "```rust,editable");
            continue;
        }
        if !in_block {
            continue;
        }
        let words = line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'));
        for word in words {
            if let Some((first, _)) = word.split_once("::")
                && crates.contains(first)
                && !named.contains(&first.to_string())
            {
                named.push(first.to_string());
            }
        }
    }
    named
}

/// ▶ in `spintop book` builds a snippet in a crate that depends on spintop's
/// own crates alone, while a doctest sees all of spintop's dependencies: a snippet that
/// names `nalgebra::…` passes `cargo test` and fails in the reader's
/// browser. Every runnable block names no crate but spintop and std (what
/// it needs of a dependency, spintop re-exports: `spintop::math::Complex`).
#[test]
fn book_runnable_snippets_name_no_dependency_but_spintop() {
    let crates = dependency_crates();
    assert!(
        crates.contains("nalgebra") && crates.contains("ratatui"),
        "{crates:?}"
    );
    let mut problems = Vec::new();
    for entry in fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let named = crates_named_by_snippets(&fs::read_to_string(&path).unwrap(), &crates);
            if !named.is_empty() {
                problems.push(format!("{}: {}", path.display(), named.join(", ")));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "snippets that ▶ cannot build:\n{}",
        problems.join("\n")
    );
    // The check itself sees a hidden line and leaves an ignored block alone.
    let sample = "```rust\n# use nalgebra::Vector3;\n```\n```rust,ignore\nratatui::init();\n```\n";
    assert_eq!(
        crates_named_by_snippets(sample, &crates),
        vec!["nalgebra".to_string()]
    );
}
