//! The source rule: what a student's copy may not contain, checked on the
//! parsed syntax tree of every `.rs` file under its `src/` (subfolders
//! included), macro bodies and attributes included, before anything of it is
//! compiled or run.
//!
//! The graders compare the student's answers with spintop's own functions,
//! and spintop is a dependency of the copy, so nothing in the language stops
//! an assignment from calling the reference. The rule stops it, and the
//! cheap ways around a grader's verdict:
//!
//! - any path into `spintop` other than `spintop::math` and
//!   `spintop::assignment` (`use spintop as s`, a glob, `::spintop::…`),
//!   `extern crate`;
//! - `#[path]`, also inside `cfg_attr`; `include!`, `include_str!`,
//!   `include_bytes!` under any name or spelling;
//! - `std::process`, `std::fs`, `std::env`, `std::net`, `std::os` (and the
//!   same under `core`, `alloc`, an alias of `std`, or a glob);
//! - `unsafe` code, `extern` blocks and the attributes that export or place
//!   symbols (`no_mangle`, `link_section`, …): the ways to reach the verdict
//!   channel, the process or the memory behind the grader's back;
//! - a string literal that names a file outside the copy;
//! - a build script (`build.rs`, or `build =` in the manifest).
//!
//! It runs in the course's shell (`spintop course`, `course watch`, `learn`,
//! `course grade`), not in the graded test process: the instructor's
//! `course grade` builds a fresh copy with the repository's own tests and
//! manifest and checks the student's files itself, so a student cannot skip
//! the rule, and a student's build never compiles a Rust parser.

use std::fmt;
use std::path::{Component, Path, PathBuf};
use syn::ext::IdentExt;
use syn::visit::Visit;

/// The modules of spintop an assignment file may name.
pub const ALLOWED_MODULES: [&str; 2] = ["math", "assignment"];

/// The modules of the standard library an assignment may not name.
pub const FORBIDDEN_STD: [&str; 5] = ["process", "fs", "env", "net", "os"];

/// The crates that hold the standard library.
const STD_CRATES: [&str; 3] = ["std", "core", "alloc"];

/// The macros that paste another file into this one.
const INCLUDES: [&str; 3] = ["include", "include_str", "include_bytes"];

/// Attributes that place, export or link symbols, or move a module's file.
const FORBIDDEN_ATTRIBUTES: [&str; 9] = [
    "path",
    "no_mangle",
    "export_name",
    "link_section",
    "link",
    "link_name",
    "used",
    "global_allocator",
    "naked",
];

/// One place where a copy breaks the rule.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// The file, relative to the copy.
    pub file: PathBuf,
    /// The line (1-based).
    pub line: usize,
    /// What is there, and why it is not allowed.
    pub what: String,
    /// Whether the file could not be parsed at all (then the compiler's
    /// error says more, if the file is part of the crate).
    pub unreadable: bool,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file.display(), self.line, self.what)
    }
}

/// Every violation of the rule in the copy at `dir` (a lessons crate): its
/// `src/**/*.rs`, its build script, its manifest. Empty when it keeps it.
pub fn check_copy(dir: &Path) -> Vec<Violation> {
    let root = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    let mut out = Vec::new();
    if root.join("build.rs").exists() {
        out.push(Violation {
            file: "build.rs".into(),
            line: 1,
            what: "a build script: it runs code while the copy is built, before any grader; the course has none".into(),
            unreadable: false,
        });
    }
    out.extend(check_manifest(&root));
    for path in super::export::rust_files(&root.join("src"), &[]) {
        let rel = path.strip_prefix(&root).unwrap_or(&path).to_path_buf();
        match std::fs::read_to_string(&path) {
            Ok(text) => out.extend(check_source(&rel, &text, &root)),
            Err(e) => out.push(Violation {
                file: rel,
                line: 1,
                what: format!("cannot be read ({e})"),
                unreadable: true,
            }),
        }
    }
    out
}

