//! Diagnoses measured: a folder of wrong answers, each graded, each with the
//! diagnosis its grader gives, so that an instructor (or a reviewer who did
//! not write the graders) can count how often the diagnosis names the
//! actual mistake.
//!
//! A wrong answer is one `.rs` file: a header of `//!` lines naming the
//! assignment and the mistake, then the student's function (and any helper
//! it needs), written as in `lessons/src/`:
//!
//! ```text
//! //! assignment: larmor_rate
//! //! mistake: the cross product in the wrong order
//! //! says: sign
//! use spintop::assignment::{Jet, Vec3};
//! pub fn larmor_rate(jet: &Jet) -> Vec3 {
//!     jet[2].cross(&jet[1])
//! }
//! ```
//!
//! `says:` (optional) is a few words the diagnosis is expected to contain.
//! The answers are compiled together into one program beside the reference
//! solutions (so `crate::ch4::reduced_ale_rhs` and the like are right), and
//! each is graded in a process of its own, under a time limit.

use super::compile::{self, Built};
use super::process::{self, Ctx};
use super::{Assignment, find};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// One wrong answer of a folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrongAnswer {
    /// Its file.
    pub file: PathBuf,
    /// The assignment it answers.
    pub assignment: &'static Assignment,
    /// What is wrong with it, in its author's words.
    pub mistake: String,
    /// Words the diagnosis should contain, if its author gave them.
    pub says: Option<String>,
    /// Its code (the header included).
    pub code: String,
}

/// Reads every `*.rs` file of `dir` as a wrong answer, sorted by name.
pub fn read_folder(dir: &Path) -> Result<Vec<WrongAnswer>, String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!(
            "{}: no .rs files (one wrong answer each)",
            dir.display()
        ));
    }
    files.into_iter().map(|f| read_answer(&f)).collect()
}

fn read_answer(file: &Path) -> Result<WrongAnswer, String> {
    let code = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let field = |key: &str| {
        code.lines()
            .filter_map(|l| l.trim().strip_prefix("//!"))
            .find_map(|l| l.trim().strip_prefix(key).map(|v| v.trim().to_string()))
    };
    let name = field("assignment:").ok_or_else(|| {
        format!(
            "{}: the header has no `//! assignment: NAME` line",
            file.display()
        )
    })?;
    let assignment =
        find(&name).ok_or_else(|| format!("{}: no assignment called {name}", file.display()))?;
    if !code.contains(&format!("fn {}(", assignment.function)) {
        return Err(format!(
            "{}: no `pub fn {}(…)` in it",
            file.display(),
            assignment.function
        ));
    }
    Ok(WrongAnswer {
        file: file.to_path_buf(),
        assignment,
        mistake: field("mistake:").unwrap_or_default(),
        says: field("says:").filter(|s| !s.is_empty()),
        code,
    })
}

/// A wrong answer and what its grader said.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnosed {
    /// The answer.
    pub answer: WrongAnswer,
    /// Whether the grader accepted it (a wrong answer should not pass).
    pub passed: bool,
    /// The grader's diagnosis (or why there is none).
    pub diagnosis: String,
}

impl Diagnosed {
    /// Whether the diagnosis contains the words the answer's file expects
    /// (`None` when it expects none): a phrase, or a list of words separated
    /// by commas of which more than half must be there (see [`contains`]).
    pub fn says_it(&self) -> Option<bool> {
        self.words_found().map(|(found, of)| 2 * found > of)
    }

    /// How many of the expected words the diagnosis contains, of how many.
    pub fn words_found(&self) -> Option<(usize, usize)> {
        let says = self.answer.says.as_ref()?;
        let words: Vec<&str> = says
            .split(',')
            .map(str::trim)
            .filter(|w| !w.is_empty())
            .collect();
        let found = words
            .iter()
            .filter(|w| contains(&self.diagnosis, w))
            .count();
        Some((found, words.len()))
    }

    /// One block of text.
    pub fn text(&self) -> String {
        let name = self
            .answer
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let verdict = if self.passed {
            "PASSED (the grader accepted a wrong answer)".to_string()
        } else {
            self.diagnosis.clone()
        };
        let check = match (self.says_it(), self.words_found()) {
            (Some(true), Some((f, n))) if n > 1 => format!(" [says it: {f} of {n} words]"),
            (Some(false), Some((f, n))) if n > 1 => format!(" [does not say it: {f} of {n} words]"),
            (Some(true), _) => " [says it]".to_string(),
            (Some(false), _) => " [does not say it]".to_string(),
            (None, _) => String::new(),
        };

        format!(
            "{name} ({}): {}\n  diagnosis: {verdict}{check}",
            self.answer.assignment.function, self.answer.mistake
        )
    }

