//! One entry point per question: the flags of `simulate`, `balance`,
//! `orbit`, `shell` and `plot` and the keys of a scene file are read by the
//! same code against one table (`spintop::scene::table`). For the same bad
//! value a flag and its scene key give the same message, the one naming the
//! flag (`--ratio 3`), the other the key at its line (`probe.toml:8:
//! [top] ratio = 3`); and `--help` states the ranges and defaults the table
//! holds.
//!
//! Both run in process through `spintop_app::cli::run`, as the binary does.

use spintop::scene::table::{self, Command, Spec};
use std::path::Path;

/// Run the command line in process: (exit code, stdout, stderr).
pub(super) fn run(args: &[&str]) -> (u8, String, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let argv = std::iter::once("spintop").chain(args.iter().copied());
    let code = spintop_app::cli::run_code(argv, &mut out, &mut err);
    (
        code,
        String::from_utf8_lossy(&out).into_owned(),
        String::from_utf8_lossy(&err).into_owned(),
    )
}

/// A scene of `kind` with `own` in its section and `solve` in `[solve]`.
pub(super) fn scene(dir: &Path, n: usize, kind: &str, own: &str, solve: &str) -> String {
    let text = format!(
        "[scene]\nname = \"probe\"\nkind = \"{kind}\"\ndescription = \"A probe.\"\n\n[{kind}]\n{own}\n\n[solve]\n{solve}\n"
    );
    let path = dir.join(format!("probe-{n}.toml"));
    std::fs::write(&path, text).expect("a scratch scene file");
    path.display().to_string()
}

/// One bad value, asked by flags and by a scene file: the command's
/// arguments, and the scene's kind, own section and `[solve]`.
struct Case {
    args: &'static [&'static str],
    kind: &'static str,
    own: &'static str,
    solve: &'static str,
}

const fn case(
    args: &'static [&'static str],
    kind: &'static str,
    own: &'static str,
    solve: &'static str,
) -> Case {
    Case {
        args,
        kind,
        own,
        solve,
    }
}

