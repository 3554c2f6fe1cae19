//! mdBook's `{{#include file:anchor}}`, resolved as mdBook resolves it, and
//! the library's own source marked to be folded to one line.

use std::path::Path;

/// Resolves mdBook's `{{#include path}}` and `{{#include path:anchor}}`
/// against `dir` (the chapter's folder), as mdBook does: an anchor keeps the
/// lines between `ANCHOR: name` and `ANCHOR_END: name`, minus any other
/// anchor lines. A file that cannot be read leaves a visible note.
pub fn resolve_includes(source: &str, dir: &Path) -> String {
    let mut out = String::with_capacity(source.len());
    let mut rest = source;
    while let Some(start) = rest.find("{{#include ") {
        out.push_str(&rest[..start]);
        let after = &rest[start + "{{#include ".len()..];
        let Some(end) = after.find("}}") else {
            out.push_str(&rest[start..]);
            return out;
        };
        let spec = after[..end].trim();
        out.push_str(&include(spec, dir));
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    out
}

/// The first line of an included excerpt of the library's own source (a
/// file under `src/`), which [`render_with`] folds to one line: the marker,
/// then `path:anchor`. No source line starts with this control character.
pub(super) const FOLD: &str = "\u{1}library ";

fn include(spec: &str, dir: &Path) -> String {
    let body = include_body(spec, dir);
    // The library's source (`../../src/…`), not a lesson or a program's output.
    let library = spec.split(['/', '\\']).any(|part| part == "src")
        && !spec.contains("lessons/")
        && spec
            .rsplit_once(':')
            .map_or(spec, |(p, _)| p)
            .ends_with(".rs");
    if library {
        let shown = spec.trim_start_matches("../").trim_start_matches("../");
        format!("{FOLD}{shown}\n{body}")
    } else {
        body
    }
}

fn include_body(spec: &str, dir: &Path) -> String {
    let (path, anchor) = match spec.rsplit_once(':') {
        Some((p, a)) if !a.is_empty() && !a.contains('/') => (p, Some(a)),
        _ => (spec, None),
    };
    let Ok(text) = std::fs::read_to_string(dir.join(path)) else {
        return format!("(not found: {path})");
    };
    let Some(anchor) = anchor else {
        return text.trim_end_matches('\n').to_string();
    };
    let mut keep = false;
    let mut lines = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if t.contains(&format!("ANCHOR_END: {anchor}")) {
            break;
        }
        if keep && !t.contains("ANCHOR:") && !t.contains("ANCHOR_END:") {
            lines.push(line);
        }
        if t.contains(&format!("ANCHOR: {anchor}")) {
            keep = true;
        }
    }
    // mdBook removes the common indentation of an anchored region.
    let indent = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    lines
        .iter()
        .map(|l| {
            if l.len() >= indent {
                &l[indent..]
            } else {
                l.trim_start()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}
