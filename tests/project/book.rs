//! The book stays true to the code.
//!
//! mdBook renders a missing `{{#include file:anchor}}` as an empty block with no
//! error, so these tests are the only guard: every chapter in SUMMARY.md exists
//! and is compiled as a doctest, every included file and anchor exists, and the
//! program output shown in each chapter is what the lesson program prints now.
//!
//! The same holds for the SVG figures: the book's `figures/figure-N.svg` are
//! what `spintop figure N --svg FILE` draws now.
//!
//! After a deliberate change to a lesson or a figure, refresh the book's copies
//! with `UPDATE_BOOK=1 cargo test --test project`, and review the diff.

use std::collections::BTreeSet;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

#[path = "../../lessons/appendix_shell.rs"]
mod appendix;
#[path = "../../lessons/asymmetric_top.rs"]
mod asymmetric;
#[path = "../../lessons/ch2_balance_laws.rs"]
mod ch2;
#[path = "../../lessons/ch3_equations_of_motion.rs"]
mod ch3;
#[path = "../../lessons/ch4_symmetric_top.rs"]
mod ch4;
#[path = "../../lessons/where_methods_fail.rs"]
mod fail;
#[path = "../../lessons/figures.rs"]
mod figures;
#[path = "../../lessons/real_particles.rs"]
mod particles;
#[path = "../../lessons/speed_accuracy.rs"]
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

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn book_src() -> PathBuf {
    root().join("book/src")
}

/// Chapter files linked from SUMMARY.md (drafts, `[Title]()`, have no file).
fn summary_chapters() -> Vec<String> {
    let summary = fs::read_to_string(book_src().join("SUMMARY.md")).expect("SUMMARY.md");
    summary
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .filter(|link| !link.is_empty())
        .map(str::to_string)
        .collect()
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

fn lesson_output(run: Lesson) -> String {
    let mut buf = Vec::new();
    run(&mut buf).expect("a lesson writes to memory without failing");
    String::from_utf8(buf).expect("lessons print UTF-8")
}

/// Compare a lesson's output with the copy the book shows; `None` when fresh.
fn stale(name: &str, output: &str, shown: &Path) -> Option<String> {
    let shown_text = fs::read_to_string(shown).unwrap_or_default();
    if shown_text == output {
        return None;
    }
    let line = shown_text
        .lines()
        .zip(output.lines())
        .position(|(a, b)| a != b)
        .map_or_else(|| "its length".to_string(), |i| format!("line {}", i + 1));
    Some(format!(
        "the book's copy of `{name}` output ({}) is stale at {line}; run UPDATE_BOOK=1 cargo test --test project",
        shown.display()
    ))
}

#[test]
fn book_every_summary_chapter_exists_and_is_compiled_as_a_doctest() {
    let lib = fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let chapters = summary_chapters();
    assert!(chapters.len() >= 4, "{chapters:?}");
    for chapter in &chapters {
        assert!(
            book_src().join(chapter).is_file(),
            "SUMMARY.md lists {chapter}, which is missing"
        );
        let include = format!("include_str!(\"../book/src/{chapter}\")");
        assert!(
            lib.contains(&include),
            "src/lib.rs does not doctest {chapter}: add {include}"
        );
    }
    // And no chapter file sits outside SUMMARY.md, unseen.
    let listed: BTreeSet<&str> = chapters.iter().map(String::as_str).collect();
    for entry in fs::read_dir(book_src()).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".md") && name != "SUMMARY.md" {
            assert!(
                listed.contains(name.as_str()),
                "{name} is not in SUMMARY.md"
            );
        }
    }
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

