//! The export: a self-contained student's copy of the course (stubs without
//! the reference solutions, the graders, the assignments page, a README, a
//! manifest, the crates it builds against and the book `spintop learn` reads
//! ([`book`])), optionally with a CI workflow that grades it on every push.

use std::path::{Path, PathBuf};

mod book;
pub use book::{CHAPTER_REWRITES, REPOSITORY_ONLY, copy_chapter};

/// The lessons crate of the repository at `repo` (where `spintop course`
/// and `spintop learn` look unless told otherwise).
pub fn lessons_dir(repo: &Path) -> PathBuf {
    repo.join("lessons")
}

/// Why `dir` is not a lessons crate spintop can grade, if it is not.
pub fn check_lessons_dir(dir: &Path) -> Result<(), String> {
    if !dir.join("Cargo.toml").is_file() || !dir.join("src").is_dir() {
        return Err(format!(
            "{} is not a course: it needs a Cargo.toml and a src/ folder (the repository's lessons/, or a copy made by `spintop course export`)",
            dir.display()
        ));
    }
    Ok(())
}

/// The files under `dir` whose name ends in `.rs`, every folder deep but the
/// ones `skip` names (relative to `dir`), sorted; symbolic links are not
/// followed.
pub(crate) fn rust_files(dir: &Path, skip: &[&str]) -> Vec<PathBuf> {
    walk(dir, skip, |kind, path| {
        kind.is_file() && path.extension().is_some_and(|x| x == "rs")
    })
}

/// The symbolic links under `dir` (to files or to folders), every folder
/// deep but the ones `skip` names, sorted.
pub(crate) fn symbolic_links(dir: &Path, skip: &[&str]) -> Vec<PathBuf> {
    walk(dir, skip, |kind, _| kind.is_symlink())
}

/// The entries under `dir` that `keep` accepts, every real folder deep (a
/// link to a folder is not entered) but the ones `skip` names, sorted.
fn walk(
    dir: &Path,
    skip: &[&str],
    keep: impl Fn(std::fs::FileType, &Path) -> bool,
) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let path = entry.path();
            let rel = path.strip_prefix(dir).unwrap_or(&path);
            if skip.iter().any(|s| rel == Path::new(s)) {
                continue;
            }
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                stack.push(path.clone());
            }
            if keep(kind, &path) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// A student's file with the instructor's solutions taken out: the
/// `#[cfg(not(feature = "solutions"))]` attributes (always true once the
/// feature is gone), each `#[cfg(feature = "solutions")]` item, and the
/// comment that announces it.
pub fn strip_solutions(source: &str) -> String {
    let mut out = Vec::new();
    let mut skip_next = false;
    for line in source.lines() {
        let t = line.trim();
        if skip_next {
            skip_next = false;
            continue;
        }
        if t == "#[cfg(not(feature = \"solutions\"))]" {
            continue;
        }
        if t == "#[cfg(feature = \"solutions\")]" {
            skip_next = true;
            continue;
        }
        if t.starts_with("// The instructor's reference solutions")
            || (t.starts_with("// src/solutions/") && t.contains("handing out"))
        {
            continue;
        }
        out.push(line);
    }
    let mut text = out.join("\n").trim_end().to_string();
    text.push('\n');
    text
}

/// What [`export`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Export {
    /// Every file written, relative to the export's folder.
    pub files: Vec<PathBuf>,
}

/// A CI service a copy can be graded on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ci {
    /// GitHub Actions: `.github/workflows/grade.yml`.
    Github,
}

/// Where a copy finds the crates it builds against.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Link {
    /// Inside the copy: the core and the graders' sources are carried in
    /// `crates/` (never `lessons/src/solutions/`), so the copy builds and is
    /// graded on a machine where the repository does not exist. What a
    /// student is handed.
    #[default]
    Carried,
    /// In the repository, by absolute path: the scratch copies `course grade`
    /// builds on this machine, which then share one build of the crates.
    Repository,
}

/// How to export.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ExportOptions {
    /// Add a workflow that grades the copy on every push.
    pub ci: Option<Ci>,
    /// Where the copy finds spintop's crates.
    pub link: Link,
}

/// The crates a copy builds against, as the repository holds them (the
/// core, and the graders the tests call with the wire they speak).
pub const CARRIED_CRATES: [&str; 3] = [
    "crates/spintop",
    "crates/spintop-runner",
    "crates/spintop-grading",
];