/// For each of the five commands, bad values of its flags and of the keys
/// they stand for (out of range, not finite, a name the model does not
/// take, a key of another trajectory, times out of order).
const CASES: &[Case] = &[
    // simulate: [top] and [solve]
    case(
        &["simulate", "--model", "reduced", "--ratio", "3"],
        "top",
        "model = \"reduced\"\nratio = 3.0",
        "",
    ),
    case(
        &["simulate", "--model", "reduced", "--ratio", "nan"],
        "top",
        "model = \"reduced\"\nratio = nan",
        "",
    ),
    case(
        &["simulate", "--model", "truncated", "--omega", "1e101,0,0"],
        "top",
        "model = \"truncated\"\nomega = [1e101, 0.0, 0.0]",
        "",
    ),
    case(
        &["simulate", "--model", "truncated", "--euler", "0,inf,0"],
        "top",
        "model = \"truncated\"\neuler = [0.0, inf, 0.0]",
        "",
    ),
    case(
        &[
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,1,3",
            "--dipole",
            "0,0,1",
        ],
        "top",
        "model = \"general\"\ninertia = [1.0, 1.0, 3.0]\ndipole = [0.0, 0.0, 1.0]",
        "",
    ),
    case(
        &[
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,2,2.5",
            "--dipole",
            "0,0,0",
        ],
        "top",
        "model = \"general\"\ninertia = [1.0, 2.0, 2.5]\ndipole = [0.0, 0.0, 0.0]",
        "",
    ),
    case(
        &[
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,2,2.5",
            "--dipole",
            "0,0,1",
            "--ratio",
            "0.4",
        ],
        "top",
        "model = \"general\"\ninertia = [1.0, 2.0, 2.5]\ndipole = [0.0, 0.0, 1.0]\nratio = 0.4",
        "",
    ),
    case(
        &["simulate", "--model", "full", "--method", "rk4"],
        "top",
        "model = \"full\"",
        "method = \"rk4\"",
    ),
    case(
        &["simulate", "--model", "reduced", "--t-end", "-1"],
        "top",
        "model = \"reduced\"",
        "t_end = -1.0",
    ),
    case(
        &[
            "simulate",
            "--model",
            "reduced",
            "--t-end",
            "1",
            "--samples",
            "0",
        ],
        "top",
        "model = \"reduced\"",
        "t_end = 1.0\nsamples = 0",
    ),
    case(
        &[
            "simulate",
            "--model",
            "reduced",
            "--t-end",
            "1",
            "--samples",
            "2000000",
        ],
        "top",
        "model = \"reduced\"",
        "t_end = 1.0\nsamples = 2000000",
    ),
    case(
        &["simulate", "--model", "reduced", "--times", "3,2,1"],
        "top",
        "model = \"reduced\"",
        "times = [3.0, 2.0, 1.0]",
    ),
    case(
        &["simulate", "--model", "reduced", "--times", "-1,2"],
        "top",
        "model = \"reduced\"",
        "times = [-1.0, 2.0]",
    ),
    case(
        &["simulate", "--model", "reduced", "--rtol", "1e-15"],
        "top",
        "model = \"reduced\"",
        "rtol = 1e-15",
    ),
    case(
        &["simulate", "--model", "reduced", "--rtol", "2"],
        "top",
        "model = \"reduced\"",
        "rtol = 2.0",
    ),
    case(
        &[
            "simulate", "--model", "reduced", "--method", "rk4", "--step", "0",
        ],
        "top",
        "model = \"reduced\"",
        "method = \"rk4\"\nstep = 0.0",
    ),
    case(
        &[
            "simulate", "--model", "reduced", "--method", "rk4", "--rtol", "1e-6",
        ],
        "top",
        "model = \"reduced\"",
        "method = \"rk4\"\nrtol = 1e-6",
    ),
    // orbit: [orbit] and [solve]
    case(
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "0",
            "--times",
            "1",
        ],
        "orbit",
        "potential = \"coulomb\"\ntau0 = 0.0",
        "times = [1.0]",
    ),
    case(
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "inf",
            "--times",
            "1",
        ],
        "orbit",
        "potential = \"coulomb\"\ntau0 = inf",
        "times = [1.0]",
    ),
    case(
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "0.001",
            "--r0",
            "-1",
            "--times",
            "1",
        ],
        "orbit",
        "potential = \"coulomb\"\ntau0 = 0.001\nr0 = -1.0",
        "times = [1.0]",
    ),
    case(
        &[
            "orbit",
            "--potential",
            "harmonic",
            "--tau0",
            "0.001",
            "--eccentricity",
            "1",
            "--times",
            "1",
        ],
        "orbit",
        "potential = \"harmonic\"\ntau0 = 0.001\neccentricity = 1.0",
        "times = [1.0]",
    ),
    case(
        &[
            "orbit",
            "--potential",
            "harmonic",
            "--tau0",
            "0.001",
            "--rtol",
            "0.01",
            "--times",
            "1",
        ],
        "orbit",
        "potential = \"harmonic\"\ntau0 = 0.001",
        "rtol = 0.01\ntimes = [1.0]",
    ),
    case(
        &[
            "orbit",
            "--potential",
            "harmonic",
            "--tau0",
            "0.001",
            "--times",
            "2,1",
        ],
        "orbit",
        "potential = \"harmonic\"\ntau0 = 0.001",
        "times = [2.0, 1.0]",
    ),
    // shell: [shell] and [solve]
    case(
        &["shell", "--tau0", "0", "--delay", "0.03", "--times", "1"],
        "shell",
        "tau0 = 0.0\ndelay = 0.03",
        "times = [1.0]",
    ),
    case(
        &["shell", "--tau0", "0.001", "--delay", "-1", "--times", "1"],
        "shell",
        "tau0 = 0.001\ndelay = -1.0",
        "times = [1.0]",
    ),
    case(
        &[
            "shell", "--tau0", "0.001", "--delay", "0.001", "--times", "1",
        ],
        "shell",
        "tau0 = 0.001\ndelay = 0.001",
        "times = [1.0]",
    ),
    case(
        &[
            "shell", "--tau0", "0.001", "--delay", "0.03", "--times", "-1",
        ],
        "shell",
        "tau0 = 0.001\ndelay = 0.03",
        "times = [-1.0]",
    ),
    // balance: [balance] and [solve]
    case(
        &[
            "balance",
            "--dipole",
            "precessing",
            "--cone",
            "4",
            "--times",
            "0",
        ],
        "balance",
        "dipole = \"precessing\"\ncone = 4.0",
        "times = [0.0]",
    ),
    case(
        &[
            "balance",
            "--dipole",
            "precessing",
            "--rate",
            "0",
            "--times",
            "0",
        ],
        "balance",
        "dipole = \"precessing\"\nrate = 0.0",
        "times = [0.0]",
    ),
    case(
        &[
            "balance",
            "--dipole",
            "precessing",
            "--b",
            "0.5",
            "--times",
            "0",
        ],
        "balance",
        "dipole = \"precessing\"\nb = 0.5",
        "times = [0.0]",
    ),
    case(
        &[
            "balance", "--dipole", "dumbbell", "--masses", "0,1", "--times", "0",
        ],
        "balance",
        "dipole = \"dumbbell\"\nmasses = [0.0, 1.0]",
        "times = [0.0]",
    ),
    case(
        &[
            "balance", "--dipole", "dumbbell", "--length", "0", "--times", "0",
        ],
        "balance",
        "dipole = \"dumbbell\"\nlength = 0.0",
        "times = [0.0]",
    ),
    case(
        &["balance", "--dipole", "loop", "--times", "0,nan"],
        "balance",
        "dipole = \"loop\"",
        "times = [0.0, nan]",
    ),
    // plot: the keys of a top it shares with simulate
    case(
        &["plot", "--model", "truncated", "--ratio", "3"],
        "top",
        "model = \"truncated\"\nratio = 3.0",
        "",
    ),
    case(
        &["plot", "--model", "truncated", "--ratio", "-0.4"],
        "top",
        "model = \"truncated\"\nratio = -0.4",
        "",
    ),
    case(
        &["plot", "--model", "reduced", "--omega", "0,1e200,0"],
        "top",
        "model = \"reduced\"\nomega = [0.0, 1e200, 0.0]",
        "",
    ),
];

