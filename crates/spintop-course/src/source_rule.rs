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
//! - `std::process`, `std::fs`, `std::env`, `std::net`, `std::os`,
//!   `std::arch` (and the same under `core`, `alloc`, an alias of `std`, a
//!   glob, or further down a path: `self::m::std::fs`), `std` itself
//!   imported as a name (`use std::{self}`), and `env!`/`option_env!`;
//! - a macro of the copy's own (`macro_rules!`): it builds code out of its
//!   arguments, a path pasted together from words, an attribute, and the
//!   rule could read that code only after expanding it; inline assembly
//!   (`global_asm!`, `asm!`);
//! - `unsafe` code, `extern` blocks and the attributes that export or place
//!   symbols (`no_mangle`, `link_section`, …): the ways to reach the verdict
//!   channel, the process or the memory behind the grader's back;
//! - a string literal that names a file outside the copy;
//! - a build script (`build.rs`, or `build =` in the manifest);
//! - a symbolic link under `src/` (the compiler reads the file it points to,
//!   wherever that is, and the rule reads only the copy's own files).
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
pub const FORBIDDEN_STD: [&str; 6] = ["process", "fs", "env", "net", "os", "arch"];

/// The crates that hold the standard library.
const STD_CRATES: [&str; 3] = ["std", "core", "alloc"];

/// The macros that paste another file into this one.
const INCLUDES: [&str; 3] = ["include", "include_str", "include_bytes"];

/// The built-in macros that read the build's environment.
const ENV_MACROS: [&str; 2] = ["env", "option_env"];

/// The built-in macros of inline assembly (`global_asm!` needs no `unsafe`
/// and runs before `main` when placed in `.init_array`).
const ASM_MACROS: [&str; 3] = ["asm", "global_asm", "naked_asm"];

/// Why a macro of the copy's own is refused.
const OWN_MACRO: &str = "`macro_rules!` defines a macro, which builds code out of its arguments (a path pasted together from separate words, an attribute); the rule could read that code only after expanding it, and an assignment needs no macro of its own";

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
    if std::fs::symlink_metadata(root.join("src")).is_ok_and(|m| m.file_type().is_symlink()) {
        out.push(Violation {
            file: "src".into(),
            line: 1,
            what: "src/ is a symbolic link: the files it stands for are not your copy's own (and the rule does not walk a folder elsewhere)".into(),
            unreadable: false,
        });
        return out;
    }
    for link in super::export::symbolic_links(&root.join("src"), &[]) {
        let rel = link.strip_prefix(&root).unwrap_or(&link).to_path_buf();
        let target =
            std::fs::read_link(&link).map_or_else(|_| "?".into(), |t| t.display().to_string());
        out.push(Violation {
            file: rel,
            line: 1,
            what: format!(
                "a symbolic link (to {target}): the compiler reads the file it stands for, wherever that is, and the rule reads only your copy's own files; put the file itself here"
            ),
            unreadable: false,
        });
    }
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

/// The most a file the rule reads may nest brackets, and the most tokens it
/// may put in one run without a comma or a semicolon (attributes and doc
/// comments not counted; an item ends a run), and its largest size.
///
/// NOTE: syn parses and walks a syntax tree by recursion, some 10 kB of
/// stack a level in a debug build: 1,000 nested brackets overflowed the main
/// thread's 8 MB and aborted `spintop course grade`, CSV and the whole
/// class with it. So the rule first measures the nesting on proc-macro2's
/// tokens (lexed and dropped without recursion) and refuses a file beyond
/// these bounds, which no assignment comes near (the course's own files nest
/// 8 deep, in runs under 200 tokens), then parses within them on a thread
/// whose stack holds the deepest tree they allow.
const MAX_NESTING: usize = 100;
const MAX_RUN: usize = 4000;
const MAX_BYTES: usize = 1 << 20;
const PARSER_STACK: usize = 256 << 20;

/// The violations in one file, `rel` (relative to the copy at `root`), of
/// text `text`.
pub fn check_source(rel: &Path, text: &str, root: &Path) -> Vec<Violation> {
    let refuse = |line: usize, what: String, unreadable: bool| Violation {
        file: rel.to_path_buf(),
        line,
        what,
        unreadable,
    };
    if text.len() > MAX_BYTES {
        let what = format!(
            "{} kB, more than the rule reads ({} kB): an assignment's file is a few kB",
            text.len() >> 10,
            MAX_BYTES >> 10
        );
        return vec![refuse(1, what, false)];
    }
    let (owned_rel, owned_text, owned_root) =
        (rel.to_path_buf(), text.to_string(), root.to_path_buf());
    let parsed = std::thread::Builder::new()
        .name("source rule".into())
        .stack_size(PARSER_STACK)
        .spawn(move || check_parsed(&owned_rel, &owned_text, &owned_root))
        .map_err(|e| e.to_string())
        .and_then(|t| t.join().map_err(|_| "its parser stopped".to_string()));
    parsed.unwrap_or_else(|why| {
        vec![refuse(
            1,
            format!("the rule could not read it ({why}), so it cannot vouch for it"),
            true,
        )]
    })
}

