//! The rules: each crate's layers, neighbours and launchers, the rule an
//! import breaks, and the circles among modules.

use super::reader::{Import, disguises, imports};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The layers of one crate's modules, bottom (0) to top: each top-level
/// module's layer, what a module may use in its own layer, and where one
/// shell may launch another.
pub(super) struct Rules {
    /// Every top-level module and its layer.
    pub(super) layers: &'static [(&'static str, u8)],
    /// The layer of the shells.
    shell: u8,
    /// What a module may use beside the layers below it (and nothing uses
    /// a module of its own layer not listed here).
    neighbours: &'static [(&'static str, &'static [&'static str])],
    /// The only places one shell may reach another: (file, the shell it launches).
    launchers: &'static [(&'static str, &'static str)],
}

impl Rules {
    fn layer(&self, module: &str) -> Option<u8> {
        self.layers
            .iter()
            .find(|(m, _)| *m == module)
            .map(|(_, l)| *l)
    }

    fn neighbours(&self, module: &str) -> &'static [&'static str] {
        self.neighbours
            .iter()
            .find(|(m, _)| *m == module)
            .map_or(&[], |(_, n)| n)
    }
}

/// The core (`crates/spintop`): no shell in it.
const CORE: Rules = Rules {
    layers: &[
        ("math", 0),
        ("numbers", 0),
        ("physics", 1),
        ("integrate", 2),
        ("sim", 3),
        ("assignment", 4),
        ("figure", 4),
        ("output", 4),
        ("plot", 4),
        ("scene", 4),
        ("stability", 4),
        ("workprecision", 4),
    ],
    shell: u8::MAX,
    neighbours: &[
        // A scene is answered by the commands' computations, and a stability
        // scene by its row.
        ("scene", &["output", "stability"]),
        // The sweep's charts.
        ("workprecision", &["plot"]),
        // The figures as text and SVG.
        ("plot", &["figure"]),
    ],
    launchers: &[],
};

/// The application (`src/`): shells side by side. The two full-screen
/// shells, the live view (`tui`) and the reader (`learn`), never import each
/// other: what both need sits below them, the live models (`live`) over the
/// terminal (`term`). The command line launches each.
const APP: Rules = Rules {
    layers: &[
        ("term", 3),
        ("live", 4),
        ("cli", 5),
        ("learn", 5),
        ("tui", 5),
    ],
    shell: 5,
    neighbours: &[],
    launchers: &[("src/cli/tui.rs", "tui"), ("src/cli/learn.rs", "learn")],
};

/// The rules of the crate when it was one package (every kind of module at
/// once): the checker's own tests run on scratch trees under them.
pub(super) const WHOLE: Rules = Rules {
    layers: &[
        ("math", 0),
        ("numbers", 0),
        ("physics", 1),
        ("integrate", 2),
        ("sim", 3),
        ("assignment", 4),
        ("course", 4),
        ("figure", 4),
        ("grading", 4),
        ("output", 4),
        ("plot", 4),
        ("scene", 4),
        ("stability", 4),
        ("workprecision", 4),
        ("cli", 5),
        ("server", 5),
        ("tui", 5),
    ],
    shell: 5,
    neighbours: &[
        ("scene", &["output", "stability"]),
        ("workprecision", &["plot"]),
        ("plot", &["figure"]),
        ("course", &["grading"]),
        ("grading", &["assignment"]),
    ],
    launchers: &[
        ("src/cli/tui.rs", "tui"),
        ("src/cli/learn.rs", "tui"),
        ("src/cli/book.rs", "server"),
    ],
};

/// The crates this test reads, with their rules: (folder, rules).
pub(super) const CRATES: [(&str, &Rules); 2] = [("crates/spintop", &CORE), (".", &APP)];

/// The rule an import between top-level modules breaks, if any.
fn rule_broken(import: &Import, rules: &Rules) -> Option<String> {
    let (from, to) = (&import.from[0], &import.to[0]);
    if from == to {
        return None;
    }
    let (Some(lf), Some(lt)) = (rules.layer(from), rules.layer(to)) else {
        let unknown = if rules.layer(from).is_none() {
            from
        } else {
            to
        };
        return Some(format!(
            "{unknown} is in no layer: place it in its crate's rules on purpose"
        ));
    };
    if lf == rules.shell && lt == rules.shell {
        let launcher = rules
            .launchers
            .iter()
            .any(|(f, s)| *f == import.file && *s == to);
        return (!launcher).then(|| {
            format!("the {from} shell imports the {to} shell: shells stand side by side; move what both need below them")
        });
    }
    if lt > lf {
        return Some(format!(
            "{from} (layer {lf}) imports {to} (layer {lt}): nothing reaches up"
        ));
    }
    if lt == lf && !rules.neighbours(from).contains(&to.as_str()) {
        return Some(format!(
            "{from} imports {to}, in its own layer ({lf}) but not one of its neighbours"
        ));
    }
    None
}

/// The circles of a graph (each as its nodes, smallest first), by depth-first
/// search over its strongly connected components.
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    // Tarjan's algorithm.
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<String, usize>,
        low: BTreeMap<String, usize>,
        stack: Vec<String>,
        on_stack: BTreeSet<String>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit(s: &mut State, v: &str) {
        s.index.insert(v.to_string(), s.next);
        s.low.insert(v.to_string(), s.next);
        s.next += 1;
        s.stack.push(v.to_string());
        s.on_stack.insert(v.to_string());
        let targets: Vec<String> = s.edges.get(v).into_iter().flatten().cloned().collect();
        for w in targets {
            if !s.index.contains_key(&w) {
                visit(s, &w);
                let low = s.low[v].min(s.low[&w]);
                s.low.insert(v.to_string(), low);
            } else if s.on_stack.contains(&w) {
                let low = s.low[v].min(s.index[&w]);
                s.low.insert(v.to_string(), low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(&w);
                let done = w == v;
                component.push(w);
                if done {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.out.push(component);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.out.sort();
    s.out
}

/// Every import that breaks the order, and every circle, as lines.
pub(super) fn violations(root: &Path, rules: &Rules) -> Vec<String> {
    let imports = imports(root);
    let mut bad: Vec<String> = disguises(root);
    bad.extend(
        imports
            .iter()
            .filter_map(|i| rule_broken(i, rules).map(|r| format!("{}:{}: {r}", i.file, i.line))),
    );
    // Circles among the top-level modules, and among the files of one module.
    let mut top: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut siblings: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for i in &imports {
        if i.from[0] != i.to[0] {
            top.entry(i.from[0].clone())
                .or_default()
                .insert(i.to[0].clone());
        } else if i.from.len() >= 2 && i.to.len() >= 2 && i.from[1] != i.to[1] {
            siblings
                .entry(i.from[..2].join("::"))
                .or_default()
                .insert(i.to[..2].join("::"));
        }
    }
    for circle in circles(&top).into_iter().chain(circles(&siblings)) {
        let lines: Vec<String> = imports
            .iter()
            .filter(|i| {
                let node = |m: &Vec<String>, n: usize| m[..n.min(m.len())].join("::");
                let n = if circle[0].contains("::") { 2 } else { 1 };
                circle.contains(&node(&i.from, n))
                    && circle.contains(&node(&i.to, n))
                    && node(&i.from, n) != node(&i.to, n)
            })
            .map(|i| format!("{}:{}", i.file, i.line))
            .collect();
        bad.push(format!(
            "an import circle: {} (imports at {})",
            circle.join(" <-> "),
            lines.join(", ")
        ));
    }
    bad
}