/// The path of the GitHub workflow in a copy.
pub const GITHUB_WORKFLOW: &str = ".github/workflows/grade.yml";

/// The workflow that grades a copy on every push with `cargo test`.
pub const GITHUB_WORKFLOW_TEXT: &str = "\
# Grades this copy of the spintop course on every push: `cargo test` runs
# every grader (each with fresh inputs), and the run fails while any does.
# The instructor's grade comes from `spintop course grade`, which also checks
# the source rule (lessons/README.md of spintop, \"No shortcut\").
name: grade
on:
  push:
  pull_request:
  workflow_dispatch:
jobs:
  grade:
    runs-on: ubuntu-latest
    timeout-minutes: 30
    steps:
      - uses: actions/checkout@v4
      - name: Rust toolchain
        run: rustup toolchain install stable --profile minimal && rustup default stable
      - name: Grade every assignment
        run: cargo test --no-fail-fast
";

/// The student's copy's manifest: the lessons package on its own (its own
/// workspace), depending on the core and the graders in `crates` (a path
/// inside the copy, or the repository's by absolute path).
///
/// NOTE: the package is named after the copy's folder (spintop-lessons-HASH;
/// the library keeps the name `spintop_lessons`). Cargo keys its build
/// artifacts on a path package's name, version and place in its own workspace,
/// not on where the workspace is, so two copies named alike that share a build
/// folder (`CARGO_TARGET_DIR`, as `course grade` and the tests do) would reuse
/// each other's test programs when one copy's sources look unchanged: one
/// student graded with another's code.
///
/// Its test programs: [`ALL_TESTS`] (every chapter's graders, the one a
/// plain `cargo test` runs), and each of `tests` (the files of `tests/`, by
/// name) on its own for `cargo test --test ch2`, outside a plain `cargo
/// test` (cargo stops at the first test program that fails: with one
/// program per chapter, a failing appendix hid every later chapter).
pub(crate) fn export_manifest(crates: &Path, out: &Path, tests: &[String]) -> String {
    let key = spintop::numbers::stable_key(
        &out.canonicalize()
            .unwrap_or_else(|_| out.to_path_buf())
            .to_string_lossy(),
    );
    let mut targets = format!(
        "\n# The plain `cargo test` runs one program, every chapter's graders in it\n\
         # (cargo stops at the first test program that fails); each chapter's own\n\
         # program is for `cargo test --test NAME` alone.\n\
         [[test]]\nname = \"{ALL_TESTS}\"\npath = \"tests/{ALL_TESTS}.rs\"\n"
    );
    for name in tests {
        targets.push_str(&format!(
            "\n[[test]]\nname = \"{name}\"\npath = \"tests/{name}.rs\"\ntest = false\n"
        ));
    }
    format!(
        r#"[package]
name = "spintop-lessons-{key:08x}"
version = "0.1.0"
edition = "2024"
publish = false
description = "Course assignments on Duviryak's polarized spinning top, graded by cargo test."
autotests = false

# A course of its own, not a member of any other workspace; its one member is
# this package, so `cargo test --workspace` grades the assignments and does not
# build the carried crates' own tests (which the copy does not carry).
# NOTE: no `members = ["."]`: cargo counts every path under a listed member as
# listed, and a listed path is never excluded.
[workspace]
exclude = ["crates"]

[lib]
name = "spintop_lessons"
path = "src/lib.rs"

[dependencies]
# The core only: grading does not compile the terminal UI or the command line.
spintop = {{ path = {core:?} }}

[dev-dependencies]
# The graders, which the tests call; never visible to src/.
spintop-grading = {{ path = {grading:?} }}
{targets}"#,
        core = crates.join("spintop").display().to_string(),
        grading = crates.join("spintop-grading").display().to_string(),
    )
}

/// The copy's test program that holds every chapter's graders.
pub const ALL_TESTS: &str = "assignments";

