//! The source rule, on a parsed syntax tree: every trick that passed the old
//! text scan fails with "no shortcut", the file and the line, through the
//! same harness that grades (the rule runs before anything is compiled, so
//! these copies are never built); the course's own files and the reference
//! solutions keep it; and the allowed paths stay allowed.

use spintop_course::{self as course, Options, State, source_rule};
use spintop_grading::NO_SHORTCUT;
use std::path::{Path, PathBuf};

fn repo() -> &'static Path {
    course::repository()
}

/// A fresh student's copy in a temporary folder.
fn copy(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("spintop-rule-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    course::export(repo(), &dir).expect("an export");
    dir
}

/// Appends `snippet` to the copy's file `rel` (creating it); the line the
/// snippet starts on.
fn append(dir: &Path, rel: &str, snippet: &str) -> usize {
    let path = dir.join(rel);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let old = std::fs::read_to_string(&path).unwrap_or_default();
    let start = old.lines().count() + 1;
    std::fs::write(&path, format!("{old}{snippet}")).unwrap();
    start
}

/// Grades the copy and checks that every assignment fails with "no
/// shortcut" at `file:line`.
fn assert_refused(dir: &Path, file: &str, line: usize, trick: &str) {
    let status = course::grade(dir, &Options::default()).expect("the harness runs");
    let place = format!("{file}:{line}:");
    let shortcut = status
        .shortcut
        .as_ref()
        .unwrap_or_else(|| panic!("{trick}: not refused"));
    assert_eq!(
        (shortcut.file.as_str(), shortcut.line),
        (file, line),
        "{trick}: {shortcut}"
    );
    for (a, s) in &status.states {
        let State::Failing(report) = s else {
            panic!("{trick}: {} is {s:?}", a.function)
        };
        assert!(report.starts_with(NO_SHORTCUT), "{trick}: {report}");
        assert!(report.contains(&place), "{trick}: {place} in {report}");
    }
    assert_eq!(status.passing(), 0);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn every_known_trick_fails_with_no_shortcut_its_file_and_its_line() {
    let solution = repo().join("lessons/src/solutions/ch2.rs");
    let tricks: Vec<(&str, &str, String, usize)> = vec![
        (
            "a string that opens a comment for a text scan",
            "src/ch2.rs",
            "\npub fn sneaky(jet: &Jet) -> Vec3 {\n    let _open = \"/*\";\n    spintop::physics::balance::larmor_rate(jet) // */\n}\n".into(),
            3,
        ),
        (
            "a char literal that opens a string for a text scan",
            "src/ch2.rs",
            "\npub fn sneaky(jet: &Jet) -> Vec3 {\n    let _q = '\"';\n    spintop::physics::balance::torque_rate(jet) // \"\n}\n".into(),
            3,
        ),
        (
            "#[cfg_attr(all(), path = …)]",
            "src/ch2.rs",
            "\n#[cfg_attr(all(), path = \"../../spintop/src/physics/balance.rs\")]\nmod reference;\n".into(),
            1,
        ),
        (
            "the call in another chapter's file",
            "src/ch4.rs",
            "\npub fn helper(jet: &spintop::assignment::Jet) -> spintop::assignment::Vec3 {\n    spintop::physics::balance::larmor_rate(jet)\n}\n".into(),
            2,
        ),
        (
            "a module in a subfolder",
            "src/extra/deep.rs",
            "pub use spintop::physics::balance::larmor_rate;\n".into(),
            0,
        ),
        (
            "include! under another name",
            "src/ch2.rs",
            "\nuse std::include as paste;\npaste!(\"balance.rs\");\n".into(),
            1,
        ),
        (
            "include! split over two lines",
            "src/ch2.rs",
            "\ninclude\n!(\"../../src/physics/balance.rs\");\n".into(),
            1,
        ),
        (
            "running the spintop binary",
            "src/ch2.rs",
            "\npub fn run() -> String {\n    let out = std::process::Command::new(\"spintop\").output();\n    format!(\"{out:?}\")\n}\n".into(),
            2,
        ),
        (
            "a module whose path is the repository's solution file",
            "src/ch2.rs",
            format!("\n#[path = {:?}]\nmod solution;\n", solution.display().to_string()),
            1,
        ),
        (
            "use spintop as s",
            "src/ch3.rs",
            "\nuse spintop as s;\n".into(),
            1,
        ),
        (
            "extern crate",
            "src/ch3.rs",
            "\nextern crate spintop as reference;\n".into(),
            1,
        ),
        (
            "a glob of spintop",
            "src/lib.rs",
            "\nuse spintop::*;\n".into(),
            1,
        ),
        (
            "a path in a macro",
            "src/appendix.rs",
            "\npub fn m() -> String {\n    format!(\"{:?}\", spintop::physics::shell::C)\n}\n".into(),
            2,
        ),
        (
            "std::fs",
            "src/numerics.rs",
            "\npub fn peek() -> String {\n    std::fs::read_to_string(\"x\").unwrap_or_default()\n}\n".into(),
            2,
        ),
        (
            "std::env through an alias of std",
            "src/numerics.rs",
            "\nuse std as s;\n".into(),
            1,
        ),
        (
            "unsafe code",
            "src/numerics.rs",
            "\npub fn u() -> u8 {\n    unsafe { std::mem::transmute(1u8) }\n}\n".into(),
            2,
        ),
        (
            "an exported symbol",
            "src/numerics.rs",
            "\n#[unsafe(no_mangle)]\npub extern \"C\" fn exit_code() -> i32 { 0 }\n".into(),
            1,
        ),
        (
            "a string naming a file outside the copy",
            "src/ch4.rs",
            "\npub const SOURCE: &str = \"../../../src/physics/symmetric_top.rs\";\n".into(),
            1,
        ),
    ];
    for (i, (trick, file, snippet, offset)) in tricks.into_iter().enumerate() {
        let dir = copy(&format!("trick-{i}"));
        let start = append(&dir, file, &snippet);
        assert_refused(&dir, file, start + offset, trick);
    }
}

/// Tricks found by a reviewer who had not read the rule: each one, before it
/// was refused, let a copy with no assignment done grade 22 of 22 (the first
/// one reads the verdict's token from the environment, writes the verdict
/// file and exits with success) or run code of its own before `main`. A
/// macro of the copy's own is refused where it is defined: what it builds
/// out of its arguments can only be read once it is expanded.
#[test]
fn the_tricks_a_reviewer_found_fail_with_no_shortcut_too() {
    let tricks: Vec<(&str, &str, &str, usize)> = vec![
        (
            "std and its module handed to a macro as separate words",
            "src/ch2.rs",
            "\nmacro_rules! call {\n    ($a:ident $b:ident $f:ident ($($x:expr),*)) => { $a::$b::$f($($x),*) };\n}\npub fn token() -> String {\n    call!(std env var(\"SPINTOP_GRADE_NONCE\")).unwrap_or_default()\n}\n",
            1,
        ),
        (
            "std pasted in front of a module named in the macro",
            "src/ch2.rs",
            "\nmacro_rules! leave {\n    ($m:ident) => { ::std::$m::exit(0) };\n}\npub fn done() {\n    leave!(process)\n}\n",
            1,
        ),
        (
            "std re-exported by a module of the copy, then reached through it",
            "src/ch3.rs",
            "\nmod x {\n    pub use std;\n}\npub fn pid() -> u32 {\n    self::x::std::process::id()\n}\n",
            2,
        ),
        (
            "std brought in as a name with `use std::{self}`",
            "src/ch3.rs",
            "\nuse std::{self};\npub fn pid() -> u32 {\n    self::std::process::id()\n}\n",
            1,
        ),
        (
            "assembly at global scope (safe to write, runs before main)",
            "src/ch4.rs",
            "\ncore::arch::global_asm!(\n    \".pushsection .init_array,\\\"aw\\\"\",\n    \".quad early\",\n    \".popsection\",\n    \".text\",\n    \"early: mov eax, 231\",\n    \"xor edi, edi\",\n    \"syscall\",\n);\n",
            1,
        ),
        (
            "global_asm! under another name",
            "src/ch4.rs",
            "\nuse std::arch::global_asm as early;\n",
            1,
        ),
        (
            "#[path] inside a cfg_attr inside a cfg_attr",
            "src/lib.rs",
            "\n#[cfg_attr(all(), cfg_attr(all(), path = \"notes.txt\"))]\nmod notes;\n",
            1,
        ),
        (
            "#[path] written by a macro",
            "src/lib.rs",
            "\nmacro_rules! module_at {\n    ($p:literal) => {\n        #[path = $p]\n        mod notes;\n    };\n}\nmodule_at!(\"notes.txt\");\n",
            1,
        ),
    ];
    for (i, (trick, file, snippet, offset)) in tricks.into_iter().enumerate() {
        let dir = copy(&format!("reviewer-{i}"));
        let start = append(&dir, file, snippet);
        assert_refused(&dir, file, start + offset, trick);
    }
}

/// Tricks found on a second pass.
#[test]
fn the_tricks_of_a_second_pass_fail_with_no_shortcut_too() {
    let deep = format!(
        "\npub fn f() -> i32 {{\n    {}1{}\n}}\n",
        "(".repeat(50_000),
        ")".repeat(50_000)
    );
    let tricks: Vec<(&str, &str, &str, usize)> = vec![
        (
            "the build's environment read by env!",
            "src/ch2.rs",
            "\npub fn home() -> &'static str {\n    env!(\"HOME\")\n}\n",
            2,
        ),
        (
            "std::fs further down a path",
            "src/ch3.rs",
            "\npub fn f() -> bool {\n    crate::ch4::std::fs::exists(\"x\").is_ok()\n}\n",
            2,
        ),
        (
            "brackets nested 50,000 deep (the parser's stack overflowed: spintop course grade aborted, no CSV for the class)",
            "src/ch4.rs",
            &deep,
            2,
        ),
    ];
    for (i, (trick, file, snippet, offset)) in tricks.into_iter().enumerate() {
        let dir = copy(&format!("second-{i}"));
        let start = append(&dir, file, snippet);
        assert_refused(&dir, file, start + offset, trick);
    }
}

/// A module whose file is a symbolic link to the repository's reference
/// solution: the rule reads only real files, the compiler follows the link.
/// Refused, on the student's machine and in the instructor's clean checkout.
#[cfg(unix)]
#[test]
fn a_symbolic_link_to_the_solution_is_refused() {
    let dir = copy("link");
    let solution = repo().join("lessons/src/solutions/ch2.rs");
    std::os::unix::fs::symlink(&solution, dir.join("src/done.rs")).unwrap();
    append(&dir, "src/lib.rs", "\nmod done;\n");
    assert_refused(&dir, "src/done.rs", 1, "a symbolic link");
}

/// The whole `src/` a symbolic link (to the repository's lessons, where the
/// solutions are): refused without walking the folder it stands for.
#[cfg(unix)]
#[test]
fn a_src_folder_that_is_a_symbolic_link_is_refused() {
    let dir = copy("src-link");
    std::fs::remove_dir_all(dir.join("src")).unwrap();
    std::os::unix::fs::symlink(repo().join("lessons/src"), dir.join("src")).unwrap();
    assert_refused(&dir, "src", 1, "src/ a symbolic link");
}

/// A build script, a manifest that names one, and edited tests count for
/// nothing: a grading takes the copy's `src/` alone into a workspace whose
/// manifests are spintop's.
#[test]
fn a_build_script_and_a_manifest_of_the_copy_count_for_nothing() {
    let dir = copy("build-script");
    std::fs::write(dir.join("build.rs"), "fn main() {}\n").unwrap();
    append(
        &dir,
        "Cargo.toml",
        "\n[package.metadata]\nx = 1\nbuild = \"build.rs\"\n",
    );
    let ws = course::workspace::Workspace::at(&dir.join("graded"));
    ws.lay_out(repo()).unwrap();
    let snap = course::snapshot::take(&dir, &ws.course(), &Default::default()).unwrap();
    assert!(snap.refused.is_empty(), "{snap:?}");
    assert!(snap.files.iter().all(|f| f.starts_with("src")), "{snap:?}");
    assert!(!ws.course().join("build.rs").exists());
    let manifest = std::fs::read_to_string(ws.course().join("Cargo.toml")).unwrap();
    assert!(!manifest.contains("build"), "{manifest}");
    assert!(source_rule::check_copy(&ws.course()).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_course_files_and_the_reference_solutions_keep_the_rule() {
    let lessons = course::lessons_dir(repo());
    assert_eq!(
        source_rule::check_copy(&lessons),
        vec![],
        "lessons/ and its solutions"
    );
    let dir = copy("clean");
    assert_eq!(source_rule::check_copy(&dir), vec![], "an export");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_allowed_paths_stay_allowed() {
    let root = Path::new("/copy");
    let allowed = "\
use spintop::assignment::{Jet, Vec3};
use spintop::math::{Mat3, State};
use spintop::math as m;
use spintop :: assignment :: C;
use spintop::math::*;
use std::io::Write;
use std::f64::consts::PI;
use std::fmt::Write as _;
// spintop::physics::balance::larmor_rate is the reference; not used
/* spintop::sim */
#[derive(Debug, Clone, Copy)]
struct Stage {
    env: f64,
    os: [f64; 2],
}
#[allow(clippy::many_single_char_names)]
#[inline]
fn helper(h: f64) -> f64 {
    let env = Stage { env: h, os: [0.0; 2] };
    let arch = std::array::from_fn::<f64, 3, _>(|i| i as f64 * env.env);
    let mut text = String::new();
    let _ = write!(text, \"{:?}\", env.os);
    debug_assert!(matches!(arch.len(), 3));
    std::mem::swap(&mut text, &mut String::new());
    const { 2.0 } * arch[1]
}
#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn small() {
        assert_eq!(helper(1.0), 2.0);
    }
}
pub fn f(jet: &Jet) -> Vec3 {
    let v = spintop::math::Vec3::zeros();
    let s = crate::ch4::reduced_ale_rhs(0.4, 1.0, v);
    let _ = format!(\"{} rad/s, 1/2 of it, {}/{}\", PI, 1, 2);
    let _ = \"../src/ch4.rs\";
    println!(\"{}\", m::Vec3::x());
    jet[0] + s
}
";
    let found = source_rule::check_source(Path::new("src/ch2.rs"), allowed, root);
    assert_eq!(found, vec![]);
}
