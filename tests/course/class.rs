//! `course grade` as an instructor runs it on a class that holds every kind
//! of copy at once, each of which must cost only its own rows: a honest
//! one, its progress file a FIFO or a link to /dev/zero, a 3 GB sparse
//! file, a 2 GiB `static`, the memory-reading exploit of
//! rust-lang/rust#25860, a panic that writes a formula, a student whose
//! name is a formula, code kept in the student's own `src/solutions/`, and
//! a `src/` swapped for a link to the reference solutions while grading
//! runs. A second run grades at the same time; a third on a terminal (a
//! pseudo-terminal) shows its progress bar and finishes.

use super::{export_linked, repo, scratch, solution_file, spintop};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// The exploit's Section 2: reads the grader's expected answer off its
/// caller's stack (and so passes where the grader runs in its process).
pub(super) const EXPLOIT: &str = include_str!("exploit_ch2.rs.txt");

/// A copy with the reference solution of Section 2 in `src/ch2.rs`.
fn honest(dir: &Path) {
    export_linked(dir);
    std::fs::write(dir.join("src/ch2.rs"), solution_file("ch2")).unwrap();
}

fn progress_file(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir.join("target")).unwrap();
    dir.join("target/spintop-course.json")
}

/// The CSV's rows of `student`, by assignment: (state, score, rungs, reason).
fn rows(csv: &str, student: &str) -> Vec<(String, Vec<String>)> {
    csv.lines()
        .skip(1)
        .filter(|l| l.starts_with(&format!("{student},")))
        .map(|l| {
            let fields: Vec<String> = l.splitn(8, ',').map(String::from).collect();
            (fields[1].clone(), fields)
        })
        .collect()
}

/// The total row of `student`: (passing, reason).
fn total(csv: &str, student: &str) -> (usize, String) {
    let all = rows(csv, student);
    let (_, t) = all
        .iter()
        .find(|(a, _)| a == "total")
        .unwrap_or_else(|| panic!("no total for {student}:\n{csv}"));
    (t[4].parse().unwrap(), t[7].trim_matches('"').to_string())
}

/// Swaps `copy/src` for a link to the reference solutions and back, again
/// and again, until `stop`.
fn swapper(copy: PathBuf, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let (src, real) = (copy.join("src"), copy.join("src.real"));
        let solutions = repo().join("lessons/src/solutions");
        while !stop.load(Ordering::Relaxed) {
            if std::fs::rename(&src, &real).is_ok() {
                let _ = std::os::unix::fs::symlink(&solutions, &src);
                std::thread::sleep(Duration::from_millis(3));
                let _ = std::fs::remove_file(&src);
                let _ = std::fs::rename(&real, &src);
            }
            std::thread::sleep(Duration::from_millis(3));
        }
    })
}