/// Where `tokens` nest deeper, or run longer, than the rule reads: the line
/// and what it is. Without recursion.
fn too_deep(tokens: proc_macro2::TokenStream) -> Option<(usize, String)> {
    use proc_macro2::{Delimiter, TokenTree};
    let item = [
        "fn", "pub", "struct", "enum", "impl", "trait", "mod", "use", "const", "static", "type",
        "let",
    ];
    // Each open group: its tokens, the run so far, and the previous token.
    let mut stack = vec![(tokens.into_iter().peekable(), 0usize, None::<TokenTree>)];
    while let Some((iter, run, previous)) = stack.last_mut() {
        let Some(t) = iter.next() else {
            stack.pop();
            continue;
        };
        let attribute = matches!(&t, TokenTree::Punct(p) if p.as_char() == '#' || (p.as_char() == '!' && matches!(previous, Some(TokenTree::Punct(q)) if q.as_char() == '#')))
            || matches!((&t, &*previous), (TokenTree::Group(g), Some(TokenTree::Punct(p))) if g.delimiter() == Delimiter::Bracket && (p.as_char() == '#' || p.as_char() == '!'));
        match &t {
            TokenTree::Punct(p) if p.as_char() == ';' || p.as_char() == ',' => *run = 0,
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                // An item or a statement after a block starts a new run.
                let next_starts = match iter.peek() {
                    None => true,
                    Some(TokenTree::Ident(i)) => item.contains(&i.to_string().as_str()),
                    Some(TokenTree::Punct(p)) => p.as_char() == '#',
                    _ => false,
                };
                *run = if next_starts { 0 } else { *run + 1 };
            }
            _ if attribute => {}
            _ => *run += 1,
        }
        let line = t.span().start().line.max(1);
        if *run > MAX_RUN {
            return Some((
                line,
                format!(
                    "more than {MAX_RUN} tokens in one expression, without a comma or a semicolon: deeper than the rule reads, and far beyond what an assignment needs"
                ),
            ));
        }
        *previous = Some(t.clone());
        if let TokenTree::Group(g) = t {
            if stack.len() >= MAX_NESTING {
                return Some((
                    line,
                    format!(
                        "brackets nested more than {MAX_NESTING} deep: deeper than the rule reads, and far beyond what an assignment needs"
                    ),
                ));
            }
            stack.push((g.stream().into_iter().peekable(), 0, None));
        }
    }
    None
}

