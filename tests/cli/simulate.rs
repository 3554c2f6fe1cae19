//! `spintop simulate` as a user meets it: the JSON contract, the choice of
//! method, and bad input refused with one line and exit code 2 (never a panic,
//! exit code 101), numerical failures with exit code 3 and the time.

use crate::support;
use support::spintop;

use serde_json::Value;
use spintop::math::Vec3;
use std::process::Command;

fn json(args: &[&str]) -> Value {
    support::json("simulate", args)
}

fn vec_of(v: &Value, n: usize) -> Vec<f64> {
    let a = v.as_array().expect("an array");
    assert_eq!(a.len(), n);
    a.iter().map(|x| x.as_f64().expect("a number")).collect()
}

/// The first `samples` samples of two runs agree: every component of Ω
/// within `omega`, and, when `rotation` is given, every entry of the
/// rotation matrix within it.
fn assert_samples_agree(a: &Value, b: &Value, samples: usize, omega: f64, rotation: Option<f64>) {
    for k in 0..samples {
        let x = vec_of(&a["samples"][k]["omega"], 3);
        let y = vec_of(&b["samples"][k]["omega"], 3);
        for i in 0..3 {
            assert!((x[i] - y[i]).abs() < omega, "t #{k}: {x:?} vs {y:?}");
        }
        let Some(tolerance) = rotation else {
            continue;
        };
        for row in 0..3 {
            let x = vec_of(&a["samples"][k]["rotation"][row], 3);
            let y = vec_of(&b["samples"][k]["rotation"][row], 3);
            for i in 0..3 {
                assert!((x[i] - y[i]).abs() < tolerance, "t #{k}: {x:?} vs {y:?}");
            }
        }
    }
}

#[test]
fn simulate_json_follows_the_contract_for_every_model() {
    let cases: [(&[&str], &str, &str); 6] = [
        (&["--model", "truncated"], "truncated", "exact"),
        (&["--model", "reduced"], "reduced", "exact+dop853"),
        (
            &[
                "--model",
                "general",
                "--inertia",
                "1,1.5,0.8",
                "--dipole",
                "0.2,0,1",
            ],
            "general",
            // auto at the default rtol 1e-10: below the measured crossover.
            "taylor",
        ),
        (
            &["--model", "truncated", "--method", "rk4", "--step", "0.05"],
            "truncated",
            "rk4",
        ),
        (
            &["--model", "reduced", "--method", "dopri5", "--rtol", "1e-8"],
            "reduced",
            "dopri5",
        ),
        (&["--model", "full"], "full", "physical"),
    ];
    for (args, model, method) in cases {
        let mut a = args.to_vec();
        a.extend_from_slice(&["--times", "0,0.5,10,250"]);
        let v = json(&a);
        assert_eq!(v["model"], model);
        assert_eq!(v["method"], method, "{args:?}");
        for key in ["rhs_evals", "steps", "rejected"] {
            assert!(v["stats"][key].is_u64(), "stats.{key}");
        }
        let samples = v["samples"].as_array().unwrap();
        assert_eq!(samples.len(), 4);
        for (s, t) in samples.iter().zip([0.0, 0.5, 10.0, 250.0]) {
            assert_eq!(s["t"].as_f64(), Some(t));
            let omega = vec_of(&s["omega"], 3);
            let rows = s["rotation"].as_array().unwrap();
            assert_eq!(rows.len(), 3);
            let o: Vec<Vec<f64>> = rows.iter().map(|r| vec_of(r, 3)).collect();
            let euler = vec_of(&s["euler"], 3);
            let l_lab = vec_of(&s["l_lab"], 3);
            let energy = s["energy"].as_f64().unwrap();
            let omega_perp = s["omega_perp"].as_f64().unwrap();
            // The fields agree with one another: Ω⊥ from Ω, and O IΩ = L_lab.
            assert!((omega_perp - omega[0].hypot(omega[1])).abs() < 1e-15);
            let inertia = vec_of(&v["parameters"]["inertia"], 3);
            let l_body: Vec<f64> = (0..3).map(|i| inertia[i] * omega[i]).collect();
            for i in 0..3 {
                let l = (0..3).map(|j| o[i][j] * l_body[j]).sum::<f64>();
                assert!((l - l_lab[i]).abs() < 1e-14, "row {i}");
            }
            let e: f64 = 0.5
                * (0..3)
                    .map(|i| inertia[i] * omega[i] * omega[i])
                    .sum::<f64>();
            assert!((e - energy).abs() < 1e-15);
            assert!(euler.iter().all(|x| x.is_finite()));
        }
        if method == "exact" {
            assert_eq!(v["stats"]["rhs_evals"], 0);
        } else {
            assert!(v["stats"]["rhs_evals"].as_u64().unwrap() > 0);
        }
    }
}

