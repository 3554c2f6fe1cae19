//! The harness and the grade book on real copies of the course, each built
//! in a workspace of its own from the warm build of the stubs (so spintop is
//! compiled once): a stub that prints the test harness's own lines grades
//! 0 of 22; a class with a copy that loops, one that does not compile, one
//! missing and one that is not a course gets every row, with reasons, within
//! its time limits, and an exit code that says so; Gradescope's results.json
//! has the documented fields; an export for GitHub holds a workflow that
//! grades with `cargo test`; every printed command repeats `--course DIR`.
//! `sandbox` tries the launcher as an attacker; `class` grades a class of
//! adversarial copies, two runs at once, and a run on a terminal.

mod book;
mod class;
mod sandbox;

use spintop_course::{self as course, COURSE, Options, State};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod diagnose;
mod no_cargo;
mod plain_test;

/// The seeds the grading tests run at: the same assertions must hold for
/// any grading's inputs.
const SEEDS: [u64; 3] = [2026, 7, 918_273_645];

pub(crate) fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The build folder the copies share.
pub(crate) fn target() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("target"))
}

pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("spintop-harness-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A student's copy that builds against the repository's crates (so the
/// tests' copies share one build of them); what a student is handed carries
/// them instead, as `a_copy_exported_from_a_deleted_clone_builds_and_is_graded`
/// checks.
pub(crate) fn export_linked(dir: &Path) {
    course::export_with(
        repo(),
        dir,
        &course::ExportOptions {
            ci: None,
            link: course::Link::Repository,
        },
    )
    .unwrap();
}

/// The reference solution of `function` (its text in lessons/src/solutions/).
pub(crate) fn solution(module: &str, function: &str) -> String {
    let text = std::fs::read_to_string(
        repo()
            .join("lessons/src/solutions")
            .join(format!("{module}.rs")),
    )
    .unwrap();
    let start = text.find(&format!("pub fn {function}(")).unwrap();
    let end = start + text[start..].find("\n}\n").unwrap() + 3;
    text[start..end].to_string()
}

/// The reference solutions' whole `module` (a file a student could hand in).
pub(super) fn solution_file(module: &str) -> String {
    std::fs::read_to_string(
        repo()
            .join("lessons/src/solutions")
            .join(format!("{module}.rs")),
    )
    .unwrap()
}

/// How the tests grade a copy in process: through the `spintop` binary's
/// sandbox, in the workspace `work`.
fn options(work: &Path) -> Options {
    Options {
        launcher: Some(PathBuf::from(env!("CARGO_BIN_EXE_spintop"))),
        work: Some(work.to_path_buf()),
        ..Options::default()
    }
}

/// Replaces the stub `pub fn NAME(…) { todo!(…) }` of the copy's `module`
/// with `replacement`.
pub(crate) fn write_function(dir: &Path, module: &str, function: &str, replacement: &str) {
    let path = dir.join("src").join(format!("{module}.rs"));
    let text = std::fs::read_to_string(&path).unwrap();
    let start = text.find(&format!("pub fn {function}(")).unwrap();
    let end = start + text[start..].find("\n}\n").unwrap() + 3;
    std::fs::write(
        &path,
        format!("{}{replacement}{}", &text[..start], &text[end..]),
    )
    .unwrap();
}

pub(super) fn spintop(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .env("CARGO_TARGET_DIR", target())
        .output()
        .expect("spintop runs")
}

#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn a_stub_that_prints_the_harness_lines_grades_zero_of_22() {
    let dir = scratch("printing-stub").join("copy");
    export_linked(&dir);
    // Every stub first prints what cargo's test harness prints for 22 passes.
    let lines: String = COURSE
        .iter()
        .map(|a| format!("test {} ... ok\\n", a.test))
        .collect();
    let spoof = format!(
        "\n/// Prints the harness's lines of a full pass.\npub fn spoof() {{\n    print!(\"running 22 tests\\n{lines}\\ntest result: ok. 22 passed; 0 failed\\n\");\n    eprint!(\"{lines}\");\n}}\n"
    );
    let lib = dir.join("src/lib.rs");
    let text = std::fs::read_to_string(&lib).unwrap();
    std::fs::write(&lib, format!("{text}{spoof}")).unwrap();
    for module in ["ch2", "ch3", "ch4", "numerics", "appendix"] {
        let path = dir.join("src").join(format!("{module}.rs"));
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(
            &path,
            text.replace("    todo!(", "    crate::spoof();\n    todo!("),
        )
        .unwrap();
    }
    let options = Options {
        seed: Some(1),
        ..options(&dir.parent().unwrap().join("work"))
    };
    let status = course::grade(&dir, &options).expect("the harness runs");
    assert_eq!(status.compile_error, None);
    assert_eq!(status.passing(), 0, "{status:?}");
    assert!(
        status.states.iter().all(|(_, s)| *s == State::NotStarted),
        "{status:?}"
    );
    // The lines really are printed: a reader of text would have counted them.
    let out = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .current_dir(&dir)
        .args(["test", "--quiet", "--test", "ch2", "--", "--nocapture"])
        .env("CARGO_TARGET_DIR", target())
        .output()
        .unwrap();
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(
        printed.matches("test eq_2_1_larmor_rate ... ok").count() >= 6,
        "{printed}"
    );
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}

