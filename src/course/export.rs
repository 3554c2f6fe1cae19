//! The export: a self-contained student's copy of the course (stubs without
//! the reference solutions, the graders, the assignments page, a README, a
//! manifest), optionally with a CI workflow that grades it on every push.

use std::path::{Path, PathBuf};

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
                stack.push(path);
            } else if kind.is_file() && path.extension().is_some_and(|x| x == "rs") {
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

/// How to export.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ExportOptions {
    /// Add a workflow that grades the copy on every push (and, so that the
    /// copy builds on a machine without this repository, a copy of
    /// spintop's core in `spintop/`).
    pub ci: Option<Ci>,
}

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
/// workspace), depending on spintop at `spintop` (an absolute path, or a
/// path inside the copy).
///
/// NOTE: the package is named after the copy's folder (spintop-lessons-HASH;
/// the library keeps the name `spintop_lessons`). Cargo keys its build
/// artifacts on a path package's name, version and place in its own workspace,
/// not on where the workspace is, so two copies named alike that share a build
/// folder (`CARGO_TARGET_DIR`, as `course grade` and the tests do) would reuse
/// each other's test programs when one copy's sources look unchanged: one
/// student graded with another's code.
pub(crate) fn export_manifest(spintop: &Path, out: &Path) -> String {
    let key = crate::numbers::stable_key(
        &out.canonicalize()
            .unwrap_or_else(|_| out.to_path_buf())
            .to_string_lossy(),
    );
    format!(
        r#"[package]
name = "spintop-lessons-{key:08x}"
version = "0.1.0"
edition = "2024"
publish = false
description = "Course assignments on Duviryak's polarized spinning top, graded by cargo test."

# A course of its own, not a member of any other workspace.
[workspace]

[lib]
name = "spintop_lessons"
path = "src/lib.rs"

[dependencies]
# The core only: grading does not compile the terminal UI, the plots or the command line.
spintop = {{ path = {path:?}, default-features = false }}
"#,
        path = spintop.display().to_string()
    )
}

const EXPORT_README: &str = "# The spintop course

Assignments on A. Duviryak's polarized spinning top, graded by `cargo test`.
Every function under `src/` is a stub that ends in `todo!()`; the chapter of
the book it comes from is named in its doc comment (the assignments page is in
`book/`).

Two commands:

```sh
cargo test                     # grade every assignment (fresh inputs each time)
cargo test --test ch2          # grade one chapter's assignments
SPINTOP_SEED=123 cargo test    # the inputs of a failure again (its report gives the seed)
```

With spintop installed, `spintop course --course .` lists the assignments in
course order with their state and what to do next (it also checks the source
rule, as the instructor's grading does: your files may use `spintop::math`
and `spintop::assignment`, and nothing that reads files, the environment or
other programs), and `spintop learn --course .` opens the book in the
terminal and re-grades on every save.
";

/// The manifest of spintop's core alone (no feature `app`), for a copy that
/// must build without the repository: the core's dependencies of `repo`'s
/// manifest, as pinned there.
fn core_manifest(repo: &Path) -> Result<String, String> {
    let path = repo.join("Cargo.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let manifest: toml::Table = text
        .parse()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let package = manifest.get("package").and_then(|p| p.as_table());
    let field = |k: &str| {
        package
            .and_then(|p| p.get(k))
            .and_then(|v| v.as_str())
            .unwrap_or_default()
            .to_string()
    };
    let mut deps = toml::Table::new();
    if let Some(all) = manifest.get("dependencies").and_then(|d| d.as_table()) {
        for (name, spec) in all {
            let optional = spec
                .get("optional")
                .and_then(|o| o.as_bool())
                .unwrap_or(false);
            if !optional {
                deps.insert(name.clone(), spec.clone());
            }
        }
    }
    let deps: Vec<String> = deps
        .iter()
        .map(|(name, spec)| format!("{name} = {}", toml_value(spec)))
        .collect();
    Ok(format!(
        "# spintop's core (physics, integrators, graders), copied by `spintop course export --ci github`\n\
         # so that this course builds where the repository is not.\n\
         [package]\nname = \"spintop\"\nversion = {}\nedition = {}\nlicense = {}\npublish = false\n\n\
         [lib]\npath = \"src/lib.rs\"\n\n\
         # Declared so that the core's `cfg(feature = \"app\")` items stay known (and off).\n\
         [features]\ndefault = []\napp = []\n\n[dependencies]\n{}\n",
        toml_value(&field("version").into()),
        toml_value(&field("edition").into()),
        toml_value(&field("license").into()),
        deps.join("\n")
    ))
}

/// A TOML value as it is written in a manifest (strings, numbers, booleans,
/// arrays and inline tables: what a dependency's line holds).
fn toml_value(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => f.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Array(items) => {
            let items: Vec<String> = items.iter().map(toml_value).collect();
            format!("[{}]", items.join(", "))
        }
        toml::Value::Table(t) => {
            let items: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", toml_value(v)))
                .collect();
            format!("{{ {} }}", items.join(", "))
        }
        toml::Value::Datetime(d) => format!("{d:?}"),
    }
}