/// Two independent paths through the binary agree: RK4 with a small step
/// against the closed form.
/// `--model reduced --inertia --dipole` (the reduced ALE of any top, (3.4)
/// reduced) on a symmetric top with its dipole on the axis is the symmetric
/// reduced model (4.12)-(4.14), whose Ω(t) is the closed form (4.15)-(4.16).
#[test]
fn eq_3_4_reduced_general_top_through_the_cli_is_the_closed_form_for_a_symmetric_top() {
    let exact = json(&["--model", "reduced", "--times", "50,100,400"]);
    let general = json(&[
        "--model",
        "reduced",
        "--inertia",
        "1,1,0.4",
        "--dipole",
        "0,0,1",
        "--rtol",
        "1e-11",
        "--times",
        "50,100,400",
    ]);
    assert_eq!(general["model"], "general-reduced");
    assert_samples_agree(&exact, &general, 3, 1e-9, None);
    // An asymmetric top keeps more spin than under (3.3): the Schott term
    // protects the axial part, so the two models part.
    let args = [
        "--inertia",
        "1,1.5,2",
        "--dipole",
        "0.3,0.2,1",
        "--omega",
        "0.05,0.1,0.2",
        "--times",
        "200",
    ];
    let reduced = json(&[&["--model", "reduced"][..], &args[..]].concat());
    let truncated = json(&[&["--model", "general"][..], &args[..]].concat());
    let r = vec_of(&reduced["samples"][0]["omega"], 3);
    let t = vec_of(&truncated["samples"][0]["omega"], 3);
    assert!(r[2].abs() > t[2].abs(), "{r:?} vs {t:?}");
}

#[test]
fn simulate_rk4_agrees_with_the_closed_form_through_the_cli() {
    let exact = json(&["--model", "truncated", "--times", "50,100"]);
    let rk4 = json(&[
        "--model",
        "truncated",
        "--method",
        "rk4",
        "--step",
        "0.01",
        "--times",
        "50,100",
    ]);
    assert_samples_agree(&exact, &rk4, 2, 1e-9, None);
}

/// `--method radau5` (Radau IIA 5, implicit) on the reduced model agrees with
/// the closed form (4.15)-(4.16) for Omega, and with the closed form's
/// orientation integrated by DOP853, through the CLI.
#[test]
fn eq_4_15_radau5_through_the_cli_agrees_with_the_closed_form() {
    let exact = json(&["--model", "reduced", "--times", "10,50,100"]);
    let radau = json(&[
        "--model",
        "reduced",
        "--method",
        "radau5",
        "--rtol",
        "1e-10",
        "--times",
        "10,50,100",
    ]);
    assert_eq!(radau["method"], "radau5");
    // RADAU5's tolerance map: its error is a few hundred times rtol.
    assert_samples_agree(&exact, &radau, 3, 1e-7, Some(1e-6));
}

/// `--method taylor` on the reduced model agrees with the closed form
/// (4.15)-(4.16) for Omega and with the closed form's orientation (integrated
/// by DOP853 at 1e-12), through the CLI; `auto` on the general top picks the
/// Taylor method at a tight rtol and says so.
#[test]
fn eq_4_15_taylor_through_the_cli_agrees_with_the_closed_form() {
    let times = ["--times", "10,50,100"];
    let exact = json(&["--model", "reduced", "--rtol", "1e-12", times[0], times[1]]);
    let taylor = json(&[
        "--model", "reduced", "--method", "taylor", "--rtol", "1e-12", times[0], times[1],
    ]);
    assert_eq!(taylor["method"], "taylor");
    assert_samples_agree(&exact, &taylor, 3, 1e-13, Some(1e-10));
    let general = |rtol: &str| {
        json(&[
            "--model",
            "general",
            "--inertia",
            "1,1.5,0.8",
            "--dipole",
            "0.2,0,1",
            "--rtol",
            rtol,
            "--times",
            "10",
        ])["method"]
            .clone()
    };
    assert_eq!(general("1e-12"), "taylor");
    assert_eq!(general("1e-6"), "dop853");
}

