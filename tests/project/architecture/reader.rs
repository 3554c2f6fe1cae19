//! Reading a crate's sources: the files and their modules, the code
//! without comments and strings, every path into the crate (`use` trees,
//! `super::` chains, paths in code and in attributes, exported macros)
//! resolved to the module it reaches, and the forms of import that cannot be
//! followed.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

pub(super) fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
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
pub(super) fn module_of(root: &Path, file: &Path) -> Vec<String> {
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
                let word = word_at(&chars, i);
                let inline_names: Vec<String> = inline.iter().map(|(n, _)| n.clone()).collect();
                if word == "mod" {
                    let name = word_at(&chars, after_space(&chars, i + 3));
                    if !name.is_empty() {
                        pending_mod = Some(name);
                    }
                } else if word == "use" {
                    // A use tree, up to its `;` (over any number of lines).
                    let rest: String = chars[i + 3..].iter().collect();
                    if let Some(end) = rest.find(';') {
                        let tree = &rest[..end];
                        found.extend(use_tree_paths(tree, line, &inline_names));
                        line += tree.matches('\n').count();
                        i += 3 + end;
                        continue;
                    }
                } else if word == "crate" || word == "super" || word == "self" {
                    let (segments, j) = code_path(&chars, i);
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

/// The identifier that starts at `chars[i]` (empty when none does).
fn word_at(chars: &[char], i: usize) -> String {
    chars[i..]
        .iter()
        .take_while(|c| c.is_alphanumeric() || **c == '_')
        .collect()
}

/// The first index from `k` on that is not white space.
fn after_space(chars: &[char], mut k: usize) -> usize {
    while chars.get(k).is_some_and(|c| c.is_whitespace()) {
        k += 1;
    }
    k
}

/// The paths into the crate of one `use` tree (the text between `use` and
/// its `;`, which starts on `line`), written inside the inline modules
/// `inline`.
fn use_tree_paths(tree: &str, line: usize, inline: &[String]) -> Vec<Written> {
    let mut found = Vec::new();
    for (mut segments, offset) in expand(tree) {
        // A relative path (`use plan::Chosen` in `scene.rs`) is read from
        // this module; an outside crate's (`use serde::…`) then resolves to
        // this module itself and is no import.
        if segments.first().is_some_and(|s| {
            !s.is_empty()
                && !["crate", "super", "self", "std", "core", "alloc"].contains(&s.as_str())
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
                inline: inline.to_vec(),
                from_use: true,
            });
        }
    }
    found
}

/// A path in code that starts at `chars[i]` (`crate::a::b`,
/// `super::super::c`, also with spaces or line breaks round `::`): its
/// segments, and the index just after it.
fn code_path(chars: &[char], i: usize) -> (Vec<String>, usize) {
    let mut segments = Vec::new();
    let mut j = i;
    loop {
        let w = word_at(chars, j);
        if w.is_empty() {
            break;
        }
        j += w.chars().count();
        segments.push(w);
        let k = after_space(chars, j);
        if chars.get(k) == Some(&':') && chars.get(k + 1) == Some(&':') {
            j = after_space(chars, k + 2);
        } else {
            break;
        }
    }
    (segments, j)
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
pub(super) struct Import {
    pub(super) from: Vec<String>,
    pub(super) to: Vec<String>,
    pub(super) file: String,
    pub(super) line: usize,
}

/// Every import between two different modules of the tree under `root/src`.
pub(super) fn imports(root: &Path) -> Vec<Import> {
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
pub(super) fn disguises(root: &Path) -> Vec<String> {
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
