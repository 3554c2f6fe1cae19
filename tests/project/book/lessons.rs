//! The lesson programs as the book shows them: every `{{#include …}}` and
//! anchor exists, and the output shown in each chapter (and the asymmetric
//! top's figure) is what the lesson prints (draws) now.

use super::{book_src, figure_is_current, stale, summary_chapters};
use std::fs;
use std::io;
use std::path::Path;

#[path = "../../../lessons/appendix_shell.rs"]
mod appendix;
#[path = "../../../lessons/asymmetric_top.rs"]
mod asymmetric;
#[path = "../../../lessons/ch2_balance_laws.rs"]
mod ch2;
#[path = "../../../lessons/ch3_equations_of_motion.rs"]
mod ch3;
#[path = "../../../lessons/ch4_symmetric_top.rs"]
mod ch4;
#[path = "../../../lessons/where_methods_fail.rs"]
mod fail;
#[path = "../../../lessons/figures.rs"]
mod figures;
#[path = "../../../lessons/real_particles.rs"]
mod particles;
#[path = "../../../lessons/speed_accuracy.rs"]
mod speed;

type Lesson = fn(&mut dyn io::Write) -> io::Result<()>;

/// Every lesson program whose output a chapter shows, by example name.
const LESSONS: &[(&str, Lesson)] = &[
    ("ch2_balance_laws", ch2::run),
    ("ch3_equations_of_motion", ch3::run),
    ("ch4_symmetric_top", ch4::run),
    ("appendix_shell", appendix::run),
    ("where_methods_fail", fail::run),
    ("real_particles", particles::run),
    ("speed_accuracy", speed::run),
    ("figures", figures::run),
    ("asymmetric_top", asymmetric::run),
];

fn lesson_output(run: Lesson) -> String {
    let mut buf = Vec::new();
    run(&mut buf).expect("a lesson writes to memory without failing");
    String::from_utf8(buf).expect("lessons print UTF-8")
}

/// Problems with the `{{#include …}}` / `{{#rustdoc_include …}}` directives of
/// one chapter: missing files, or anchors without both markers.
fn include_problems(chapter: &Path) -> Vec<String> {
    let text = fs::read_to_string(chapter).unwrap_or_default();
    let dir = chapter.parent().expect("a chapter lives in a folder");
    let mut problems = Vec::new();
    for directive in ["{{#include ", "{{#rustdoc_include "] {
        for piece in text.split(directive).skip(1) {
            let Some(arg) = piece.split("}}").next() else {
                continue;
            };
            let arg = arg.trim();
            let (file, anchor) = match arg.split_once(':') {
                Some((f, a)) => (f, Some(a)),
                None => (arg, None),
            };
            let path = dir.join(file);
            let Ok(source) = fs::read_to_string(&path) else {
                problems.push(format!("{}: missing file {file}", chapter.display()));
                continue;
            };
            // Line-number ranges (`:10:20`, `:10:`) are plain numbers; names are anchors.
            if let Some(anchor) =
                anchor.filter(|a| !a.chars().next().is_some_and(|c| c.is_ascii_digit()))
            {
                let start = format!("ANCHOR: {anchor}");
                let end = format!("ANCHOR_END: {anchor}");
                let has = |marker: &str| {
                    source
                        .lines()
                        .any(|l| l.trim_start().trim_start_matches("//").trim() == marker)
                };
                if !has(&start) || !has(&end) {
                    problems.push(format!(
                        "{}: anchor '{anchor}' missing in {file}",
                        chapter.display()
                    ));
                }
            }
        }
    }
    problems
}

#[test]
fn book_every_include_and_anchor_exists() {
    let problems: Vec<String> = summary_chapters()
        .iter()
        .flat_map(|c| include_problems(&book_src().join(c)))
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The guard itself can fail: a chapter that includes an anchor which has been
/// removed from its source file is reported.
#[test]
fn book_anchor_check_reports_a_removed_anchor() {
    let dir = std::env::temp_dir().join(format!("spintop-book-anchor-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let chapter = dir.join("chapter.md");
    fs::write(
        &chapter,
        "```rust,ignore\n{{#include code.rs:kept}}\n{{#include code.rs:removed}}\n{{#include gone.rs}}\n```\n",
    )
    .unwrap();
    fs::write(
        dir.join("code.rs"),
        "// ANCHOR: kept\nfn f() {}\n// ANCHOR_END: kept\n",
    )
    .unwrap();
    let problems = include_problems(&chapter);
    fs::remove_dir_all(&dir).unwrap();
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(
        problems[0].contains("missing file gone.rs")
            || problems[1].contains("missing file gone.rs")
    );
    assert!(problems.iter().any(|p| p.contains("anchor 'removed'")));
    assert!(!problems.iter().any(|p| p.contains("'kept'")));
}

#[test]
fn book_shows_the_current_output_of_every_lesson() {
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    let mut problems = Vec::new();
    for (name, run) in LESSONS {
        let output = lesson_output(*run);
        let shown = book_src().join("generated").join(format!("{name}.txt"));
        if update {
            fs::write(&shown, &output).unwrap();
        } else if let Some(problem) = stale(name, &output, &shown) {
            problems.push(problem);
        }
        // The chapter that shows the output also says how to produce it.
        let chapters = summary_chapters();
        let shows = chapters.iter().any(|c| {
            let text = fs::read_to_string(book_src().join(c)).unwrap_or_default();
            text.contains(&format!("generated/{name}.txt"))
                && text.contains(&format!("cargo run --release --example {name}"))
        });
        assert!(
            shows,
            "no chapter shows {name}'s output with its Run it command"
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The staleness check can fail: a changed line is caught and located.
#[test]
fn book_stale_check_reports_changed_output() {
    let path = std::env::temp_dir().join(format!("spintop-book-stale-{}.txt", std::process::id()));
    fs::write(&path, "line one\nline two\n").unwrap();
    assert!(stale("x", "line one\nline two\n", &path).is_none());
    let report = stale("x", "line one\nline 2\n", &path).expect("stale");
    fs::remove_file(&path).unwrap();
    assert!(report.contains("line 2"), "{report}");
}

/// The asymmetric-top chapter's figure is what its lesson draws now
/// (`asymmetric_top::energy_figure`), and the chapter embeds it.
#[test]
fn book_asymmetric_energy_figure_is_what_the_lesson_draws_now() {
    let fresh = asymmetric::energy_figure();
    figure_is_current(
        "figures/asymmetric-energy.svg",
        &fresh,
        "asymmetric-top.md",
        "the asymmetric_top lesson",
    );
    assert!(fresh.contains("dE/dt") && fresh.starts_with("<svg"));
}