/// `--model full --inertia --dipole`: the physical solution of (3.4) for any
/// top. For a symmetric top with its dipole on the axis it is the symmetric
/// physical solution (a separate shoot); for an asymmetric one `--method
/// forward` runs away and says when, in the kappa = 1 unit of time.
#[test]
fn eq_3_4_full_general_top_through_the_cli() {
    let times = ["--times", "0,10,50,100"];
    let symmetric = json(&[&["--model", "full", "--rtol", "1e-12"][..], &times[..]].concat());
    let general = json(
        &[
            &[
                "--model",
                "full",
                "--inertia",
                "1,1,0.4",
                "--dipole",
                "0,0,1",
                "--rtol",
                "1e-12",
            ][..],
            &times[..],
        ]
        .concat(),
    );
    assert_eq!(general["model"], "general-full");
    assert_eq!(general["method"], "physical");
    for k in 0..4 {
        let a = vec_of(&symmetric["samples"][k]["omega"], 3);
        let b = vec_of(&general["samples"][k]["omega"], 3);
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-9, "t #{k}: {a:?} vs {b:?}");
        }
    }
    let asymmetric = [
        "--model",
        "full",
        "--inertia",
        "1,2,2.5",
        "--dipole",
        "0.3,0.15,0.06",
        "--omega",
        "0.3,-0.2,0.1",
    ];
    let out = spintop(
        &[
            &["simulate"][..],
            &asymmetric[..],
            &["--method", "forward", "--times", "0,1,100"],
        ]
        .concat(),
    );
    assert_eq!(out.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("runaway at t = ") && stderr.contains("per time unit (kappa = 1)"),
        "{stderr}"
    );
    let physical = json(&[&asymmetric[..], &["--times", "0,1,100"]].concat());
    assert_eq!(physical["samples"].as_array().unwrap().len(), 3);
    // Spun so fast that the slow motion decays nearly as fast as the runaway
    // grows (tau_f |Omega0| ~ 8): there is no slow manifold to shoot onto.
    // One line, exit 3, at once (it used to run into the step budget).
    let out = spintop(&[
        "simulate",
        "--model",
        "full",
        "--inertia",
        "1,2,2.5",
        "--dipole",
        "1,0.5,0.2",
        "--omega",
        "5,3,1",
        "--t-end",
        "10",
    ]);
    assert_eq!(out.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("no slow manifold") && stderr.contains("--model reduced"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

#[test]
fn simulate_default_times_and_table_and_csv() {
    let out = spintop(&["simulate", "--model", "reduced"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("method: exact+dop853"));
    let rows = text.lines().filter(|l| !l.starts_with('#')).count();
    assert_eq!(rows, 1 + 11, "a header and 11 samples from 0 to 100");

    let out = spintop(&[
        "simulate",
        "--model",
        "truncated",
        "--t-end",
        "10",
        "--samples",
        "3",
        "--format",
        "csv",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4);
    assert!(lines[0].starts_with("t,omega1,omega2,omega3"));
    assert_eq!(lines[2].split(',').next(), Some("5"));
    assert_eq!(lines[0].split(',').count(), lines[3].split(',').count());
}

#[test]
fn simulate_refuses_bad_input_with_one_line_and_exit_code_2() {
    let cases: &[&[&str]] = &[
        &["--model", "truncated", "--ratio", "3"],
        &["--model", "reduced", "--ratio", "0"],
        &["--model", "truncated", "--ratio", "-0.5"],
        &["--model", "truncated", "--ratio", "nan"],
        &["--model", "truncated", "--omega", "nan,0,0"],
        &["--model", "truncated", "--omega", "inf,0,0"],
        &["--model", "truncated", "--omega", "1,2"],
        &["--model", "truncated", "--omega", "1e200,0,0"],
        &["--model", "truncated", "--omega", "a,b,c"],
        &["--model", "truncated", "--euler", "0,1e999,0"],
        &["--model", "spinning"],
        &["--ratio", "0.4"],
        &["--model", "general"],
        &[
            "--model",
            "general",
            "--inertia",
            "1,1,3",
            "--dipole",
            "0,0,1",
        ],
        &[
            "--model",
            "general",
            "--inertia",
            "1,-1,1",
            "--dipole",
            "0,0,1",
        ],
        &[
            "--model",
            "general",
            "--inertia",
            "1,1,1",
            "--dipole",
            "0,0,0",
        ],
        &[
            "--model",
            "general",
            "--inertia",
            "1,1,1",
            "--dipole",
            "0,0,1",
            "--method",
            "exact",
        ],
        &[
            "--model",
            "general",
            "--inertia",
            "1,1,1",
            "--dipole",
            "0,0,1",
            "--ratio",
            "0.4",
        ],
        &["--model", "truncated", "--inertia", "1,1,1"],
        &["--model", "truncated", "--times", "3,1"],
        &["--model", "truncated", "--times", "-1,2"],
        &["--model", "truncated", "--times", ""],
        &["--model", "truncated", "--t-end", "-5"],
        &["--model", "truncated", "--samples", "0"],
        &["--model", "truncated", "--method", "dop853", "--rtol", "0"],
        &["--model", "truncated", "--method", "dop853", "--rtol", "2"],
        &[
            "--model",
            "truncated",
            "--method",
            "dop853",
            "--rtol",
            "1e-20",
        ],
        &["--model", "truncated", "--method", "rk4", "--step", "0"],
        &["--model", "truncated", "--method", "rk4", "--step", "-1"],
        &[
            "--model",
            "truncated",
            "--method",
            "dop853",
            "--step",
            "0.1",
        ],
        &["--model", "truncated", "--method", "rk4", "--rtol", "1e-6"],
        &["--model", "truncated", "--format", "xml"],
        &["--model", "truncated", "--method", "forward"],
        &["--model", "full", "--method", "rk4"],
        &["--model", "truncated", "--bogus"],
    ];
    for args in cases {
        let mut all = vec!["simulate"];
        all.extend_from_slice(args);
        let out = spintop(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(
            stderr.lines().count(),
            1,
            "{args:?}: one line, got:\n{stderr}"
        );
        assert!(stderr.starts_with("spintop: error: "), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}: nothing on stdout");
    }
}

#[test]
fn simulate_ratio_3_says_why() {
    let out = spintop(&["simulate", "--model", "truncated", "--ratio", "3"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("I3 <= I1 + I2"), "{stderr}");
}

/// A step far beyond RK4's stability limit (τΩ²h ≫ 1) blows up: reported with
/// the time and what to try, exit code 3, and no NaN table.
/// The physical solution of (3.4) at fast spin, τk = 4 and τk = 10
/// (I₃/I₁ = 2/5, Ω₃ = 10 and 25), where the shoot used to find no bracket
/// and exit 3: late in the run |z| falls at linear theory's rate
/// 1/σ_phys = (α − 1)/(2τ), α = √((1 + √(1 + 16τ²k²))/2) (the slow root of
/// τf² − (1 − 2iτΩ₃)f − (iΩ̃₃ + τΩ₃²) = 0).
#[test]
fn eq_3_4_physical_solution_at_fast_spin_decays_at_linear_theorys_rate() {
    for (omega3, tau_k) in [(10.0, 4.0_f64), (25.0, 10.0)] {
        let omega = format!("0,0.1,{omega3}");
        let v = json(&["--model", "full", "--omega", &omega, "--times", "0,2,6,10"]);
        assert_eq!(v["method"], "physical");
        let perp = |i: usize| v["samples"][i]["omega_perp"].as_f64().unwrap();
        assert!((perp(0) / 0.1 - 1.0).abs() < 1e-9, "{}", perp(0));
        let slope = -(perp(3) / perp(2)).ln() / 4.0;
        let alpha: f64 = ((1.0 + (1.0 + 16.0 * tau_k * tau_k).sqrt()) / 2.0).sqrt();
        let rate = (alpha - 1.0) / 2.0;
        assert!(
            (slope / rate - 1.0).abs() < 1e-6,
            "tau k = {tau_k}: |z| falls at {slope}, linear theory {rate}"
        );
    }
}

#[test]
fn simulate_reports_a_numerical_failure_with_its_time() {
    let out = spintop(&[
        "simulate",
        "--model",
        "truncated",
        "--method",
        "rk4",
        "--step",
        "5",
        "--omega",
        "0,3,3",
        "--t-end",
        "100",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert!(stderr.contains("non-finite at t = "), "{stderr}");
    // The advice fits RK4 on a model with a closed form: a smaller step, an
    // adaptive method, or the closed form; never an option that is refused.
    assert!(
        stderr.contains("smaller --step") && stderr.contains("--method exact"),
        "{stderr}"
    );
    assert!(!String::from_utf8_lossy(&out.stdout).contains("NaN"));
}

/// `--model full --method forward` integrates (3.4) forward: it runs away, and
/// the output says when, how fast, and what to do instead.
#[test]
fn simulate_full_forward_reports_the_runaway() {
    let out = spintop(&[
        "simulate", "--model", "full", "--method", "forward", "--times", "0,1,2,50", "--format",
        "json",
    ]);
    // The samples before the runaway are written whole; the run failed to
    // give the last one, so it exits 3 with one line saying why.
    assert_eq!(out.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("runaway at t = ") && stderr.contains("1 of 4 samples omitted"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "forward");
    let rate = v["runaway"]["growth_rate"].as_f64().unwrap();
    assert!((rate - 1.025).abs() < 0.05, "{rate}");
    assert!(v["runaway"]["t"].as_f64().unwrap() < 50.0);
    assert_eq!(v["samples"].as_array().unwrap().len(), 3);
    assert_eq!(v["samples_omitted"], 1);
    assert!(
        v["runaway"]["advice"]
            .as_str()
            .unwrap()
            .contains("integrate backward or use the reduced model")
    );
}

#[test]
fn help_lists_the_commands() {
    let out = spintop(&["--help"]);
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for command in ["simulate", "tui", "plot"] {
        assert!(help.contains(command), "{command}: {help}");
    }
}

/// Every example that `spintop simulate --help` prints runs and succeeds.
#[test]
fn every_example_in_simulate_help_runs() {
    let help = String::from_utf8_lossy(&spintop(&["simulate", "--help"]).stdout).into_owned();
    let examples: Vec<&str> = help
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("spintop simulate "))
        .collect();
    assert!(examples.len() >= 3, "{help}");
    for example in examples {
        // The command is what precedes a parenthesised note.
        let command = example.split("  (").next().unwrap_or(example);
        let args: Vec<&str> = command.split_whitespace().skip(1).collect();
        let out = spintop(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        // The forward example is there to show the runaway: exit 3, said so.
        if command.contains("--method forward") {
            assert_eq!(out.status.code(), Some(3), "{example}: {stderr}");
            assert!(stderr.contains("runaway at t = "), "{example}: {stderr}");
        } else {
            assert!(out.status.success(), "{example}: {stderr}");
        }
    }
}

/// The same 3·10⁶-rad run on the command line, where DOP853 is asked for
/// outright: refused before it starts (exit 2, about 1.2e7 steps at 4 per
/// radian), no longer stopped by the step budget after 24 s. `auto` steps it
/// with the Taylor method at the default rtol (1.9 steps per radian), so
/// the same refusal comes at 6·10⁶ rad.
#[test]
fn a_long_asymmetric_run_on_the_command_line_is_refused_before_it_starts() {
    let rate = (Vec3::new(0.1, 0.05, 0.2).dot(&Vec3::new(0.1, 0.075, 0.16)) / 0.8).sqrt();
    for (method, radians) in [("dop853", 3e6), ("auto", 6e6)] {
        let t_end = format!("{:e}", radians / rate);
        let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
            .args([
                "simulate",
                "--model",
                "general",
                "--inertia",
                "1,1.5,0.8",
                "--dipole",
                "2e-7,0,1e-6",
                "--omega",
                "0.1,0.05,0.2",
                "--t-end",
                &t_end,
                "--method",
                method,
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{method}: {err}");
        assert!(
            err.contains("steps per radian") && err.contains("more than the 1e7 allowed"),
            "{method}: {err}"
        );
    }
}

/// τ|Ω| ≳ 1 is outside the slow rotation the paper's radiation laws are
/// expanded for: the answer comes with one note, on stderr and in the JSON,
/// where τk (here τ·(I₃/I₁)Ω₃ = 20) passes 1, and none for the book's top
/// (τ|Ω₀| = 0.22). The fast spin's transverse rate is gone by t = 5 (its
/// linear decay rate, (Re √(1 − 80i) − 1)/2 ≈ 2.7/τ, over 5τ is e^{−13.6}).
#[test]
fn a_fast_spin_is_answered_with_one_note_that_it_leaves_the_slow_rotation_regime() {
    let args = [
        "simulate",
        "--model",
        "full",
        "--ratio",
        "1",
        "--omega",
        "0.1,0,20",
        "--t-end",
        "5",
        "--samples",
        "3",
        "--rtol",
        "1e-8",
        "--format",
        "json",
    ];
    let out = spintop(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    let v: Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    let notes = v["warnings"].as_array().expect("a note in the JSON");
    assert_eq!(notes.len(), 1, "{notes:?}");
    let note = notes[0].as_str().unwrap();
    assert_eq!(stderr.matches(note).count(), 1, "{stderr}");
    let rate = (0.5 * ((1.0 + (1.0 + 16.0 * 400.0f64).sqrt()) / 2.0).sqrt() - 0.5) * 1.0;
    let last = vec_of(&v["samples"][2]["omega"], 3);
    let perp = last[0].hypot(last[1]);
    assert!(
        (perp / (0.1 * (-rate * 5.0).exp()) - 1.0).abs() < 1e-3,
        "{perp:e}"
    );
    assert_eq!(last[2], 20.0);
    let slow = json(&["--model", "full", "--omega", "0,0.1,0.2", "--t-end", "10"]);
    assert!(slow.get("warnings").is_none(), "{slow}");
}
