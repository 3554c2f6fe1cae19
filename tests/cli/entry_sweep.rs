//! The sweep behind "a flag and its scene key give the same message for the
//! same bad value", driven by the table (`spintop::scene::table`): for every
//! key whose flag a command's `--help` lists (`simulate`, `balance`,
//! `orbit`, `shell`, and the keys of a top `plot` shares), bad values made
//! from the key's range (beyond each end, not finite, a name not offered,
//! a list of the wrong kind) are asked once as the flag and once as the key
//! of a scene file (`spintop run scene.toml`). Both must exit with code 2,
//! the scene's message must be located at its line, and the two messages
//! must be the same apart from the key's name (see [`super::entry`]'s
//! `neutral`).
//!
//! In process through `spintop_app::cli::run_code`, as the binary runs
//! (a few of the same pairs are run through the real binary by
//! `the_binary_gives_a_flag_and_its_key_the_same_message`).

use super::entry::{neutral, run, scene};
use spintop::math::Real;
use spintop::scene::table::{self, Bound, Command, Range, Spec};

/// A value as both sources write it.
#[derive(Clone, Debug)]
enum Val {
    Num(Real),
    List(Vec<Real>),
    Whole(i64),
    Name(&'static str),
    /// A number written beyond the largest double (`1e400`), first of
    /// `n` numbers (zeros after it); 0: a list of one (output times).
    Overflow(usize),
}

/// A number too large for a double, as typed.
const TOO_LARGE: &str = "1e400";

/// A number as TOML and the command line both read it.
fn num_text(x: Real) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:?}")
    }
}