/// The copy's manifest: no build script, the library where the course keeps
/// it, spintop the only dependency, nothing patched.
fn check_manifest(root: &Path) -> Vec<Violation> {
    let Ok(text) = std::fs::read_to_string(root.join("Cargo.toml")) else {
        return Vec::new();
    };
    let Ok(manifest) = text.parse::<toml::Table>() else {
        return Vec::new(); // cargo says what is wrong with it
    };
    let line_of = |key: &str| {
        text.lines()
            .position(|l| l.trim_start().starts_with(key))
            .map_or(1, |i| i + 1)
    };
    let mut out = Vec::new();
    let mut refuse = |key: &str, what: &str| {
        out.push(Violation {
            file: "Cargo.toml".into(),
            line: line_of(key),
            what: what.into(),
            unreadable: false,
        })
    };
    let package = manifest.get("package").and_then(|p| p.as_table());
    if package.is_some_and(|p| p.get("build").is_some_and(|b| b.as_bool() != Some(false))) {
        refuse(
            "build",
            "the manifest names a build script, which runs code before any grader",
        );
    }
    let lib_path = manifest
        .get("lib")
        .and_then(|l| l.get("path"))
        .and_then(|p| p.as_str());
    if lib_path.is_some_and(|p| Path::new(p) != Path::new("src/lib.rs")) {
        refuse("path", "the library is moved out of src/lib.rs");
    }
    for section in ["patch", "replace"] {
        if manifest.contains_key(section) {
            refuse(&format!("[{section}"), "the manifest replaces a dependency");
        }
    }
    if let Some(deps) = manifest.get("dependencies").and_then(|d| d.as_table()) {
        for name in deps.keys().filter(|n| *n != "spintop") {
            refuse(name, "a dependency other than spintop");
        }
    }
    out
}

/// The violations in one file, `rel` (relative to the copy at `root`), of
/// text `text`.
pub fn check_source(rel: &Path, text: &str, root: &Path) -> Vec<Violation> {
    let file = match syn::parse_file(text) {
        Ok(f) => f,
        Err(e) => {
            return vec![Violation {
                file: rel.to_path_buf(),
                line: e.span().start().line.max(1),
                what: format!("cannot be read as Rust ({e}), so the rule cannot vouch for it"),
                unreadable: true,
            }];
        }
    };
    let mut checker = Checker {
        rel,
        dir: root
            .join(rel)
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default(),
        root,
        found: Vec::new(),
    };
    checker.visit_file(&file);
    checker.found.sort_by_key(|v| v.line);
    checker.found.dedup();
    checker.found
}

struct Checker<'a> {
    rel: &'a Path,
    /// The file's folder (absolute), for relative paths in string literals.
    dir: PathBuf,
    root: &'a Path,
    found: Vec<Violation>,
}

