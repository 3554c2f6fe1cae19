//! The checkers can fail: scratch trees with each kind of wrong import, in
//! each disguise, a circle through a parent's re-exports, and a circle among
//! a shell's files, each caught, and the right imports beside them passing.

use super::inner::{import_circle, module_edges};
use super::rules::{WHOLE, violations};
use std::path::Path;

/// The violations of a scratch tree of `files` (path, text) written under
/// `dir`, which is removed after.
fn violations_of_scratch(dir: &Path, files: &[(&str, &str)]) -> Vec<String> {
    for (path, text) in files {
        let path = dir.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let bad = violations(dir, &WHOLE);
    let _ = std::fs::remove_dir_all(dir);
    bad
}

/// The checker itself can fail, on each kind of wrong import: a scratch tree
/// with one of each, and a right import of each kind beside it.
#[test]
fn the_checker_fails_on_each_kind_of_wrong_import() {
    let dir = std::env::temp_dir().join(format!("spintop-arch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files: &[(&str, &str)] = &[
        ("src/lib.rs", "pub mod math;\n"),
        (
            "src/math.rs",
            "// crate::sim in a comment is fine\npub fn f() { let s = \"crate::tui::x\"; }\n",
        ),
        ("src/numbers.rs", ""),
        // 1. A one-line `use` up the layers: physics → sim.
        (
            "src/physics.rs",
            "use crate::sim::Simulation;\npub mod top;\n",
        ),
        // 2. A `use` tree over several lines, nested: integrate → scene (its
        // line is the line of the item, 4).
        (
            "src/integrate.rs",
            "use crate::{\n    math::Real,\n    scene::{\n        parse,\n    },\n};\n",
        ),
        // 3. A `super::` chain: physics/top/deep.rs reaches the crate's tui.
        ("src/physics/top.rs", "pub mod deep;\n"),
        (
            "src/physics/top/deep.rs",
            "use super::super::super::tui::app;\nuse super::super::Energy;\n",
        ),
        // 4. A fully qualified path in code: sim → cli.
        (
            "src/sim.rs",
            "fn g() {\n    let x = crate::math::Real::default();\n    crate::cli::run(x);\n}\n",
        ),
        // 5. A shell importing a shell outside the launchers: tui → cli.
        ("src/tui.rs", "pub mod app;\n"),
        (
            "src/tui/app.rs",
            "use crate::cli::parse_number;\nuse crate::sim::Model;\n",
        ),
        ("src/cli.rs", "pub mod tui;\npub mod run;\n"),
        ("src/cli/tui.rs", "use crate::tui::app::App;\n"),
        // 6. A service that is not a neighbour: stability → figure.
        (
            "src/stability.rs",
            "use crate::figure::Figure;\nuse crate::sim::Model;\n",
        ),
        ("src/figure.rs", ""),
        // 7. A circle between two files of one module, each in `use self`.
        ("src/scene.rs", "pub mod a;\npub mod b;\n"),
        (
            "src/scene/a.rs",
            "use crate::scene::b::B;\nuse crate::output as out;\npub struct A;\n",
        ),
        (
            "src/scene/b.rs",
            "mod inner {\n    use super::super::a::A;\n}\n",
        ),
        // 8. A circle between two neighbours: scene ↔ output.
        (
            "src/output.rs",
            "pub fn h() -> crate::scene::a::A { todo!() }\n",
        ),
        ("src/server.rs", ""),
    ];
    let bad = violations_of_scratch(&dir, files);
    let expect = [
        "src/physics.rs:1: physics (layer 1) imports sim (layer 3)",
        "src/integrate.rs:4: integrate (layer 2) imports scene (layer 4)",
        "src/physics/top/deep.rs:1: physics (layer 1) imports tui (layer 5)",
        "src/sim.rs:3: sim (layer 3) imports cli (layer 5)",
        "src/tui/app.rs:1: the tui shell imports the cli shell",
        "src/stability.rs:1: stability imports figure, in its own layer (4) but not one of its neighbours",
        "src/output.rs:1: output imports scene, in its own layer (4) but not one of its neighbours",
        "an import circle: output <-> scene",
        "an import circle: scene::a <-> scene::b",
        // sim → cli (4. above) closes a circle through the launcher and 5.
        "an import circle: cli <-> sim <-> tui",
    ];
    for e in expect {
        assert!(
            bad.iter().any(|b| b.starts_with(e)),
            "not caught: {e}\ngot:\n{}",
            bad.join("\n")
        );
    }
    // And nothing else: the right imports beside them (a comment, a string,
    // math from anywhere, super::super within physics, the launcher, sim
    // from a service and a shell) pass.
    assert_eq!(bad.len(), expect.len(), "{}", bad.join("\n"));
}

/// The checker reads paths in every form the compiler reads them: with
/// spaces round `::`, in the strings of attributes (`serde`'s
/// `with = "crate::…"`), and through exported macros; and it refuses the
/// forms it cannot follow (an alias of the crate, a glob of its root, a
/// re-export at the root, another module's file compiled in with `#[path]`
/// or `include!`). Nothing else is reported: a doc link is not an import.
#[test]
fn the_checker_sees_imports_in_every_disguise() {
    let dir = std::env::temp_dir().join(format!("spintop-arch-disguise-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files: &[(&str, &str)] = &[
        // 1. A re-export at the root hides the module an item comes from.
        ("src/lib.rs", "pub mod math;\npub use cli::run as launch;\n"),
        ("src/math.rs", "pub type Real = f64;\n"),
        ("src/numbers.rs", ""),
        // 2. Spaces round `::` in code: sim → cli.
        ("src/sim.rs", "fn g() {\n    crate :: cli :: run();\n}\n"),
        // 3. An alias of the crate: physics reaches sim through it.
        (
            "src/physics.rs",
            "use crate as root;\nfn f() {\n    root::sim::g();\n}\n",
        ),
        // 4. A glob of the crate root brings every module into scope.
        (
            "src/integrate.rs",
            "use crate::*;\nfn f() { cli::run(); }\n",
        ),
        // 5. A doc link is no import (rustdoc reads it, the compiler does
        // not): a lower module may name who calls it.
        (
            "src/stability.rs",
            "/// Compare [`crate::workprecision::Sweep`].\npub fn s() {}\n",
        ),
        ("src/workprecision.rs", ""),
        // 6. A path in an attribute's string: figure → tui.
        (
            "src/figure.rs",
            "#[derive(serde::Serialize)]\npub struct F {\n    #[serde(serialize_with = \"crate::tui::fmt\")]\n    x: f64,\n}\n",
        ),
        ("src/tui.rs", ""),
        // 7. Another module's file compiled in: plot takes the server's.
        (
            "src/plot.rs",
            "#[path = \"server/http.rs\"]\nmod http;\nfn f() { include!(\"server/page.rs\"); }\n",
        ),
        ("src/server.rs", "pub mod http;\n"),
        ("src/server/http.rs", ""),
        // 8. An exported macro that reaches the cli, used from the scene.
        (
            "src/cli.rs",
            "#[macro_export]\nmacro_rules! launch_cli {\n    () => { $crate::cli::run() };\n}\npub fn run() {}\n",
        ),
        ("src/scene.rs", "fn f() {\n    crate::launch_cli!();\n}\n"),
        // 9. `extern crate self` is an alias of the crate too.
        (
            "src/output.rs",
            "extern crate self as spintop;\nfn f() { spintop_app::cli::run(); }\n",
        ),
    ];
    let bad = violations_of_scratch(&dir, files);
    let expect = [
        "src/lib.rs:2: the crate root re-exports",
        "src/sim.rs:2: sim (layer 3) imports cli (layer 5)",
        "src/physics.rs:1: an alias of the crate",
        "src/integrate.rs:1: a glob of the crate root",
        "src/figure.rs:3: figure (layer 4) imports tui (layer 5)",
        "src/plot.rs:1: `#[path]`",
        "src/plot.rs:3: `include!`",
        "src/scene.rs:2: scene (layer 4) imports cli (layer 5)",
        "src/output.rs:1: an alias of the crate",
    ];
    let missed: Vec<&str> = expect
        .iter()
        .copied()
        .filter(|e| !bad.iter().any(|b| b.starts_with(e)))
        .collect();
    assert!(
        missed.is_empty(),
        "not caught:\n{}\ngot:\n{}",
        missed.join("\n"),
        bad.join("\n")
    );
    assert_eq!(bad.len(), expect.len(), "{}", bad.join("\n"));
}

/// Two files of one module that import each other through their parent's
/// re-exports make a circle too: `scene/answer.rs` writes
/// `use super::Chosen` for what `scene.rs` brings in from `scene/plan.rs`,
/// so it imports `plan`; with `plan` importing `answer` back, the checker
/// must see the circle (it read `super::Chosen` as an import of `scene`).
#[test]
fn a_circle_through_a_parents_re_exports_is_caught() {
    let dir = std::env::temp_dir().join(format!("spintop-reexport-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = "pub mod answer;\npub mod plan;\npub use plan::Chosen as Pick;\npub use answer::{Answer as Reply};\n";
    let circle = violations_of_scratch(
        &dir,
        &[
            ("src/lib.rs", "pub mod scene;\n"),
            ("src/scene.rs", scene),
            (
                "src/scene/answer.rs",
                "use super::Pick;\npub struct Answer;\n",
            ),
            (
                "src/scene/plan.rs",
                "use super::Reply;\npub struct Chosen;\n",
            ),
        ],
    );
    let none = violations_of_scratch(
        &dir,
        &[
            ("src/lib.rs", "pub mod scene;\n"),
            ("src/scene.rs", scene),
            (
                "src/scene/answer.rs",
                "use super::Pick;\npub struct Answer;\n",
            ),
            ("src/scene/plan.rs", "pub struct Chosen;\n"),
        ],
    );
    assert!(
        circle
            .iter()
            .any(|v| v.contains("an import circle: scene::answer <-> scene::plan")),
        "{circle:?}"
    );
    assert!(none.is_empty(), "{none:?}");
}

#[test]
fn the_circle_check_catches_a_circle() {
    // A scratch tree with the old circle: app.rs imports event.rs for its
    // command, event.rs imports app.rs for its state; and a parent and a
    // child module that import each other.
    let dir = std::env::temp_dir().join(format!("spintop-circle-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src/tui/learn")).unwrap();
    std::fs::write(
        dir.join("src/tui.rs"),
        "pub mod app;\npub mod event;\npub mod learn;\n",
    )
    .unwrap();
    std::fs::write(dir.join("src/tui/app.rs"), "use super::event::Command;\n").unwrap();
    std::fs::write(
        dir.join("src/tui/event.rs"),
        "use super::{app::{App, Mode}, theme};\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("src/tui/learn.rs"),
        "pub mod view;\nfn f() { view::draw(); }\n",
    )
    .unwrap();
    std::fs::write(dir.join("src/tui/learn/view.rs"), "use super::Learn;\n").unwrap();
    let edges = module_edges(&dir, "tui");
    let circle = import_circle(&edges);
    std::fs::write(dir.join("src/tui/app.rs"), "pub enum Command {}\n").unwrap();
    let edges_after = module_edges(&dir, "tui");
    let learn_circle = import_circle(&edges_after);
    std::fs::write(dir.join("src/tui/learn.rs"), "pub mod view;\n").unwrap();
    let none = import_circle(&module_edges(&dir, "tui"));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        circle.as_deref(),
        Some("tui::app → tui::event → tui::app"),
        "{edges:?}"
    );
    assert_eq!(
        learn_circle.as_deref(),
        Some("tui::learn → tui::learn::view → tui::learn"),
        "{edges_after:?}"
    );
    assert_eq!(none, None);
}
