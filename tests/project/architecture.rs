//! The direction of imports inside a crate, read from the sources: what
//! the compiler cannot see. Between crates the manifests hold the layers
//! (`crates/spintop` → `spintop-grading` → `spintop-course`,
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

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers of one crate's modules, bottom (0) to top: each top-level
/// module's layer, what a module may use in its own layer, and where one
/// shell may launch another.
struct Rules {
    /// Every top-level module and its layer.
    layers: &'static [(&'static str, u8)],
    /// The layer of the shells.
    shell: u8,
    /// What a module may use beside the layers below it (and nothing uses
    /// a module of its own layer not listed here).
    neighbours: &'static [(&'static str, &'static [&'static str])],
    /// The only places one shell may reach another: (file, the shell it launches).
    launchers: &'static [(&'static str, &'static str)],
}

impl Rules {
    fn layer(&self, module: &str) -> Option<u8> {
        self.layers
            .iter()
            .find(|(m, _)| *m == module)
            .map(|(_, l)| *l)
    }

    fn neighbours(&self, module: &str) -> &'static [&'static str] {
        self.neighbours
            .iter()
            .find(|(m, _)| *m == module)
            .map_or(&[], |(_, n)| n)
    }
}

/// The core (`crates/spintop`): no shell in it.
const CORE: Rules = Rules {
    layers: &[
        ("math", 0),
        ("numbers", 0),
        ("physics", 1),
        ("integrate", 2),
        ("sim", 3),
        ("assignment", 4),
        ("figure", 4),
        ("output", 4),
        ("plot", 4),
        ("scene", 4),
        ("stability", 4),
        ("workprecision", 4),
    ],
    shell: u8::MAX,
    neighbours: &[
        // A scene is answered by the commands' computations, and a stability
        // scene by its row.
        ("scene", &["output", "stability"]),
        // The sweep's charts.
        ("workprecision", &["plot"]),
        // The figures as text and SVG.
        ("plot", &["figure"]),
    ],
    launchers: &[],
};

/// The application (`src/`): shells side by side. The two full-screen
/// shells, the live view (`tui`) and the reader (`learn`), never import each
/// other: what both need sits below them, the live models (`live`) over the
/// terminal (`term`). The command line launches each.
const APP: Rules = Rules {
    layers: &[
        ("term", 3),
        ("live", 4),
        ("cli", 5),
        ("learn", 5),
        ("tui", 5),
    ],
    shell: 5,
    neighbours: &[],
    launchers: &[("src/cli/tui.rs", "tui"), ("src/cli/learn.rs", "learn")],
};

/// The rules of the crate when it was one package (every kind of module at
/// once): the checker's own tests run on scratch trees under them.
const WHOLE: Rules = Rules {
    layers: &[
        ("math", 0),
        ("numbers", 0),
        ("physics", 1),
        ("integrate", 2),
        ("sim", 3),
        ("assignment", 4),
        ("course", 4),
        ("figure", 4),
        ("grading", 4),
        ("output", 4),
        ("plot", 4),
        ("scene", 4),
        ("stability", 4),
        ("workprecision", 4),
        ("cli", 5),
        ("server", 5),
        ("tui", 5),
    ],
    shell: 5,
    neighbours: &[
        ("scene", &["output", "stability"]),
        ("workprecision", &["plot"]),
        ("plot", &["figure"]),
        ("course", &["grading"]),
        ("grading", &["assignment"]),
    ],
    launchers: &[
        ("src/cli/tui.rs", "tui"),
        ("src/cli/learn.rs", "tui"),
        ("src/cli/book.rs", "server"),
    ],
};

/// The crates this test reads, with their rules: (folder, rules).
const CRATES: [(&str, &Rules); 2] = [("crates/spintop", &CORE), (".", &APP)];

// ---------------------------------------------------------------- reading

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