impl Checker<'_> {
    fn refuse(&mut self, span: proc_macro2::Span, what: impl Into<String>) {
        self.found.push(Violation {
            file: self.rel.to_path_buf(),
            line: span.start().line.max(1),
            what: what.into(),
            unreadable: false,
        });
    }

    /// A path, as its segments; `leading` when it starts with `::`.
    fn path(&mut self, span: proc_macro2::Span, segments: &[String], leading: bool) {
        if let Some(why) = path_violation(segments, leading) {
            self.refuse(span, why);
        }
    }

    /// Every token of a macro's or an attribute's body: paths, `include!`
    /// under any name, `unsafe`, string literals.
    fn tokens(&mut self, stream: proc_macro2::TokenStream) {
        use proc_macro2::TokenTree;
        let tokens: Vec<TokenTree> = stream.into_iter().collect();
        let mut i = 0;
        while i < tokens.len() {
            match &tokens[i] {
                TokenTree::Group(g) => self.tokens(g.stream()),
                TokenTree::Literal(lit) => self.literal(lit.clone()),
                TokenTree::Ident(id) => {
                    let name = id.unraw().to_string();
                    if name == "unsafe" || name == "extern" {
                        self.refuse(id.span(), format!("`{name}` inside a macro: {}", UNSAFE));
                    }
                    if INCLUDES.contains(&name.as_str()) && is_punct(tokens.get(i + 1), '!') {
                        self.refuse(
                            id.span(),
                            format!("`{name}!` pastes another file into this one"),
                        );
                    }
                    // A path: ident (:: ident)*, possibly after a leading ::.
                    let after_colons = i >= 2
                        && is_punct(tokens.get(i - 1), ':')
                        && is_punct(tokens.get(i - 2), ':');
                    let continues = after_colons
                        && i >= 3
                        && matches!(tokens.get(i - 3), Some(TokenTree::Ident(_)));
                    let (starts, leading) = (!continues, after_colons);
                    if starts {
                        let mut segments = vec![name];
                        let mut j = i;
                        while is_punct(tokens.get(j + 1), ':') && is_punct(tokens.get(j + 2), ':') {
                            if let Some(TokenTree::Ident(next)) = tokens.get(j + 3) {
                                segments.push(next.unraw().to_string());
                                j += 3;
                            } else {
                                break;
                            }
                        }
                        self.path(id.span(), &segments, leading);
                    }
                }
                TokenTree::Punct(_) => {}
            }
            i += 1;
        }
    }

    /// A string literal inside a macro's or an attribute's tokens.
    fn literal(&mut self, lit: proc_macro2::Literal) {
        let span = lit.span();
        match syn::Lit::new(lit) {
            syn::Lit::Str(s) => self.string(span, &s.value()),
            syn::Lit::ByteStr(s) => self.string(span, &String::from_utf8_lossy(&s.value())),
            _ => {}
        }
    }

    /// A string that names a file outside the copy.
    fn string(&mut self, span: proc_macro2::Span, text: &str) {
        if names_file_outside(text, &self.dir, self.root) {
            self.refuse(
                span,
                format!("the string \"{text}\" names a file outside your copy"),
            );
        }
    }

    fn attribute_named(&mut self, span: proc_macro2::Span, name: &str) {
        if name == "unsafe" {
            self.refuse(span, format!("an `#[unsafe(…)]` attribute: {UNSAFE}"));
        } else if FORBIDDEN_ATTRIBUTES.contains(&name) {
            let why = if name == "path" {
                "`#[path]` compiles another file as this module".to_string()
            } else {
                format!("`#[{name}]` places or exports a symbol: {UNSAFE}")
            };
            self.refuse(span, why);
        }
    }
}

const UNSAFE: &str = "unsafe code can reach the process and the memory behind the grader's back; the course needs none";

fn is_punct(t: Option<&proc_macro2::TokenTree>, c: char) -> bool {
    matches!(t, Some(proc_macro2::TokenTree::Punct(p)) if p.as_char() == c)
}

/// Why a path (its segments, after an optional leading `::`) is not
/// allowed, if it is not.
fn path_violation(segments: &[String], _leading: bool) -> Option<String> {
    let first = segments.first()?.as_str();
    if let Some(name) = segments.iter().find(|s| INCLUDES.contains(&s.as_str())) {
        return Some(format!("`{name}` pastes another file into this one"));
    }
    if first == "spintop" {
        return match segments.get(1) {
            Some(m) if ALLOWED_MODULES.contains(&m.as_str()) => None,
            Some(m) => Some(format!(
                "`spintop::{m}` reaches into spintop itself, where the reference answers live; only spintop::math and spintop::assignment are allowed"
            )),
            None => Some(
                "`spintop` named on its own (an alias or a glob) reaches every module of spintop; only spintop::math and spintop::assignment are allowed".into(),
            ),
        };
    }
    if STD_CRATES.contains(&first)
        && let Some(m) = segments.get(1)
        && FORBIDDEN_STD.contains(&m.as_str())
    {
        return Some(format!(
            "`{first}::{m}` reaches files, the environment, other processes or the network; an assignment computes from its arguments alone"
        ));
    }
    None
}