/// The keys Gradescope's autograder specification documents for
/// results.json, at the top level and for each test.
const GRADESCOPE_TOP: [&str; 11] = [
    "score",
    "execution_time",
    "output",
    "output_format",
    "test_output_format",
    "test_name_format",
    "visibility",
    "stdout_visibility",
    "extra_data",
    "tests",
    "leaderboard",
];
const GRADESCOPE_TEST: [&str; 11] = [
    "score",
    "max_score",
    "status",
    "name",
    "name_format",
    "number",
    "output",
    "output_format",
    "tags",
    "visibility",
    "extra_data",
];

fn check_gradescope(json: &serde_json::Value) {
    let top = json.as_object().expect("an object");
    for key in top.keys() {
        assert!(
            GRADESCOPE_TOP.contains(&key.as_str()),
            "undocumented key {key}"
        );
    }
    assert!(top["score"].is_number() && top["output"].is_string());
    assert!(top["execution_time"].is_u64());
    let tests = top["tests"].as_array().expect("tests");
    assert_eq!(tests.len(), COURSE.len());
    let mut total = 0.0;
    for (t, a) in tests.iter().zip(COURSE) {
        let t = t.as_object().expect("a test object");
        for key in t.keys() {
            assert!(
                GRADESCOPE_TEST.contains(&key.as_str()),
                "undocumented test key {key}"
            );
        }
        assert!(t["name"].as_str().unwrap().contains(a.function));
        assert_eq!(t["max_score"].as_f64(), Some(1.0));
        let score = t["score"].as_f64().unwrap();
        let status = t["status"].as_str().unwrap();
        assert!(matches!(status, "passed" | "failed"));
        assert_eq!(score == 1.0, status == "passed");
        assert!(matches!(
            t["visibility"].as_str(),
            Some("hidden" | "after_due_date" | "after_published" | "visible")
        ));
        assert!(t["output"].is_string() && t["number"].is_string());
        total += score;
    }
    assert_eq!(top["score"].as_f64(), Some(total));
}