/// That program's source: each chapter's test file as a module of it.
fn all_tests_source(chapters: &[&str]) -> String {
    let mut text = String::from(
        "//! Every chapter's assignments in one test program, so that a plain\n\
         //! `cargo test` grades them all (cargo stops at the first test program\n\
         //! that fails; within one, every test runs). `cargo test --test ch2`\n\
         //! grades one chapter. Written by `spintop course export`.\n\n",
    );
    for c in chapters {
        text.push_str(&format!("#[path = \"{c}.rs\"]\nmod {c};\n"));
    }
    text
}

const EXPORT_README: &str = "# The spintop course

Assignments on A. Duviryak's polarized spinning top, graded by `cargo test`.
Every function under `src/` is a stub that ends in `todo!()`; the chapter of
the book it comes from is named in its doc comment (the assignments page is
`book/assignments.md`; the whole book is in `book/src`, and the programs its
chapters show in `lessons/`). The copy stands alone: spintop's core and its
graders are carried in `crates/` (do not edit them: the instructor grades
with their own), so it builds anywhere Rust is installed.

Two commands:

```sh
cargo test                     # grade every assignment (fresh inputs each time)
cargo test --test ch2          # grade one chapter's assignments
SPINTOP_SEED=123 cargo test    # the inputs of a failure again (its report gives the seed)
```

(Every chapter's graders are one test program, `tests/assignments.rs`, so
`cargo test` reports every assignment however many fail; each chapter's
file also builds alone for `cargo test --test NAME`.)

With spintop installed, `spintop course` run in this folder (or any folder
in it: it finds the course it stands in, as cargo finds its manifest) lists
the assignments in course order with their state and what to do next (it
also checks the source rule, as the instructor's grading does: your files
may use `spintop::math` and `spintop::assignment`, and nothing that reads
files, the environment or other programs), and `spintop learn` opens the
book this copy carries in the terminal beside this copy's grades,
re-grading on every save.
";

/// The largest file a carried crate may hold (its sources and data are a few
/// hundred kB; anything larger is not spintop's).
const MAX_CARRIED_FILE: u64 = 4 << 20;

/// The files of the crate at `dir` that a copy carries, relative to it: its
/// sources and the data they include, not its tests, benchmarks or examples
/// (which name files outside the crate), and never a build folder.
fn carried_files(dir: &Path) -> Vec<PathBuf> {
    let skip = ["tests", "benches", "examples", "target"];
    walk(dir, &skip, |kind, _| kind.is_file())
        .into_iter()
        .filter_map(|p| p.strip_prefix(dir).ok().map(Path::to_path_buf))
        .filter(|rel| rel != Path::new("Cargo.toml"))
        .collect()
}

/// A carried crate's manifest: the repository's, without what names files
/// the copy does not carry (examples, test targets, benchmarks) and without
/// the dev-dependencies those need.
fn carried_manifest(path: &Path) -> Result<String, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut manifest: toml::Table = text
        .parse()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    for key in ["example", "test", "bench", "dev-dependencies"] {
        manifest.remove(key);
    }
    if let Some(package) = manifest.get_mut("package").and_then(|p| p.as_table_mut()) {
        package.remove("autotests");
    }
    let body = toml::to_string(&manifest).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(format!(
        "# Carried from spintop's repository by `spintop course export`, so that this\n\
         # course builds and is graded where the repository is not.\n{body}"
    ))
}

/// The carried crates' files: (where in the copy, what it holds).
fn carried(repo: &Path) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
    let mut files = Vec::new();
    for krate in CARRIED_CRATES {
        let dir = repo.join(krate);
        let manifest = carried_manifest(&dir.join("Cargo.toml"))?;
        files.push((Path::new(krate).join("Cargo.toml"), manifest.into_bytes()));
        for rel in carried_files(&dir) {
            let path = dir.join(&rel);
            let size = std::fs::metadata(&path)
                .map_err(|e| format!("{}: {e}", path.display()))?
                .len();
            if size > MAX_CARRIED_FILE {
                return Err(format!(
                    "{}: {size} bytes, more than a carried crate holds",
                    path.display()
                ));
            }
            let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            files.push((Path::new(krate).join(rel), bytes));
        }
    }
    Ok(files)
}

