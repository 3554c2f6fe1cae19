//! The modules inside one shell (the live view and `spintop learn`): the
//! edges between its files, read line by line, and the first circle among
//! them.

use super::reader::rust_files;
use super::root;
use std::path::Path;

/// The module path of a file under `src/` (`src/tui/learn/view.rs` →
/// `tui::learn::view`, `src/tui.rs` → `tui`).
fn module_name(root: &Path, file: &Path) -> String {
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
pub(super) fn module_edges(root: &Path, shell: &str) -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(&root.join("src").join(shell), &mut files);
    let top = root.join("src").join(format!("{shell}.rs"));
    if top.is_file() {
        files.push(top);
    }
    files.sort();
    let modules: Vec<String> = files.iter().map(|f| module_name(root, f)).collect();
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
pub(super) fn import_circle(edges: &[(String, String)]) -> Option<String> {
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

/// The live view, `spintop learn` and what they share have no import
/// circle among their modules: each command lives beside the state it
/// changes, and a view or an event map imports its state, never the other
/// way round (the reader's commands are in files its state never imports).
#[test]
fn no_import_circle_inside_the_full_screen_shells() {
    for (shell, edge) in [
        ("tui", ("tui::event", "tui::view")),
        ("learn", ("learn::event", "learn")),
        ("live", ("live::app", "live::settings")),
        ("term", ("term::session", "term::signals")),
    ] {
        let edges = module_edges(&root(), shell);
        assert!(
            edges.iter().any(|(a, b)| (a.as_str(), b.as_str()) == edge),
            "the edges of {shell} are read ({} imports {}): {edges:?}",
            edge.0,
            edge.1
        );
        assert_eq!(import_circle(&edges), None, "{shell}: edges: {edges:?}");
    }
}