    /// One JSON object.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "file": self.answer.file.display().to_string(),
            "assignment": self.answer.assignment.function,
            "mistake": self.answer.mistake,
            "passed": self.passed,
            "diagnosis": self.diagnosis,
            "says": self.answer.says,
            "says_it": self.says_it(),
        })
    }
}

/// Text as the word test reads it: lower case, a hyphen as a space (so
/// "left-hand" is "left hand"), the cross product's `×` as `x`.
fn normal(text: &str) -> String {
    text.to_lowercase().replace('-', " ").replace('×', "x")
}

/// Whether `text` contains `word` as a word (or words): not inside another
/// word ("p" is not found in "step", "d'" not in "d''"), though a plural or
/// a possessive counts ("rows" for "row", "Euler's" for "euler").
/// Letters, digits, `_` and `'` make up words.
pub fn contains(text: &str, word: &str) -> bool {
    let (text, word) = (normal(text), normal(word));
    let is_word = |c: char| c.is_alphanumeric() || c == '_' || c == '\'';
    let (first, last) = match (word.chars().next(), word.chars().last()) {
        (Some(f), Some(l)) => (f, l),
        _ => return false,
    };
    text.match_indices(&word).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = &text[i + word.len()..];
        let starts = !is_word(first) || before.is_none_or(|c| !is_word(c));
        let ends = !is_word(last)
            || ["'s", "es", "s", "ed", "d", ""].iter().any(|suffix| {
                after
                    .strip_prefix(suffix)
                    .is_some_and(|r| r.chars().next().is_none_or(|c| !is_word(c)))
            });
        starts && ends
    })
}

/// The program that grades answer number ARG at seed ARG.
fn main_rs(answers: &[WrongAnswer]) -> String {
    let mut arms = String::new();
    for (i, a) in answers.iter().enumerate() {
        arms.push_str(&format!(
            "        {i} => spintop_grading::{f}(seed, wrong::w{i:03}::{f}),\n",
            f = a.assignment.function
        ));
    }
    let mods: String = (0..answers.len())
        .map(|i| format!("    pub mod w{i:03};\n"))
        .collect();
    format!(
        "//! Generated by `spintop course diagnose`: grades one wrong answer.\n#![allow(dead_code, unused_imports, unused_variables, unused_mut, clippy::all)]\n\nmod appendix;\nmod ch2;\nmod ch3;\nmod ch4;\nmod numerics;\nmod wrong {{\n{mods}}}\n\nfn main() {{\n    let mut args = std::env::args().skip(1);\n    let which: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(usize::MAX);\n    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(0);\n    let grade = match which {{\n{arms}        _ => return,\n    }};\n    match grade {{\n        Ok(_) => println!(\"passed\"),\n        Err(f) => println!(\"failed\\t{{}}\", f.diagnosis.replace(['\\n', '\\t'], \" \")),\n    }}\n}}\n"
    )
}

/// Grades every answer at `seed` and returns what each grader said. `work`
/// is a scratch folder (emptied first); the build shares the repository's
/// build folder.
pub fn run(
    repo: &Path,
    answers: &[WrongAnswer],
    seed: u64,
    work: &Path,
) -> Result<Vec<Diagnosed>, String> {
    lay_out(repo, answers, work)?;
    let ctx = Ctx {
        stop: None,
        deadline: Some(Instant::now() + Duration::from_secs(1800)),
    };
    let exe = build(repo, answers, work, &ctx)?;
    grade_each(&exe, answers, seed, &ctx)
}