/// The rewrites that make the book's assignments page true in a copy: the
/// repository's page names `lessons/`, the package `spintop-lessons` and the
/// workspace's other packages, none of which a copy holds (its tests are
/// `tests/CHAPTER.rs` of its one package). Each `from` occurs in the page
/// (a test checks it, so that a change to the page is seen here).
pub(crate) const PAGE_REWRITES: [(&str, &str); 9] = [
    (
        "The directory `lessons/` is also a small Cargo package,\n`spintop-lessons`, and a member of the workspace. It holds",
        "This copy is a small Cargo package of its own. It holds",
    ),
    (
        "The plain `cargo test` at the top of the repository does not build this\npackage (the workspace's default member is spintop itself), so the project's\nown tests stay green while the stubs are unsolved.",
        "`cargo test` grades every chapter (one test program holds them all,\nso a failing chapter hides none of the others); `cargo test --test ch2`\ngrades one.",
    ),
    (
        "`spintop course` (from the repository: `cargo run --release -- course`)",
        "`spintop course --course .` (with spintop installed)",
    ),
    (
        "`lessons/README.md` lists the rule, the\nthreat model behind it,",
        "The course's README in spintop's repository\nlists the rule, the threat model behind it,",
    ),
    (
        "cargo test -p spintop-lessons --features solutions\n",
        "cargo test\n",
    ),
    (
        "on the page [Teaching with spintop](instructors.md).",
        "on the page \"Teaching with spintop\" of spintop's book.",
    ),
    ("cargo test -p spintop-course --test course graders::\n", ""),
    ("cargo test -p spintop-lessons --test", "cargo test --test"),
    ("`lessons/src/", "`src/"),
];

/// The book's assignments page as a copy carries it ([`PAGE_REWRITES`]).
pub(crate) fn copy_page(text: &str) -> String {
    PAGE_REWRITES
        .iter()
        .fold(text.to_string(), |t, (from, to)| t.replace(from, to))
}

/// Cuts the repository's `Cargo.lock`, copied to `out`, down to the copy's
/// own packages, at the versions the repository pinned: cargo drops what the
/// copy does not use (the application's, the server's, the carried crates'
/// dev-dependencies) and adds the copy's package, so that `--locked` holds in
/// the copy. Offline first (the repository's build has every package); on a
/// machine whose cache lacks one, cargo may fetch its index.
fn prune_lock(out: &Path) -> Result<(), String> {
    let mut last = String::new();
    for offline in [true, false] {
        let mut cmd = std::process::Command::new(crate::compile::cargo_program());
        cmd.args(["metadata", "--format-version", "1"])
            .arg("--manifest-path")
            .arg(out.join("Cargo.toml"))
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        if offline {
            cmd.arg("--offline");
        }
        match cmd.output() {
            Ok(o) if o.status.success() => return Ok(()),
            Ok(o) => last = String::from_utf8_lossy(&o.stderr).trim().to_string(),
            Err(e) => last = format!("cargo: {e}"),
        }
    }
    Err(format!(
        "{}: the copy's Cargo.lock could not be made ({last})",
        out.display()
    ))
}

/// Writes a self-contained student's copy of the course in `repo` to `out`
/// (a folder that must not exist yet, or be empty): the stubs without the
/// reference solutions, the graders' tests, the book's assignments page, a
/// README, a manifest, the sources of spintop's core and graders in
/// `crates/`, so that the copy builds and grades where the repository is
/// not, and the book (`book/src`, and the lesson programs its chapters
/// include in `lessons/`), so that `spintop learn` reads it there. It names
/// no path outside itself.
pub fn export(repo: &Path, out: &Path) -> Result<Export, String> {
    export_with(repo, out, &ExportOptions::default())
}