/// The class of adversarial copies in `class`, one folder each.
#[cfg(unix)]
fn adversaries(class: &Path) {
    let copy = |name: &str| class.join(name);
    for name in ["good", "fifo", "zero", "keeper", "alone"] {
        honest(&copy(name));
    }
    for name in ["giant", "static", "exploit", "panics", "=2+3", "swap"] {
        export_linked(&copy(name));
    }
    // The progress file a FIFO, and a link to /dev/zero.
    let fifo = progress_file(&copy("fifo"));
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    std::os::unix::fs::symlink("/dev/zero", progress_file(&copy("zero"))).unwrap();
    // A 3 GB sparse file (32 kB as a .tgz).
    let giant = std::fs::File::create(copy("giant").join("src/giant.rs")).unwrap();
    giant.set_len(3 << 30).unwrap();
    // A 2 GiB static, used.
    let ch2 = copy("static").join("src/ch2.rs");
    let text = std::fs::read_to_string(&ch2).unwrap();
    std::fs::write(
        &ch2,
        text.replacen(
            "pub fn larmor_rate(jet: &Jet) -> Vec3 {\n",
            "static BIG: [u8; 2 << 30] = [1; 2 << 30];\n\npub fn larmor_rate(jet: &Jet) -> Vec3 {\n    if BIG[jet.len()] == 7 { return Vec3::zeros(); }\n",
            1,
        ),
    )
    .unwrap();
    std::fs::write(copy("exploit").join("src/ch2.rs"), EXPLOIT).unwrap();
    // A panic whose message is a formula, and a path.
    let ch2 = copy("panics").join("src/ch2.rs");
    let text = std::fs::read_to_string(&ch2).unwrap();
    std::fs::write(
        &ch2,
        text.replacen(
            "pub fn larmor_rate(jet: &Jet) -> Vec3 {\n",
            "pub fn larmor_rate(jet: &Jet) -> Vec3 {\n    if jet[0].x < 10.0 { panic!(\"=HYPERLINK(\\\"http://evil\\\",\\\"/root\\\")\"); }\n",
            1,
        ),
    )
    .unwrap();
    // Honest code kept in the student's own src/solutions/.
    let keeper = copy("keeper");
    std::fs::create_dir_all(keeper.join("src/solutions")).unwrap();
    std::fs::rename(
        keeper.join("src/ch2.rs"),
        keeper.join("src/solutions/ch2.rs"),
    )
    .unwrap();
    std::fs::write(keeper.join("src/solutions/mod.rs"), "pub mod ch2;\n").unwrap();
    std::fs::write(
        keeper.join("src/ch2.rs"),
        "pub use crate::solutions::ch2::*;\n",
    )
    .unwrap();
    let lib = keeper.join("src/lib.rs");
    let text = std::fs::read_to_string(&lib).unwrap();
    std::fs::write(&lib, format!("{text}\nmod solutions;\n")).unwrap();
}

/// Each adversarial copy's rows in the CSV `grades`: only its own cost.
#[cfg(unix)]
fn check_adversaries(grades: &str) {
    for (name, passing) in [("good", 6), ("fifo", 6), ("zero", 6), ("keeper", 6)] {
        assert_eq!(total(grades, name).0, passing, "{name}");
    }
    for name in ["fifo", "zero"] {
        let (_, why) = total(grades, name);
        assert!(
            why.contains("hint rungs unknown") && why.contains("not a regular file"),
            "{why}"
        );
    }
    let (giant, why) = total(grades, "giant");
    assert_eq!(giant, 0);
    let giant_row = &rows(grades, "giant")[0].1;
    assert!(
        giant_row[7].contains("src/giant.rs") && giant_row[7].contains("larger than"),
        "{giant_row:?}"
    );
    assert!(why.contains("0 of 22"), "{why}");
    let big = &rows(grades, "static")[0].1;
    assert_eq!(
        (total(grades, "static").0, big[3].as_str()),
        (0, "does not compile"),
        "{big:?}"
    );
    assert_eq!(
        total(grades, "exploit").0,
        0,
        "the exploit finds nothing to read"
    );
    let panicked = rows(grades, "panics");
    let (_, larmor) = panicked.iter().find(|(a, _)| a == "larmor_rate").unwrap();
    assert_eq!(larmor[3], "failing");
    assert!(
        !larmor[7].contains("HYPERLINK") && larmor[7].contains("panicked"),
        "{larmor:?}"
    );
    assert!(
        grades.lines().any(|l| l.starts_with("'=2+3,larmor_rate,")),
        "{grades}"
    );
    assert!(!grades.lines().any(|l| l.starts_with("=")), "{grades}");
    assert_eq!(
        total(grades, "swap").0,
        0,
        "the swap never reaches the solutions"
    );
}