/// Writes the scratch crate in `work` (emptied first): the reference
/// solutions as the course's modules, each answer a module of `wrong`, and
/// a `main` that grades one by its number.
fn lay_out(repo: &Path, answers: &[WrongAnswer], work: &Path) -> Result<(), String> {
    if work.exists() {
        std::fs::remove_dir_all(work).map_err(|e| format!("{}: {e}", work.display()))?;
    }
    let src = work.join("src");
    std::fs::create_dir_all(src.join("wrong")).map_err(|e| format!("{}: {e}", src.display()))?;
    let spintop = repo
        .canonicalize()
        .map_err(|e| format!("{}: {e}", repo.display()))?;
    // NOTE: named after the scratch folder, as an exported copy is (see
    // `export_manifest`): two gradings of two folders that share a build
    // folder would otherwise overwrite each other's program.
    let key = spintop::numbers::stable_key(
        &work
            .canonicalize()
            .unwrap_or_else(|_| work.to_path_buf())
            .to_string_lossy(),
    );
    let manifest = format!(
        "[package]\nname = \"spintop-diagnose-{key:08x}\"\nversion = \"0.1.0\"\nedition = \"2024\"\npublish = false\n\n[workspace]\n\n[dependencies]\nspintop = {{ path = {:?} }}\nspintop-grading = {{ path = {:?} }}\n",
        spintop.join("crates/spintop").display().to_string(),
        spintop.join("crates/spintop-grading").display().to_string()
    );
    let mut files: Vec<(PathBuf, String)> = vec![
        (work.join("Cargo.toml"), manifest),
        (src.join("main.rs"), main_rs(answers)),
    ];
    for module in ["appendix", "ch2", "ch3", "ch4", "numerics"] {
        let from = super::lessons_dir(repo)
            .join("src/solutions")
            .join(format!("{module}.rs"));
        let text =
            std::fs::read_to_string(&from).map_err(|e| format!("{}: {e}", from.display()))?;
        files.push((src.join(format!("{module}.rs")), text));
    }
    for (i, a) in answers.iter().enumerate() {
        files.push((
            src.join("wrong").join(format!("w{i:03}.rs")),
            a.code.clone(),
        ));
    }
    if let Ok(lock) = std::fs::read_to_string(repo.join("Cargo.lock")) {
        files.push((work.join("Cargo.lock"), lock));
    }
    for (path, text) in &files {
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

/// Builds the scratch crate in `work` (in the repository's build folder):
/// its program, or the first error, named by the wrong answer's own file.
fn build(repo: &Path, answers: &[WrongAnswer], work: &Path, ctx: &Ctx) -> Result<PathBuf, String> {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo.join("target"));
    let built =
        compile::cargo_json(work, &["build"], Some(&target), ctx).map_err(|e| e.to_string())?;
    match built {
        Built::Programs(p) => p
            .into_iter()
            .next()
            .map(|(_, exe)| exe)
            .ok_or_else(|| "cargo built no program".to_string()),
        Built::Failed(errors) => {
            let e = errors.first().cloned().unwrap_or_else(|| super::Located {
                file: "?".into(),
                line: 1,
                message: "the build failed".into(),
            });
            // Name the wrong answer's own file, not the scratch copy.
            let file = Path::new(&e.file)
                .file_stem()
                .and_then(|s| s.to_str())
                .and_then(|s| s.strip_prefix('w'))
                .and_then(|n| n.parse::<usize>().ok())
                .and_then(|i| answers.get(i))
                .map(|a| a.file.display().to_string())
                .unwrap_or(e.file.clone());
            Err(format!(
                "{file}:{}: {} (fix it, or leave it out)",
                e.line, e.message
            ))
        }
        Built::OutOfTime | Built::Bounded(_) => {
            Err("the build did not finish in 30 minutes".into())
        }
    }
}

/// Runs the program `exe` once per answer at `seed`: what each grader said.
fn grade_each(
    exe: &Path,
    answers: &[WrongAnswer],
    seed: u64,
    ctx: &Ctx,
) -> Result<Vec<Diagnosed>, String> {
    let mut out = Vec::new();
    for (i, a) in answers.iter().enumerate() {
        let mut cmd = Command::new(exe);
        cmd.args([i.to_string(), seed.to_string()])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null());
        let mut child =
            process::spawn_group(&mut cmd).map_err(|e| format!("{}: {e}", exe.display()))?;
        let stdout = process::drain(child.stdout.take(), 64 * 1024);
        let status = process::wait_within(&mut child, Duration::from_secs(60), ctx);
        let text = String::from_utf8_lossy(&stdout.join().unwrap_or_default()).into_owned();
        let line = text.lines().next().unwrap_or_default();
        let (passed, diagnosis) = match (status, line.split_once('\t')) {
            (None, _) => (
                false,
                "(no verdict within 60 s: the grader or the answer loops)".into(),
            ),
            (Some(_), None) if line == "passed" => (true, String::new()),
            (Some(_), Some(("failed", d))) => (false, d.to_string()),
            (Some(s), _) => (
                false,
                format!("(the grading process ended without a verdict: {s})"),
            ),
        };
        out.push(Diagnosed {
            answer: a.clone(),
            passed,
            diagnosis,
        });
    }
    Ok(out)
}
