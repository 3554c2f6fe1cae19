//! The layers between crates, read from the manifests.

use super::root;

/// The workspace's crates, bottom up, with the layer of each: a crate may
/// depend on crates of lower layers only.
const WORKSPACE: [(&str, &str, u8); 9] = [
    ("crates/spintop", "spintop", 0),
    // The core's integration tests and the book's examples (unoptimised).
    ("crates/spintop-tests", "spintop-tests", 1),
    // The wire a student's runner and the graders share (no answer in it).
    ("crates/spintop-runner", "spintop-runner", 1),
    ("crates/spintop-grading", "spintop-grading", 2),
    ("crates/spintop-course", "spintop-course", 3),
    ("crates/spintop-server", "spintop-server", 3),
    (".", "spintop-app", 4),
    // What a student builds and what measures speed: the core (and the graders).
    ("lessons", "spintop-lessons", 3),
    ("benches", "spintop-benches", 3),
];

/// The crates only a shell may depend on: a terminal, a command line, a
/// progress bar, signals.
const SHELL_CRATES: [&str; 6] = [
    "clap",
    "crossterm",
    "ratatui",
    "indicatif",
    "signal-hook",
    "pulldown-cmark",
];

/// The dependencies of a manifest, by section (`dependencies`,
/// `dev-dependencies`, and the same under every `target.*`).
fn manifest_dependencies(dir: &str) -> Vec<(String, String, toml::Value)> {
    let path = root().join(dir).join("Cargo.toml");
    let manifest: toml::Table = std::fs::read_to_string(&path)
        .unwrap()
        .parse()
        .expect("a manifest");
    let mut tables = vec![manifest.clone()];
    if let Some(targets) = manifest.get("target").and_then(|t| t.as_table()) {
        tables.extend(targets.values().filter_map(|t| t.as_table()).cloned());
    }
    let mut out = Vec::new();
    for t in tables {
        for section in ["dependencies", "dev-dependencies", "build-dependencies"] {
            for (name, spec) in t
                .get(section)
                .and_then(|d| d.as_table())
                .into_iter()
                .flatten()
            {
                out.push((section.to_string(), name.clone(), spec.clone()));
            }
        }
    }
    out
}

/// The manifests show the layers: every path dependency of a workspace crate
/// lies in a lower layer; the lessons and the benchmarks use the core (and
/// the lessons' tests the graders) only; no crate but the application
/// depends on a shell's crate, so `cargo doc -p spintop` shows no shell.
#[test]
fn the_manifests_show_the_layers() {
    let members: Vec<String> = {
        let manifest: toml::Table = std::fs::read_to_string(root().join("Cargo.toml"))
            .unwrap()
            .parse()
            .unwrap();
        manifest["workspace"]["members"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m.as_str().unwrap().to_string())
            .collect()
    };
    let mut listed: Vec<&str> = WORKSPACE.iter().map(|(d, _, _)| *d).collect();
    listed.sort();
    let mut members_sorted: Vec<&str> = members.iter().map(String::as_str).collect();
    members_sorted.sort();
    assert_eq!(
        listed, members_sorted,
        "a crate was added: give it a layer here"
    );
    let layer_of = |name: &str| WORKSPACE.iter().find(|(_, n, _)| *n == name).map(|w| w.2);
    let mut bad = Vec::new();
    for (dir, name, layer) in WORKSPACE {
        for (section, dep, spec) in manifest_dependencies(dir) {
            if spec.get("path").is_some() {
                match layer_of(&dep) {
                    Some(l) if l < layer => {}
                    _ => bad.push(format!("{name} ({section}) depends on {dep}, not below it")),
                }
            }
            if name != "spintop-app" && SHELL_CRATES.contains(&dep.as_str()) {
                bad.push(format!(
                    "{name} ({section}) depends on {dep}, a shell's crate"
                ));
            }
        }
    }
    for (dir, allowed) in [
        ("lessons", &["spintop", "spintop-grading"][..]),
        ("benches", &["spintop"][..]),
    ] {
        for (section, dep, spec) in manifest_dependencies(dir) {
            if spec.get("path").is_some() && !allowed.contains(&dep.as_str()) {
                bad.push(format!("{dir} ({section}) depends on {dep}"));
            }
        }
    }
    // Only the lessons' tests see the graders: the student's src/ sees the core.
    assert!(
        manifest_dependencies("lessons")
            .iter()
            .any(|(s, d, _)| s == "dev-dependencies" && d == "spintop-grading")
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
