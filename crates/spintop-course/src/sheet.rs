//! What a class's grading writes: a CSV file and Gradescope's
//! `results.json`, each safe to open. A CSV cell that a spreadsheet would
//! read as a formula (`=`, `+`, `-`, `@` first, after any spaces, or a tab
//! or a carriage return first: OWASP's list) is neutralised with a leading `'`; a reason comes from the
//! verdict's structure (the diagnosis, the compiler's error), never from
//! text the student's code chose (a panic's message); each student has a
//! total.

use super::gradebook::{Class, Copy, Outcome};
use super::{COURSE, COURSE_LEN};
use std::path::Path;

/// The CSV header.
pub const CSV_HEADER: &str = "student,assignment,equation,state,score,hint_rungs_used,seed,reason";

/// The assignment column of a student's total row.
pub const TOTAL: &str = "total";

/// Whether a spreadsheet may read `s` as a formula: `=`, `+`, `-` or `@`
/// first, after any white space (some spreadsheets skip leading spaces), or
/// a tab or carriage return first (OWASP's list).
fn formula_like(s: &str) -> bool {
    s.starts_with(['\t', '\r']) || s.trim_start().starts_with(['=', '+', '-', '@'])
}

/// A CSV cell: neutralised when a spreadsheet would take it for a formula,
/// quoted when it holds a separator, a quote or a line break.
pub fn csv_cell(s: &str) -> String {
    let s = if formula_like(s) {
        format!("'{s}")
    } else {
        s.to_string()
    };
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

/// The hint rungs `copy` recorded for `function` (empty when its record
/// could not be read).
fn rungs(copy: &Copy, function: &str) -> String {
    match &copy.progress {
        Ok(p) => p.hints.get(function).copied().unwrap_or(0).to_string(),
        Err(_) => String::new(),
    }
}

impl Class {
    /// One CSV row per student and assignment, then the student's total,
    /// after the header.
    pub fn csv(&self) -> String {
        let mut rows = vec![CSV_HEADER.to_string()];
        for copy in &self.copies {
            let seed = copy.seed().map(|s| s.to_string()).unwrap_or_default();
            let student = csv_cell(&copy.student);
            for a in &COURSE {
                let (word, why) = copy.row(a);
                let score = u8::from(word == "passing");
                rows.push(
                    [
                        student.clone(),
                        a.function.to_string(),
                        csv_cell(a.equation),
                        word.to_string(),
                        score.to_string(),
                        rungs(copy, a.function),
                        seed.clone(),
                        csv_cell(&why),
                    ]
                    .join(","),
                );
            }
            let used: Option<u32> = copy
                .progress
                .as_ref()
                .ok()
                .map(|p| p.hints.values().map(|&r| u32::from(r)).sum());
            let state = if copy.fully_graded() {
                "graded"
            } else {
                "not fully graded"
            };
            let why = match &copy.progress {
                Ok(_) => format!("{} of {COURSE_LEN} passing", copy.passing()),
                Err(e) => format!(
                    "{} of {COURSE_LEN} passing; hint rungs unknown: target/spintop-course.json {e}",
                    copy.passing()
                ),
            };
            rows.push(
                [
                    student,
                    TOTAL.to_string(),
                    String::new(),
                    state.to_string(),
                    copy.passing().to_string(),
                    used.map(|u| u.to_string()).unwrap_or_default(),
                    seed,
                    csv_cell(&why),
                ]
                .join(","),
            );
        }
        rows.join("\n") + "\n"
    }

    /// Gradescope's `results.json` for one copy: one test per assignment
    /// (1 point each), its status and output, the score, the time spent.
    /// The fields are those of Gradescope's autograder specification; the
    /// output shows the grader's report without the student's own text.
    pub fn gradescope(&self, copy: &Copy) -> serde_json::Value {
        let tests: Vec<serde_json::Value> = COURSE
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let (word, why) = copy.row(a);
                let passed = word == "passing";
                let output = match copy.state(a).and_then(|s| s.public()) {
                    Some(r) => format!("{word}\n\n{r}"),
                    None if why.is_empty() => word.to_string(),
                    None => format!("{word}: {why}"),
                };
                serde_json::json!({
                    "name": format!("{} {}", a.equation, a.function),
                    "number": (i + 1).to_string(),
                    "score": if passed { 1.0 } else { 0.0 },
                    "max_score": 1.0,
                    "status": if passed { "passed" } else { "failed" },
                    "output": output,
                    "visibility": "visible",
                })
            })
            .collect();
        let passing = copy.passing();
        let summary = match &copy.outcome {
            Outcome::Graded(s) => format!(
                "spintop course grade: {passing} of {COURSE_LEN} passing (inputs from seed {}; the same inputs again: spintop course --seed {})",
                s.seed, s.seed
            ),
            Outcome::Missing(why) | Outcome::NotACourse(why) | Outcome::NotGraded(why) => {
                format!("spintop course grade: not graded: {why}")
            }
        };
        serde_json::json!({
            "score": passing as f64,
            "execution_time": copy.seconds.round() as u64,
            "output": summary,
            "tests": tests,
        })
    }
}

/// The file that keeps the seeds shown to students (in Gradescope's
/// output), one per line, below a grading's work folder.
fn shown_file(work: &Path) -> std::path::PathBuf {
    work.join("seeds-shown-to-students")
}

/// Notes that `seed` was shown to students (a Gradescope output written).
pub fn record_shown_seed(work: &Path, seed: u64) {
    use std::io::Write;
    if super::workspace::private_dir(work).is_err() {
        return;
    }
    let line = format!(
        "{seed} {}\n",
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs())
            .unwrap_or(0)
    );
    if let Ok(mut f) = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(shown_file(work))
    {
        let _ = f.write_all(line.as_bytes());
    }
}