/// The command whose keys a case's flags are.
fn command_of(args: &[&str]) -> Command {
    match args[0] {
        "simulate" | "plot" => Command::Simulate,
        "balance" => Command::Balance,
        "orbit" => Command::Orbit,
        "shell" => Command::Shell,
        other => panic!("no command {other}"),
    }
}

/// A message in words common to both sources: the file and line dropped,
/// each key of the table by its bare name (`[top] ratio = 3` and
/// `--ratio 3` both as `ratio 3`, `dipole = "loop"` and `--dipole loop` as
/// `dipole loop`), the bare section dropped.
pub(super) fn neutral(message: &str, command: Command) -> String {
    let mut m = message.to_string();
    // `path:line: ` before a scene's message.
    if let Some(i) = m.find(".toml:")
        && let Some(j) = m[i + 6..].find(": ")
    {
        m = m[i + 6 + j + 2..].to_string();
    }
    for s in table::specs().iter().filter(|s| s.command == command) {
        m = m
            .replace(&format!("[{}] {}", s.section, s.key), s.key)
            .replace(&format!("{} = ", s.key), &format!("{} ", s.key))
            .replace(&s.flag(), s.key);
    }
    for section in ["top", "solve", "balance", "orbit", "shell"] {
        m = m.replace(&format!("[{section}] "), "");
    }
    // Who gives both of two keys: the section in a file, the command line.
    m.replace("the command line ", "").replace('"', "")
}

