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
const SHARED: &[&str] = &["present", "course", "output", "scene"];

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

/// The module path of a file under `src/` (`src/tui/learn/view.rs` →
/// `tui::learn::view`, `src/tui.rs` → `tui`).
fn module_of(root: &Path, file: &Path) -> String {
    let rel = file
        .strip_prefix(root.join("src"))
        .expect("under src/")
        .with_extension("");
    rel.components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("::")
}

/// The paths a line names that may lead to another module: `crate::…`,
/// `super::…` (also inside `use super::{a::b, c}` groups), and names that
/// start with one of `children` (`view::draw` in `learn.rs`), as segment lists.
fn module_paths(line: &str, children: &[String]) -> Vec<Vec<String>> {
    let code = line.trim_start();
    if code.starts_with("//") {
        return Vec::new();
    }
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut i = 0;
    while i < chars.len() {
        let starts_word = i == 0 || !(ident(chars[i - 1]) || chars[i - 1] == ':');
        if starts_word && ident(chars[i]) {
            // Read a path: segments joined by `::`, then a `{…}` group.
            let mut segments = Vec::new();
            let mut j = i;
            loop {
                let start = j;
                while j < chars.len() && ident(chars[j]) {
                    j += 1;
                }
                segments.push(chars[start..j].iter().collect::<String>());
                if chars.get(j) == Some(&':') && chars.get(j + 1) == Some(&':') {
                    j += 2;
                    if chars.get(j) == Some(&'{') {
                        // A group: each top-level item continues the path.
                        let mut depth = 0;
                        let mut item = String::new();
                        let mut items = Vec::new();
                        for &c in &chars[j + 1..] {
                            match c {
                                '{' => depth += 1,
                                '}' if depth == 0 => break,
                                '}' => depth -= 1,
                                ',' if depth == 0 => {
                                    items.push(std::mem::take(&mut item));
                                    continue;
                                }
                                _ => {}
                            }
                            item.push(c);
                        }
                        items.push(item);
                        for item in items {
                            let mut path = segments.clone();
                            path.extend(
                                item.trim()
                                    .split("::")
                                    .map(|s| {
                                        s.chars().take_while(|c| ident(*c)).collect::<String>()
                                    })
                                    .filter(|s| !s.is_empty()),
                            );
                            out.push(path);
                        }
                        segments.clear();
                        break;
                    }
                    continue;
                }
                break;
            }
            let first = segments.first().cloned().unwrap_or_default();
            if segments.len() > 1
                && (first == "crate"
                    || first == "super"
                    || first == "self"
                    || children.contains(&first))
            {
                out.push(segments);
            }
            i = j.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// Every `uses` edge between the modules of `shell` (a folder under `src/`),
/// as (from, to) module paths.
fn module_edges(root: &Path, shell: &str) -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(&root.join("src").join(shell), &mut files);
    let top = root.join("src").join(format!("{shell}.rs"));
    if top.is_file() {
        files.push(top);
    }
    files.sort();
    let modules: Vec<String> = files.iter().map(|f| module_of(root, f)).collect();
    let mut edges = Vec::new();
    for (file, module) in files.iter().zip(&modules) {
        let prefix = format!("{module}::");
        let children: Vec<String> = modules
            .iter()
            .filter_map(|m| m.strip_prefix(&prefix))
            .filter(|rest| !rest.contains("::"))
            .map(str::to_string)
            .collect();
        let parent: Vec<&str> = module.split("::").collect();
        let text = std::fs::read_to_string(file).expect("a readable source file");
        // Inline modules (`mod tests { use super::*; }`): their `super` is
        // this file's module. The brace depth at which each one opened.
        let mut depth = 0usize;
        let mut inline: Vec<usize> = Vec::new();
        for line in text.lines() {
            let code = line.trim_start();
            let opens_inline = !code.starts_with("//")
                && code.trim_start_matches("pub ").starts_with("mod ")
                && code.trim_end().ends_with('{');
            if opens_inline {
                inline.push(depth);
            }
            if !code.starts_with("//") {
                depth += code.matches('{').count();
                depth = depth.saturating_sub(code.matches('}').count());
            }
            while inline.last().is_some_and(|d| depth <= *d) && !opens_inline {
                inline.pop();
            }
            let nested = inline.len();
            for mut path in module_paths(line, &children) {
                // `super` inside an inline module first leaves the inline ones.
                let mut skip = 0;
                while skip < nested && path.first().is_some_and(|s| s == "super") {
                    path.remove(0);
                    skip += 1;
                }
                if skip > 0 {
                    path.insert(0, "self".to_string());
                }
                if path.len() < 2 {
                    continue;
                }
                // Resolve the path's start to a module, then take the longest
                // existing module it names.
                let mut base: Vec<String> = Vec::new();
                let mut rest = path.as_slice();
                match rest[0].as_str() {
                    "crate" => rest = &rest[1..],
                    "self" => {
                        base = parent.iter().map(|s| s.to_string()).collect();
                        rest = &rest[1..];
                    }
                    "super" => {
                        base = parent.iter().map(|s| s.to_string()).collect();
                        while rest.first().is_some_and(|s| s == "super") {
                            base.pop();
                            rest = &rest[1..];
                        }
                    }
                    _ => base = parent.iter().map(|s| s.to_string()).collect(),
                }
                let mut full = base;
                full.extend(rest.iter().cloned());
                let target = (1..=full.len())
                    .rev()
                    .map(|n| full[..n].join("::"))
                    .find(|m| modules.contains(m));
                if let Some(target) = target
                    && target != *module
                    && !edges.contains(&(module.clone(), target.clone()))
                {
                    edges.push((module.clone(), target));
                }
            }
        }
    }
    edges
}

/// A circle written from its smallest module: `b → a → b` reads `a → b → a`.
fn from_smallest(circle: &str) -> String {
    let mut nodes: Vec<&str> = circle.split(" → ").collect();
    nodes.pop();
    let at = (0..nodes.len()).min_by_key(|&i| nodes[i]).unwrap_or(0);
    nodes.rotate_left(at);
    nodes.push(nodes[0]);
    nodes.join(" → ")
}

/// The first circle of imports among `edges`, as `a → b → … → a`.
fn import_circle(edges: &[(String, String)]) -> Option<String> {
    fn visit(
        node: &str,
        edges: &[(String, String)],
        path: &mut Vec<String>,
        done: &mut Vec<String>,
    ) -> Option<String> {
        if let Some(at) = path.iter().position(|n| n == node) {
            let mut circle = path[at..].to_vec();
            circle.push(node.to_string());
            return Some(circle.join(" → "));
        }
        if done.iter().any(|d| d == node) {
            return None;
        }
        path.push(node.to_string());
        for (_, to) in edges.iter().filter(|(from, _)| from == node) {
            if let Some(c) = visit(to, edges, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.push(node.to_string());
        None
    }
    let mut done = Vec::new();
    edges
        .iter()
        .find_map(|(from, _)| visit(from, edges, &mut Vec::new(), &mut done))
        .map(|c| from_smallest(&c))
}

/// The live view and `spintop learn` have no import circle among their
/// modules: each command lives beside the state it changes (app.rs, not
/// event.rs), and a view or an event map imports its state, never the other
/// way round.
#[test]
fn no_import_circle_inside_the_live_view() {
    let edges = module_edges(&root(), "tui");
    assert!(
        edges
            .iter()
            .any(|(a, b)| a == "tui::event" && b == "tui::app"),
        "the edges are read (event imports app): {edges:?}"
    );
    assert_eq!(import_circle(&edges), None, "edges: {edges:?}");
}

#[test]
fn the_circle_check_catches_a_circle() {
    // A scratch tree with the old circle: app.rs imports event.rs for its
    // command, event.rs imports app.rs for its state; and a parent and a
    // child module that import each other.
    let dir = std::env::temp_dir().join(format!("spintop-circle-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src/tui/learn")).unwrap();
    std::fs::write(
        dir.join("src/tui.rs"),
        "pub mod app;\npub mod event;\npub mod learn;\n",
    )
    .unwrap();
    std::fs::write(dir.join("src/tui/app.rs"), "use super::event::Command;\n").unwrap();
    std::fs::write(
        dir.join("src/tui/event.rs"),
        "use super::{app::{App, Mode}, theme};\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("src/tui/learn.rs"),
        "pub mod view;\nfn f() { view::draw(); }\n",
    )
    .unwrap();
    std::fs::write(dir.join("src/tui/learn/view.rs"), "use super::Learn;\n").unwrap();
    let edges = module_edges(&dir, "tui");
    let circle = import_circle(&edges);
    std::fs::write(dir.join("src/tui/app.rs"), "pub enum Command {}\n").unwrap();
    let edges_after = module_edges(&dir, "tui");
    let learn_circle = import_circle(&edges_after);
    std::fs::write(dir.join("src/tui/learn.rs"), "pub mod view;\n").unwrap();
    let none = import_circle(&module_edges(&dir, "tui"));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        circle.as_deref(),
        Some("tui::app → tui::event → tui::app"),
        "{edges:?}"
    );
    assert_eq!(
        learn_circle.as_deref(),
        Some("tui::learn → tui::learn::view → tui::learn"),
        "{edges_after:?}"
    );
    assert_eq!(none, None);
}