#[cfg(unix)]
#[test]
#[ignore = "end-to-end: builds copies"]
fn every_adversarial_copy_costs_only_its_own_rows_and_two_runs_at_once_agree() {
    let class = scratch("adversaries");
    adversaries(&class);
    let copy = |name: &str| class.join(name);
    let csv = class.join("grades.csv");
    let names = [
        "good", "fifo", "zero", "giant", "static", "exploit", "panics", "=2+3", "keeper", "swap",
    ];
    let mut args: Vec<String> = vec!["course".into(), "grade".into()];
    args.extend(names.iter().map(|n| copy(n).display().to_string()));
    args.extend(
        [
            "--out",
            csv.to_str().unwrap(),
            "--timeout",
            "300",
            "--test-timeout",
            "20",
            "--seed",
            "5",
            "--jobs",
            "2",
        ]
        .map(String::from),
    );
    let stop = Arc::new(AtomicBool::new(false));
    let swapping = swapper(copy("swap"), Arc::clone(&stop));
    // A second run at the same time, of one copy: its own folders, the same
    // warm cache.
    let alone_csv = class.join("alone.csv");
    let alone = {
        let (copy, csv) = (copy("alone"), alone_csv.clone());
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_secs(1));
            spintop(&[
                "course",
                "grade",
                copy.to_str().unwrap(),
                "--out",
                csv.to_str().unwrap(),
                "--seed",
                "6",
            ])
        })
    };
    let start = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(&args)
        .env("CARGO_TARGET_DIR", super::target())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spintop runs");
    let pid = child.id();
    let out = child.wait_with_output().expect("spintop ends");
    let elapsed = start.elapsed();
    stop.store(true, Ordering::Relaxed);
    swapping.join().unwrap();
    let alone = alone.join().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let grades = std::fs::read_to_string(&csv).unwrap_or_else(|_| panic!("no CSV: {stderr}"));
    eprintln!("{grades}\n{stderr}\ngraded in {elapsed:?}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert_eq!(
        grades.lines().next(),
        Some(spintop_course::sheet::CSV_HEADER)
    );
    check_adversaries(&grades);
    // The build folders of this run are gone; nothing large is left. (Only
    // this run's: other tests grade at the same time in the same folder.)
    let left = repo().join("target/course-grade");
    for entry in std::fs::read_dir(&left).unwrap().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        assert!(
            !name.starts_with(&format!("run-{pid}-")),
            "{name} was left behind"
        );
    }
    // The run at the same time: right too.
    assert!(
        alone.status.success(),
        "{}",
        String::from_utf8_lossy(&alone.stderr)
    );
    let alone_grades = std::fs::read_to_string(&alone_csv).unwrap();
    assert_eq!(total(&alone_grades, "alone").0, 6, "{alone_grades}");
    std::fs::remove_dir_all(&class).ok();
}

#[cfg(unix)]
#[test]
#[ignore = "end-to-end: builds copies"]
fn the_exploit_reads_the_expected_answer_in_process_and_gets_nothing_from_the_runner() {
    // In the student's own process (plain `cargo test`, where the grader
    // runs beside the student's code) the exploit passes: it is a real one.
    let dir = scratch("exploit").join("copy");
    export_linked(&dir);
    std::fs::write(dir.join("src/ch2.rs"), EXPLOIT).unwrap();
    let test = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .current_dir(&dir)
        .args(["test", "--offline", "--test", "ch2"])
        .env("CARGO_TARGET_DIR", super::target())
        .output()
        .unwrap();
    let printed = String::from_utf8_lossy(&test.stdout);
    let stolen = [
        "eq_2_1_larmor_rate",
        "eq_2_4_schott_angular_momentum",
        "eq_2_2_torque_rate",
    ]
    .iter()
    .filter(|t| printed.contains(&format!("test {t} ... ok")))
    .count();
    assert!(
        stolen >= 1,
        "the exploit passes nothing in process:\n{printed}"
    );
    // Through the runner: nothing to read, 0 points.
    let options = spintop_course::Options {
        launcher: Some(PathBuf::from(env!("CARGO_BIN_EXE_spintop"))),
        work: Some(dir.parent().unwrap().join("work")),
        seed: Some(11),
        ..spintop_course::Options::default()
    };
    let status = spintop_course::grade(&dir, &options).unwrap();
    assert_eq!(status.passing(), 0, "{status:?}");
    std::fs::remove_dir_all(dir.parent().unwrap()).ok();
}