/// The paper's figures in the book are what `spintop figure N --svg FILE`
/// draws now, and a chapter embeds each of them.
#[test]
fn book_figures_are_what_spintop_figure_draws_now() {
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    let mut problems = Vec::new();
    for n in ["1", "2"] {
        let fresh_path = std::env::temp_dir().join(format!(
            "spintop-book-figure-{n}-{}.svg",
            std::process::id()
        ));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_spintop"))
            .args(["figure", n, "--svg"])
            .arg(&fresh_path)
            .output()
            .expect("the binary runs");
        assert!(
            out.status.success(),
            "spintop figure {n}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let fresh = fs::read_to_string(&fresh_path).expect("the SVG was written");
        fs::remove_file(&fresh_path).unwrap();
        let name = format!("figures/figure-{n}.svg");
        let shown = book_src().join(&name);
        if update {
            fs::create_dir_all(shown.parent().unwrap()).unwrap();
            fs::write(&shown, &fresh).unwrap();
        } else if fs::read_to_string(&shown).unwrap_or_default() != fresh {
            problems.push(format!(
                "the book's {name} is not what `spintop figure {n} --svg` draws now; run UPDATE_BOOK=1 cargo test --test project"
            ));
        }
        let embedded = summary_chapters().iter().any(|c| {
            fs::read_to_string(book_src().join(c))
                .unwrap_or_default()
                .contains(&format!("]({name})"))
        });
        assert!(embedded, "no chapter embeds {name}");
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The asymmetric-top chapter's figure is what its lesson draws now
/// (`asymmetric_top::energy_figure`), and the chapter embeds it.
#[test]
fn book_asymmetric_energy_figure_is_what_the_lesson_draws_now() {
    let fresh = asymmetric::energy_figure();
    let name = "figures/asymmetric-energy.svg";
    let shown = book_src().join(name);
    if std::env::var_os("UPDATE_BOOK").is_some() {
        fs::write(&shown, &fresh).unwrap();
    }
    assert!(
        fs::read_to_string(&shown).unwrap_or_default() == fresh,
        "the book's {name} is not what the asymmetric_top lesson draws now; run UPDATE_BOOK=1 cargo test --test project"
    );
    let chapter = fs::read_to_string(book_src().join("asymmetric-top.md")).unwrap();
    assert!(
        chapter.contains(&format!("]({name})")),
        "the chapter embeds {name}"
    );
    assert!(fresh.contains("dE/dt") && fresh.starts_with("<svg"));
}

/// The modules whose header tables make up the book's symbol table, in the
/// paper's order, with the chapter that uses them.
const SYMBOL_MODULES: &[(&str, &str, &str, &str)] = &[
    (
        "src/physics/balance.rs",
        "physics::balance",
        "section-2.md",
        "Section 2",
    ),
    (
        "src/physics/central.rs",
        "physics::central",
        "section-2.md",
        "Section 2",
    ),
    (
        "src/physics/rigid_body.rs",
        "physics::rigid_body",
        "section-3.md",
        "Section 3",
    ),
    (
        "src/physics/euler_angles.rs",
        "physics::euler_angles",
        "section-3.md",
        "Section 3",
    ),
    (
        "src/physics/general_top.rs",
        "physics::general_top",
        "section-3.md",
        "Section 3",
    ),
    (
        "src/physics/full_ale.rs",
        "physics::full_ale",
        "section-3.md",
        "Section 3",
    ),
    (
        "src/sim/physical.rs",
        "sim::physical",
        "where-methods-fail.md",
        "Where methods fail",
    ),
    (
        "src/physics/symmetric_top.rs",
        "physics::symmetric_top",
        "section-4-1.md",
        "Section 4.1",
    ),
    ("src/figure.rs", "figure", "section-5.md", "Section 5"),
    (
        "src/physics/shell.rs",
        "physics::shell",
        "appendix.md",
        "Appendix",
    ),
    (
        "src/physics/particle.rs",
        "physics::particle",
        "real-particles.md",
        "Real particles",
    ),
    (
        "src/math.rs",
        "math",
        "numerical-methods.md",
        "Numerical methods",
    ),
];

/// The symbol table page: for each module in [`SYMBOL_MODULES`], the first
/// paragraph of its documentation and its `| code name | symbol | …` table,
/// copied from the source so that the page cannot drift from the code.
fn symbol_table() -> String {
    let mut out = String::from(
        "<!-- Generated from the module headers by tests/project/book.rs; refresh with UPDATE_BOOK=1 cargo test --test project -->\n",
    );
    for (file, module, chapter, title) in SYMBOL_MODULES {
        let source = fs::read_to_string(root().join(file)).expect("a listed module exists");
        let doc: Vec<&str> = source
            .lines()
            .take_while(|l| l.starts_with("//!"))
            .map(|l| l.trim_start_matches("//!").trim())
            .collect();
        let summary = doc
            .iter()
            .take_while(|l| !l.is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join(" ");
        let start = doc
            .iter()
            .position(|l| l.starts_with("| code name | symbol |"))
            .unwrap_or_else(|| panic!("{file} has no | code name | symbol | table"));
        let table: Vec<&str> = doc[start..]
            .iter()
            .take_while(|l| l.starts_with('|'))
            .copied()
            .collect();
        out.push_str(&format!(
            "\n## `spintop::{module}`\n\n{} Chapter: [{title}]({chapter}).\n\n{}\n",
            plain_code_names(&summary),
            plain_code_names(&table.join("\n"))
        ));
    }
    out
}

/// Rustdoc's intra-doc links, [`name`], as plain code, `name`: mdBook does
/// not resolve them and would show the brackets.
fn plain_code_names(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find("[`") {
        let Some(close) = rest[open + 2..].find("`]").map(|i| i + open + 2) else {
            break;
        };
        let after = &rest[close + 2..];
        out.push_str(&rest[..open]);
        if after.starts_with('(') {
            // A real Markdown link: keep it.
            out.push_str(&rest[open..close + 2]);
        } else {
            out.push_str(&rest[open + 1..close + 1]);
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

#[test]
fn book_symbol_table_drops_intra_doc_brackets_only() {
    assert_eq!(
        plain_code_names("a [`f`] b [`g`](x.md) c [`T::m`]"),
        "a `f` b [`g`](x.md) c `T::m`"
    );
}

#[test]
fn book_symbol_table_is_the_module_headers_now() {
    let fresh = symbol_table();
    let shown = book_src().join("generated/symbols.md");
    if std::env::var_os("UPDATE_BOOK").is_some() {
        fs::write(&shown, &fresh).unwrap();
    } else if let Some(problem) = stale("symbol table", &fresh, &shown) {
        panic!("{problem}");
    }
    let chapters = summary_chapters();
    assert!(
        chapters
            .iter()
            .any(|c| fs::read_to_string(book_src().join(c))
                .unwrap_or_default()
                .contains("{{#include generated/symbols.md}}")),
        "no chapter shows the symbol table"
    );
    for (_, _, chapter, _) in SYMBOL_MODULES {
        assert!(
            chapters.iter().any(|c| c == chapter),
            "{chapter} is not in SUMMARY.md"
        );
    }
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

/// The paper's equation numbers in `text`: (2.1), (4.12), (A.3), …
fn equation_numbers(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (i, _) in text.match_indices('(') {
        let rest = &text[i + 1..];
        let Some(end) = rest.find(')') else { continue };
        let inner = &rest[..end];
        let ok = inner.len() <= 5
            && inner.split_once('.').is_some_and(|(a, b)| {
                matches!(a, "2" | "3" | "4" | "A")
                    && !b.is_empty()
                    && b.chars().all(|c| c.is_ascii_digit())
            });
        if ok {
            out.insert(inner.to_string());
        }
    }
    out
}

/// The numbers a display block tags, ranges such as (4.2)–(4.4) included.
fn typeset_numbers(block: &str) -> BTreeSet<String> {
    let mut out = equation_numbers(block);
    for (i, _) in block.match_indices(")–(") {
        let before = &block[..i];
        let after = &block[i + ")–(".len()..];
        let (Some(open), Some(close)) = (before.rfind('('), after.find(')')) else {
            continue;
        };
        let (from, to) = (&before[open + 1..], &after[..close]);
        if let (Some((p, a)), Some((q, b))) = (from.split_once('.'), to.split_once('.'))
            && p == q
            && let (Ok(a), Ok(b)) = (a.parse::<u32>(), b.parse::<u32>())
        {
            for n in a..=b {
                out.insert(format!("{p}.{n}"));
            }
        }
    }
    out
}

#[test]
fn book_every_cited_equation_is_typeset() {
    let mut cited = BTreeSet::new();
    let mut typeset = BTreeSet::new();
    for chapter in summary_chapters() {
        let text = fs::read_to_string(book_src().join(&chapter)).unwrap();
        cited.extend(equation_numbers(&text));
        for (k, block) in text.split("$$").enumerate() {
            if k % 2 == 1 {
                typeset.extend(typeset_numbers(block));
            }
        }
    }
    let missing: Vec<&String> = cited.difference(&typeset).collect();
    assert!(
        missing.is_empty(),
        "cited but never typeset as display math: {missing:?}"
    );
    // The paper's equations, all of them.
    for n in (1..=9)
        .map(|n| format!("2.{n}"))
        .chain((1..=5).map(|n| format!("3.{n}")))
    {
        assert!(typeset.contains(&n), "({n}) is not typeset");
    }
    for n in (1..=18).map(|n| format!("4.{n}")) {
        assert!(typeset.contains(&n), "({n}) is not typeset");
    }
    for n in 1..=3 {
        assert!(
            typeset.contains(&format!("A.{n}")),
            "(A.{n}) is not typeset"
        );
    }
    // The check can fail: a block's tags are read, ranges included.
    assert_eq!(
        typeset_numbers(r"\dot x \qquad\text{(4.2)–(4.4)}"),
        ["4.2", "4.3", "4.4"].map(String::from).into()
    );
}

/// The diagrams of the book: each exists, is an SVG with a title, and is
/// shown by a chapter.
#[test]
fn book_diagrams_exist_and_are_shown() {
    let mut text = String::new();
    for chapter in summary_chapters() {
        text.push_str(&fs::read_to_string(book_src().join(&chapter)).unwrap());
    }
    for name in [
        "top-axes-dipole",
        "euler-angles",
        "precession-cone",
        "shell-model",
        "slow-manifold",
    ] {
        let path = book_src().join(format!("figures/{name}.svg"));
        let svg =
            fs::read_to_string(&path).unwrap_or_else(|_| panic!("{} is missing", path.display()));
        assert!(svg.starts_with("<svg") && svg.contains("<title>"), "{name}");
        assert!(
            !svg.contains("http://") || svg.matches("http://").count() == 1,
            "{name}: only the SVG namespace"
        );
        assert!(
            text.contains(&format!("(figures/{name}.svg)")),
            "{name}.svg is not shown in any chapter"
        );
    }
}

/// The speed chapter's cost-against-horizon chart is drawn by code from the
/// committed benchmark medians (benches/results/horizon-2026-11-25.csv).
#[test]
fn book_cost_horizon_figure_is_drawn_from_the_committed_medians() {
    let csv = fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("benches/results/horizon-2026-11-25.csv"),
    )
    .unwrap();
    let fresh = spintop::workprecision::report::horizon_figure(&csv).expect("the medians parse");
    let name = "figures/cost-horizon.svg";
    let shown = book_src().join(name);
    if std::env::var_os("UPDATE_BOOK").is_some() {
        fs::write(&shown, &fresh).unwrap();
    }
    assert!(
        fs::read_to_string(&shown).unwrap_or_default() == fresh,
        "the book's {name} is not what horizon_figure draws from the CSV; run UPDATE_BOOK=1 cargo test --test project"
    );
    let chapter = fs::read_to_string(book_src().join("speed-accuracy.md")).unwrap();
    assert!(
        chapter.contains(&format!("]({name})")),
        "the chapter embeds {name}"
    );
    // The closed form's cost does not grow with T; DOP853's does.
    let rows: Vec<(String, f64, f64)> = csv
        .lines()
        .skip(1)
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (
                c[0].to_string(),
                c[1].parse().unwrap(),
                c[2].parse().unwrap(),
            )
        })
        .collect();
    let of = |m: &str| -> Vec<f64> {
        rows.iter()
            .filter(|r| r.0.starts_with(m))
            .map(|r| r.2)
            .collect()
    };
    let (closed, dop) = (of("closed form"), of("DOP853"));
    assert!(
        closed.iter().cloned().fold(0.0, f64::max)
            < 1.5 * closed.iter().cloned().fold(f64::INFINITY, f64::min)
    );
    assert!(dop.last().unwrap() > &(100.0 * dop[0]));
}