impl Val {
    /// As a scene file's value.
    fn toml(&self) -> String {
        match self {
            Val::Num(x) => num_text(*x),
            Val::List(v) => format!(
                "[{}]",
                v.iter()
                    .map(|x| num_text(*x))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Val::Whole(n) => n.to_string(),
            Val::Name(s) => format!("\"{s}\""),
            Val::Overflow(0) => format!("[{TOO_LARGE}]"),
            Val::Overflow(1) => TOO_LARGE.into(),
            Val::Overflow(n) => format!("[{TOO_LARGE}{}]", ", 0.0".repeat(n - 1)),
        }
    }

    /// As a flag's value.
    fn flag(&self) -> String {
        match self {
            Val::Num(x) => num_text(*x),
            Val::List(v) => v.iter().map(|x| num_text(*x)).collect::<Vec<_>>().join(","),
            Val::Whole(n) => n.to_string(),
            Val::Name(s) => s.to_string(),
            Val::Overflow(n) => format!("{TOO_LARGE}{}", ",0".repeat((*n).max(1) - 1)),
        }
    }
}

/// How many numbers a key holds: its value name's commas (`W1,W2,W3`), or
/// `None` for one number.
fn arity(spec: &Spec) -> Option<usize> {
    let n = spec.value_name.matches(',').count();
    (n > 0 && !spec.value_name.ends_with("...")).then_some(n + 1)
}

/// `x` in the first place of a key of `spec`'s arity, zeros elsewhere.
fn shaped(spec: &Spec, x: Real) -> Val {
    match arity(spec) {
        Some(n) => {
            let mut v = vec![0.0; n];
            v[0] = x;
            Val::List(v)
        }
        None => Val::Num(x),
    }
}

/// Values the key's range refuses: beyond each finite end, not finite, a
/// name not offered, a list of the wrong kind.
fn bad_values(spec: &Spec) -> Vec<Val> {
    let mut out = Vec::new();
    match spec.range {
        Range::Finite => out.push(shaped(spec, Real::NAN)),
        Range::Between(lo, hi) => {
            match lo {
                Bound::Open(a) => out.push(Val::Num(a)),
                Bound::Closed(0.0) => out.push(Val::Num(-1.0)),
                Bound::Closed(a) => out.push(Val::Num(a / 10.0)),
                Bound::None => {}
            }
            match hi {
                Bound::Open(b) => out.push(Val::Num(b)),
                Bound::Closed(b) if b >= 1.0 => out.push(Val::Num(b + 1.0)),
                Bound::Closed(b) => out.push(Val::Num(b * 10.0)),
                Bound::None => {}
            }
            out.push(Val::Num(Real::NAN));
            out.push(Val::Num(Real::INFINITY));
        }
        Range::NonZero => out.extend([shaped(spec, 0.0), shaped(spec, Real::NAN)]),
        Range::EachAtMost(m) => out.push(shaped(spec, 10.0 * m)),
        Range::EachPositive => out.push(Val::List(vec![1.0, 0.0])),
        Range::RigidBody => out.extend([
            Val::List(vec![1.0, 1.0, 3.0]),
            Val::List(vec![0.0, 1.0, 1.0]),
        ]),
        Range::Count(lo, hi) => out.extend([Val::Whole(lo as i64 - 1), Val::Whole(hi as i64 + 1)]),
        Range::Times { forward: true } => out.extend([
            Val::List(vec![3.0, 2.0, 1.0]),
            Val::List(vec![-1.0]),
            Val::List(vec![0.0, Real::NAN]),
        ]),
        Range::Times { forward: false } => out.push(Val::List(vec![0.0, Real::INFINITY])),
        Range::Names(_) => out.push(Val::Name("nonsense")),
    }
    // Every number key: a number beyond the largest double, which TOML and
    // Rust both refuse to read as a number (Rust as infinity).
    match spec.range {
        Range::Names(_) | Range::Count(..) => {}
        Range::Times { .. } => out.push(Val::Overflow(0)),
        _ => out.push(Val::Overflow(arity(spec).unwrap_or(1))),
    }
    out
}

/// A question of one command: its own section's keys and `[solve]`'s, each
/// with its value.
struct Question {
    own: Vec<(&'static str, Val)>,
    solve: Vec<(&'static str, Val)>,
}

impl Question {
    fn set(list: &mut Vec<(&'static str, Val)>, key: &'static str, v: Val) {
        list.retain(|(k, _)| *k != key);
        list.push((key, v));
    }
}

/// A valid question of `command` in which `spec`'s key can be given (the
/// trajectory, model or method it belongs to), with that key set to `bad`.
fn question(command: Command, spec: &Spec, bad: Val) -> Question {
    let name = Val::Name;
    let mut q = match command {
        Command::Simulate | Command::Plot => Question {
            own: vec![("model", name("truncated"))],
            solve: vec![("t_end", Val::Num(1.0))],
        },
        Command::Balance => Question {
            own: vec![("dipole", name("precessing"))],
            solve: vec![("times", Val::List(vec![0.0]))],
        },
        Command::Orbit => Question {
            own: vec![("potential", name("harmonic")), ("tau0", Val::Num(1e-3))],
            solve: vec![("times", Val::List(vec![1.0]))],
        },
        Command::Shell => Question {
            own: vec![("tau0", Val::Num(1e-3)), ("delay", Val::Num(0.03))],
            solve: vec![("times", Val::List(vec![1.0]))],
        },
    };
    match (spec.command, spec.key) {
        (Command::Simulate, "inertia" | "dipole") => {
            Question::set(&mut q.own, "model", name("general"));
            Question::set(&mut q.own, "inertia", Val::List(vec![1.0, 2.0, 2.5]));
            Question::set(&mut q.own, "dipole", Val::List(vec![0.0, 0.0, 1.0]));
        }
        (Command::Simulate, "step") => Question::set(&mut q.solve, "method", name("rk4")),
        (Command::Balance, "b" | "eps") => Question::set(&mut q.own, "dipole", name("loop")),
        (Command::Balance, "charges" | "masses" | "length") => {
            Question::set(&mut q.own, "dipole", name("dumbbell"))
        }
        _ => {}
    }
    match (spec.section, spec.key) {
        ("solve", "t_end") => q.solve.clear(),
        ("solve", "samples") => {
            q.solve.clear();
            Question::set(&mut q.solve, "t_end", Val::Num(1.0));
        }
        ("solve", "times") => q.solve.retain(|(k, _)| *k == "method"),
        _ => {}
    }
    let list = if spec.section == "solve" {
        &mut q.solve
    } else {
        &mut q.own
    };
    Question::set(list, spec.key, bad);
    q
}

/// The command-line name and the scene kind of a command.
fn names_of(command: Command) -> (&'static str, &'static str) {
    match command {
        Command::Simulate => ("simulate", "top"),
        Command::Plot => ("plot", "top"),
        Command::Balance => ("balance", "balance"),
        Command::Orbit => ("orbit", "orbit"),
        Command::Shell => ("shell", "shell"),
    }
}

/// The arguments of `command` that ask `q`.
fn args(command: Command, q: &Question) -> Vec<String> {
    let mut out = vec![names_of(command).0.to_string()];
    for (key, v) in q.own.iter().chain(&q.solve) {
        out.push(table::flag_of(key));
        out.push(v.flag());
    }
    out
}

/// The two sections of a scene that asks `q`.
fn sections(q: &Question) -> (String, String) {
    let lines = |list: &[(&str, Val)]| {
        list.iter()
            .map(|(k, v)| format!("{k} = {}", v.toml()))
            .collect::<Vec<_>>()
            .join("\n")
    };
    (lines(&q.own), lines(&q.solve))
}

/// The flags `spintop <command> --help` lists.
fn listed_flags(command: &str) -> String {
    let (code, out, err) = run(&[command, "--help"]);
    assert_eq!(code, 0, "{err}");
    out
}

/// Every key with a flag, asked by the commands that have the flag: the
/// command whose flags ask it, and the key (plot: the keys of a top it
/// shares with simulate and has no row of its own for).
fn keys_with_flags() -> Vec<(Command, &'static Spec)> {
    let mut out = Vec::new();
    for command in [
        Command::Simulate,
        Command::Balance,
        Command::Orbit,
        Command::Shell,
        Command::Plot,
    ] {
        let help = listed_flags(names_of(command).0);
        let owner = if command == Command::Plot {
            Command::Simulate
        } else {
            command
        };
        let own_row = |s: &Spec| {
            command == Command::Plot && table::keys_of(Command::Plot).any(|p| p.key == s.key)
        };
        for spec in table::keys_of(owner) {
            if help.contains(&format!("{} <", spec.flag())) && !own_row(spec) {
                out.push((command, spec));
            }
        }
    }
    out
}

/// How the command line is run: in process, or the real binary.
type Runner = fn(&[&str]) -> (u8, String, String);

/// The real binary, as a user runs it: (exit code, stdout, stderr).
fn spawned(args: &[&str]) -> (u8, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the spintop binary runs");
    let code = out.status.code().map_or(255, |c| c as u8);
    (
        code,
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// One bad value's two messages, or what is wrong with them.
fn compare(
    run: Runner,
    dir: &std::path::Path,
    n: usize,
    command: Command,
    spec: &Spec,
    bad: Val,
) -> Result<(), String> {
    let q = question(command, spec, bad.clone());
    let argv = args(command, &q);
    let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
    let (own, solve) = sections(&q);
    let path = scene(dir, n, names_of(command).1, &own, &solve);
    let (flag_code, _, flag_err) = run(&argv);
    let (key_code, _, key_err) = run(&["run", &path]);
    let strip = |e: &str| e.trim().trim_start_matches("spintop: error: ").to_string();
    let (flag, key) = (strip(&flag_err), strip(&key_err));
    let what = format!(
        "{argv:?} / [{}] {} = {}",
        spec.section,
        spec.key,
        bad.toml()
    );
    if flag_code != 2 || key_code != 2 {
        return Err(format!(
            "{what}: exit {flag_code} and {key_code}\n  flag: {flag}\n  key:  {key}"
        ));
    }
    if !key.starts_with(&format!("{path}:")) {
        return Err(format!("{what}: the scene's message has no line: {key}"));
    }
    let owner = if command == Command::Plot {
        Command::Simulate
    } else {
        command
    };
    let (flag, key) = (neutral(&flag, owner), neutral(&key, owner));
    let same = match (&spec.range, names_listed(&flag), names_listed(&key)) {
        // A name refused: the same sentence, each listing the names its
        // entry point takes (a scene's key the table's, a flag those its
        // command offers: simulate no `auto`, plot its own `both`).
        (Range::Names(all), Some((f, f_names)), Some((k, k_names))) => {
            f == k
                && k_names == *all
                && f_names
                    .iter()
                    .all(|n| all.contains(n) || (command == Command::Plot && *n == "both"))
        }
        _ => flag == key,
    };
    if !same {
        return Err(format!("{what}\n  flag: {flag}\n  key:  {key}"));
    }
    // One range from the table, everywhere: a number of `[solve]` refused
    // states what the table's row expects (as `--help` does; the keys a
    // constructor of the core checks, `ratio`, `cone`, …, keep its words on
    // the same range); a number too large for a double says so, naming the
    // key.
    let expected = match bad {
        Val::Num(_) if spec.section == "solve" && matches!(spec.range, Range::Between(..)) => {
            format!("; expected {}", spec.expected())
        }
        Val::Overflow(_) => format!("{}: {TOO_LARGE} overflows f64", spec.key),
        _ => String::new(),
    };
    if !key.contains(&expected) {
        return Err(format!("{what}: not `{expected}`: {key}"));
    }
    Ok(())
}

/// A refused name's message split at its list: the sentence before it and
/// the names listed.
fn names_listed(message: &str) -> Option<(&str, Vec<&str>)> {
    let (sentence, list) = message.split_once("; expected one of ")?;
    Some((sentence, list.split(", ").collect()))
}

/// Ask every `every`-th bad value of every key with a flag through `run`:
/// (keys, values asked, what differed).
fn sweep(run: Runner, tag: &str, every: usize) -> (usize, usize, Vec<String>) {
    let dir = std::env::temp_dir().join(format!("spintop-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let keys = keys_with_flags();
    let mut differ = Vec::new();
    let (mut seen, mut asked) = (0, 0);
    for (command, spec) in &keys {
        for bad in bad_values(spec) {
            seen += 1;
            if seen % every != 0 {
                continue;
            }
            if let Err(e) = compare(run, &dir, asked, *command, spec, bad) {
                differ.push(e);
            }
            asked += 1;
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    (keys.len(), asked, differ)
}

#[test]
fn every_flag_and_its_scene_key_give_the_same_message_for_each_bad_value() {
    let (keys, asked, differ) = sweep(run, "sweep", 1);
    eprintln!("{keys} keys with a flag, {asked} bad values, each asked twice");
    // Every key of the four kinds with a flag, and plot's ratio and omega.
    assert!(keys >= 35, "{keys} keys");
    assert!(asked >= 110, "{asked} values");
    assert!(
        differ.is_empty(),
        "{} of {asked} differ:\n{}",
        differ.len(),
        differ.join("\n")
    );
}

/// A few of the sweep's pairs through the real binary (every 20th value).
#[test]
fn the_binary_gives_a_flag_and_its_key_the_same_message() {
    let (_, asked, differ) = sweep(spawned, "sweep-bin", 20);
    assert!(asked >= 4, "{asked} values");
    assert!(differ.is_empty(), "{}", differ.join("\n"));
}

#[test]
#[ignore = "end-to-end: spawns the binary twice for each of the sweep's ~90 values"]
fn the_binary_gives_every_flag_and_its_key_the_same_message() {
    let (_, asked, differ) = sweep(spawned, "sweep-bin-all", 1);
    assert!(asked >= 80, "{asked} values");
    assert!(
        differ.is_empty(),
        "{} of {asked} differ:\n{}",
        differ.len(),
        differ.join("\n")
    );
}

/// `plot`'s own keys (a chart's last time, width and height) have no scene
/// key; a bad value of each is refused by its own row of the table, in the
/// words a key gets (`--t-end 0 is out of range; expected a positive last
/// time of a chart`), not by the top's `[solve] t_end` it is passed on as.
#[test]
fn plots_own_flags_are_refused_by_their_own_rows() {
    let keys: Vec<&Spec> = table::keys_of(Command::Plot)
        .filter(|s| s.section == "plot")
        .collect();
    assert_eq!(keys.len(), 3);
    for spec in keys {
        for bad in bad_values(spec) {
            let value = bad.flag();
            let (code, _, err) = run(&["plot", &spec.flag(), &value]);
            let expected = match bad {
                Val::Overflow(_) => "; expected a finite number".to_string(),
                _ => format!("; expected {}", spec.expected()),
            };
            assert_eq!(code, 2, "plot {} {value}: {err}", spec.flag());
            assert!(
                err.starts_with(&format!("spintop: error: {}", spec.flag()))
                    && err.trim_end().ends_with(&expected),
                "plot {} {value}: {err}",
                spec.flag()
            );
        }
    }
}

/// The live view's flags (`spintop tui --ratio …`) are read by the same
/// validation as `simulate`'s: for each key of a top the live view takes,
/// each bad value gets the same message and exit code from both commands
/// (the view refuses before it looks for a terminal); its `--method` takes
/// the names `plot` takes (both draw the truncated and the reduced model),
/// and refuses a name as `plot` does.
#[test]
fn the_live_views_flags_give_simulates_messages() {
    let help = listed_flags("tui");
    let keys: Vec<&Spec> = table::keys_of(Command::Simulate)
        .filter(|s| help.contains(&format!("{} <", s.flag())))
        .collect();
    assert_eq!(keys.len(), 3, "ratio, omega, method");
    let mut asked = 0;
    for spec in keys {
        for bad in bad_values(spec) {
            let value = bad.flag();
            let tui = run(&["tui", &spec.flag(), &value]);
            let simulate = if spec.key == "method" {
                run(&["plot", &spec.flag(), &value])
            } else {
                run(&[
                    "simulate",
                    "--model",
                    "truncated",
                    "--t-end",
                    "1",
                    &spec.flag(),
                    &value,
                ])
            };
            assert_eq!(
                simulate.0,
                2,
                "simulate {} {value}: {}",
                spec.flag(),
                simulate.2
            );
            assert_eq!(
                (tui.0, &tui.2),
                (simulate.0, &simulate.2),
                "tui {} {value}",
                spec.flag()
            );
            asked += 1;
        }
    }
    assert!(asked >= 4, "{asked}");
}

/// The methods a command's `--help` lists for `--method`.
fn listed_methods(command: &str) -> Vec<String> {
    let help = listed_flags(command);
    let start = help.find("--method <METHOD>").expect("--method is listed");
    let after = &help[start..];
    let end = after
        .find("\n\n  -")
        .or(after.find("\n      --"))
        .unwrap_or(after.len());
    after[..end]
        .lines()
        .filter_map(|l| l.trim().strip_prefix("- "))
        .map(|l| l.split(':').next().unwrap_or("").trim().to_string())
        .collect()
}

/// `spintop tui --help` lists the methods the view takes and no other (the
/// table's row of `plot`: every method but `forward`, which the view
/// refuses), and each listed name is taken.
#[test]
fn the_live_views_help_lists_only_the_methods_it_takes() {
    let Range::Names(names) = table::key(Command::Plot, "solve", "method").range else {
        panic!("a method is a name");
    };
    let listed = listed_methods("tui");
    assert_eq!(listed, names.to_vec(), "{listed:?}");
    assert!(!listed.iter().any(|m| m == "forward"));
    let (code, _, err) = run(&["tui", "--method", "forward"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("expected one of"), "{err}");
}

/// A method's help line names the setting it takes as the command spells
/// it, where the command has it: `simulate` lists `rk4 ... (--step)` and
/// `dop853 ... (--rtol)`; `plot` and the live view, which take neither flag,
/// name none. The core's help line names no flag (a core type does not
/// spell a shell's flags).
#[test]
fn method_help_names_a_flag_only_where_the_command_has_it() {
    for m in spintop::sim::MethodChoice::ALL {
        assert!(!m.help().contains("--"), "{}", m.help());
    }
    let line = |help: &str, name: &str| {
        help.lines()
            .find(|l| l.trim().starts_with(&format!("- {name}:")))
            .unwrap_or("")
            .to_string()
    };
    let simulate = listed_flags("simulate");
    assert!(line(&simulate, "rk4").ends_with("(--step)"), "{simulate}");
    assert!(
        line(&simulate, "dop853").ends_with("(--rtol)"),
        "{simulate}"
    );
    for command in ["plot", "tui"] {
        let help = listed_flags(command);
        assert!(!line(&help, "rk4").contains("--step"), "{help}");
        assert!(!line(&help, "dop853").contains("--rtol"), "{help}");
    }
}