/// [`check_source`] itself, on a stack deep enough for what [`too_deep`] lets through.
fn check_parsed(rel: &Path, text: &str, root: &Path) -> Vec<Violation> {
    if let Ok(tokens) = text.parse::<proc_macro2::TokenStream>()
        && let Some((line, what)) = too_deep(tokens)
    {
        return vec![Violation {
            file: rel.to_path_buf(),
            line,
            what,
            unreadable: false,
        }];
    }
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
    // One violation a line (an `unsafe` attribute is both unsafe and an attribute).
    checker.found.sort_by_key(|v| v.line);
    checker.found.dedup_by_key(|v| v.line);
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
    /// and the other refused macros under any name, `unsafe`, attributes,
    /// string literals.
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
                    if is_punct(tokens.get(i + 1), '!') {
                        self.macro_named(id.span(), &name);
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
                TokenTree::Punct(p) if p.as_char() == '#' => {
                    // An attribute among a macro's tokens (`thread_local!`
                    // passes its items' attributes on): its name and what a
                    // `cfg_attr` in it may add; its tokens are read next.
                    let at = if is_punct(tokens.get(i + 1), '!') {
                        i + 2
                    } else {
                        i + 1
                    };
                    if let Some(TokenTree::Group(g)) = tokens.get(at)
                        && g.delimiter() == proc_macro2::Delimiter::Bracket
                    {
                        self.attribute_names(g.stream());
                    }
                }
                TokenTree::Punct(_) => {}
            }
            i += 1;
        }
    }

    /// A macro called (or defined) by the name `name`.
    fn macro_named(&mut self, span: proc_macro2::Span, name: &str) {
        if name == "macro_rules" {
            self.refuse(span, OWN_MACRO);
        } else if INCLUDES.contains(&name) {
            self.refuse(span, format!("`{name}!` pastes another file into this one"));
        } else if ENV_MACROS.contains(&name) {
            self.refuse(
                span,
                format!("`{name}!` reads the environment of the build; an assignment computes from its arguments alone"),
            );
        } else if ASM_MACROS.contains(&name) {
            self.refuse(span, format!("`{name}!` is assembly: {UNSAFE}"));
        }
    }

    /// An attribute's tokens without its `#[…]` (`path = "…"`,
    /// `cfg_attr(cond, attr, …)`, `unsafe(no_mangle)`): its name and every
    /// attribute a `cfg_attr` may add.
    fn attribute_names(&mut self, stream: proc_macro2::TokenStream) {
        use proc_macro2::TokenTree;
        let mut tokens = stream.into_iter();
        if let Some(TokenTree::Ident(id)) = tokens.next() {
            let list = match tokens.next() {
                Some(TokenTree::Group(g)) => Some(g.stream()),
                _ => None,
            };
            self.attribute(&id, list);
        }
    }

    /// The attribute named `id`, with the tokens of its list if it has
    /// one: refused by name, and a `cfg_attr`'s attributes too, however
    /// deep they are nested.
    fn attribute(&mut self, id: &proc_macro2::Ident, list: Option<proc_macro2::TokenStream>) {
        use proc_macro2::TokenTree;
        let name = id.unraw().to_string();
        self.attribute_named(id.span(), &name);
        let Some(list) = list.filter(|_| name == "cfg_attr") else {
            return;
        };
        // cfg_attr(condition, attr, attr…): the condition, then attributes.
        let mut parts = vec![proc_macro2::TokenStream::new()];
        for t in list {
            match &t {
                TokenTree::Punct(p) if p.as_char() == ',' => parts.push(Default::default()),
                _ => parts
                    .last_mut()
                    .into_iter()
                    .for_each(|s| s.extend([t.clone()])),
            }
        }
        for part in parts.into_iter().skip(1) {
            self.attribute_names(part);
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
    if let Some(name) = segments.iter().find(|s| ASM_MACROS.contains(&s.as_str())) {
        return Some(format!("`{name}` is assembly: {UNSAFE}"));
    }
    // Anywhere along the path, not only at its start: a module of the copy
    // that holds `std` as a name (`self::m::std::fs`) reaches it as well.
    segments.windows(2).find_map(|w| {
        (STD_CRATES.contains(&w[0].as_str()) && FORBIDDEN_STD.contains(&w[1].as_str())).then(|| {
            format!(
                "`{}::{}` reaches files, the environment, other processes, the network or the machine itself; an assignment computes from its arguments alone",
                w[0], w[1]
            )
        })
    })
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
            if crate_only && std_crate {
                let how = match leaf {
                    Leaf::Name => {
                        "imported as a name (`use std;`, `use std::{self}`) lets a longer path reach it (`self::std::fs`)"
                    }
                    Leaf::Alias | Leaf::Glob => "under another name or as a glob",
                };
                self.refuse(
                    span,
                    format!(
                        "`{}` {how} hides which of its modules the file reaches",
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
        if let Some(last) = mac.path.segments.last() {
            self.macro_named(last.ident.span(), &last.ident.unraw().to_string());
        }
        self.tokens(mac.tokens.clone());
        syn::visit::visit_macro(self, mac);
    }

    fn visit_attribute(&mut self, attr: &'ast syn::Attribute) {
        // Its name, what a `cfg_attr` may add, and everything inside:
        // `#[doc = include_str!(…)]`, paths, strings. The attribute's own
        // path is not walked again as a path.
        let Some(first) = attr.path().segments.first() else {
            return;
        };
        match &attr.meta {
            syn::Meta::Path(_) => self.attribute(&first.ident, None),
            syn::Meta::List(list) => {
                self.attribute(&first.ident, Some(list.tokens.clone()));
                self.tokens(list.tokens.clone());
            }
            syn::Meta::NameValue(nv) => {
                self.attribute(&first.ident, None);
                self.visit_expr(&nv.value);
            }
        }
    }

    // What syn keeps as bare tokens (syntax it has no node for) is read
    // token by token, like a macro's body.
    fn visit_item(&mut self, i: &'ast syn::Item) {
        match i {
            syn::Item::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_item(self, i),
        }
    }

    fn visit_expr(&mut self, e: &'ast syn::Expr) {
        match e {
            syn::Expr::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_expr(self, e),
        }
    }

    fn visit_type(&mut self, t: &'ast syn::Type) {
        match t {
            syn::Type::Verbatim(v) => self.tokens(v.clone()),
            _ => syn::visit::visit_type(self, t),
        }
    }

    fn visit_pat(&mut self, p: &'ast syn::Pat) {
        match p {
            syn::Pat::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_pat(self, p),
        }
    }

    fn visit_impl_item(&mut self, i: &'ast syn::ImplItem) {
        match i {
            syn::ImplItem::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_impl_item(self, i),
        }
    }

    fn visit_trait_item(&mut self, i: &'ast syn::TraitItem) {
        match i {
            syn::TraitItem::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_trait_item(self, i),
        }
    }

    fn visit_foreign_item(&mut self, i: &'ast syn::ForeignItem) {
        match i {
            syn::ForeignItem::Verbatim(t) => self.tokens(t.clone()),
            _ => syn::visit::visit_foreign_item(self, i),
        }
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
    fn an_attribute_among_a_macros_tokens_is_read_with_its_cfg_attrs() {
        let v = check(
            "thread_local! {\n    #[cfg_attr(all(), cfg_attr(all(), used))]\n    static X: u8 = 0;\n}\n",
        );
        assert_eq!(v.len(), 1, "{v:?}");
        assert_eq!(v[0].line, 2);
        assert!(v[0].what.contains("#[used]"), "{v:?}");
    }

    #[test]
    fn syntax_syn_keeps_as_bare_tokens_is_read_token_by_token() {
        // `builtin # …` has no syntax-tree node of its own in syn.
        let v = check("fn f() -> usize {\n    builtin # offset_of(std::process::Child, x)\n}\n");
        assert_eq!(v.len(), 1, "{v:?}");
        assert_eq!(v[0].line, 2);
    }

    /// A file nested far deeper than any assignment once overflowed the
    /// parser's stack and aborted the whole grade book; now it is refused
    /// with its line, and the long plain files a student may write are not.
    #[test]
    fn a_file_nested_beyond_the_rules_bounds_is_refused_not_a_crash() {
        let deep = |open: &str, inner: &str, close: &str, n: usize| {
            format!(
                "pub fn f() -> i32 {{\n    {}{inner}{}\n}}\n",
                open.repeat(n),
                close.repeat(n)
            )
        };
        for (text, what) in [
            (deep("(", "1", ")", 50_000), "nested"),
            (deep("[", "1", "]", 50_000), "nested"),
            (deep("", "1", " + 1", 100_000), "tokens"),
            (deep("-", "1", "", 100_000), "tokens"),
            (deep("if true { 1 } else ", "{ 1 }", "", 20_000), "tokens"),
        ] {
            let v = check(&text);
            assert_eq!(v.len(), 1, "{v:?}");
            assert_eq!(v[0].line, 2, "{v:?}");
            assert!(v[0].what.contains(what) && !v[0].unreadable, "{v:?}");
        }
        // Just within the bounds, the deepest trees they allow are read on
        // the rule's stack without a violation (nor a crash).
        for text in [
            deep("(", "1", ")", MAX_NESTING - 3),
            deep("", "1", " + 1", MAX_RUN / 2 - 10),
            deep("-", "1", "", MAX_RUN - 10),
            deep("if true { 1 } else ", "{ 1 }", "", MAX_RUN / 4 - 10),
            deep("", "1.0f64", ".abs()", MAX_RUN / 4 - 10),
        ] {
            assert_eq!(check(&text), vec![]);
        }
        // Long, plain and legitimate: many items, long doc comments, a
        // table of numbers.
        let mut long = String::new();
        for i in 0..600 {
            long.push_str(&format!(
                "/// A helper.\n/// It returns {i}.\npub fn h{i}() -> f64 {{ {i}.0 }}\n"
            ));
        }
        long.push_str("pub const TABLE: [f64; 3000] = [");
        long.push_str(&"0.5, ".repeat(3000));
        long.push_str("];\n");
        assert_eq!(check(&long), vec![]);
        let big = "// padding\n".repeat(200_000);
        assert!(check(&big)[0].what.contains("more than the rule reads"));
    }

    #[test]
    fn a_use_of_std_io_is_fine_and_std_process_is_not() {
        assert!(check("use std::io::Write;\nfn f() { println!(\"{}\", 1); }").is_empty());
        let v = check("fn f() {\n    std::process::exit(0);\n}\n");
        assert_eq!(v.len(), 1, "{v:?}");
        assert_eq!(v[0].line, 2);
    }
}