#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn course_grade_writes_every_row_of_a_class_within_its_time_limits() {
    let class = scratch("class");
    // alice solved (2.1); bob's (2.2) never returns; carol's ch3.rs does not
    // parse; dave handed in nothing; erin handed in a folder that is no course.
    let (alice, bob, carol) = (class.join("alice"), class.join("bob"), class.join("carol"));
    let (dave, erin) = (class.join("dave"), class.join("erin"));
    for d in [&alice, &bob, &carol] {
        export_linked(d);
    }
    write_function(
        &alice,
        "ch2",
        "larmor_rate",
        &solution("ch2", "larmor_rate"),
    );
    write_function(
        &bob,
        "ch2",
        "torque_rate",
        "pub fn torque_rate(jet: &Jet) -> Vec3 {\n    let mut v = jet[0];\n    loop {\n        v = v.cross(&jet[3]);\n    }\n}\n",
    );
    let ch3 = carol.join("src/ch3.rs");
    let text = std::fs::read_to_string(&ch3).unwrap();
    let broken_line = text.lines().count() + 2;
    std::fs::write(&ch3, format!("{text}\npub fn broken( {{\n")).unwrap();
    std::fs::create_dir_all(&erin).unwrap();
    let csv = class.join("grades.csv");
    let start = Instant::now();
    let copies = [&alice, &bob, &carol, &dave, &erin].map(|p| p.display().to_string());
    let mut args = vec!["course", "grade"];
    args.extend(copies.iter().map(String::as_str));
    args.extend([
        "--out",
        csv.to_str().unwrap(),
        "--timeout",
        "240",
        "--test-timeout",
        "5",
        "--seed",
        "3",
    ]);
    let out = spintop(&args);
    let elapsed = start.elapsed();
    let stderr = String::from_utf8_lossy(&out.stderr);
    // Some copies could not be graded: exit 4 (could not grade), and it
    // says which.
    assert_eq!(out.status.code(), Some(4), "{stderr}");
    assert!(
        stderr.contains("bob (timed out)") && stderr.contains("dave (missing)"),
        "{stderr}"
    );
    let grades = std::fs::read_to_string(&csv).expect("the CSV is written");
    let rows: Vec<&str> = grades.lines().collect();
    assert_eq!(rows[0], course::sheet::CSV_HEADER);
    assert_eq!(rows.len(), 1 + 5 * (COURSE.len() + 1), "{grades}");
    let row = |student: &str, function: &str| -> Vec<String> {
        let line = rows
            .iter()
            .find(|r| r.starts_with(&format!("{student},{function},")))
            .unwrap_or_else(|| panic!("no row {student} {function}"));
        // The reason may hold commas (quoted); the first seven fields do not.
        let mut fields: Vec<String> = line.splitn(8, ',').map(String::from).collect();
        fields[7] = fields[7].trim_matches('"').to_string();
        fields
    };
    assert_eq!(row("alice", "larmor_rate")[3], "passing");
    assert_eq!(row("alice", "larmor_rate")[4], "1", "the score");
    assert_eq!(row("alice", "larmor_rate")[6], "3", "the seed");
    assert_eq!(row("alice", "torque_rate")[3], "not started");
    assert_eq!(row("alice", "total")[4], "1", "alice's total");
    let hang = row("bob", "torque_rate");
    assert_eq!(hang[3], "timed out");
    assert!(hang[7].contains("no verdict within 5 s"), "{hang:?}");
    // The rest of bob's copy is graded all the same.
    assert_eq!(row("bob", "larmor_rate")[3], "not started");
    assert_eq!(row("bob", "characteristic_root")[3], "not started");
    for a in COURSE {
        // Carol's syntax error costs the assignments of ch3.rs alone.
        let c = row("carol", a.function);
        if a.binary == "ch3" {
            assert_eq!(c[3], "does not compile");
            assert!(
                c[7].starts_with(&format!("src/ch3.rs:{broken_line}:")),
                "{c:?}"
            );
        } else {
            assert_eq!(c[3], "not started", "{c:?}");
        }
        assert_eq!(row("dave", a.function)[3], "missing");
        assert_eq!(row("erin", a.function)[3], "not a course");
    }
    // Within the time limits: bob's hang costs its 5 s, not the whole limit.
    assert!(elapsed < Duration::from_secs(600), "{elapsed:?}");
    // The student with the syntax error sees it with its file and line, and
    // "next" points at that file.
    let out = spintop(&["course", "--course", carol.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!(
            "next: fix src/ch3.rs:{broken_line} (the lessons do not compile)"
        )),
        "{text}"
    );
    gradescope_of_one(&alice, &class);
    std::fs::remove_dir_all(&class).ok();
}

/// Gradescope's results.json for the one copy `alice` (one assignment
/// solved), with the documented fields.
fn gradescope_of_one(alice: &Path, class: &Path) {
    let results = class.join("results.json");
    let out = spintop(&[
        "course",
        "grade",
        alice.to_str().unwrap(),
        "--format",
        "gradescope",
        "--out",
        results.to_str().unwrap(),
        "--seed",
        "3",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&results).unwrap()).unwrap();
    check_gradescope(&json);
    assert_eq!(json["score"].as_f64(), Some(1.0));
    assert_eq!(json["tests"][0]["status"], "passed");
    assert!(
        json["tests"][1]["output"]
            .as_str()
            .unwrap()
            .starts_with("not started")
    );
}