/// Whether `seed` was shown to students before (then a grade at that seed
/// can be met by a table of one grading's answers): the warning to give.
pub fn seed_shown_before(work: &Path, seed: u64) -> Option<String> {
    let bytes =
        super::snapshot::read_bounded(work, Path::new("seeds-shown-to-students"), 1 << 20).ok()?;
    let text = String::from_utf8_lossy(&bytes);
    let when = text.lines().find_map(|l| {
        let (s, t) = l.split_once(' ')?;
        (s.parse::<u64>().ok()? == seed).then(|| t.trim().to_string())
    })?;
    Some(format!(
        "seed {seed} was shown to students in a Gradescope output (at {when} s since 1970): a table of that grading's answers passes at it; use it to replay a grading, and grade with a fresh seed"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cell_a_spreadsheet_would_run_is_neutralised() {
        assert_eq!(csv_cell("=2+3"), "'=2+3");
        assert_eq!(csv_cell("+1"), "'+1");
        assert_eq!(csv_cell("-1"), "'-1");
        assert_eq!(csv_cell("@SUM(A1)"), "'@SUM(A1)");
        assert_eq!(csv_cell("\tx"), "'\tx");
        assert_eq!(
            csv_cell("=HYPERLINK(\"http://x\",\"y\")"),
            "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\""
        );
        assert_eq!(csv_cell("\r=1"), "\"'\r=1\"");
        assert_eq!(csv_cell("alice"), "alice");
        assert_eq!(csv_cell("a, b"), "\"a, b\"");
        assert_eq!(csv_cell("(2.1)"), "(2.1)");
    }

    /// The cells of one CSV line (quoted cells unquoted).
    fn cells(line: &str) -> Vec<String> {
        let (mut out, mut cell, mut quoted, mut chars) =
            (Vec::new(), String::new(), false, line.chars().peekable());
        while let Some(c) = chars.next() {
            match (c, quoted) {
                ('"', true) if chars.peek() == Some(&'"') => {
                    cell.push('"');
                    chars.next();
                }
                ('"', _) => quoted = !quoted,
                (',', false) => out.push(std::mem::take(&mut cell)),
                _ => cell.push(c),
            }
        }
        out.push(cell);
        out
    }

    /// A class whose student names, panics and reasons are formulas: no
    /// CSV cell a spreadsheet would run, a total per student, and no panic
    /// text (a formula, a path) in Gradescope's visible output.
    #[test]
    fn a_class_of_formulas_writes_cells_a_spreadsheet_will_not_run() {
        use crate::gradebook::{Class, Copy, Outcome};
        use crate::status::{Failure, State, Status};
        let panic = "=HYPERLINK(\"http://evil\",\"/root /home/alice\")";
        let failed = spintop_grading::Failed {
            assignment: "larmor_rate",
            equation: "(2.1)",
            seed: 5,
            input: "jet".into(),
            expected: "(1, 2, 3)".into(),
            actual: format!("panicked: {panic}"),
            diagnosis: "your function panicked on a valid input".into(),
            course: None,
        };
        let graded = Status::new(5, |a| match a.function {
            "larmor_rate" => State::Failing(Failure::of(&failed)),
            "torque_rate" => State::Passing,
            _ => State::DoesNotCompile("-src/ch3.rs:1: @expected item".into()),
        });
        let copy = |student: &str, outcome: Outcome| Copy {
            student: student.into(),
            folder: student.into(),
            outcome,
            progress: Err("+not a regular file".into()),
            seconds: 1.0,
        };
        let class = Class {
            copies: vec![
                copy("=2+3", Outcome::Graded(graded)),
                copy("@bob", Outcome::NotGraded("\t=1+1".into())),
                copy("\r-carol", Outcome::Missing("+1".into())),
                copy("dave", Outcome::NotACourse("=cmd|' /C calc'!A0".into())),
                copy(" =1", Outcome::NotGraded(" \u{a0}+2".into())),
            ],
            seed: 5,
        };
        let csv = class.csv();
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some(CSV_HEADER));
        let rows: Vec<Vec<String>> = lines.map(cells).collect();
        assert_eq!(rows.len(), 5 * (COURSE_LEN + 1), "{csv}");
        for row in &rows {
            assert_eq!(row.len(), 8, "{row:?}");
            for cell in row {
                assert!(
                    !cell.starts_with(['\t', '\r'])
                        && !cell.trim_start().starts_with(['=', '+', '-', '@']),
                    "{cell:?} in {row:?}"
                );
            }
        }
        let totals: Vec<&Vec<String>> = rows.iter().filter(|r| r[1] == TOTAL).collect();
        assert_eq!(totals.len(), 5);
        assert_eq!(totals[4][0], "' =1");
        assert_eq!(
            (totals[0][0].as_str(), totals[0][4].as_str()),
            ("'=2+3", "1")
        );
        assert!(totals[0][7].contains("1 of 22 passing"), "{:?}", totals[0]);
        assert!(!csv.contains("HYPERLINK"), "{csv}");
        let json = class.gradescope(&class.copies[0]).to_string();
        assert!(json.contains("your function panicked"), "{json}");
        for leak in ["HYPERLINK", "/root", "/home/alice"] {
            assert!(!json.contains(leak), "{leak} in {json}");
        }
    }

    #[test]
    fn a_seed_shown_to_students_is_remembered() {
        let work = std::env::temp_dir().join(format!("spintop-seeds-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&work);
        assert_eq!(seed_shown_before(&work, 42), None);
        record_shown_seed(&work, 42);
        assert!(seed_shown_before(&work, 42).is_some_and(|w| w.contains("seed 42")));
        assert_eq!(seed_shown_before(&work, 43), None);
        std::fs::remove_dir_all(&work).unwrap();
    }
}
