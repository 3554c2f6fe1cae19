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
//! with `UPDATE_BOOK=1 cargo test -p spintop-app --test app project::`, and review the diff.

use std::collections::{BTreeMap, BTreeSet};
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

/// A figure the book embeds is what code draws now: `fresh` is written to
/// `book/src/NAME` under `UPDATE_BOOK=1`, must equal the file otherwise, and
/// `chapter` must embed it. Returns the chapter's text.
fn figure_is_current(name: &str, fresh: &str, chapter: &str, drawn_by: &str) -> String {
    let shown = book_src().join(name);
    if std::env::var_os("UPDATE_BOOK").is_some() {
        fs::write(&shown, fresh).unwrap();
    }
    assert!(
        fs::read_to_string(&shown).unwrap_or_default() == fresh,
        "the book's {name} is not what {drawn_by} draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::"
    );
    let text = fs::read_to_string(book_src().join(chapter)).unwrap();
    assert!(
        text.contains(&format!("]({name})")),
        "{chapter} embeds {name}"
    );
    text
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
        "the book's copy of `{name}` output ({}) is stale at {line}; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::",
        shown.display()
    ))
}

#[test]
fn book_every_summary_chapter_exists_and_is_compiled_as_a_doctest() {
    // The core doctests the chapters; the course's chapters, whose snippets
    // use the graders and the course runner, are doctested by spintop-course.
    let lib = [
        "crates/spintop/src/lib.rs",
        "crates/spintop-course/src/lib.rs",
    ]
    .map(|f| fs::read_to_string(root().join(f)).unwrap())
    .concat();
    let chapters = summary_chapters();
    assert!(chapters.len() >= 4, "{chapters:?}");
    for chapter in &chapters {
        assert!(
            book_src().join(chapter).is_file(),
            "SUMMARY.md lists {chapter}, which is missing"
        );
        let include = format!("include_str!(\"../../../book/src/{chapter}\")");
        assert!(
            lib.contains(&include),
            "crates/spintop/src/lib.rs does not doctest {chapter}: add {include}"
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
                "the book's {name} is not what `spintop figure {n} --svg` draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::"
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
    figure_is_current(
        "figures/asymmetric-energy.svg",
        &fresh,
        "asymmetric-top.md",
        "the asymmetric_top lesson",
    );
    assert!(fresh.contains("dE/dt") && fresh.starts_with("<svg"));
}

/// The modules whose header tables make up the book's symbol table, in the
/// paper's order, with the chapter that uses them.
const SYMBOL_MODULES: &[(&str, &str, &str, &str)] = &[
    (
        "crates/spintop/src/physics/balance.rs",
        "physics::balance",
        "section-2.md",
        "Section 2",
    ),
    (
        "crates/spintop/src/physics/radiation.rs",
        "physics::radiation",
        "section-2.md",
        "Section 2",
    ),
    (
        "crates/spintop/src/physics/central.rs",
        "physics::central",
        "section-2.md",
        "Section 2",
    ),
    (
        "crates/spintop/src/physics/rigid_body.rs",
        "physics::rigid_body",
        "section-3.md",
        "Section 3",
    ),
    (
        "crates/spintop/src/physics/euler_angles.rs",
        "physics::euler_angles",
        "section-3.md",
        "Section 3",
    ),
    (
        "crates/spintop/src/physics/general_top.rs",
        "physics::general_top",
        "section-3.md",
        "Section 3",
    ),
    (
        "crates/spintop/src/physics/full_ale.rs",
        "physics::full_ale",
        "section-3.md",
        "Section 3",
    ),
    (
        "crates/spintop/src/sim/physical.rs",
        "sim::physical",
        "where-methods-fail.md",
        "Where methods fail",
    ),
    (
        "crates/spintop/src/physics/symmetric_top.rs",
        "physics::symmetric_top",
        "section-4-1.md",
        "Section 4.1",
    ),
    (
        "crates/spintop/src/figure.rs",
        "figure",
        "section-5.md",
        "Section 5",
    ),
    (
        "crates/spintop/src/physics/shell.rs",
        "physics::shell",
        "appendix.md",
        "Appendix",
    ),
    (
        "crates/spintop/src/physics/particle.rs",
        "physics::particle",
        "real-particles.md",
        "Real particles",
    ),
    (
        "crates/spintop/src/math.rs",
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
        "<!-- Generated from the module headers by tests/project/book.rs; refresh with UPDATE_BOOK=1 cargo test -p spintop-app --test app project:: -->\n",
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
            accents_as_math(&plain_code_names(&summary)),
            accents_as_math(&plain_code_names(&table.join("\n")))
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

/// A combining accent (the dot of Ω̇, the tilde of Ω̃₃, the three dots of 𝔡⃛).
fn is_accent(c: char) -> bool {
    matches!(c, '\u{300}'..='\u{36f}' | '\u{20d0}'..='\u{20ff}')
}

/// The module headers write symbols in Unicode (rustdoc shows them so); on the
/// book's symbol page an accented symbol becomes inline math, which KaTeX draws
/// with the accent over its letter: `Ω̃₃` becomes `$\tilde\Omega_3$`, `L̇_S`
/// becomes `$\dot{L}_S$`. Code spans are left alone.
fn accents_as_math(text: &str) -> String {
    let text = text.replace('Ż', "Z\u{307}").replace('ż', "z\u{307}");
    let greek = |c: char| -> Option<&'static str> {
        Some(match c {
            'Ω' => r"\Omega",
            'ω' => r"\omega",
            'φ' => r"\varphi",
            'ψ' => r"\psi",
            'θ' => r"\theta",
            'σ' => r"\sigma",
            'τ' => r"\tau",
            'α' => r"\alpha",
            '𝔡' => r"{\bfrak d}",
            _ => return None,
        })
    };
    let accent = |c: char| match c {
        '\u{307}' => r"\dot",
        '\u{308}' => r"\ddot",
        '\u{20db}' => r"\dddot",
        '\u{303}' => r"\tilde",
        '\u{304}' => r"\bar",
        '\u{302}' => r"\hat",
        other => panic!("an accent the symbol page does not know: {:?}", other),
    };
    let subscript = |c: char| "₀₁₂₃₄₅₆₇₈₉".chars().position(|d| d == c);
    let mut out = String::new();
    let mut in_code = false;
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '`' {
            in_code = !in_code;
        }
        let accented = !in_code
            && (c.is_alphabetic() || greek(c).is_some())
            && chars.get(i + 1).is_some_and(|&n| is_accent(n));
        if !accented {
            out.push(c);
            i += 1;
            continue;
        }
        // One symbol: a letter, its accents, its subscripts (₃, ⊥ or _S).
        let mut tex = greek(c).map_or_else(|| c.to_string(), str::to_string);
        i += 1;
        while let Some(&m) = chars.get(i).filter(|&&m| is_accent(m)) {
            // \dot\Omega and \dot{\bfrak d} as they stand; a letter in braces.
            tex = if tex.starts_with(['\\', '{']) {
                format!("{}{tex}", accent(m))
            } else {
                format!("{}{{{tex}}}", accent(m))
            };
            i += 1;
        }
        let mut sub = String::new();
        while let Some(&d) = chars.get(i) {
            if let Some(k) = subscript(d) {
                sub.push(char::from(b'0' + k as u8));
            } else if d == '⊥' {
                sub.push_str(r"\perp");
            } else if d == '_' && chars.get(i + 1).is_some_and(|n| n.is_ascii_alphabetic()) {
                i += 1;
                while let Some(&l) = chars.get(i).filter(|l| l.is_ascii_alphabetic()) {
                    sub.push(l);
                    i += 1;
                }
                continue;
            } else {
                break;
            }
            i += 1;
        }
        if !sub.is_empty() {
            tex = format!("{tex}_{{{sub}}}");
        }
        out.push_str(&format!("${tex}$"));
    }
    out
}

#[test]
fn book_symbol_table_writes_accented_symbols_as_math() {
    assert_eq!(accents_as_math("Ω̃₃ and `Ω̇`"), r"$\tilde\Omega_{3}$ and `Ω̇`");
    assert_eq!(
        accents_as_math("L̇_S = 𝔡̇ × 𝔡̈"),
        r"$\dot{L}_{S}$ = $\dot{\bfrak d}$ × $\ddot{\bfrak d}$"
    );
    assert_eq!(accents_as_math("(φ̇, Ż)"), r"($\dot\varphi$, $\dot{Z}$)");
    // Outside code spans, no accent is left on the page.
    let page = symbol_table();
    let prose = page.split('`').step_by(2).collect::<String>();
    assert!(!prose.chars().any(is_accent));
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

/// The numbers a display block tags: `\tag{4.2}`, and ranges such as
/// (4.2)–(4.4) written out.
fn typeset_numbers(block: &str) -> BTreeSet<String> {
    let mut out = equation_numbers(block);
    for piece in block.split("\\tag{").skip(1) {
        if let Some(end) = piece.find('}') {
            out.extend(equation_numbers(&format!("({})", &piece[..end])));
        }
    }
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
    assert_eq!(
        typeset_numbers(r"a &= b \tag{4.12}\\ c &= d \tag{4.13}"),
        ["4.12", "4.13"].map(String::from).into()
    );
    assert!(typeset_numbers(r"a = b").is_empty());
}

/// The prose of a chapter: its text without code blocks, inline code (the
/// live view's experiments among it), math, HTML comments and image
/// descriptions.
fn prose(chapter: &str) -> String {
    let mut out = String::new();
    let mut rest = chapter;
    // Pairs of delimiters whose content is not prose, longest first.
    let skip = [
        ("```", "```"),
        ("<!--", "-->"),
        ("$$", "$$"),
        ("![", "]("),
        ("`", "`"),
        ("$", "$"),
    ];
    'outer: while !rest.is_empty() {
        for (open, close) in skip {
            if let Some(body) = rest.strip_prefix(open) {
                let end = body.find(close).map_or(body.len(), |e| e + close.len());
                rest = &body[end..];
                out.push(' ');
                continue 'outer;
            }
        }
        let c = rest.chars().next().unwrap();
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}

/// Accents are drawn by KaTeX over their letters; in the prose a browser's
/// text font puts a combining accent beside its letter or drops it, so an
/// accented symbol in the text is written as inline math.
#[test]
fn book_prose_writes_accented_symbols_as_math() {
    let mut problems = Vec::new();
    for chapter in summary_chapters() {
        let text = fs::read_to_string(book_src().join(&chapter)).unwrap();
        let text = prose(&text);
        for line in text.lines().filter(|l| l.chars().any(is_accent)) {
            problems.push(format!("{chapter}: {}", line.trim()));
        }
    }
    assert!(
        problems.is_empty(),
        "combining accents in the prose:\n{}",
        problems.join("\n")
    );
    // The check can fail.
    assert!(prose("a Ω̇ b `Ω̇` $\\dot\\Omega$").chars().any(is_accent));
    assert!(
        !prose("a `Ω̇` $\\dot\\Omega$ <!-- Ω̇ --> ![Ω̇](x.svg)")
            .chars()
            .any(is_accent)
    );
}

/// The diagrams of the book: each is what `spintop::plot::diagram` draws now
/// (refresh with UPDATE_BOOK=1), is an SVG with a title, and is shown by a
/// chapter; the slow-manifold sketch is the one drawn by hand.
#[test]
fn book_diagrams_are_what_the_generator_draws_now_and_are_shown() {
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    let mut text = String::new();
    for chapter in summary_chapters() {
        text.push_str(&fs::read_to_string(book_src().join(&chapter)).unwrap());
    }
    let mut problems = Vec::new();
    for d in spintop::plot::diagram::all() {
        let path = book_src().join(format!("figures/{}.svg", d.name));
        if update {
            fs::write(&path, &d.svg).unwrap();
        } else if fs::read_to_string(&path).unwrap_or_default() != d.svg {
            problems.push(format!(
                "the book's figures/{}.svg is not what the diagram generator draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::",
                d.name
            ));
        }
        assert!(
            text.contains(&format!("(figures/{}.svg)", d.name)),
            "{}.svg is not shown in any chapter",
            d.name
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    let sketch = fs::read_to_string(book_src().join("figures/slow-manifold.svg")).unwrap();
    assert!(sketch.starts_with("<svg") && sketch.contains("<title>"));
    assert!(text.contains("(figures/slow-manifold.svg)"));
}

/// One element of an SVG: its name, attributes and text.
#[derive(Debug, Default, Clone)]
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    text: String,
}

impl Element {
    fn get(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn num(&self, key: &str) -> f64 {
        self.get(key)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("<{}> has no number {key}", self.name))
    }
    fn has_class(&self, class: &str) -> bool {
        self.get("class")
            .is_some_and(|c| c.split_whitespace().any(|x| x == class))
    }
}

/// The elements of an SVG in document order, each with the `data-frame` of
/// the `<g class="frame">` around it (the generator writes one tag per
/// element, so a small reader does; a malformed file fails loudly).
fn svg_elements(svg: &str) -> Vec<(Option<String>, Element)> {
    let mut out = Vec::new();
    let mut frame: Option<String> = None;
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        let end = rest.find('>').expect("a tag ends");
        let tag = &rest[..end];
        rest = &rest[end + 1..];
        if tag.starts_with('/') {
            if tag == "/g" {
                frame = None;
            }
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| !c.is_whitespace() && *c != '/')
            .collect();
        let mut attrs = Vec::new();
        let mut a = &tag[name.len()..];
        while let Some(eq) = a.find("=\"") {
            let key = a[..eq].trim().to_string();
            let after = &a[eq + 2..];
            let close = after.find('"').expect("an attribute ends");
            attrs.push((key, after[..close].to_string()));
            a = &after[close + 1..];
        }
        let mut e = Element {
            name: name.clone(),
            attrs,
            text: String::new(),
        };
        if name == "text" || name == "title" {
            let close = rest.find('<').expect("text ends");
            e.text = rest[..close]
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
        }
        if name == "g" && e.has_class("frame") {
            frame = e.get("data-frame").map(str::to_string);
        }
        out.push((frame.clone(), e));
    }
    out
}

/// The page points of a path's `d` ("M x,y L x,y …").
fn path_points(d: &str) -> Vec<(f64, f64)> {
    d.split(['M', 'L'])
        .filter(|p| !p.trim().is_empty())
        .map(|p| {
            let (x, y) = p.trim().split_once(',').expect("x,y");
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// A box on the page: left, top, right, bottom.
type PageBox = (f64, f64, f64, f64);

/// The box a label takes on the page, from its position, size and anchor
/// (an estimate on the generous side: 0.6 em per character, none for a
/// combining accent).
fn label_box(e: &Element) -> PageBox {
    let size = e.num("font-size");
    let width: f64 = e
        .text
        .chars()
        .map(|c| match c {
            '\u{300}'..='\u{36f}' => 0.0,
            ' ' => 0.3,
            _ => 0.6,
        })
        .sum::<f64>()
        * size;
    let x = e.num("x");
    let left = match e.get("text-anchor") {
        Some("middle") => x - width / 2.0,
        Some("end") => x - width,
        _ => x,
    };
    let y = e.num("y");
    (left, y - 0.8 * size, left + width, y + 0.25 * size)
}

/// Everything wrong with one diagram's geometry, read from its SVG alone.
fn diagram_problems(name: &str, elements: &[(Option<String>, Element)]) -> Vec<String> {
    let mut problems = Vec::new();
    // Frames: rebuild each axis as (dx, up, toward) and check the triple.
    let mut frames: BTreeMap<String, Vec<(String, [f64; 3])>> = BTreeMap::new();
    for (frame, e) in elements {
        if let (Some(frame), true) = (frame, e.has_class("axis")) {
            let v = [
                e.num("x2") - e.num("x1"),
                -(e.num("y2") - e.num("y1")),
                e.num("data-depth"),
            ];
            frames
                .entry(frame.clone())
                .or_default()
                .push((e.get("data-axis").unwrap_or("?").to_string(), v));
        }
    }
    if frames.is_empty() {
        problems.push(format!("{name}: no frame drawn"));
    }
    for (frame, axes) in &frames {
        if axes.len() != 3 {
            problems.push(format!("{name}: frame {frame} has {} axes", axes.len()));
            continue;
        }
        let unit = |v: [f64; 3]| {
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / n, v[1] / n, v[2] / n]
        };
        let (a, b, c) = (unit(axes[0].1), unit(axes[1].1), unit(axes[2].1));
        let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        for (p, q) in [(a, b), (b, c), (c, a)] {
            if dot(p, q).abs() > 0.02 {
                problems.push(format!("{name}: frame {frame} is not orthogonal"));
            }
        }
        let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
        if det < 0.98 {
            problems.push(format!(
                "{name}: frame {frame} ({}, {}, {}) is left-handed on the page (det {det:.3})",
                axes[0].0, axes[1].0, axes[2].0
            ));
        }
        if frame == "lab" {
            // Seen from above: z goes up the page and leans toward the viewer.
            let z = axes[2].1;
            if !(z[1] > 0.0 && z[2] > 0.0) {
                problems.push(format!("{name}: the lab frame is not seen from above"));
            }
        }
    }
    // Arcs about lab z turn counterclockwise on the page, as seen from above.
    for (_, e) in elements {
        if e.has_class("arc") && e.get("data-about") == Some("z") {
            let pts = path_points(e.get("d").unwrap());
            let (cx, cy) = (e.num("data-cx"), e.num("data-cy"));
            let (s, t) = (pts[0], pts[pts.len() - 1]);
            // y down on the page: counterclockwise is a negative cross product.
            let cross = (s.0 - cx) * (t.1 - cy) - (s.1 - cy) * (t.0 - cx);
            if cross >= 0.0 {
                problems.push(format!("{name}: an arc about z turns clockwise"));
            }
        }
    }
    // Cones: each edge ends on its rim, and touches it there (the whole rim
    // on one side of the edge's line).
    let mut rims: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for (_, e) in elements {
        if e.has_class("rim") {
            rims.entry(e.get("data-cone").unwrap().to_string())
                .or_default()
                .extend(path_points(e.get("d").unwrap()));
        }
    }
    for (_, e) in elements {
        if !e.has_class("cone-edge") {
            continue;
        }
        let cone = e.get("data-cone").unwrap();
        let Some(rim) = rims.get(cone) else {
            problems.push(format!("{name}: cone {cone} has an edge and no rim"));
            continue;
        };
        let (a, b) = ((e.num("x1"), e.num("y1")), (e.num("x2"), e.num("y2")));
        let gap = rim
            .windows(2)
            .map(|w| point_segment_distance(b, w[0], w[1]))
            .fold(f64::INFINITY, f64::min);
        if gap > 0.75 {
            problems.push(format!(
                "{name}: an edge of cone {cone} misses its rim by {gap:.2} px"
            ));
        }
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let side = |p: (f64, f64)| (dx * (p.1 - a.1) - dy * (p.0 - a.0)) / len;
        let (lo, hi) = rim
            .iter()
            .map(|&p| side(p))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
                (l.min(s), h.max(s))
            });
        if lo < -0.75 && hi > 0.75 {
            problems.push(format!(
                "{name}: an edge of cone {cone} cuts across its rim"
            ));
        }
    }
    // Labels: no two overlap.
    let labels: Vec<(&Element, PageBox)> = elements
        .iter()
        .filter(|(_, e)| e.name == "text" && e.has_class("label") && e.text.trim() != "+")
        .map(|(_, e)| (e, label_box(e)))
        .collect();
    for (i, (e, p)) in labels.iter().enumerate() {
        for (f, q) in &labels[i + 1..] {
            if p.0 < q.2 && q.0 < p.2 && p.1 < q.3 && q.1 < p.3 {
                problems.push(format!(
                    "{name}: labels '{}' and '{}' overlap",
                    e.text, f.text
                ));
            }
        }
    }
    problems
}

fn point_segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// Every generated diagram in the book is right-handed, its cones meet their
/// rims, and its labels do not overlap: read from the SVG files themselves.
#[test]
fn book_diagrams_are_right_handed_with_cones_on_their_rims_and_no_overlapping_labels() {
    let mut problems = Vec::new();
    let mut cones = 0;
    for name in spintop::plot::diagram::NAMES {
        let svg = fs::read_to_string(book_src().join(format!("figures/{name}.svg"))).unwrap();
        cones += svg.matches("class=\"cone-edge\"").count();
        problems.extend(
            diagram_problems(name, &svg_elements(&svg))
                .into_iter()
                // The shell is a plane sketch: no frame to check.
                .filter(|p| !(name == "shell-model" && p.contains("no frame drawn"))),
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert_eq!(
        cones, 6,
        "the precession cone and the two cones of the free top"
    );
}

/// The checks can fail: a diagram mirrored left to right is left-handed and
/// its arcs about z turn the wrong way; a moved cone edge misses its rim; a
/// label put on top of another overlaps it.
#[test]
fn book_diagram_checks_catch_a_mirror_a_loose_edge_and_a_label_on_a_label() {
    let svg = fs::read_to_string(book_src().join("figures/precession-cone.svg")).unwrap();
    let elements = svg_elements(&svg);
    assert!(diagram_problems("precession-cone", &elements).is_empty());
    // Every page x mirrored (x -> 600 - x), the depths kept: a left-handed drawing.
    let mirrored: Vec<(Option<String>, Element)> = elements
        .iter()
        .map(|(f, e)| {
            let mut e = e.clone();
            for (k, v) in e.attrs.iter_mut() {
                if ["x1", "x2", "x", "data-cx"].contains(&k.as_str()) {
                    *v = format!("{:.1}", 600.0 - v.parse::<f64>().unwrap());
                } else if k == "d" && v.starts_with('M') && !v.contains('z') {
                    *v = path_points(v)
                        .iter()
                        .enumerate()
                        .map(|(i, p)| {
                            format!(
                                "{}{:.1},{:.1}",
                                if i == 0 { "M" } else { "L" },
                                600.0 - p.0,
                                p.1
                            )
                        })
                        .collect::<Vec<_>>()
                        .join(" ");
                }
            }
            (f.clone(), e)
        })
        .collect();
    let found = diagram_problems("mirror", &mirrored);
    assert!(found.iter().any(|p| p.contains("left-handed")), "{found:?}");
    assert!(found.iter().any(|p| p.contains("clockwise")), "{found:?}");
    // A cone edge whose end is moved 4 px off its rim, across the edge.
    let mut loose = elements.clone();
    let edge = loose
        .iter_mut()
        .find(|(_, e)| e.has_class("cone-edge"))
        .unwrap();
    let (x1, y1, x2, y2) = (
        edge.1.num("x1"),
        edge.1.num("y1"),
        edge.1.num("x2"),
        edge.1.num("y2"),
    );
    let len = (x2 - x1).hypot(y2 - y1);
    for (k, v) in edge.1.attrs.iter_mut() {
        match k.as_str() {
            "x2" => *v = format!("{:.1}", x2 - 4.0 * (y2 - y1) / len),
            "y2" => *v = format!("{:.1}", y2 + 4.0 * (x2 - x1) / len),
            _ => {}
        }
    }
    let found = diagram_problems("loose", &loose);
    assert!(
        found.iter().any(|p| p.contains("misses its rim")),
        "{found:?}"
    );
    // A second label on top of the first.
    let mut doubled = elements.clone();
    let first = doubled
        .iter()
        .find(|(_, e)| e.has_class("label"))
        .unwrap()
        .clone();
    doubled.push(first);
    let found = diagram_problems("doubled", &doubled);
    assert!(found.iter().any(|p| p.contains("overlap")), "{found:?}");
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
    figure_is_current(
        "figures/cost-horizon.svg",
        &fresh,
        "speed-accuracy.md",
        "horizon_figure (from the CSV)",
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

/// The speed chapter's work-precision figure (time of a solve against its
/// error, the Taylor method beside the Runge–Kutta methods of every crate)
/// is drawn by code from a committed peers run, and the numbers the chapter
/// gives from that run are the run's: the best Runge–Kutta method's time
/// over the Taylor method's at matched errors 1e-8 and 1e-14 in its
/// interleaved head-to-head (median over the rounds), spintop's DOP853 being
/// that best method in most rounds at 1e-14, whether the 2× goal on the
/// general top is met, and where DOP853 is the faster at loose tolerances
/// in the sweep.
#[test]
fn book_work_precision_figure_is_drawn_from_the_committed_peers_run() {
    use spintop::workprecision::{Target, report};
    let read = |file: &str| fs::read_to_string(root().join(file)).unwrap();
    let rows = report::parse_csv(&read(TAYLOR_PEERS_RUN)).expect("the run parses");
    let fresh = report::work_precision_figure(&rows).expect("rows to draw");
    let chapter = figure_is_current(
        "figures/work-precision.svg",
        &fresh,
        "speed-accuracy.md",
        &format!("work_precision_figure (from {TAYLOR_PEERS_RUN})"),
    );
    // The claims are read across line breaks.
    let chapter = chapter.split_whitespace().collect::<Vec<_>>().join(" ");
    for file in [TAYLOR_PEERS_RUN, TAYLOR_H2H_RUN] {
        assert!(chapter.contains(file), "the chapter names {file}");
    }
    // The head-to-head: (model, error, "source method") -> time per round.
    let mut h2h: BTreeMap<(String, String, String), Vec<f64>> = BTreeMap::new();
    for line in read(TAYLOR_H2H_RUN).lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let key = (
            c[0].to_string(),
            c[1].to_string(),
            format!("{} {}", c[2], c[3]),
        );
        h2h.entry(key).or_default().push(c[5].parse().unwrap());
    }
    // The best Runge–Kutta time over the Taylor method's, median over the
    // rounds, and how often each method was the best Runge–Kutta method.
    let versus_rk = |model: &str, error: &str| -> (f64, BTreeMap<String, usize>) {
        let at =
            |name: &str| h2h[&(model.to_string(), error.to_string(), name.to_string())].clone();
        let taylor = at("spintop taylor");
        let others: Vec<(&String, &Vec<f64>)> = h2h
            .iter()
            .filter(|((m, e, n), _)| m == model && e == error && n != "spintop taylor")
            .map(|((_, _, n), t)| (n, t))
            .collect();
        let mut best_names = BTreeMap::new();
        let mut ratios: Vec<f64> = (0..taylor.len())
            .map(|r| {
                let (name, best) = others
                    .iter()
                    .map(|(n, t)| (n, t[r]))
                    .filter(|(_, t)| t.is_finite())
                    .fold(
                        (&others[0].0, f64::INFINITY),
                        |a, b| if b.1 < a.1 { b } else { a },
                    );
                *best_names.entry(name.to_string()).or_insert(0) += 1;
                best / taylor[r]
            })
            .collect();
        ratios.sort_by(f64::total_cmp);
        (ratios[ratios.len() / 2], best_names)
    };
    let models = ["truncated model", "reduced model", "general top"];
    for (error, words) in [("1e-14", "an error of 10⁻¹⁴"), ("1e-8", "an error of 10⁻⁸")] {
        let ratios: Vec<String> = ["truncated", "reduced", "general"]
            .iter()
            .map(|m| format!("{:.1}×", versus_rk(m, error).0))
            .collect();
        let claim = format!(
            "at {words} {} on the {}, {} on the {} and {} on the {}",
            ratios[0], models[0], ratios[1], models[1], ratios[2], models[2]
        );
        assert!(chapter.contains(&claim), "the chapter should say: {claim}");
    }
    for model in ["truncated", "reduced", "general"] {
        let names = versus_rk(model, "1e-14").1;
        let most = names
            .iter()
            .max_by_key(|(_, n)| **n)
            .map(|(m, _)| m.as_str());
        assert_eq!(most, Some("spintop dop853"), "{model}: {names:?}");
    }
    let goal = versus_rk("general", "1e-14").0 >= 2.0;
    let verdict = if goal {
        "the goal of 2× on the general top is met"
    } else {
        "the goal of 2× on the general top is missed"
    };
    assert!(
        chapter.contains(verdict),
        "the chapter should say: {verdict}"
    );
    // Loose tolerances, in the sweep: DOP853's time at a matched error of
    // 1e-5 (interpolated in log-log as the join does) against the Taylor
    // method's, per problem, as the chapter words it.
    let at_1e5 = |model: &str, method: &str| {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.ok() && r.target == Target::Omega && r.model == model)
            .filter(|r| r.source == "spintop" && r.method == method)
            .filter_map(|r| Some((r.time_s?, r.omega_error?)))
            .collect();
        report::cost_at(&points, 1e-5).unwrap()
    };
    let dop853_faster: Vec<&str> = ["truncated", "reduced", "general"]
        .into_iter()
        .filter(|m| at_1e5(m, "dop853") < at_1e5(m, "taylor"))
        .collect();
    let claim = match dop853_faster[..] {
        [] => {
            "at an error of 10⁻⁵ the Taylor method is the faster on all three problems".to_string()
        }
        [m] => format!("at an error of 10⁻⁵ DOP853 is the faster on the {m} problem"),
        [a, b] => format!("at an error of 10⁻⁵ DOP853 is the faster on the {a} and {b} problems"),
        _ => "at an error of 10⁻⁵ DOP853 is the faster on all three problems".to_string(),
    };
    assert!(chapter.contains(&claim), "the chapter should say: {claim}");
}

/// The peers run the speed chapter's work-precision figure is drawn from,
/// and the interleaved head-to-head of the same run.
const TAYLOR_PEERS_RUN: &str = "benches/results/peers-2026-11-26-taylor.csv";
const TAYLOR_H2H_RUN: &str = "benches/results/peers-h2h-2026-11-26-run3.csv";

/// The crates `Cargo.toml` names as dependencies (the application's, not
/// the dev-dependencies; those of every target included), with `-` written
/// `_` as code names them, but the ones ▶'s scratch project depends on
/// (`spintop_server::SNIPPET_CRATES`).
fn dependency_crates() -> BTreeSet<String> {
    let manifest: toml::Table = fs::read_to_string(root().join("Cargo.toml"))
        .unwrap()
        .parse()
        .expect("Cargo.toml parses");
    let tables = |t: &toml::Table| -> Vec<toml::Table> {
        t.get("dependencies")
            .and_then(|d| d.as_table())
            .into_iter()
            .cloned()
            .collect()
    };
    let mut all = tables(&manifest);
    if let Some(targets) = manifest.get("target").and_then(|t| t.as_table()) {
        for target in targets.values().filter_map(|t| t.as_table()) {
            all.extend(tables(target));
        }
    }
    let snippet_crates: Vec<String> = spintop_server::SNIPPET_CRATES
        .iter()
        .map(|c| c.replace('-', "_"))
        .collect();
    all.iter()
        .flat_map(|d| d.keys())
        .map(|k| k.replace('-', "_"))
        .filter(|k| !snippet_crates.contains(k))
        .collect()
}

/// The crates a runnable Rust block of `chapter` names by path
/// (`name::…`) among `crates`; hidden lines (`# …`) included.
fn crates_named_by_snippets(chapter: &str, crates: &BTreeSet<String>) -> Vec<String> {
    let mut named = Vec::new();
    let mut in_block = false;
    for line in chapter.lines() {
        let fence = line.trim_start();
        if fence.starts_with("```") {
            in_block = !in_block && (fence == "```rust" || fence == "```rust,editable");
            continue;
        }
        if !in_block {
            continue;
        }
        let words = line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == ':'));
        for word in words {
            if let Some((first, _)) = word.split_once("::")
                && crates.contains(first)
                && !named.contains(&first.to_string())
            {
                named.push(first.to_string());
            }
        }
    }
    named
}

/// ▶ in `spintop book` builds a snippet in a crate that depends on spintop's
/// own crates alone, while a doctest sees all of spintop's dependencies: a snippet that
/// names `nalgebra::…` passes `cargo test` and fails in the reader's
/// browser. Every runnable block names no crate but spintop and std (what
/// it needs of a dependency, spintop re-exports: `spintop::math::Complex`).
#[test]
fn book_runnable_snippets_name_no_dependency_but_spintop() {
    let crates = dependency_crates();
    assert!(
        crates.contains("nalgebra") && crates.contains("ratatui"),
        "{crates:?}"
    );
    let mut problems = Vec::new();
    for entry in fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let named = crates_named_by_snippets(&fs::read_to_string(&path).unwrap(), &crates);
            if !named.is_empty() {
                problems.push(format!("{}: {}", path.display(), named.join(", ")));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "snippets that ▶ cannot build:\n{}",
        problems.join("\n")
    );
    // The check itself sees a hidden line and leaves an ignored block alone.
    let sample = "```rust\n# use nalgebra::Vector3;\n```\n```rust,ignore\nratatui::init();\n```\n";
    assert_eq!(
        crates_named_by_snippets(sample, &crates),
        vec!["nalgebra".to_string()]
    );
}