/// The instructor's clean checkout keeps a submission's symbolic link as a
/// link, so the source rule names it: a module linked to the reference
/// solution grades "failing", "no shortcut", with its file, never passing
/// (and never "does not compile" for want of the file).
#[cfg(unix)]
#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn course_grade_names_a_symbolic_link_to_the_solution_in_the_reason() {
    let class = scratch("link");
    let frank = class.join("frank");
    export_linked(&frank);
    let solution = repo().join("lessons/src/solutions/ch2.rs");
    std::os::unix::fs::symlink(&solution, frank.join("src/done.rs")).unwrap();
    let lib = frank.join("src/lib.rs");
    let text = std::fs::read_to_string(&lib).unwrap();
    std::fs::write(&lib, format!("{text}\nmod done;\n")).unwrap();
    let csv = class.join("grades.csv");
    let out = spintop(&[
        "course",
        "grade",
        frank.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
        "--seed",
        "3",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let grades = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<&str> = grades.lines().skip(1).collect();
    assert_eq!(rows.len(), COURSE.len() + 1, "{grades}");
    for row in rows.iter().filter(|r| !r.starts_with("frank,total,")) {
        assert!(row.contains(",failing,"), "{row}");
        assert!(
            row.contains("no shortcut") && row.contains("src/done.rs:1: a symbolic link"),
            "{row}"
        );
    }
    std::fs::remove_dir_all(&class).ok();
}

#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn an_export_for_github_grades_itself_with_cargo_test_on_every_push() {
    let dir = scratch("ci").join("copy");
    let written = course::export_with(
        repo(),
        &dir,
        &course::ExportOptions {
            ci: Some(course::Ci::Github),
            link: course::Link::Carried,
        },
    )
    .unwrap();
    let workflow = std::fs::read_to_string(dir.join(course::export::GITHUB_WORKFLOW)).unwrap();
    assert!(
        written
            .files
            .iter()
            .any(|f| f == Path::new(course::export::GITHUB_WORKFLOW))
    );
    for line in [
        "on:",
        "  push:",
        "runs-on: ubuntu-latest",
        "- uses: actions/checkout@v4",
        "run: cargo test --no-fail-fast",
    ] {
        assert!(
            workflow
                .lines()
                .any(|l| l.trim_end().ends_with(line.trim()) && l.contains(line.trim())),
            "{line}\n{workflow}"
        );
    }
    assert!(!workflow.contains('\t'), "YAML indents with spaces");
    // The book's instructor page shows this very workflow.
    let page = std::fs::read_to_string(repo().join("book/src/instructors.md")).unwrap();
    assert!(
        page.contains(&format!("```yaml\n{workflow}```")),
        "book/src/instructors.md shows another workflow"
    );
    // The copy builds where the repository is not: the core and the graders are inside it.
    let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
    assert!(
        manifest.contains("spintop = { path = \"crates/spintop\" }")
            && manifest.contains("spintop-grading = { path = \"crates/spintop-grading\" }"),
        "{manifest}"
    );
    assert!(
        dir.join("crates/spintop/src/lib.rs").is_file()
            && dir.join("crates/spintop/src/physics.rs").is_file()
            && dir.join("crates/spintop-grading/src/lib.rs").is_file()
    );
    let meta = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .current_dir(&dir)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--offline",
            "--no-deps",
        ])
        .output()
        .unwrap();
    assert!(
        meta.status.success(),
        "{}",
        String::from_utf8_lossy(&meta.stderr)
    );
    // `--no-deps` lists the workspace's members only: the copy's package,
    // whose path dependencies name the carried crates.
    let meta: serde_json::Value = serde_json::from_slice(&meta.stdout).unwrap();
    let packages = meta["packages"].as_array().unwrap();
    assert_eq!(packages.len(), 1, "the copy's package alone: {packages:?}");
    for name in ["spintop", "spintop-grading"] {
        let dependency = packages[0]["dependencies"]
            .as_array()
            .unwrap()
            .iter()
            .find(|d| d["name"] == name)
            .unwrap_or_else(|| panic!("{name} is a dependency"));
        assert!(
            dependency["path"]
                .as_str()
                .is_some_and(|p| p.ends_with(&format!("/copy/crates/{name}"))),
            "{name}: {dependency}"
        );
    }
    // No solution, and the copy keeps the source rule (spintop/ is not its source).
    assert!(!dir.join("src/solutions").exists());
    assert_eq!(course::source_rule::check_copy(&dir), vec![]);
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}

#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn every_printed_command_repeats_the_course_it_was_given() {
    let dir = scratch("hint").join("copy");
    export_linked(&dir);
    let given = dir.display().to_string();
    let out = spintop(&["course", "hint", "larmor_rate", "--course", &given]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!("spintop course hint larmor_rate --course {given}")),
        "{text}"
    );
    // The rung is kept in the copy, not in the repository.
    let progress = course::load_progress(&dir);
    assert_eq!(progress.hints.get("larmor_rate"), Some(&1));
    // A grader's own report, as `cargo test` prints it in the copy, names the copy.
    let failed = spintop_grading::larmor_rate(1, |_| spintop::math::Vec3::zeros()).unwrap_err();
    let mine = spintop_grading::Failed {
        course: Some(given.clone()),
        ..*failed
    };
    assert!(
        mine.to_string()
            .contains(&format!("spintop course hint larmor_rate --course {given}"))
    );
    assert!(
        mine.to_string()
            .contains(&format!("spintop course --seed 1 --course {given}"))
    );
    assert_eq!(course::course_arg_for(&course::lessons_dir(repo())), None);
    assert_eq!(course::course_arg_for(&dir), Some(given));
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}

