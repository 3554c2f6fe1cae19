//! The book a copy carries, so that `spintop learn` run in the copy reads
//! its chapters where the repository is not: `book/src` as the repository
//! holds it (the chapters, `SUMMARY.md`, the generated outputs, the
//! diagrams; not KaTeX's stylesheet and fonts, which only the HTML book
//! needs), and the files its chapters `{{#include}}` from outside it (the
//! book's lesson programs, `lessons/NAME.rs`) at the same paths from the
//! copy's top, so that every include resolves as it does in the repository.
//! The core's sources, which the chapters also include, are carried in
//! `crates/` already. Nothing carried here is a target of the copy's
//! package: cargo builds `src/` and `tests/` only.

use std::path::{Component, Path, PathBuf};

/// The book's sources, from the repository's (and the copy's) top.
pub(crate) const BOOK_SRC: &str = "book/src";

/// What the book's folder holds that `spintop learn` does not read: the
/// HTML book's stylesheet and fonts.
const NOT_CARRIED: [&str; 1] = ["katex"];

/// The README of the copy's `lessons/`, which holds only what the book shows.
const LESSONS_README: &str = "# The book's programs

The example programs of spintop's book, carried so that the chapters
`spintop learn` shows in this copy can show their code as the book does. They
are not part of the course: nothing here is built or graded (your work is in
`src/`, its graders in `tests/`).
";

/// The files of the book a copy carries: (where in the copy, what it holds).
/// `page` makes the assignments page true in a copy; `carried` says whether
/// a path of the copy is written already (the core's sources).
pub(crate) fn book_files(
    repo: &Path,
    page: impl Fn(&str) -> String,
    carried: impl Fn(&Path) -> bool,
) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
    let src = repo.join(BOOK_SRC);
    let mut files = Vec::new();
    for path in super::walk(&src, &NOT_CARRIED, |kind, _| kind.is_file()) {
        let rel = path.strip_prefix(repo).unwrap_or(&path).to_path_buf();
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let bytes = if rel == Path::new(BOOK_SRC).join("assignments.md") {
            page(&String::from_utf8_lossy(&bytes)).into_bytes()
        } else {
            bytes
        };
        files.push((rel, bytes));
    }
    let mut included: Vec<PathBuf> = Vec::new();
    for (rel, bytes) in &files {
        if rel.extension().is_none_or(|x| x != "md") {
            continue;
        }
        let dir = rel.parent().unwrap_or(Path::new(""));
        for target in includes(&String::from_utf8_lossy(bytes), dir) {
            if !target.starts_with(BOOK_SRC) && is_carried_include(&target) && !carried(&target) {
                included.push(target);
            }
        }
    }
    included.sort();
    included.dedup();
    for rel in &included {
        let path = repo.join(rel);
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        files.push((rel.clone(), bytes));
    }
    if included.iter().any(|p| p.starts_with("lessons")) {
        files.push((
            "lessons/README.md".into(),
            LESSONS_README.as_bytes().to_vec(),
        ));
    }
    Ok(files)
}

/// Whether an included file (a path from the top) is one the book carries
/// itself: not the stubs or the reference solutions (`lessons/src/`, which
/// no chapter includes and a copy must never hold), not the crates (whose
/// sources `crates/` carries, and whose other folders would become cargo
/// targets there).
fn is_carried_include(target: &Path) -> bool {
    !target.starts_with("lessons/src") && !target.starts_with("crates")
}

/// The files the text `{{#include}}`s, as paths from the top, for a chapter
/// in the folder `dir` (from the top); those that would leave the top are
/// left out. mdBook's syntax: `{{#include path}}`, `{{#include path:anchor}}`.
pub(crate) fn includes(text: &str, dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for piece in text.split("{{#include ").skip(1) {
        let Some(end) = piece.find("}}") else {
            continue;
        };
        let spec = piece[..end].trim();
        let path = match spec.rsplit_once(':') {
            Some((p, a)) if !a.is_empty() && !a.contains('/') => p,
            _ => spec,
        };
        if let Some(target) = normal(&dir.join(path)) {
            out.push(target);
        }
    }
    out
}

/// `path` (relative) with its `.` and `..` taken out, or `None` if it
/// leaves the folder it is relative to or is absolute.
fn normal(path: &Path) -> Option<PathBuf> {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::Normal(p) => out.push(p),
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    return None;
                }
            }
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn includes_are_read_as_mdbook_reads_them() {
        let text = "a {{#include ../../lessons/x.rs:part}} b {{#include generated/y.txt}}\n\
                    {{#include ../../crates/spintop/src/m.rs:anchor}} {{#include ../../../etc/passwd}}\
                    {{#include /etc/passwd}} {{#include ./z.md:a/b}}";
        assert_eq!(
            includes(text, Path::new("book/src")),
            [
                "lessons/x.rs",
                "book/src/generated/y.txt",
                "crates/spintop/src/m.rs",
                "book/src/z.md:a/b",
            ]
            .map(PathBuf::from)
        );
        for (path, carried) in [
            ("lessons/x.rs", true),
            ("lessons/src/solutions/ch2.rs", false),
            ("lessons/src/ch2.rs", false),
            ("crates/spintop/tests/t.rs", false),
        ] {
            assert_eq!(is_carried_include(Path::new(path)), carried, "{path}");
        }
    }
}
