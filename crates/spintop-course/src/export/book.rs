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
        } else if rel.extension().is_some_and(|x| x == "md") {
            let name = rel.file_name().unwrap_or_default().to_string_lossy();
            copy_chapter(&name, &String::from_utf8_lossy(&bytes)).into_bytes()
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

/// The sentences of the book a copy says otherwise, beyond the rule of
/// [`copy_chapter`]: (chapter, as the repository says it, as a copy does).
/// Each `from` occurs in its chapter (a test checks it).
pub const CHAPTER_REWRITES: [(&str, &str, &str); 1] = [(
    "preface.md",
    "From the repository root,\n\n```sh\ncargo run --release\ncargo test\n```\n\nopen the live terminal view of the paper's two tops, and run every test,\nevery snippet of this book included.",
    "With spintop installed,\n\n```sh\nspintop\nspintop learn\n```\n\nopen the live terminal view of the paper's two tops, and this book beside\nits scenes. In this copy `cargo test` grades your assignments; the book's\nown tests and snippets run in spintop's repository (`cargo test` there).",
)];

/// What marks a command or a file that only spintop's repository has.
pub const REPOSITORY_ONLY: &str = "in spintop's repository";

/// A chapter of the book as a copy carries it: its commands as a student
/// runs them there. The one rule: `cargo run --release -- ARGS` is
/// `spintop ARGS` (the program, installed); any other `cargo` command of a
/// code block (an example, a test of the repository's packages) is marked
/// as the repository's, as are the repository's test files named in the
/// text (a copy carries the core's sources, not its tests); and the
/// sentences of [`CHAPTER_REWRITES`].
pub fn copy_chapter(file: &str, text: &str) -> String {
    let mut text = text.to_string();
    for (chapter, from, to) in CHAPTER_REWRITES {
        if chapter == file {
            text = text.replace(from, to);
        }
    }
    let text = text.replace("cargo run --release -- ", "spintop ").replace(
        "`cargo run --release --example",
        &format!("({REPOSITORY_ONLY}) `cargo run --release --example"),
    );
    let mut out = String::with_capacity(text.len());
    let mut fenced = false;
    for line in text.split_inclusive('\n') {
        let lead = line.len() - line.trim_start().len();
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if fenced && line.trim_start().starts_with("cargo ") {
            out.push_str(&line[..lead]);
            out.push_str(&format!("# {REPOSITORY_ONLY}: "));
            out.push_str(&line[lead..]);
            continue;
        }
        out.push_str(&mark_repository_files(line));
    }
    out
}

/// `line` with each repository test file it names (`crates/spintop/tests/…`)
/// marked as the repository's.
fn mark_repository_files(line: &str) -> String {
    const TESTS: &str = "crates/spintop/tests/";
    let mut out = String::new();
    let mut rest = line;
    while let Some(at) = rest.find(TESTS) {
        let tail = &rest[at..];
        let len = tail
            .find(|c: char| c.is_whitespace() || matches!(c, '`' | ')' | ',' | ';'))
            .unwrap_or(tail.len());
        let mut end = at + len;
        // A path ends before a full stop that ends its sentence.
        while rest[..end].ends_with('.') {
            end -= 1;
        }
        if rest[end..].starts_with('`') {
            end += 1;
        }
        out.push_str(&rest[..end]);
        if rest[end..].starts_with(')') {
            out.push_str(&format!(", {REPOSITORY_ONLY}"));
        } else {
            out.push_str(&format!(" ({REPOSITORY_ONLY})"));
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
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

    /// Every chapter as a copy carries it: no `cargo run --release --`
    /// left (each is `spintop …`), every other `cargo` line of a code block
    /// and every repository test file named marked as the repository's;
    /// the commands the reviewer found, as a copy must show them.
    #[test]
    fn a_copys_chapters_give_spintop_commands_and_mark_the_repositorys() {
        let src = crate::repository().join(BOOK_SRC);
        for (chapter, from, _) in CHAPTER_REWRITES {
            let text = std::fs::read_to_string(src.join(chapter)).unwrap();
            assert!(text.contains(from), "{chapter} no longer says {from:?}");
        }
        let mut marked = 0;
        for entry in std::fs::read_dir(&src).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if !name.ends_with(".md") || name == "assignments.md" {
                continue;
            }
            let copy = copy_chapter(&name, &std::fs::read_to_string(&path).unwrap());
            assert!(!copy.contains("cargo run --release -- "), "{name}");
            assert!(!copy.contains("From the repository root"), "{name}");
            let mut fenced = false;
            for line in copy.lines() {
                let t = line.trim_start();
                if t.starts_with("```") {
                    fenced = !fenced;
                }
                assert!(!(fenced && t.starts_with("cargo ")), "{name}: {line}");
                if fenced && t.starts_with(&format!("# {REPOSITORY_ONLY}: cargo ")) {
                    marked += 1;
                }
                for (at, _) in line.match_indices("crates/spintop/tests/") {
                    assert!(line[at..].contains(REPOSITORY_ONLY), "{name}: {line}");
                }
            }
        }
        assert!(marked >= 5, "{marked} repository commands marked");
        let read = |f: &str| copy_chapter(f, &std::fs::read_to_string(src.join(f)).unwrap());
        assert!(read("section-4-1.md").contains("\nspintop figure 1\n"));
        assert!(read("section-4-2.md").contains(
            "# in spintop's repository: cargo run --release --example ch4_symmetric_top\n"
        ));
        let fail = read("where-methods-fail.md");
        assert!(
            fail.contains("`crates/spintop/tests/numerics/stability.rs` (in spintop's repository)")
        );
    }
}