/// What `command` prints on a pseudo-terminal (util-linux's `script`), run
/// to its end (at most ten minutes); None without `script`.
fn on_a_terminal(command: &str) -> Option<String> {
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("SKIPPED: no `script` (util-linux) to give the run a pseudo-terminal");
        return None;
    }
    let start = Instant::now();
    let mut child = Command::new("script")
        .args(["-qec", command, "/dev/null"])
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut seen = String::new();
    let stdout = child.stdout.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = std::io::Read::read_to_string(&mut { stdout }, &mut text);
        text
    });
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "{status:?}");
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(600),
            "course grade on a terminal hangs"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    seen.push_str(&reader.join().unwrap());
    Some(seen)
}

#[test]
#[ignore = "end-to-end: builds copies"]
fn course_grade_on_a_terminal_shows_its_progress_and_finishes() {
    let class = scratch("terminal");
    let copy = class.join("ada");
    honest(&copy);
    let csv = class.join("grades.csv");
    let command = format!(
        "{} course grade {} --out {} --seed 9",
        env!("CARGO_BIN_EXE_spintop"),
        copy.display(),
        csv.display()
    );
    let Some(seen) = on_a_terminal(&command) else {
        return;
    };
    assert!(seen.contains("copies"), "no progress bar: {seen:?}");
    assert!(seen.contains("rows written to"), "{seen:?}");
    let grades = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(total(&grades, "ada").0, 6);
    std::fs::remove_dir_all(&class).ok();
}

/// A student's `spintop course` in their copy, on a terminal: a line says
/// how far the grading has got while it builds and grades (it had said
/// nothing for the minutes of a first build), and the table follows.
#[test]
#[ignore = "end-to-end: builds copies"]
fn spintop_course_on_a_terminal_shows_how_far_the_grading_has_got() {
    let class = scratch("student-terminal");
    let copy = class.join("ada");
    honest(&copy);
    let command = format!(
        "cd '{}' && CARGO_TARGET_DIR='{}' {} course --seed 9",
        copy.display(),
        super::target().display(),
        env!("CARGO_BIN_EXE_spintop"),
    );
    let Some(seen) = on_a_terminal(&command) else {
        return;
    };
    let phases = [
        "starting, 0:0",
        "reading the copy's files, ",
        "compiling ",
        "running the graders, ",
    ];
    assert!(
        phases.iter().any(|p| seen.contains(p)),
        "no progress line: {seen:?}"
    );
    assert!(seen.contains("6 of 22 passing"), "{seen:?}");
    std::fs::remove_dir_all(&class).ok();
}

/// Two gradings of one copy at the same moment (two terminals, a script
/// beside the student): both finish with the same grades. The second waits
/// for the first instead of clearing the sources under it (a reviewer saw
/// "Directory not empty" and exit 2 in 3 of 5 tries).
#[test]
#[ignore = "end-to-end: builds copies"]
fn two_gradings_of_one_copy_at_once_both_finish() {
    let class = scratch("twice");
    let copy = class.join("ada");
    honest(&copy);
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_spintop"))
            .current_dir(&copy)
            .env("CARGO_TARGET_DIR", super::target())
            .args(["course", "--seed", "3"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("spintop runs")
    };
    let graded = |out: std::process::Output| {
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success() && text.contains("6 of 22 passing"),
            "{:?}\n{text}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    };
    // The first grading builds the copy; then three pairs at once.
    graded(run().wait_with_output().unwrap());
    for _ in 0..3 {
        let (a, b) = (run(), run());
        graded(a.wait_with_output().unwrap());
        graded(b.wait_with_output().unwrap());
    }
    std::fs::remove_dir_all(&class).ok();
}