/// The modules of the library `repo/src/lib.rs` that only the shells build
/// (`#[cfg(feature = "app")] pub mod NAME;`).
fn app_modules(repo: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(repo.join("src/lib.rs")).unwrap_or_default();
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    lines
        .windows(2)
        .filter(|w| w[0] == "#[cfg(feature = \"app\")]")
        .filter_map(|w| w[1].strip_prefix("pub mod ")?.strip_suffix(';'))
        .map(str::to_string)
        .collect()
}

/// Writes a self-contained student's copy of the course in `repo` to `out`
/// (a folder that must not exist yet, or be empty): the stubs without the
/// reference solutions, the graders, the book's assignments page, a README
/// and a manifest that builds on its own against the spintop in `repo`.
pub fn export(repo: &Path, out: &Path) -> Result<Export, String> {
    export_with(repo, out, &ExportOptions::default())
}

/// [`export`], with options: `ci` adds a workflow that grades the copy on
/// every push, and a copy of spintop's core for it to build against.
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
    let spintop = repo
        .canonicalize()
        .map_err(|e| format!("{}: {e}", repo.display()))?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let dependency = match options.ci {
        Some(Ci::Github) => PathBuf::from("spintop"),
        None => spintop.clone(),
    };
    let mut files: Vec<(PathBuf, String)> = vec![
        ("Cargo.toml".into(), export_manifest(&dependency, out)),
        ("README.md".into(), EXPORT_README.to_string()),
        (".gitignore".into(), "/target\n".to_string()),
    ];
    for (from, strip, skip) in [("src", true, &["solutions"][..]), ("tests", false, &[][..])] {
        let base = lessons.join(from);
        for path in rust_files(&base, skip) {
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let text = if strip { strip_solutions(&text) } else { text };
            let rel = path.strip_prefix(&base).unwrap_or(&path);
            files.push((Path::new(from).join(rel), text));
        }
    }
    let page = repo.join("book/src/assignments.md");
    if let Ok(text) = std::fs::read_to_string(&page) {
        files.push(("book/assignments.md".into(), text));
    }
    if let Ok(lock) = std::fs::read_to_string(repo.join("Cargo.lock")) {
        files.push(("Cargo.lock".into(), lock));
    }
    if options.ci == Some(Ci::Github) {
        files.push((GITHUB_WORKFLOW.into(), GITHUB_WORKFLOW_TEXT.to_string()));
        files.push(("spintop/Cargo.toml".into(), core_manifest(&spintop)?));
        let src = spintop.join("src");
        let skip: Vec<String> = app_modules(&spintop)
            .into_iter()
            .flat_map(|m| [format!("{m}.rs"), m])
            .collect();
        let skip: Vec<&str> = skip.iter().map(String::as_str).collect();
        for path in rust_files(&src, &skip) {
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let rel = path.strip_prefix(&src).unwrap_or(&path);
            files.push((Path::new("spintop/src").join(rel), text));
        }
    }
    for (rel, text) in &files {
        let path = out.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        }
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(Export {
        files: files.into_iter().map(|(p, _)| p).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::course::COURSE;

    #[test]
    fn an_export_holds_the_stubs_and_graders_and_no_solution() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
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
                for rel in written.files.iter().filter(|p| p.starts_with("src")) {
                    let text = std::fs::read_to_string(out.join(rel)).unwrap();
                    assert!(!text.contains(body), "{} holds a solution", rel.display());
                }
            }
        }
        let manifest = std::fs::read_to_string(out.join("Cargo.toml")).unwrap();
        assert!(
            manifest.contains("[workspace]")
                && manifest.contains("spintop = { path")
                && manifest.contains("default-features = false")
        );
        // A second export into the same folder is refused, nothing overwritten.
        assert!(export(root, &out).unwrap_err().contains("not empty"));
        std::fs::remove_dir_all(&out).unwrap();
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
        let spintop = Path::new(env!("CARGO_MANIFEST_DIR"));
        let a = export_manifest(spintop, Path::new("/tmp/course/alice"));
        let b = export_manifest(spintop, Path::new("/tmp/course/bob"));
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
