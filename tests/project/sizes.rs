//! One concept per room: no function over 120 lines and no file over 1,000
//! lines, in every Rust file of the workspace (the crates, the application,
//! the lessons, the benchmarks and the tests), read as syntax trees (`syn`).
//! A lookup table may be longer: a function whose body is one `match` whose
//! arms all map literals to literals, or a file whose long items are such
//! tables and `const`/`static` arrays of literals, is a table, not a room of
//! concepts, and is measured without them.

use proc_macro2::Span;
use std::path::{Path, PathBuf};
use syn::spanned::Spanned;
use syn::visit::Visit;

/// The most lines a function may span (its signature to its closing brace).
const MAX_FUNCTION: usize = 120;
/// The most lines a file may hold, its lookup tables not counted.
const MAX_FILE: usize = 1000;

/// The folders whose Rust files are measured, from the repository's root.
const ROOTS: [&str; 5] = ["src", "crates", "tests", "lessons", "benches"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        if name == "target" || name == "snapshots" {
            continue;
        }
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn lines(span: Span) -> usize {
    span.end().line + 1 - span.start().line
}

/// A literal, possibly negated or a path to a constant or a unit variant
/// (`Key::Up`, `'a'`, `"alpha"`, `-1.0`).
fn is_literal_expr(e: &syn::Expr) -> bool {
    match e {
        syn::Expr::Lit(_) | syn::Expr::Path(_) => true,
        syn::Expr::Unary(u) => is_literal_expr(&u.expr),
        syn::Expr::Tuple(t) => t.elems.iter().all(is_literal_expr),
        syn::Expr::Array(a) => a.elems.iter().all(is_literal_expr),
        syn::Expr::Reference(r) => is_literal_expr(&r.expr),
        syn::Expr::Call(c) => c.args.iter().all(is_literal_expr) && is_literal_expr(&c.func),
        syn::Expr::Macro(m) => m.mac.path.is_ident("vec"),
        syn::Expr::Group(g) => is_literal_expr(&g.expr),
        syn::Expr::Paren(p) => is_literal_expr(&p.expr),
        _ => false,
    }
}

/// A `match` whose arms all map patterns to literals: a lookup table.
fn is_table_match(m: &syn::ExprMatch) -> bool {
    m.arms.iter().all(|arm| {
        arm.guard.is_none()
            && match &*arm.body {
                syn::Expr::Block(b) => {
                    b.block.stmts.len() == 1
                        && matches!(&b.block.stmts[0], syn::Stmt::Expr(e, None) if is_literal_expr(e))
                }
                e => is_literal_expr(e),
            }
    })
}

/// A function body that is a lookup table: its last expression a table
/// `match` (what comes before it short).
fn is_table_body(block: &syn::Block) -> bool {
    match block.stmts.last() {
        Some(syn::Stmt::Expr(syn::Expr::Match(m), None)) => {
            is_table_match(m) && lines(block.span()) - lines(m.span()) < 20
        }
        _ => false,
    }
}

/// Everything measured in one file.
#[derive(Default)]
struct Measure {
    /// (function, line, lines) of each function over the limit.
    long: Vec<(String, usize, usize)>,
    /// Lines held by lookup tables (table functions, literal arrays).
    table_lines: usize,
}

impl<'a> Visit<'a> for Measure {
    fn visit_item_fn(&mut self, f: &'a syn::ItemFn) {
        self.function(&f.sig, &f.block);
        syn::visit::visit_item_fn(self, f);
    }

    fn visit_impl_item_fn(&mut self, f: &'a syn::ImplItemFn) {
        self.function(&f.sig, &f.block);
        syn::visit::visit_impl_item_fn(self, f);
    }

    fn visit_trait_item_fn(&mut self, f: &'a syn::TraitItemFn) {
        if let Some(block) = &f.default {
            self.function(&f.sig, block);
        }
        syn::visit::visit_trait_item_fn(self, f);
    }

    fn visit_item_const(&mut self, c: &'a syn::ItemConst) {
        if is_literal_expr(&c.expr) {
            self.table_lines += lines(c.span());
        }
        syn::visit::visit_item_const(self, c);
    }

    fn visit_item_static(&mut self, s: &'a syn::ItemStatic) {
        if is_literal_expr(&s.expr) {
            self.table_lines += lines(s.span());
        }
        syn::visit::visit_item_static(self, s);
    }
}

impl Measure {
    /// A function from its signature to its closing brace (its doc comment
    /// and attributes not counted).
    fn function(&mut self, sig: &syn::Signature, block: &syn::Block) {
        let start = sig.fn_token.span.start().line;
        let n = block.brace_token.span.close().end().line + 1 - start;
        if is_table_body(block) {
            self.table_lines += n;
        } else if n > MAX_FUNCTION {
            self.long.push((sig.ident.to_string(), start, n));
        }
    }
}

/// Every function over [`MAX_FUNCTION`] lines and every file over
/// [`MAX_FILE`] (tables not counted), as `file:line: what`.
fn oversized(files: &[PathBuf]) -> Vec<String> {
    let mut out = Vec::new();
    for path in files {
        let rel = path
            .strip_prefix(root())
            .unwrap_or(path)
            .display()
            .to_string();
        let text = std::fs::read_to_string(path).expect("a readable source file");
        let Ok(file) = syn::parse_file(&text) else {
            out.push(format!("{rel}: does not parse as Rust"));
            continue;
        };
        let mut m = Measure::default();
        m.visit_file(&file);
        for (name, line, n) in &m.long {
            out.push(format!(
                "{rel}:{line}: fn {name} has {n} lines (at most {MAX_FUNCTION})"
            ));
        }
        let counted = text.lines().count().saturating_sub(m.table_lines);
        if counted > MAX_FILE {
            out.push(format!(
                "{rel}: {counted} lines besides its tables (at most {MAX_FILE})"
            ));
        }
    }
    out
}

#[test]
fn no_function_over_120_lines_and_no_file_over_1000() {
    let mut files = Vec::new();
    for dir in ROOTS {
        rust_files(&root().join(dir), &mut files);
    }
    files.sort();
    assert!(files.len() > 200, "the workspace's files: {}", files.len());
    let bad = oversized(&files);
    assert!(
        bad.is_empty(),
        "split these along the lines they already show:\n{}",
        bad.join("\n")
    );
}

/// The measure itself can fail: a long function and a long file are found,
/// a long lookup table is not.
#[test]
fn the_measure_finds_a_long_function_and_a_long_file_but_not_a_table() {
    let dir = std::env::temp_dir().join(format!("spintop-sizes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let body: String = (0..130).map(|i| format!("    let x{i} = {i};\n")).collect();
    let long_fn = dir.join("long_fn.rs");
    std::fs::write(&long_fn, format!("fn long() {{\n{body}}}\n")).unwrap();
    let arms: String = (0..200)
        .map(|i| format!("        {i} => \"{i}\",\n"))
        .collect();
    let table = dir.join("table.rs");
    std::fs::write(
        &table,
        format!("fn name(i: u32) -> &'static str {{\n    match i {{\n{arms}        _ => \"?\",\n    }}\n}}\n"),
    )
    .unwrap();
    let items: String = (0..1001).map(|i| format!("pub fn f{i}() {{}}\n")).collect();
    let long_file = dir.join("long_file.rs");
    std::fs::write(&long_file, items).unwrap();
    let bad = oversized(&[long_fn, table, long_file]);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(bad.len(), 2, "{bad:?}");
    assert!(
        bad[0].contains("long_fn.rs:1: fn long has 132 lines"),
        "{bad:?}"
    );
    assert!(bad[1].contains("long_file.rs: 1001 lines"), "{bad:?}");
}