/// [`export`], with options: `ci` adds a workflow that grades the copy on
/// every push; `link` says whether the copy carries spintop's crates (what a
/// student is handed) or names the repository's (a scratch copy graded here).
pub fn export_with(repo: &Path, out: &Path, options: &ExportOptions) -> Result<Export, String> {
    let lessons = lessons_dir(repo);
    check_lessons_dir(&lessons)?;
    if out.exists() {
        let empty = std::fs::read_dir(out)
            .map_err(|e| format!("{}: {e}", out.display()))?
            .next()
            .is_none();
        if !empty {
            return Err(format!(
                "{} is not empty; give a new folder, so that nothing is overwritten",
                out.display()
            ));
        }
    }
    let repo = repo
        .canonicalize()
        .map_err(|e| format!("{}: {e}", repo.display()))?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let crates = match options.link {
        Link::Carried => PathBuf::from("crates"),
        Link::Repository => repo.join("crates"),
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = vec![
        ("README.md".into(), EXPORT_README.as_bytes().to_vec()),
        (".gitignore".into(), b"/target\n".to_vec()),
    ];
    let tests: Vec<String> = rust_files(&lessons.join("tests"), &[])
        .iter()
        .filter(|p| p.parent() == Some(lessons.join("tests").as_path()))
        .filter_map(|p| Some(p.file_stem()?.to_str()?.to_string()))
        .collect();
    let chapters = super::binaries();
    if let Some(missing) = chapters.iter().find(|c| !tests.iter().any(|t| t == *c)) {
        return Err(format!(
            "{}: no tests/{missing}.rs, whose graders the course names",
            lessons.display()
        ));
    }
    files.push((
        "Cargo.toml".into(),
        export_manifest(&crates, out, &tests).into_bytes(),
    ));
    files.push((
        Path::new("tests").join(format!("{ALL_TESTS}.rs")),
        all_tests_source(&chapters).into_bytes(),
    ));
    for (from, strip, skip) in [("src", true, &["solutions"][..]), ("tests", false, &[][..])] {
        let base = lessons.join(from);
        for path in rust_files(&base, skip) {
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let text = if strip { strip_solutions(&text) } else { text };
            let rel = path.strip_prefix(&base).unwrap_or(&path);
            files.push((Path::new(from).join(rel), text.into_bytes()));
        }
    }
    let page = repo.join("book/src/assignments.md");
    if let Ok(text) = std::fs::read_to_string(&page) {
        files.push(("book/assignments.md".into(), copy_page(&text).into_bytes()));
    }
    if let Ok(lock) = std::fs::read(repo.join("Cargo.lock")) {
        files.push(("Cargo.lock".into(), lock));
    }
    if options.link == Link::Carried {
        files.extend(carried(&repo)?);
        // The book `spintop learn` reads in the copy, with what its chapters
        // include (a scratch copy graded here has no reader).
        let written: std::collections::HashSet<PathBuf> =
            files.iter().map(|(p, _)| p.clone()).collect();
        files.extend(book::book_files(&repo, copy_page, |p| written.contains(p))?);
    }
    if options.ci == Some(Ci::Github) {
        files.push((
            GITHUB_WORKFLOW.into(),
            GITHUB_WORKFLOW_TEXT.as_bytes().to_vec(),
        ));
    }
    for (rel, bytes) in &files {
        let path = out.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        }
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    if out.join("Cargo.lock").is_file() {
        prune_lock(out)?;
    }
    Ok(Export {
        files: files.into_iter().map(|(p, _)| p).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::COURSE;

    #[test]
    fn an_export_holds_the_stubs_and_graders_and_no_solution() {
        let root = crate::repository();
        let out = std::env::temp_dir().join(format!("spintop-export-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        let written = export(root, &out).unwrap();
        for a in COURSE {
            let file = a.file.trim_start_matches("lessons/");
            let text = std::fs::read_to_string(out.join(file)).unwrap();
            let start = text.find(&format!("pub fn {}(", a.function)).unwrap();
            let body = &text[start..start + text[start..].find("\n}").unwrap()];
            assert!(
                body.contains("todo!("),
                "{}: the stub, not a solution",
                a.function
            );
            assert!(out.join("tests").join(format!("{}.rs", a.binary)).is_file());
        }
        for rel in &written.files {
            let text = std::fs::read_to_string(out.join(rel)).unwrap();
            if rel.starts_with("src") || rel.ends_with("Cargo.toml") {
                assert!(
                    !text.contains("solutions"),
                    "{} mentions the solutions",
                    rel.display()
                );
            }
        }
        assert!(!out.join("src/solutions").exists());
        // Every solution's body is absent from every exported source file.
        for entry in std::fs::read_dir(root.join("lessons/src/solutions")).unwrap() {
            let solution = std::fs::read_to_string(entry.unwrap().path()).unwrap();
            for body in solution.split("\npub fn ").skip(1) {
                let body = &body[body.find('{').unwrap()..];
                let body = &body[..body.find("\n}").unwrap_or(body.len())];
                if body.lines().count() < 3 {
                    continue;
                }
                // Nor in the book and the lessons it includes.
                let outside_crates = |p: &&PathBuf| !p.starts_with("crates");
                for rel in written.files.iter().filter(outside_crates) {
                    let text = std::fs::read_to_string(out.join(rel)).unwrap();
                    assert!(!text.contains(body), "{} holds a solution", rel.display());
                }
            }
        }
        let manifest = std::fs::read_to_string(out.join("Cargo.toml")).unwrap();
        assert!(
            manifest.contains("[workspace]")
                && manifest.contains("spintop = { path")
                && manifest.contains("spintop-grading = { path")
        );
        // The copy's workspace is its own package: the carried crates are
        // not members (their tests and dev-dependencies are not carried).
        // Asked of cargo itself (`--no-deps`: offline, no resolution), since
        // what the manifest says and what cargo makes of it have differed
        // (`members = ["."]` once made every carried crate a member).
        let metadata = std::process::Command::new(crate::compile::cargo_program())
            .args([
                "metadata",
                "--no-deps",
                "--offline",
                "--format-version",
                "1",
            ])
            .current_dir(&out)
            .env_remove("CARGO_TARGET_DIR")
            .output()
            .unwrap();
        assert!(
            metadata.status.success(),
            "{}",
            String::from_utf8_lossy(&metadata.stderr)
        );
        let metadata: serde_json::Value = serde_json::from_slice(&metadata.stdout).unwrap();
        let members = metadata["workspace_members"].as_array().unwrap();
        assert_eq!(members.len(), 1, "{members:?}");
        assert!(
            members[0].as_str().unwrap().contains("spintop-lessons-"),
            "{members:?}"
        );
        // The book and its lessons are read, never built: the package's
        // targets are its src/ and tests/ alone.
        let copy = out.canonicalize().unwrap();
        let targets = metadata["packages"][0]["targets"].as_array().unwrap();
        assert!(targets.len() > 5, "{targets:?}");
        for t in targets {
            let path = Path::new(t["src_path"].as_str().unwrap());
            assert!(
                path.starts_with(copy.join("src")) || path.starts_with(copy.join("tests")),
                "{}",
                path.display()
            );
        }
        copy_carries_the_book(root, &out, &written);
        // The lock is the copy's own: its package in, the application's and
        // the dev-dependencies' out (the repository's would fail --locked).
        let lock = std::fs::read_to_string(out.join("Cargo.lock")).unwrap();
        assert!(lock.contains("name = \"spintop-lessons-"), "{lock}");
        for absent in ["ratatui", "clap", "proptest", "insta", "spintop-course"] {
            assert!(
                !lock.contains(&format!("name = \"{absent}\"")),
                "the copy's Cargo.lock holds {absent}"
            );
        }
        one_test_program_holds_every_chapter(&out, targets);
        // A second export into the same folder is refused, nothing overwritten.
        assert!(export(root, &out).unwrap_err().contains("not empty"));
        std::fs::remove_dir_all(&out).unwrap();
    }

    /// A plain `cargo test` in the copy runs one program that holds every
    /// chapter's graders (cargo stops at the first test program that
    /// fails); each chapter's is built only when named (`targets`: cargo's
    /// metadata of the copy's package).
    fn one_test_program_holds_every_chapter(out: &Path, targets: &[serde_json::Value]) {
        let tests: Vec<(&str, bool)> = targets
            .iter()
            .filter(|t| t["kind"][0] == "test")
            .map(|t| (t["name"].as_str().unwrap(), t["test"].as_bool().unwrap()))
            .collect();
        let plain: Vec<&str> = tests.iter().filter(|t| t.1).map(|t| t.0).collect();
        assert_eq!(plain, [ALL_TESTS], "{tests:?}");
        for c in crate::binaries().into_iter().chain(["probe"]) {
            assert!(tests.contains(&(c, false)), "{c}: {tests:?}");
        }
        let all =
            std::fs::read_to_string(out.join("tests").join(format!("{ALL_TESTS}.rs"))).unwrap();
        for c in crate::binaries() {
            assert!(
                all.contains(&format!("#[path = \"{c}.rs\"]\nmod {c};")),
                "{all}"
            );
        }
        assert!(!all.contains("probe"), "{all}");
    }

    /// The copy's book: `book/src` as the repository holds it but KaTeX's
    /// files, its assignments page the copy's, and every file a chapter
    /// includes there, with the anchor the chapter names.
    fn copy_carries_the_book(root: &Path, out: &Path, written: &Export) {
        let src = Path::new(book::BOOK_SRC);
        let summary = std::fs::read(root.join(src).join("SUMMARY.md")).unwrap();
        assert_eq!(
            std::fs::read(out.join(src).join("SUMMARY.md")).unwrap(),
            summary
        );
        assert!(!out.join(src).join("katex").exists());
        assert!(root.join(src).join("katex").is_dir());
        let page = std::fs::read_to_string(root.join(src).join("assignments.md")).unwrap();
        let copied = std::fs::read_to_string(out.join(src).join("assignments.md")).unwrap();
        assert_eq!(copied, copy_page(&page));
        assert_ne!(copied, page);
        let mut resolved = 0;
        for rel in written.files.iter().filter(|p| p.starts_with(src)) {
            if rel.extension().is_none_or(|x| x != "md") {
                continue;
            }
            let text = std::fs::read_to_string(out.join(rel)).unwrap();
            let dir = rel.parent().unwrap();
            for piece in text.split("{{#include ").skip(1) {
                let spec = &piece[..piece.find("}}").unwrap()];
                let (path, anchor) = spec.rsplit_once(':').unwrap_or((spec, ""));
                let target = std::fs::read_to_string(out.join(dir).join(path))
                    .unwrap_or_else(|e| panic!("{}: {spec}: {e}", rel.display()));
                assert!(
                    anchor.is_empty() || target.contains(&format!("ANCHOR: {anchor}")),
                    "{}: {spec}",
                    rel.display()
                );
                resolved += 1;
            }
        }
        assert!(resolved >= 50, "{resolved} includes");
        assert!(out.join("lessons/README.md").is_file());
    }

    /// The assignments page a copy carries names only what the copy holds:
    /// no `lessons/` folder, no other package, no `solutions` feature, and
    /// every `--test` target it names is one of its `tests/*.rs`.
    #[test]
    fn the_copys_assignments_page_names_what_the_copy_holds() {
        let root = crate::repository();
        let page = std::fs::read_to_string(root.join("book/src/assignments.md")).unwrap();
        for (from, _) in PAGE_REWRITES {
            assert!(page.contains(from), "the page no longer says {from:?}");
        }
        let copy = copy_page(&page);
        for absent in [
            "lessons/",
            " -p ",
            "--features",
            "spintop-lessons",
            "workspace",
            "cargo run",
            "](",
        ] {
            assert!(!copy.contains(absent), "the copy's page names {absent:?}");
        }
        let mut named = 0;
        for part in copy.split("cargo test").skip(1) {
            if let Some(rest) = part.trim_start().strip_prefix("--test ") {
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                assert!(
                    root.join("lessons/tests")
                        .join(format!("{name}.rs"))
                        .is_file(),
                    "--test {name}"
                );
                named += 1;
            }
        }
        assert!(named >= 2, "{copy}");
        assert!(copy.contains("\ncargo test\n"), "{copy}");
        assert!(!copy.contains("no-fail-fast"), "{copy}");
    }

    #[test]
    fn stripping_the_solutions_keeps_the_stub() {
        let text = "use a;\n#[cfg(not(feature = \"solutions\"))]\npub fn f() {\n    todo!()\n}\n\n#[cfg(feature = \"solutions\")]\npub use crate::solutions::ch2::*;\n";
        assert_eq!(
            strip_solutions(text),
            "use a;\npub fn f() {\n    todo!()\n}\n"
        );
    }

    #[test]
    fn two_copies_never_share_a_package_name() {
        // Cargo would otherwise reuse one copy's test programs for the other
        // when they share a build folder (see export_manifest).
        let spintop = crate::repository();
        let a = export_manifest(spintop, Path::new("/tmp/course/alice"), &[]);
        let b = export_manifest(spintop, Path::new("/tmp/course/bob"), &[]);
        let name = |m: &str| {
            m.lines()
                .find(|l| l.starts_with("name = \"spintop-lessons"))
                .unwrap()
                .to_string()
        };
        assert_ne!(name(&a), name(&b));
        for m in [&a, &b] {
            assert!(m.contains("[lib]\nname = \"spintop_lessons\""), "{m}");
        }
    }
}
