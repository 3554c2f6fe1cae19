//! The paper's equations in the book: every one cited is typeset, and the
//! prose writes accented symbols as math.

use super::symbols::is_accent;
use super::{book_src, summary_chapters};
use std::collections::BTreeSet;
use std::fs;

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