/// The module path of a file (`src/integrate/dopri5.rs` → `integrate::dopri5`);
/// empty for the crate root.
fn module_of(root: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(root.join("src")).expect("under src/");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().into_owned())
        .collect();
    if let Some(last) = parts.last_mut() {
        *last = last.trim_end_matches(".rs").to_string();
    }
    if matches!(parts.as_slice(), [only] if only == "lib" || only == "main") {
        parts.clear();
    }
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// The text with comments and the insides of string and char literals
/// blanked (lines kept), so that only code is read. A string inside an
/// attribute that is a path into the crate (`#[serde(with = "crate::a::f")]`)
/// is kept, unquoted: the compiler follows it as code.
fn code_only(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    // The depth of `[` inside the attribute being read (0: none), and
    // whether the last `#` (or `#!`) opens one.
    let (mut attribute, mut hash) = (0usize, false);
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        match c {
            '#' => hash = true,
            '!' if hash => {}
            '[' if hash || attribute > 0 => {
                attribute += 1;
                hash = false;
            }
            ']' if attribute > 0 => attribute -= 1,
            c if !c.is_whitespace() => hash = false,
            _ => {}
        }
        if c == '"' && attribute > 0 {
            let rest: String = chars[i + 1..].iter().take_while(|c| **c != '"').collect();
            if is_crate_path(&rest) {
                out.push(' ');
                out.push_str(&rest);
                out.push(' ');
                i += rest.chars().count() + 2;
                continue;
            }
        }
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(chars[i]));
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !ident_char(out.chars().last())
        {
            // A raw string r"…" or r#"…"#.
            let mut j = i + 1;
            let mut hashes = 0;
            while chars.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            let rest: String = chars[j + 1..].iter().collect();
            let len = rest
                .find(&close)
                .map_or(rest.chars().count(), |at| rest[..at].chars().count());
            out.push('"');
            for ch in rest.chars().take(len) {
                out.push(blank(ch));
            }
            out.push('"');
            i = j + 1 + len + close.chars().count();
        } else if c == '"' {
            out.push('"');
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < chars.len() {
                    out.push(blank(chars[i]));
                    i += 1;
                }
            }
            out.push('"');
            i += 1;
        } else if c == '\'' && chars.get(i + 2) == Some(&'\'') {
            out.push_str("' '");
            i += 3;
        } else if c == '\'' && next == Some('\\') {
            // '\n', '\u{..}': up to the closing quote.
            out.push('\'');
            i += 1;
            while i < chars.len() && chars[i] != '\'' {
                out.push(' ');
                i += 1 + usize::from(chars[i] == '\\');
            }
            out.push('\'');
            i += 1;
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// `crate::a::b`, `$crate::a`, `super::x`, `self::y`: a path into the crate.
fn is_crate_path(text: &str) -> bool {
    let parts: Vec<&str> = text.trim_start_matches('$').split("::").collect();
    parts.len() > 1
        && matches!(parts[0], "crate" | "super" | "self")
        && parts
            .iter()
            .all(|p| !p.is_empty() && p.chars().all(|c| c.is_alphanumeric() || c == '_'))
}

fn ident_char(c: Option<char>) -> bool {
    c.is_some_and(|c| c.is_alphanumeric() || c == '_')
}

/// A path into the crate as written, where it was written: its segments
/// (`crate`, `super`, `self` first), the line, and the inline modules it
/// sits in.
#[derive(Debug, Clone)]
struct Written {
    segments: Vec<String>,
    line: usize,
    inline: Vec<String>,
    from_use: bool,
}

/// The segments of one plain path (`a :: b as c` → `a`, `b`, `as:c`: a
/// rename is kept as a last segment no module has, so that what a module
/// brings in under another name is found by that name).
fn segments(path: &str) -> Vec<String> {
    let words: Vec<&str> = path.split_whitespace().collect();
    let cut = words.iter().position(|w| *w == "as").unwrap_or(words.len());
    let mut out: Vec<String> = words[..cut]
        .concat()
        .split("::")
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect();
    if let Some(alias) = words.get(cut + 1).filter(|a| **a != "_") {
        out.push(format!("as:{alias}"));
    }
    out
}

/// Expand a `use` tree (`crate::{a, b::{c, d}}`) into its paths, each with
/// the byte offset in `tree` where its last part starts (for its line).
fn expand(tree: &str) -> Vec<(Vec<String>, usize)> {
    expand_at(tree, 0)
}

fn expand_at(tree: &str, base: usize) -> Vec<(Vec<String>, usize)> {
    let lead = tree.len() - tree.trim_start().len();
    let Some(open) = tree.find('{') else {
        return vec![(segments(tree), base + lead)];
    };
    let prefix = segments(&tree[..open]);
    let close = tree.rfind('}').unwrap_or(tree.len()).max(open + 1);
    let inner = &tree[open + 1..close];
    // The parts of the group, split at its own commas.
    let (mut parts, mut depth, mut start) = (Vec::new(), 0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push((start, &inner[start..i]));
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push((start, &inner[start..]));
    let mut out = Vec::new();
    for (at, part) in parts {
        if part.trim().is_empty() {
            continue;
        }
        for (tail, offset) in expand_at(part, base + open + 1 + at) {
            let mut path = prefix.clone();
            path.extend(tail.into_iter().skip_while(|s| s == "self"));
            out.push((path, offset));
        }
    }
    if out.is_empty() {
        out.push((prefix, base + lead));
    }
    out
}

/// Every path into the crate a file writes, in `use` trees and in code.
fn written_paths(code: &str) -> Vec<Written> {
    let chars: Vec<char> = code.chars().collect();
    let mut found = Vec::new();
    let (mut line, mut depth) = (1usize, 0usize);
    // Inline `mod NAME {` blocks: (name, the brace depth inside it).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut pending_mod: Option<String> = None;
    let mut i = 0;
    let word_at = |i: usize| -> String {
        chars[i..]
            .iter()
            .take_while(|c| c.is_alphanumeric() || **c == '_')
            .collect()
    };
    while i < chars.len() {
        let c = chars[i];
        let starts_word = !ident_char(if i == 0 { None } else { Some(chars[i - 1]) });
        match c {
            '\n' => line += 1,
            '{' => {
                depth += 1;
                if let Some(name) = pending_mod.take() {
                    inline.push((name, depth));
                }
            }
            '}' => {
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
            }
            ';' => pending_mod = None,
            _ if starts_word && (c.is_alphabetic() || c == '_') => {
                let word = word_at(i);
                let inline_names: Vec<String> = inline.iter().map(|(n, _)| n.clone()).collect();
                if word == "mod" {
                    let rest: String = chars[i + 3..].iter().collect();
                    let name: String = rest
                        .trim_start()
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if !name.is_empty() {
                        pending_mod = Some(name);
                    }
                } else if word == "use" {
                    // A use tree, up to its `;` (over any number of lines).
                    let rest: String = chars[i + 3..].iter().collect();
                    if let Some(end) = rest.find(';') {
                        let tree = &rest[..end];
                        for (mut segments, offset) in expand(tree) {
                            // A relative path (`use plan::Chosen` in
                            // `scene.rs`) is read from this module; an
                            // outside crate's (`use serde::…`) then resolves
                            // to this module itself and is no import.
                            if segments.first().is_some_and(|s| {
                                !s.is_empty()
                                    && !["crate", "super", "self", "std", "core", "alloc"]
                                        .contains(&s.as_str())
                            }) {
                                segments.insert(0, "self".to_string());
                            }
                            if segments
                                .first()
                                .is_some_and(|s| s == "crate" || s == "super" || s == "self")
                            {
                                found.push(Written {
                                    segments,
                                    line: line + tree[..offset].matches('\n').count(),
                                    inline: inline_names.clone(),
                                    from_use: true,
                                });
                            }
                        }
                        line += tree.matches('\n').count();
                        i += 3 + end;
                        continue;
                    }
                } else if word == "crate" || word == "super" || word == "self" {
                    // A path in code: `crate::a::b`, `super::super::c`,
                    // also with spaces or line breaks round `::`.
                    let mut segments = Vec::new();
                    let mut j = i;
                    let after_space = |mut k: usize| {
                        while chars.get(k).is_some_and(|c| c.is_whitespace()) {
                            k += 1;
                        }
                        k
                    };
                    loop {
                        let w = word_at(j);
                        if w.is_empty() {
                            break;
                        }
                        segments.push(w.clone());
                        j += w.chars().count();
                        let k = after_space(j);
                        if chars.get(k) == Some(&':') && chars.get(k + 1) == Some(&':') {
                            j = after_space(k + 2);
                        } else {
                            break;
                        }
                    }
                    if segments.len() > 1 {
                        found.push(Written {
                            segments,
                            line,
                            inline: inline_names,
                            from_use: false,
                        });
                    }
                    line += chars[i..j].iter().filter(|c| **c == '\n').count();
                    i = j;
                    continue;
                }
                i += word.chars().count();
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    found
}

/// The module a written path reaches, as far as the file tree has modules
/// (`crate::integrate::Rhs` → `integrate`), or `None` for the crate root.
fn resolve(
    file_module: &[String],
    written: &Written,
    modules: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let path: Vec<String> = absolute(file_module, written)?
        .into_iter()
        .filter(|s| s != "*")
        .collect();
    // The longest prefix that is a module of the file tree.
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| modules.contains(p))
}

/// A written path from the crate root (`super::x` in `a::b` → `a::x`);
/// `*` kept for a glob.
fn absolute(file_module: &[String], written: &Written) -> Option<Vec<String>> {
    let mut here: Vec<String> = file_module.to_vec();
    here.extend(written.inline.iter().cloned());
    let mut segments = written.segments.iter().peekable();
    let mut path = match segments.next()?.as_str() {
        "crate" => Vec::new(),
        "self" => here.clone(),
        _ => {
            // `super`: one up, and one more for each further `super`.
            let mut up = here.clone();
            up.pop();
            while segments.peek().is_some_and(|s| *s == "super") {
                segments.next();
                up.pop();
            }
            up
        }
    };
    for s in segments {
        if s == "self" {
            continue;
        }
        path.push(s.clone());
    }
    Some(path)
}

/// One import between modules: from, to, the file and line.
#[derive(Debug, Clone)]
struct Import {
    from: Vec<String>,
    to: Vec<String>,
    file: String,
    line: usize,
}

/// Every import between two different modules of the tree under `root/src`.
fn imports(root: &Path) -> Vec<Import> {
    let files = sources(root);
    let modules: BTreeSet<Vec<String>> = files
        .iter()
        .map(|f| module_of(root, &f.path))
        .filter(|m| !m.is_empty())
        .collect();
    // Each `#[macro_export]` macro and the module that defines it: a use of
    // it elsewhere imports that module.
    let mut exported: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for f in &files {
        let module = module_of(root, &f.path);
        let t = tokens(&f.code);
        let mut export = false;
        for (k, (word, _)) in t.iter().enumerate() {
            if word == "macro_export" {
                export = true;
            } else if word == "macro_rules"
                && export
                && let Some((name, _)) = t.get(k + 2)
            {
                exported.insert(name.clone(), module.clone());
                export = false;
            }
        }
    }
    // What a module brings in from its own descendants by `use` (mostly
    // `pub use` re-exports): `scene::Chosen` is `scene::plan`'s, so a
    // sibling's `use super::Chosen` imports `scene::plan`, not `scene`
    // (read as `scene`, a circle between siblings through their parent's
    // re-exports would pass).
    let mut brought: BTreeMap<(Vec<String>, String), Vec<String>> = BTreeMap::new();
    for f in &files {
        let module = module_of(root, &f.path);
        for w in written_paths(&f.code).iter().filter(|w| w.from_use) {
            let (Some(path), Some(to)) = (absolute(&module, w), resolve(&module, w, &modules))
            else {
                continue;
            };
            // The name it is brought in under: its own, or its rename.
            let (name, item_at) = match path.last() {
                Some(a) if a.starts_with("as:") => (Some(a[3..].to_string()), path.len() - 1),
                last => (last.cloned(), path.len()),
            };
            let item = name.filter(|s| s != "*" && item_at > to.len());
            if let Some(item) = item
                && to.len() > module.len()
                && to.starts_with(&module)
            {
                brought.insert((module.clone(), item.clone()), to);
            }
        }
    }
    // The module a written path reaches, through what its modules bring in.
    let reach = |from: &[String], w: &Written| -> Option<Vec<String>> {
        let mut to = resolve(from, w, &modules)?;
        let path = absolute(from, w)?;
        for _ in 0..8 {
            match path
                .get(to.len())
                .and_then(|item| brought.get(&(to.clone(), item.clone())))
            {
                Some(next) if path.starts_with(&to) => to = next.clone(),
                _ => break,
            }
        }
        Some(to)
    };
    let mut out = Vec::new();
    for f in &files {
        let from = module_of(root, &f.path);
        if from.is_empty() {
            continue;
        }
        let mut reached: Vec<(Vec<String>, usize)> = written_paths(&f.code)
            .iter()
            .filter_map(|w| reach(&from, w).map(|to| (to, w.line)))
            .collect();
        let t = tokens(&f.code);
        for (k, (word, line)) in t.iter().enumerate() {
            let bang = t.get(k + 1).is_some_and(|(n, _)| n == "!");
            let defined_here = k >= 2 && t[k - 2].0 == "macro_rules";
            if bang
                && !defined_here
                && let Some(module) = exported.get(word)
            {
                reached.push((module.clone(), *line));
            }
        }
        for (to, line) in reached {
            if to != from {
                out.push(Import {
                    from: from.clone(),
                    to,
                    file: f.rel.clone(),
                    line,
                });
            }
        }
    }
    out
}

/// One source file: its path, its path from the root (`src/a.rs`) and its
/// code ([`code_only`]).
struct Source {
    path: PathBuf,
    rel: String,
    code: String,
}

/// Every `.rs` file under `root/src`, sorted.
fn sources(root: &Path) -> Vec<Source> {
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let rel = path
                .strip_prefix(root)
                .expect("under the root")
                .to_string_lossy()
                .replace('\\', "/");
            let text = std::fs::read_to_string(&path).expect("a readable source file");
            Source {
                code: code_only(&text),
                path,
                rel,
            }
        })
        .collect()
}

/// The words and the punctuation of code, one character each, with lines.
fn tokens(code: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    let mut line = 1;
    let mut chars = code.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\n' {
            line += 1;
        } else if c.is_alphanumeric() || c == '_' {
            let mut word = c.to_string();
            while let Some(&n) = chars.peek().filter(|n| n.is_alphanumeric() || **n == '_') {
                word.push(n);
                chars.next();
            }
            out.push((word, line));
        } else if !c.is_whitespace() {
            out.push((c.to_string(), line));
        }
    }
    out
}