/// One `use` tree flattened: `(segments, span)` for each leaf, with a
/// marker for a glob (`*`) or an alias (`as`).
fn use_leaves(
    tree: &syn::UseTree,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, proc_macro2::Span, Leaf)>,
) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.unraw().to_string());
            use_leaves(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let mut segs = prefix.clone();
            let name = n.ident.unraw().to_string();
            if name != "self" {
                segs.push(name);
            }
            out.push((segs, n.ident.span(), Leaf::Name));
        }
        syn::UseTree::Rename(r) => {
            let mut segs = prefix.clone();
            let name = r.ident.unraw().to_string();
            if name != "self" {
                segs.push(name);
            }
            out.push((segs, r.ident.span(), Leaf::Alias));
        }
        syn::UseTree::Glob(g) => {
            out.push((prefix.clone(), g.star_token.spans[0], Leaf::Glob));
        }
        syn::UseTree::Group(g) => {
            for t in &g.items {
                use_leaves(t, prefix, out);
            }
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Leaf {
    Name,
    Alias,
    Glob,
}

impl<'ast> Visit<'ast> for Checker<'_> {
    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        let mut leaves = Vec::new();
        use_leaves(&item.tree, &mut Vec::new(), &mut leaves);
        let leading = item.leading_colon.is_some();
        for (segments, span, leaf) in leaves {
            let crate_only = segments.len() == 1;
            let std_crate = segments
                .first()
                .is_some_and(|s| STD_CRATES.contains(&s.as_str()));
            if crate_only && std_crate && leaf != Leaf::Name {
                self.refuse(
                    span,
                    format!(
                        "`{}` under another name or as a glob hides which of its modules the file reaches",
                        segments[0]
                    ),
                );
            } else {
                self.path(span, &segments, leading);
            }
        }
        syn::visit::visit_item_use(self, item);
    }

    fn visit_item_extern_crate(&mut self, item: &'ast syn::ItemExternCrate) {
        self.refuse(
            item.extern_token.span,
            format!(
                "`extern crate {}` brings in a crate the course does not use",
                item.ident.unraw()
            ),
        );
        syn::visit::visit_item_extern_crate(self, item);
    }

    fn visit_item_foreign_mod(&mut self, item: &'ast syn::ItemForeignMod) {
        self.refuse(
            item.abi.extern_token.span,
            format!("an `extern` block: {UNSAFE}"),
        );
        syn::visit::visit_item_foreign_mod(self, item);
    }

    fn visit_expr_unsafe(&mut self, e: &'ast syn::ExprUnsafe) {
        self.refuse(e.unsafe_token.span, format!("an `unsafe` block: {UNSAFE}"));
        syn::visit::visit_expr_unsafe(self, e);
    }

    fn visit_signature(&mut self, sig: &'ast syn::Signature) {
        if let Some(u) = &sig.unsafety {
            self.refuse(u.span, format!("an `unsafe fn`: {UNSAFE}"));
        }
        if let Some(abi) = &sig.abi {
            self.refuse(
                abi.extern_token.span,
                format!("an `extern` function: {UNSAFE}"),
            );
        }
        syn::visit::visit_signature(self, sig);
    }

    fn visit_item_impl(&mut self, item: &'ast syn::ItemImpl) {
        if let Some(u) = &item.unsafety {
            self.refuse(u.span, format!("an `unsafe impl`: {UNSAFE}"));
        }
        syn::visit::visit_item_impl(self, item);
    }

    fn visit_item_trait(&mut self, item: &'ast syn::ItemTrait) {
        if let Some(u) = &item.unsafety {
            self.refuse(u.span, format!("an `unsafe trait`: {UNSAFE}"));
        }
        syn::visit::visit_item_trait(self, item);
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        let segments: Vec<String> = path
            .segments
            .iter()
            .map(|s| s.ident.unraw().to_string())
            .collect();
        let span = path
            .segments
            .first()
            .map_or_else(proc_macro2::Span::call_site, |s| s.ident.span());
        self.path(span, &segments, path.leading_colon.is_some());
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        self.tokens(mac.tokens.clone());
        syn::visit::visit_macro(self, mac);
    }

    fn visit_attribute(&mut self, attr: &'ast syn::Attribute) {
        let path = attr.path();
        if let Some(first) = path.segments.first() {
            let name = first.ident.unraw().to_string();
            self.attribute_named(first.ident.span(), &name);
            if name == "cfg_attr"
                && let syn::Meta::List(list) = &attr.meta
            {
                // cfg_attr(condition, attr, attr…): each attribute it may add.
                let mut tokens = list.tokens.clone().into_iter().peekable();
                while let Some(t) = tokens.next() {
                    if let proc_macro2::TokenTree::Ident(id) = &t {
                        let word = id.unraw().to_string();
                        let is_attr = tokens.peek().is_none_or(|n| {
                            matches!(n, proc_macro2::TokenTree::Punct(p) if p.as_char() == '=' || p.as_char() == ',')
                                || matches!(n, proc_macro2::TokenTree::Group(_))
                        });
                        if is_attr {
                            self.attribute_named(id.span(), &word);
                        }
                    }
                }
            }
        }
        // Everything inside: `#[doc = include_str!(…)]`, paths, strings.
        if let syn::Meta::List(list) = &attr.meta {
            self.tokens(list.tokens.clone());
        }
        if let syn::Meta::NameValue(nv) = &attr.meta {
            self.visit_expr(&nv.value);
        }
        // The attribute's own path was checked above; do not walk it again as a path.
    }

    fn visit_lit_str(&mut self, lit: &'ast syn::LitStr) {
        self.string(lit.span(), &lit.value());
    }

    fn visit_lit_byte_str(&mut self, lit: &'ast syn::LitByteStr) {
        self.string(lit.span(), &String::from_utf8_lossy(&lit.value()));
    }
}

