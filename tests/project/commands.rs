//! Every `cargo test … --test NAME` the repository's text tells a reader to
//! run names a test target that exists, in the package the command would run
//! in: the one `-p` names, or else the package whose folder holds the text
//! (or a student's copy, which is the lessons package on its own). Test
//! targets were renamed when the house became a workspace with one test
//! binary per crate, and a stale `--test physics` in an `#[ignore]` reason
//! sends the reader to "no test target named `physics`".

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A package of the workspace: its name and its test targets.
struct Package {
    name: String,
    tests: BTreeSet<String>,
}

/// The package whose manifest is `dir/Cargo.toml`: the `[[test]]` targets,
/// and with `autotests` (cargo's default) every `tests/NAME.rs` and
/// `tests/NAME/main.rs`.
fn package(dir: &Path) -> Option<Package> {
    let text = std::fs::read_to_string(dir.join("Cargo.toml")).ok()?;
    let manifest: toml::Table = text.parse().unwrap();
    let pkg = manifest.get("package")?.as_table()?;
    let mut tests = BTreeSet::new();
    for t in manifest
        .get("test")
        .and_then(|t| t.as_array())
        .into_iter()
        .flatten()
    {
        tests.insert(t["name"].as_str().unwrap().to_string());
    }
    if pkg.get("autotests").and_then(|a| a.as_bool()) != Some(false) {
        for e in std::fs::read_dir(dir.join("tests"))
            .into_iter()
            .flatten()
            .flatten()
        {
            let p = e.path();
            let stem = p.file_stem().unwrap().to_string_lossy().to_string();
            if p.extension().is_some_and(|x| x == "rs") || p.join("main.rs").is_file() {
                tests.insert(stem);
            }
        }
    }
    Some(Package {
        name: pkg["name"].as_str().unwrap().to_string(),
        tests,
    })
}

/// The workspace's packages, by folder relative to the root ("" for it).
fn packages() -> BTreeMap<PathBuf, Package> {
    let root = root();
    let mut dirs = vec![PathBuf::new(), "lessons".into(), "benches".into()];
    for e in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        dirs.push(Path::new("crates").join(e.file_name()));
    }
    dirs.into_iter()
        .filter_map(|d| package(&root.join(&d)).map(|p| (d, p)))
        .collect()
}

/// The repository's text files: sources, manifests, pages, scripts.
fn text_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().to_string();
        if e.file_type().unwrap().is_dir() {
            if !matches!(name.as_str(), "target" | ".git" | "node_modules") {
                text_files(&p, out);
            }
        } else if ["rs", "md", "toml", "yml", "yaml", "py", "sh"]
            .iter()
            .any(|x| name.ends_with(&format!(".{x}")))
            || p.parent()
                .is_some_and(|d| d.file_name().is_some_and(|n| n == ".ci"))
        {
            out.push(p);
        }
    }
}

/// The `cargo test` commands of `line`: for each, the package `-p` names
/// (if any) and the `--test` target.
fn commands(line: &str) -> Vec<(Option<String>, String)> {
    let mut out = Vec::new();
    for part in line.split("cargo test").skip(1) {
        let end = part
            .find(['`', '"', ')', ';', '#', '|', '&'])
            .unwrap_or(part.len());
        let words: Vec<&str> = part[..end]
            .split_whitespace()
            .take_while(|w| *w != "--")
            .collect();
        let after = |flag: &[&str]| {
            words
                .windows(2)
                .find(|w| flag.contains(&w[0]))
                .map(|w| w[1].to_string())
        };
        let name = |w: &String| {
            w.starts_with(|c: char| c.is_ascii_lowercase())
                && w.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        };
        if let Some(test) = after(&["--test"]).filter(name) {
            out.push((after(&["-p", "--package"]), test));
        }
    }
    out
}

#[test]
fn every_cargo_test_command_in_the_text_names_an_existing_test_target() {
    let root = root();
    let packages = packages();
    let by_name: BTreeMap<&str, &Package> =
        packages.values().map(|p| (p.name.as_str(), p)).collect();
    let lessons = &packages[Path::new("lessons")];
    let mut files = Vec::new();
    text_files(&root, &mut files);
    let mut checked = 0;
    let mut wrong = Vec::new();
    for file in files {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        let rel = file.strip_prefix(&root).unwrap();
        // The package whose folder holds the file (the deepest).
        let home = packages
            .iter()
            .filter(|(d, _)| rel.starts_with(d))
            .max_by_key(|(d, _)| d.components().count())
            .map(|(_, p)| p)
            .unwrap();
        for (n, line) in text.lines().enumerate() {
            for (pkg, test) in commands(line) {
                checked += 1;
                let ok = match &pkg {
                    Some(p) => by_name
                        .get(p.as_str())
                        .is_some_and(|p| p.tests.contains(&test)),
                    None => home.tests.contains(&test) || lessons.tests.contains(&test),
                };
                if !ok {
                    wrong.push(format!(
                        "{}:{}: `--test {test}` is no test target of {} (it has: {:?})",
                        rel.display(),
                        n + 1,
                        pkg.as_deref().unwrap_or(&home.name),
                        pkg.as_deref()
                            .and_then(|p| by_name.get(p))
                            .unwrap_or(&home)
                            .tests
                    ));
                }
            }
        }
    }
    assert!(checked >= 10, "only {checked} commands found");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn a_command_is_read_as_cargo_reads_it() {
    assert_eq!(
        commands("run `UPDATE_BOOK=1 cargo test -p spintop-app --test app project::` now"),
        vec![(Some("spintop-app".into()), "app".into())]
    );
    // (Written in two parts, so that this file's text names no stale target.)
    let stale = format!(
        "\"a finer grid: cargo {} --test physics auto_ -- --ignored\"",
        "test"
    );
    assert_eq!(commands(&stale), vec![(None, "physics".into())]);
    assert!(commands("cargo test -p <package> --test <binary>").is_empty());
    assert!(commands("cargo test -- --test-threads 1").is_empty());
}
