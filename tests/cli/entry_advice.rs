//! Advice and refusals that name a setting name it as the entry point the
//! user came through spells it: a flag on the command line (`--rtol`,
//! `--method exact`), a key in a scene file (`[solve] rtol`, `method =
//! "exact"`), and the setting the user actually gave (`--t-end`, not
//! `--times`, when the times came from `--t-end`). Each case is asked both
//! ways; the two messages must be the same apart from the names (see
//! [`super::entry`]'s `neutral`), the flag's must name no section, the
//! scene's no flag, and each names the setting to change as its entry point
//! spells it.

use super::entry::{neutral, run, scene};
use spintop::scene::table::Command;

/// Ask `args` and a scene of `kind` (`own`, `solve`); both must exit 2 and
/// agree; returns (flag's message, scene's message).
fn both(n: usize, args: &[&str], kind: &str, own: &str, solve: &str) -> (String, String) {
    let dir = std::env::temp_dir().join(format!("spintop-advice-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = scene(&dir, n, kind, own, solve);
    let (fc, _, flag) = run(args);
    let (kc, _, key) = run(&["run", &path]);
    let strip = |e: &str| e.trim().trim_start_matches("spintop: error: ").to_string();
    let (flag, key) = (strip(&flag), strip(&key));
    assert_eq!((fc, kc), (2, 2), "{args:?}: {flag}\n{path}: {key}");
    assert!(key.starts_with(&format!("{path}:")), "{key}");
    assert!(!flag.contains('['), "a section on the command line: {flag}");
    let body = key.splitn(3, ": ").nth(2).unwrap_or(&key);
    assert!(!body.contains("--"), "a flag in a scene: {key}");
    std::fs::remove_file(&path).ok();
    (flag, key)
}

/// `--step` given to an adaptive method, `--rtol` to RK4: the refusal
/// names the setting to use as a flag (`the adaptive methods take --rtol`).
#[test]
fn an_option_for_the_wrong_method_names_the_flag_to_use() {
    let (flag, key) = both(
        0,
        &[
            "simulate",
            "--model",
            "truncated",
            "--t-end",
            "1",
            "--method",
            "dop853",
            "--step",
            "0.1",
        ],
        "top",
        "model = \"truncated\"",
        "t_end = 1.0\nmethod = \"dop853\"\nstep = 0.1",
    );
    assert!(flag.ends_with("take --rtol"), "{flag}");
    assert_eq!(
        neutral(&flag, Command::Simulate),
        neutral(&key, Command::Simulate)
    );
    let (flag, key) = both(
        1,
        &[
            "simulate",
            "--model",
            "truncated",
            "--t-end",
            "1",
            "--method",
            "rk4",
            "--rtol",
            "0.1",
        ],
        "top",
        "model = \"truncated\"",
        "t_end = 1.0\nmethod = \"rk4\"\nrtol = 0.1",
    );
    assert!(flag.contains("--method rk4 takes --step"), "{flag}");
    assert_eq!(
        neutral(&flag, Command::Simulate),
        neutral(&key, Command::Simulate)
    );
}

/// A run over the step budget is refused in one wording by both entry
/// points (`… would take about N steps to reach t = T, more than the 1e7
/// allowed; …`), the cheaper way naming the method as each spells it: a
/// symmetric top by DOP853 over 1e12 (about 4 steps per radian, 1.3e7
/// steps), by RK4 at step 1e-3 (1e15 steps), a general top by DOP853 over
/// 1e9 (1.4e9 steps).
#[test]
fn a_run_over_the_step_budget_is_refused_in_one_wording() {
    let general = "model = \"general\"\ninertia = [1.0, 2.0, 2.5]\ndipole = [0.0, 0.0, 1.0]";
    let cases: [(&[&str], &str, &str); 3] = [
        (
            &[
                "simulate",
                "--model",
                "truncated",
                "--t-end",
                "1e12",
                "--method",
                "dop853",
            ],
            "model = \"truncated\"",
            "t_end = 1e12\nmethod = \"dop853\"",
        ),
        (
            &[
                "simulate",
                "--model",
                "truncated",
                "--t-end",
                "1e12",
                "--method",
                "rk4",
                "--step",
                "1e-3",
            ],
            "model = \"truncated\"",
            "t_end = 1e12\nmethod = \"rk4\"\nstep = 1e-3",
        ),
        (
            &[
                "simulate",
                "--model",
                "general",
                "--inertia",
                "1,2,2.5",
                "--dipole",
                "0,0,1",
                "--t-end",
                "1e9",
                "--method",
                "dop853",
            ],
            general,
            "t_end = 1e9\nmethod = \"dop853\"",
        ),
    ];
    for (n, (args, own, solve)) in cases.iter().enumerate() {
        let (flag, key) = both(10 + n, args, "top", own, solve);
        assert!(
            flag.contains("steps to reach t = ") && flag.contains("more than the 1e7 allowed"),
            "{flag}"
        );
        // The scene names the method it was asked for before the same text.
        let method = args[args.len() - if args.contains(&"rk4") { 3 } else { 1 }];
        let key = neutral(&key, Command::Simulate);
        let key = key
            .strip_prefix(&format!("method {method}: "))
            .unwrap_or(&key)
            .to_string();
        assert_eq!(neutral(&flag, Command::Simulate), key, "{args:?}");
    }
    let (flag, _) = both(20, cases[0].0, "top", cases[0].1, cases[0].2);
    assert!(flag.contains("(--method auto or --method exact)"), "{flag}");
}

/// `shell`'s refusal of too much work advises the setting the times came
/// from: `--t-end` when they came from it, `--times` when listed; a scene
/// likewise (`t_end`, `times`).
#[test]
fn shells_work_refusal_advises_the_setting_given() {
    let own = "tau0 = 1e-3\ndelay = 0.03";
    let base = ["shell", "--tau0", "1e-3", "--delay", "0.03"];
    for (n, (flag_args, solve, given)) in [
        (["--t-end", "1e7"], "t_end = 1e7", "t_end"),
        (["--times", "1e7"], "times = [1e7]", "times"),
    ]
    .into_iter()
    .enumerate()
    {
        let args: Vec<&str> = base.iter().copied().chain(flag_args).collect();
        let (flag, key) = both(30 + n, &args, "shell", own, solve);
        let as_flag = spintop::scene::table::flag_of(given);
        assert!(
            flag.contains(&format!(" {as_flag} or a longer --delay")),
            "{flag}"
        );
        assert!(
            key.contains(&format!(" {given} or a longer [shell] delay")),
            "{key}"
        );
        assert_eq!(
            neutral(&flag, Command::Shell),
            neutral(&key, Command::Shell)
        );
    }
}

/// Two keys that exclude each other, both given: the message has a subject
/// (the command line, or the scene's section) on both sides.
#[test]
fn both_times_and_t_end_given_is_said_with_a_subject() {
    let (flag, key) = both(
        40,
        &[
            "simulate",
            "--model",
            "truncated",
            "--times",
            "1",
            "--t-end",
            "2",
        ],
        "top",
        "model = \"truncated\"",
        "times = [1.0]\nt_end = 2.0",
    );
    assert!(
        flag.starts_with("the command line gives both --times and --t-end"),
        "{flag}"
    );
    assert!(
        key.contains(": [solve] gives both times and t_end"),
        "{key}"
    );
    assert_eq!(
        neutral(&flag, Command::Simulate),
        neutral(&key, Command::Simulate)
    );
}

/// A general top over 1e9 (about 3.5e8 rad): `simulate` refuses the run's
/// steps (the Taylor method, about 6.6e8 steps, over the 1e7 allowed), and
/// a scene, which also weighs the error's growth with the turning and the
/// secular model, says the same sentence about the steps first.
#[test]
fn a_general_tops_step_budget_is_worded_alike_by_both_entry_points() {
    let (flag, key) = both(
        50,
        &[
            "simulate",
            "--model",
            "general",
            "--inertia",
            "1,2,2.5",
            "--dipole",
            "0,0,1",
            "--t-end",
            "1e9",
        ],
        "top",
        "model = \"general\"\ninertia = [1.0, 2.0, 2.5]\ndipole = [0.0, 0.0, 1.0]",
        "t_end = 1e9",
    );
    let steps = flag
        .split_once("; ")
        .map_or(flag.as_str(), |(sentence, _)| sentence);
    assert!(
        steps.contains("steps to reach t = 1.0000e9, more than the 1e7 allowed"),
        "{flag}"
    );
    assert!(key.contains(&format!("[solve] {steps}; ")), "{key}\n{flag}");
}