/// The forms of import the checker cannot follow, refused wherever they
/// are: an alias of the crate (`use crate as c`, `extern crate self as c`),
/// a glob of the crate root, a re-export at the root (it hides the module an
/// item comes from), another file compiled in (`#[path]`, `include!`).
fn disguises(root: &Path) -> Vec<String> {
    let mut bad = Vec::new();
    for f in sources(root) {
        let module = module_of(root, &f.path);
        let at = |line: usize, what: &str| format!("{}:{line}: {what}", f.rel);
        for w in written_paths(&f.code).iter().filter(|w| w.from_use) {
            // A rename is not part of the path (`use crate as c` is `crate`).
            let path = absolute(&module, w).map(|mut p| {
                if p.last().is_some_and(|s| s.starts_with("as:")) {
                    p.pop();
                }
                p
            });
            match path.as_deref() {
                Some([]) => bad.push(at(w.line, "an alias of the crate: name the module instead")),
                Some([star]) if star == "*" => bad.push(at(
                    w.line,
                    "a glob of the crate root: name the modules it uses",
                )),
                _ => {}
            }
        }
        let t = tokens(&f.code);
        let word = |k: usize| t.get(k).map_or("", |(w, _)| w.as_str());
        // The depth of `[` inside an attribute (0: outside one).
        let mut attribute = 0usize;
        for (k, (w, line)) in t.iter().enumerate() {
            let line = *line;
            match w.as_str() {
                "[" if attribute > 0 || word(k.wrapping_sub(1)) == "#" => attribute += 1,
                "[" if word(k.wrapping_sub(1)) == "!" && word(k.wrapping_sub(2)) == "#" => {
                    attribute += 1;
                }
                "]" if attribute > 0 => attribute -= 1,
                "path" if attribute > 0 && word(k + 1) == "=" => bad.push(at(
                    line,
                    "`#[path]` compiles another module's file here: import the module",
                )),
                "include" if word(k + 1) == "!" => bad.push(at(
                    line,
                    "`include!` compiles another file's code here: import its module",
                )),
                "extern" if word(k + 1) == "crate" && word(k + 2) == "self" => {
                    bad.push(at(line, "an alias of the crate (`extern crate self`)"));
                }
                // `pub use` or `pub(crate) use` in the crate root.
                "use"
                    if module.is_empty()
                        && (word(k.wrapping_sub(1)) == "pub"
                            || (word(k.wrapping_sub(1)) == ")"
                                && t[..k]
                                    .iter()
                                    .rposition(|(w, _)| w == "(")
                                    .is_some_and(|p| word(p.wrapping_sub(1)) == "pub"))) =>
                {
                    bad.push(at(
                        line,
                        "the crate root re-exports an item, which hides the module it comes from",
                    ));
                }
                _ => {}
            }
        }
    }
    bad
}

