//! The book's symbol table, generated from the physics modules' headers,
//! with accented symbols written as math.

use super::{book_src, root, stale, summary_chapters};
use std::fs;

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
        "<!-- Generated from the module headers by tests/project/book/symbols.rs; refresh with UPDATE_BOOK=1 cargo test -p spintop-app --test app project:: -->\n",
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
pub(super) fn is_accent(c: char) -> bool {
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