/// A copy that allocates without bound fails alone, within its memory
/// limit, instead of taking the (shared) machine and the class's grading
/// with it: 4 GiB asked for by one grader is refused, and the row says why.
#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn a_grader_that_allocates_without_bound_is_stopped_by_its_memory_limit() {
    let class = scratch("memory");
    let greedy = class.join("greedy");
    export_linked(&greedy);
    write_function(
        &greedy,
        "ch2",
        "larmor_rate",
        "pub fn larmor_rate(jet: &Jet) -> Vec3 {\n    let big = vec![jet[0].x; 1 << 29];\n    Vec3::repeat(big[big.len() - 1])\n}\n",
    );
    let csv = class.join("grades.csv");
    let out = spintop(&[
        "course",
        "grade",
        greedy.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
        "--seed",
        "3",
    ]);
    let grades = std::fs::read_to_string(&csv)
        .unwrap_or_else(|_| panic!("no CSV: {}", String::from_utf8_lossy(&out.stderr)));
    let row = grades
        .lines()
        .find(|r| r.starts_with("greedy,larmor_rate,"))
        .expect("a row");
    assert!(row.contains(",failing,"), "{row}");
    assert!(row.contains("memory"), "{row}");
    std::fs::remove_dir_all(&class).ok();
}

/// `spintop course --course DIR` with DIR relative to where it is run (a
/// student beside their copy) grades the copy; cargo must not look for the
/// manifest relative to the copy itself ("does not compile", Cargo.toml:1).
#[test]
#[ignore = "end-to-end: builds copies of the course"]
fn a_copy_named_by_a_relative_path_is_graded() {
    let parent = scratch("relative");
    export_linked(&parent.join("mine"));
    let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(["course", "--course", "mine"])
        .current_dir(&parent)
        .env("CARGO_TARGET_DIR", target())
        .output()
        .expect("spintop runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("does not compile"), "{text}");
    assert!(text.contains("not started"), "{text}");
    std::fs::remove_dir_all(&parent).ok();
}

/// A copy exported to `root/copy` from a clone of the repository made in
/// `root/clone` (the files an export reads, as a clone holds them), the
/// clone then deleted: (the copy, where the clone was).
pub(super) fn export_from_a_deleted_clone(root: &Path) -> (PathBuf, PathBuf) {
    let clone = root.join("clone");
    std::fs::create_dir_all(&clone).unwrap();
    let cp = Command::new("cp")
        .arg("-r")
        .args(["crates", "lessons", "book", "Cargo.toml", "Cargo.lock"].map(|p| repo().join(p)))
        .arg(&clone)
        .status()
        .unwrap();
    assert!(cp.success());
    let copy = root.join("copy");
    course::export(&clone, &copy).unwrap();
    std::fs::remove_dir_all(&clone).unwrap();
    (copy, clone)
}

/// What a student is handed stands alone: exported from a clone of the
/// repository that is then deleted, the copy names no path outside itself,
/// holds no reference solution, builds offline with the crates it carries
/// (one assignment solved passes its test there), and `course grade` grades
/// it.
#[test]
#[ignore = "end-to-end: builds a copy of the course from scratch (a minute or two)"]
fn a_copy_exported_from_a_deleted_clone_builds_and_is_graded() {
    let root = scratch("standalone");
    let (copy, clone) = export_from_a_deleted_clone(&root);
    // No path outside the copy, no solution.
    names_nothing_outside(
        &copy,
        &[repo().display().to_string(), clone.display().to_string()],
    );
    let ch2 = std::fs::read_to_string(copy.join("src/ch2.rs")).unwrap();
    assert!(
        !ch2.contains(&solution("ch2", "larmor_rate")),
        "a solution in src/ch2.rs"
    );
    // Moved elsewhere, the copy is a workspace of one package whose lock is
    // its own: cargo's --locked holds, and --workspace means the student's
    // package (not the carried crates, whose tests are not carried).
    let moved = root.join("elsewhere").join("copy");
    std::fs::create_dir_all(root.join("elsewhere")).unwrap();
    std::fs::rename(&copy, &moved).unwrap();
    let copy = moved;
    let cargo = |args: &[&str]| {
        Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
            .current_dir(&copy)
            .env_remove("CARGO_TARGET_DIR")
            .args(args)
            .output()
            .unwrap()
    };
    let metadata = cargo(&["metadata", "--locked", "--offline", "--format-version", "1"]);
    assert!(
        metadata.status.success(),
        "{}",
        String::from_utf8_lossy(&metadata.stderr)
    );
    let metadata: serde_json::Value = serde_json::from_slice(&metadata.stdout).unwrap();
    let members = metadata["workspace_members"].as_array().unwrap();
    assert_eq!(members.len(), 1, "{members:?}");
    for args in [
        &[
            "check",
            "--workspace",
            "--all-targets",
            "--locked",
            "--offline",
            "--quiet",
        ][..],
        &["test", "--locked", "--offline", "--no-run", "--quiet"][..],
    ] {
        let out = cargo(args);
        assert!(
            out.status.success(),
            "cargo {args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // Solve (2.1) and build the copy offline, in a build folder of its own.
    write_function(&copy, "ch2", "larmor_rate", &solution("ch2", "larmor_rate"));
    let test = cargo(&[
        "test",
        "--locked",
        "--offline",
        "--quiet",
        "--test",
        "ch2",
        "eq_2_1_larmor_rate",
    ]);
    assert!(
        test.status.success(),
        "{}",
        String::from_utf8_lossy(&test.stderr)
    );
    // And the instructor grades it.
    let csv = root.join("grades.csv");
    let out = spintop(&[
        "course",
        "grade",
        copy.to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let grades = std::fs::read_to_string(&csv).unwrap();
    assert!(
        grades
            .lines()
            .any(|l| l.starts_with("copy,larmor_rate,(2.1),passing,")),
        "{grades}"
    );
    assert_eq!(grades.matches(",passing,").count(), 1, "{grades}");
    graded_where_it_was_moved(&root, &copy);
    std::fs::remove_dir_all(&root).ok();
}

/// No file of `copy` names one of the paths `outside`, and no folder of it
/// is called `solutions`.
fn names_nothing_outside(copy: &Path, outside: &[String]) {
    let mut texts = Vec::new();
    let mut stack = vec![copy.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if e.file_type().unwrap().is_dir() {
                stack.push(p);
            } else if let Ok(t) = std::fs::read_to_string(&p) {
                texts.push((p, t));
            }
        }
    }
    for (p, t) in &texts {
        for o in outside {
            assert!(!t.contains(o.as_str()), "{} names {o}", p.display());
        }
        assert!(
            !p.components().any(|c| c.as_os_str() == "solutions"),
            "{}",
            p.display()
        );
    }
}

/// The copy at `copy`, moved below `root` elsewhere: the student's own
/// `spintop course` builds the runner against the crates the copy carries
/// (the repository's are not needed) and grades it the same.
fn graded_where_it_was_moved(root: &Path, copy: &Path) {
    let moved = root.join("elsewhere").join("mine");
    std::fs::create_dir_all(moved.parent().unwrap()).unwrap();
    std::fs::rename(copy, &moved).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args([
            "course",
            "--course",
            moved.to_str().unwrap(),
            "--format",
            "json",
        ])
        .env_remove("CARGO_TARGET_DIR")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let status: serde_json::Value = serde_json::from_str(&text).unwrap();
    let states: Vec<(&str, &str)> = status["assignments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| {
            (
                a["function"].as_str().unwrap(),
                a["state"].as_str().unwrap(),
            )
        })
        .collect();
    assert!(states.contains(&("larmor_rate", "passing")), "{states:?}");
    assert_eq!(
        states.iter().filter(|(_, s)| *s == "passing").count(),
        1,
        "{states:?}"
    );
    let ws = course::default_work(&moved);
    for manifest in ["course/Cargo.toml", "runner/Cargo.toml"] {
        let text = std::fs::read_to_string(ws.join(manifest)).unwrap();
        let carried = moved.canonicalize().unwrap().join("crates");
        assert!(
            text.contains(carried.to_str().unwrap()),
            "{manifest}: {text}"
        );
        assert!(
            !text.contains(&repo().display().to_string()),
            "{manifest}: {text}"
        );
    }
}