/// Whether `text`, read as a file path from the folder `dir`, leads outside
/// the copy at `root`: an absolute path elsewhere, a `~`, or enough `..` to
/// climb out. Text with spaces, braces or other characters no file name
/// uses is not a path.
fn names_file_outside(text: &str, dir: &Path, root: &Path) -> bool {
    let path_like = |c: char| c.is_alphanumeric() || "/\\._-~:+@".contains(c);
    if text.is_empty()
        || text.len() > 4096
        || !text.contains(['/', '\\'])
        || !text.chars().all(path_like)
    {
        return false;
    }
    if text.starts_with('~') {
        return true;
    }
    let path = Path::new(text);
    let joined = if path.is_absolute() {
        // A root alone, or one name under it, is a separator, not a file.
        if path
            .components()
            .filter(|c| matches!(c, Component::Normal(_)))
            .count()
            < 2
        {
            return false;
        }
        path.to_path_buf()
    } else {
        if !path.components().any(|c| c == Component::ParentDir) {
            return false;
        }
        dir.join(path)
    };
    // Lexically: `..` climbs one folder, whether or not the file exists.
    let mut normal = PathBuf::new();
    for c in joined.components() {
        match c {
            Component::ParentDir => {
                normal.pop();
            }
            Component::CurDir => {}
            other => normal.push(other),
        }
    }
    !normal.starts_with(root)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Vec<Violation> {
        let root = Path::new("/copy");
        check_source(Path::new("src/ch2.rs"), text, root)
    }

    #[test]
    fn the_paths_of_a_strings_climb_are_followed_lexically() {
        let (dir, root) = (Path::new("/copy/src"), Path::new("/copy"));
        assert!(names_file_outside(
            "../../src/physics/balance.rs",
            dir,
            root
        ));
        assert!(names_file_outside(
            "/home/t/spintop/src/physics.rs",
            dir,
            root
        ));
        assert!(names_file_outside("~/spintop/src", dir, root));
        assert!(!names_file_outside("../src/ch4.rs", dir, root));
        assert!(!names_file_outside("{}/{}", dir, root));
        assert!(!names_file_outside("rad/s", dir, root));
        assert!(!names_file_outside("1/2 of it", dir, root));
    }

    #[test]
    fn a_use_of_std_io_is_fine_and_std_process_is_not() {
        assert!(check("use std::io::Write;\nfn f() { println!(\"{}\", 1); }").is_empty());
        let v = check("fn f() {\n    std::process::exit(0);\n}\n");
        assert_eq!(v.len(), 1, "{v:?}");
        assert_eq!(v[0].line, 2);
    }
}
