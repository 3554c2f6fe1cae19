//! The direction of imports, read from the sources: the pure core never
//! reaches up into a shell, what the shells share lives below them, and the
//! shells stand side by side. The command line may launch another shell, but
//! only from the one file that does so; the live view never imports the
//! command line.
//!
//! The rule is read from every `crate::NAME` path in every file under `src/`
//! (in `use` lines and inline paths alike), so a new import that runs the
//! wrong way fails here with the file, the line and the rule it breaks.

use std::path::{Path, PathBuf};

/// The shells: front ends that drive the core. Each stands beside the others.
const SHELLS: &[&str] = &["cli", "tui", "server"];

/// What the shells share, below all of them and above the core.
const SHARED: &[&str] = &["course", "output", "scene"];

/// The only places one shell may reach another: (file, the shell it launches).
const LAUNCHERS: &[(&str, &str)] = &[
    ("src/cli/tui.rs", "tui"),
    ("src/cli/learn.rs", "tui"),
    ("src/cli/book.rs", "server"),
];

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Layer {
    Core,
    Shared,
    Shell,
}

fn layer(module: &str) -> Layer {
    if SHELLS.contains(&module) {
        Layer::Shell
    } else if SHARED.contains(&module) {
        Layer::Shared
    } else {
        Layer::Core
    }
}

/// The top-level module a file under `src/` belongs to (`src/cli/plot.rs` → `cli`).
fn owner(root: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(root.join("src")).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    match name {
        "lib" | "main" => None,
        other => Some(other.to_string()),
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every `crate::NAME` on a line that is not a comment.
fn crate_paths(line: &str) -> Vec<String> {
    let code = line.trim_start();
    if code.starts_with("//") {
        return Vec::new();
    }
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = rest[..at].chars().last();
        rest = &rest[at + "crate::".len()..];
        // `spintop_crate::` or `my_crate::` are other names.
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if !name.is_empty() {
            found.push(name);
        }
    }
    // `use crate::{cli, tui}` names several at once.
    if let Some(at) = code.find("crate::{") {
        let inner = &code[at + "crate::{".len()..];
        let inner = inner.split('}').next().unwrap_or("");
        for part in inner.split(',') {
            let name: String = part
                .trim()
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                found.push(name);
            }
        }
    }
    found
}

/// Every import that runs the wrong way, as "file:line: rule".
fn violations(root: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    files.sort();
    let mut bad = Vec::new();
    for file in &files {
        let Some(from) = owner(root, file) else {
            continue;
        };
        let rel = file
            .strip_prefix(root)
            .expect("under the root")
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(file).expect("a readable source file");
        for (n, line) in text.lines().enumerate() {
            for to in crate_paths(line) {
                if to == from {
                    continue;
                }
                let (lf, lt) = (layer(&from), layer(&to));
                let rule = if lt > lf {
                    Some(format!(
                        "{from} ({lf:?}) imports {to} ({lt:?}): the core and what the shells share never reach up"
                    ))
                } else if lf == Layer::Shell && lt == Layer::Shell {
                    let launcher = LAUNCHERS.iter().any(|(f, s)| *f == rel && *s == to);
                    (!launcher).then(|| {
                        format!(
                            "the {from} shell imports the {to} shell: shells stand side by side; move what both need into a shared module"
                        )
                    })
                } else {
                    None
                };
                if let Some(rule) = rule {
                    bad.push(format!("{rel}:{}: {rule}", n + 1));
                }
            }
        }
    }
    bad
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn imports_run_from_the_shells_down_to_the_core() {
    let bad = violations(&root());
    assert!(
        bad.is_empty(),
        "imports that run the wrong way:\n{}",
        bad.join("\n")
    );
}

#[test]
fn every_top_level_module_is_placed_in_a_layer_on_purpose() {
    // A new module under src/ is core unless listed above; this test names
    // the modules it treats as core, so that a new shell added without being
    // listed in SHELLS is noticed here.
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    let mut core: Vec<String> = files
        .iter()
        .filter_map(|f| owner(&root(), f))
        .filter(|m| layer(m) == Layer::Core)
        .collect();
    core.sort();
    core.dedup();
    let expected = [
        "assignment",
        "figure",
        "grading",
        "integrate",
        "math",
        "numbers",
        "physics",
        "plot",
        "sim",
        "stability",
        "workprecision",
    ];
    assert_eq!(
        core, expected,
        "the core modules changed: list a new shell in SHELLS, a new shared module in SHARED, or a new core module here"
    );
}

#[test]
fn the_rule_catches_a_wrong_import() {
    // The checker itself can fail: a scratch tree with a live view that
    // imports the command line, and a core module that imports the live view.
    let dir = std::env::temp_dir().join(format!("spintop-arch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src/tui")).unwrap();
    std::fs::create_dir_all(dir.join("src/physics")).unwrap();
    std::fs::write(
        dir.join("src/tui/app.rs"),
        "use crate::cli::parse_number;\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("src/physics/top.rs"),
        "// crate::tui in a comment is fine\nfn f() { crate::tui::app::x(); }\n",
    )
    .unwrap();
    std::fs::write(dir.join("src/cli.rs"), "use crate::{tui, physics};\n").unwrap();
    let bad = violations(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(bad.len(), 3, "{bad:#?}");
    assert!(bad[0].starts_with("src/cli.rs:1: the cli shell imports the tui shell"));
    assert!(bad[1].starts_with("src/physics/top.rs:2: physics (Core) imports tui (Shell)"));
    assert!(bad[2].starts_with("src/tui/app.rs:1: the tui shell imports the cli shell"));
}