#[test]
fn a_flag_and_its_scene_key_give_the_same_message_for_the_same_bad_value() {
    let dir = std::env::temp_dir().join(format!("spintop-entry-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut differ = Vec::new();
    for (n, c) in CASES.iter().enumerate() {
        let (flag_code, _, flag_err) = run(c.args);
        let path = scene(&dir, n, c.kind, c.own, c.solve);
        let (key_code, _, key_err) = run(&["run", &path]);
        assert_eq!(flag_code, 2, "{:?}: {flag_err}", c.args);
        assert_eq!(key_code, 2, "{path} ({:?}): {key_err}", c.args);
        let flag = flag_err
            .trim()
            .trim_start_matches("spintop: error: ")
            .to_string();
        let key = key_err
            .trim()
            .trim_start_matches("spintop: error: ")
            .to_string();
        // The scene's message is located at its line.
        assert!(
            key.starts_with(&format!("{path}:")),
            "{:?}: the scene's message has no line: {key}",
            c.args
        );
        let command = command_of(c.args);
        if neutral(&key, command) != neutral(&flag, command) {
            differ.push(format!("{:?}\n  flag: {flag}\n  key:  {key}", c.args));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(differ.is_empty(), "{}", differ.join("\n"));
}

/// The help text of `spintop <command> --help`, its lines joined.
fn help(command: &str) -> String {
    let (code, out, err) = run(&[command, "--help"]);
    assert_eq!(code, 0, "{err}");
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[test]
fn help_states_each_flags_range_and_default_from_the_table() {
    let flags_of = |command: &str| -> Vec<&'static Spec> {
        let keys = |c: Command| table::specs().iter().filter(move |s| s.command == c);
        match command {
            "simulate" => keys(Command::Simulate)
                .filter(|s| s.key != "frame")
                .collect(),
            "balance" => keys(Command::Balance).collect(),
            "orbit" => keys(Command::Orbit).collect(),
            "shell" => keys(Command::Shell).collect(),
            // plot: its own keys, and the top's it shares.
            _ => keys(Command::Plot)
                .chain(keys(Command::Simulate).filter(|s| ["ratio", "omega"].contains(&s.key)))
                .collect(),
        }
    };
    for command in ["simulate", "balance", "orbit", "shell", "plot"] {
        let text = help(command);
        let specs = flags_of(command);
        assert!(specs.len() >= 3, "{command}");
        for spec in specs {
            let line = spec.help_line();
            let line = line.split_whitespace().collect::<Vec<_>>().join(" ");
            assert!(
                text.contains(&line),
                "spintop {command} --help lacks {}'s line {line:?}:\n{text}",
                spec.flag()
            );
            let range = spec.range.short();
            assert!(text.contains(&range), "{command} {}: {range}", spec.flag());
        }
    }
    // simulate sums the ranges up with the flags in them: 0 < --ratio <= 2, …
    let text = help("simulate");
    for phrase in table::ranges_help(Command::Simulate).split("; ") {
        assert!(text.contains(phrase), "simulate --help lacks {phrase:?}");
    }
    assert!(text.contains("0 < --ratio <= 2") && text.contains("1e-14 <= --rtol < 1"));
    assert!(text.contains("each --omega component at most 1e100"));
}

/// `spintop learn --help` says where the reading place is kept: the path the
/// one function that decides it gives, below the repository.
#[test]
fn learn_help_says_where_the_reading_place_is_kept() {
    let home = Path::new("/the/copy");
    let book = spintop_course::Book {
        src: home.join("book").join("src"),
        home: home.to_path_buf(),
        instead_of: None,
    };
    let kept = spintop_app::cli::learn::progress_file(&book);
    let below = kept
        .strip_prefix(home)
        .expect("kept below the book's folder unless SPINTOP_LEARN_PROGRESS is set");
    let text = help("learn");
    assert!(
        text.contains(&below.display().to_string()),
        "learn --help names {}:\n{text}",
        below.display()
    );
    assert!(text.contains("reading place"), "{text}");
}