// ---------------------------------------------------------------- rules

/// The rule an import between top-level modules breaks, if any.
fn rule_broken(import: &Import, rules: &Rules) -> Option<String> {
    let (from, to) = (&import.from[0], &import.to[0]);
    if from == to {
        return None;
    }
    let (Some(lf), Some(lt)) = (rules.layer(from), rules.layer(to)) else {
        let unknown = if rules.layer(from).is_none() {
            from
        } else {
            to
        };
        return Some(format!(
            "{unknown} is in no layer: place it in its crate's rules on purpose"
        ));
    };
    if lf == rules.shell && lt == rules.shell {
        let launcher = rules
            .launchers
            .iter()
            .any(|(f, s)| *f == import.file && *s == to);
        return (!launcher).then(|| {
            format!("the {from} shell imports the {to} shell: shells stand side by side; move what both need below them")
        });
    }
    if lt > lf {
        return Some(format!(
            "{from} (layer {lf}) imports {to} (layer {lt}): nothing reaches up"
        ));
    }
    if lt == lf && !rules.neighbours(from).contains(&to.as_str()) {
        return Some(format!(
            "{from} imports {to}, in its own layer ({lf}) but not one of its neighbours"
        ));
    }
    None
}

/// The circles of a graph (each as its nodes, smallest first), by depth-first
/// search over its strongly connected components.
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    // Tarjan's algorithm.
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<String, usize>,
        low: BTreeMap<String, usize>,
        stack: Vec<String>,
        on_stack: BTreeSet<String>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit(s: &mut State, v: &str) {
        s.index.insert(v.to_string(), s.next);
        s.low.insert(v.to_string(), s.next);
        s.next += 1;
        s.stack.push(v.to_string());
        s.on_stack.insert(v.to_string());
        let targets: Vec<String> = s.edges.get(v).into_iter().flatten().cloned().collect();
        for w in targets {
            if !s.index.contains_key(&w) {
                visit(s, &w);
                let low = s.low[v].min(s.low[&w]);
                s.low.insert(v.to_string(), low);
            } else if s.on_stack.contains(&w) {
                let low = s.low[v].min(s.index[&w]);
                s.low.insert(v.to_string(), low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(&w);
                let done = w == v;
                component.push(w);
                if done {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.out.push(component);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.out.sort();
    s.out
}

/// Every import that breaks the order, and every circle, as lines.
fn violations(root: &Path, rules: &Rules) -> Vec<String> {
    let imports = imports(root);
    let mut bad: Vec<String> = disguises(root);
    bad.extend(
        imports
            .iter()
            .filter_map(|i| rule_broken(i, rules).map(|r| format!("{}:{}: {r}", i.file, i.line))),
    );
    // Circles among the top-level modules, and among the files of one module.
    let mut top: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut siblings: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for i in &imports {
        if i.from[0] != i.to[0] {
            top.entry(i.from[0].clone())
                .or_default()
                .insert(i.to[0].clone());
        } else if i.from.len() >= 2 && i.to.len() >= 2 && i.from[1] != i.to[1] {
            siblings
                .entry(i.from[..2].join("::"))
                .or_default()
                .insert(i.to[..2].join("::"));
        }
    }
    for circle in circles(&top).into_iter().chain(circles(&siblings)) {
        let lines: Vec<String> = imports
            .iter()
            .filter(|i| {
                let node = |m: &Vec<String>, n: usize| m[..n.min(m.len())].join("::");
                let n = if circle[0].contains("::") { 2 } else { 1 };
                circle.contains(&node(&i.from, n))
                    && circle.contains(&node(&i.to, n))
                    && node(&i.from, n) != node(&i.to, n)
            })
            .map(|i| format!("{}:{}", i.file, i.line))
            .collect();
        bad.push(format!(
            "an import circle: {} (imports at {})",
            circle.join(" <-> "),
            lines.join(", ")
        ));
    }
    bad
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The violations of a scratch tree of `files` (path, text) written under
/// `dir`, which is removed after.
fn violations_of_scratch(dir: &Path, files: &[(&str, &str)]) -> Vec<String> {
    for (path, text) in files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let bad = violations(dir, &WHOLE);
    let _ = std::fs::remove_dir_all(dir);
    bad
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

/// The checker itself can fail, on each kind of wrong import: a scratch tree
/// with one of each, and a right import of each kind beside it.
#[test]
fn the_checker_fails_on_each_kind_of_wrong_import() {
    let dir = std::env::temp_dir().join(format!("spintop-arch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files: &[(&str, &str)] = &[
        ("src/lib.rs", "pub mod math;\n"),
        (
            "src/math.rs",
            "// crate::sim in a comment is fine\npub fn f() { let s = \"crate::tui::x\"; }\n",
        ),
        ("src/numbers.rs", ""),
        // 1. A one-line `use` up the layers: physics → sim.
        (
            "src/physics.rs",
            "use crate::sim::Simulation;\npub mod top;\n",
        ),
        // 2. A `use` tree over several lines, nested: integrate → scene (its
        // line is the line of the item, 4).
        (
            "src/integrate.rs",
            "use crate::{\n    math::Real,\n    scene::{\n        parse,\n    },\n};\n",
        ),
        // 3. A `super::` chain: physics/top/deep.rs reaches the crate's tui.
        ("src/physics/top.rs", "pub mod deep;\n"),
        (
            "src/physics/top/deep.rs",
            "use super::super::super::tui::app;\nuse super::super::Energy;\n",
        ),
        // 4. A fully qualified path in code: sim → cli.
        (
            "src/sim.rs",
            "fn g() {\n    let x = crate::math::Real::default();\n    crate::cli::run(x);\n}\n",
        ),
        // 5. A shell importing a shell outside the launchers: tui → cli.
        ("src/tui.rs", "pub mod app;\n"),
        (
            "src/tui/app.rs",
            "use crate::cli::parse_number;\nuse crate::sim::Model;\n",
        ),
        ("src/cli.rs", "pub mod tui;\npub mod run;\n"),
        ("src/cli/tui.rs", "use crate::tui::app::App;\n"),
        // 6. A service that is not a neighbour: stability → figure.
        (
            "src/stability.rs",
            "use crate::figure::Figure;\nuse crate::sim::Model;\n",
        ),
        ("src/figure.rs", ""),
        // 7. A circle between two files of one module, each in `use self`.
        ("src/scene.rs", "pub mod a;\npub mod b;\n"),
        (
            "src/scene/a.rs",
            "use crate::scene::b::B;\nuse crate::output as out;\npub struct A;\n",
        ),
        (
            "src/scene/b.rs",
            "mod inner {\n    use super::super::a::A;\n}\n",
        ),
        // 8. A circle between two neighbours: scene ↔ output.
        (
            "src/output.rs",
            "pub fn h() -> crate::scene::a::A { todo!() }\n",
        ),
        ("src/server.rs", ""),
    ];
    let bad = violations_of_scratch(&dir, files);
    let expect = [
        "src/physics.rs:1: physics (layer 1) imports sim (layer 3)",
        "src/integrate.rs:4: integrate (layer 2) imports scene (layer 4)",
        "src/physics/top/deep.rs:1: physics (layer 1) imports tui (layer 5)",
        "src/sim.rs:3: sim (layer 3) imports cli (layer 5)",
        "src/tui/app.rs:1: the tui shell imports the cli shell",
        "src/stability.rs:1: stability imports figure, in its own layer (4) but not one of its neighbours",
        "src/output.rs:1: output imports scene, in its own layer (4) but not one of its neighbours",
        "an import circle: output <-> scene",
        "an import circle: scene::a <-> scene::b",
        // sim → cli (4. above) closes a circle through the launcher and 5.
        "an import circle: cli <-> sim <-> tui",
    ];
    for e in expect {
        assert!(
            bad.iter().any(|b| b.starts_with(e)),
            "not caught: {e}\ngot:\n{}",
            bad.join("\n")
        );
    }
    // And nothing else: the right imports beside them (a comment, a string,
    // math from anywhere, super::super within physics, the launcher, sim
    // from a service and a shell) pass.
    assert_eq!(bad.len(), expect.len(), "{}", bad.join("\n"));
}

/// The checker reads paths in every form the compiler reads them: with
/// spaces round `::`, in the strings of attributes (`serde`'s
/// `with = "crate::…"`), and through exported macros; and it refuses the
/// forms it cannot follow (an alias of the crate, a glob of its root, a
/// re-export at the root, another module's file compiled in with `#[path]`
/// or `include!`). Nothing else is reported: a doc link is not an import.
#[test]
fn the_checker_sees_imports_in_every_disguise() {
    let dir = std::env::temp_dir().join(format!("spintop-arch-disguise-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files: &[(&str, &str)] = &[
        // 1. A re-export at the root hides the module an item comes from.
        ("src/lib.rs", "pub mod math;\npub use cli::run as launch;\n"),
        ("src/math.rs", "pub type Real = f64;\n"),
        ("src/numbers.rs", ""),
        // 2. Spaces round `::` in code: sim → cli.
        ("src/sim.rs", "fn g() {\n    crate :: cli :: run();\n}\n"),
        // 3. An alias of the crate: physics reaches sim through it.
        (
            "src/physics.rs",
            "use crate as root;\nfn f() {\n    root::sim::g();\n}\n",
        ),
        // 4. A glob of the crate root brings every module into scope.
        (
            "src/integrate.rs",
            "use crate::*;\nfn f() { cli::run(); }\n",
        ),
        // 5. A doc link is no import (rustdoc reads it, the compiler does
        // not): a lower module may name who calls it.
        (
            "src/stability.rs",
            "/// Compare [`crate::workprecision::Sweep`].\npub fn s() {}\n",
        ),
        ("src/workprecision.rs", ""),
        // 6. A path in an attribute's string: figure → tui.
        (
            "src/figure.rs",
            "#[derive(serde::Serialize)]\npub struct F {\n    #[serde(serialize_with = \"crate::tui::fmt\")]\n    x: f64,\n}\n",
        ),
        ("src/tui.rs", ""),
        // 7. Another module's file compiled in: plot takes the server's.
        (
            "src/plot.rs",
            "#[path = \"server/http.rs\"]\nmod http;\nfn f() { include!(\"server/page.rs\"); }\n",
        ),
        ("src/server.rs", "pub mod http;\n"),
        ("src/server/http.rs", ""),
        // 8. An exported macro that reaches the cli, used from the scene.
        (
            "src/cli.rs",
            "#[macro_export]\nmacro_rules! launch_cli {\n    () => { $crate::cli::run() };\n}\npub fn run() {}\n",
        ),
        ("src/scene.rs", "fn f() {\n    crate::launch_cli!();\n}\n"),
        // 9. `extern crate self` is an alias of the crate too.
        (
            "src/output.rs",
            "extern crate self as spintop;\nfn f() { spintop_app::cli::run(); }\n",
        ),
    ];
    let bad = violations_of_scratch(&dir, files);
    let expect = [
        "src/lib.rs:2: the crate root re-exports",
        "src/sim.rs:2: sim (layer 3) imports cli (layer 5)",
        "src/physics.rs:1: an alias of the crate",
        "src/integrate.rs:1: a glob of the crate root",
        "src/figure.rs:3: figure (layer 4) imports tui (layer 5)",
        "src/plot.rs:1: `#[path]`",
        "src/plot.rs:3: `include!`",
        "src/scene.rs:2: scene (layer 4) imports cli (layer 5)",
        "src/output.rs:1: an alias of the crate",
    ];
    let missed: Vec<&str> = expect
        .iter()
        .copied()
        .filter(|e| !bad.iter().any(|b| b.starts_with(e)))
        .collect();
    assert!(
        missed.is_empty(),
        "not caught:\n{}\ngot:\n{}",
        missed.join("\n"),
        bad.join("\n")
    );
    assert_eq!(bad.len(), expect.len(), "{}", bad.join("\n"));
}

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
fn module_edges(root: &Path, shell: &str) -> Vec<(String, String)> {
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

/// Two files of one module that import each other through their parent's
/// re-exports make a circle too: `scene/answer.rs` writes
/// `use super::Chosen` for what `scene.rs` brings in from `scene/plan.rs`,
/// so it imports `plan`; with `plan` importing `answer` back, the checker
/// must see the circle (it read `super::Chosen` as an import of `scene`).
#[test]
fn a_circle_through_a_parents_re_exports_is_caught() {
    let dir = std::env::temp_dir().join(format!("spintop-reexport-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = "pub mod answer;\npub mod plan;\npub use plan::Chosen as Pick;\npub use answer::{Answer as Reply};\n";
    let circle = violations_of_scratch(
        &dir,
        &[
            ("src/lib.rs", "pub mod scene;\n"),
            ("src/scene.rs", scene),
            (
                "src/scene/answer.rs",
                "use super::Pick;\npub struct Answer;\n",
            ),
            (
                "src/scene/plan.rs",
                "use super::Reply;\npub struct Chosen;\n",
            ),
        ],
    );
    let none = violations_of_scratch(
        &dir,
        &[
            ("src/lib.rs", "pub mod scene;\n"),
            ("src/scene.rs", scene),
            (
                "src/scene/answer.rs",
                "use super::Pick;\npub struct Answer;\n",
            ),
            ("src/scene/plan.rs", "pub struct Chosen;\n"),
        ],
    );
    assert!(
        circle
            .iter()
            .any(|v| v.contains("an import circle: scene::answer <-> scene::plan")),
        "{circle:?}"
    );
    assert!(none.is_empty(), "{none:?}");
}

/// The workspace's crates, bottom up, with the layer of each: a crate may
/// depend on crates of lower layers only.
const WORKSPACE: [(&str, &str, u8); 7] = [
    ("crates/spintop", "spintop", 0),
    ("crates/spintop-grading", "spintop-grading", 1),
    ("crates/spintop-course", "spintop-course", 2),
    ("crates/spintop-server", "spintop-server", 2),
    (".", "spintop-app", 3),
    // What a student builds and what measures speed: the core (and the graders).
    ("lessons", "spintop-lessons", 2),
    ("benches", "spintop-benches", 2),
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
