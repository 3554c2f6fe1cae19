//! `spintop balance` as a user meets it: the JSON contract, values that match
//! the closed forms of §2, and bad input refused with one line and exit code 2.

use crate::support;
use support::spintop;

use serde_json::Value;

fn json(args: &[&str]) -> Value {
    support::json("balance", args)
}

fn vec3(v: &Value) -> [f64; 3] {
    let a = v.as_array().expect("an array");
    assert_eq!(a.len(), 3);
    [
        a[0].as_f64().unwrap(),
        a[1].as_f64().unwrap(),
        a[2].as_f64().unwrap(),
    ]
}

#[test]
fn cli_balance_json_contract_for_the_precessing_dipole() {
    let (theta, omega) = (0.5_f64, 1.2_f64);
    let v = json(&[
        "--dipole",
        "precessing",
        "--cone",
        "0.5",
        "--rate",
        "1.2",
        "--times",
        "0,0.7",
    ]);
    assert_eq!(v["dipole"], "precessing");
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 2);
    for s in samples {
        for key in ["larmor", "torque", "schott", "schott_rate"] {
            vec3(&s[key]);
        }
        for key in ["t", "larmor_axial", "torque_axial", "schott_rate_axial"] {
            assert!(s[key].is_f64(), "{key}");
        }
    }
    let w3s2 = omega.powi(3) * theta.sin().powi(2);
    // (2.1) is the constant −ω³sin²θ ẑ.
    assert!((vec3(&samples[1]["larmor"])[2] + w3s2).abs() < 1e-14);
    let avg = &v["period_average"];
    for key in ["larmor", "torque", "schott", "schott_rate"] {
        vec3(&avg[key]);
    }
    assert!((avg["schott_rate_axial"].as_f64().unwrap() - w3s2 * theta.cos()).abs() < 1e-14);
    assert!(vec3(&avg["schott_rate"]).iter().all(|x| x.abs() < 1e-14));
    assert!((v["period"].as_f64().unwrap() - std::f64::consts::TAU / omega).abs() < 1e-14);
}

#[test]
fn cli_balance_loop_and_dumbbell_match_their_closed_forms() {
    let v = json(&[
        "--dipole", "loop", "--b", "0.5", "--eps", "0.2", "--times", "0",
    ]);
    let s = &v["samples"][0];
    // At t = 0: (2.1) = −b − 2ε, (2.2) = −b − 8ε, dL_S/dt = −6ε.
    assert!((vec3(&s["larmor"])[2] + 0.9).abs() < 1e-15);
    assert!((vec3(&s["torque"])[2] + 2.1).abs() < 1e-15);
    assert!((vec3(&s["schott_rate"])[2] + 1.2).abs() < 1e-15);
    assert!((vec3(&v["period_average"]["torque"])[2] + 0.5).abs() < 1e-15);
    let v = json(&[
        "--dipole",
        "dumbbell",
        "--charges",
        "1,-1",
        "--masses",
        "1,1",
        "--length",
        "2",
        "--rate",
        "1",
        "--times",
        "0.3",
    ]);
    // |d| = 2, so both laws give −|d|²ω³ ẑ = −4 ẑ and L_S = 0.
    assert!((vec3(&v["samples"][0]["larmor"])[2] + 4.0).abs() < 1e-14);
    assert!(
        vec3(&v["samples"][0]["schott"])
            .iter()
            .all(|x| x.abs() < 1e-15)
    );
}

#[test]
fn cli_balance_table_and_csv_are_readable() {
    let out = spintop(&["balance", "--dipole", "loop", "--times", "0,1"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("average over one period"));
    assert!(!text.contains("NaN") && !text.contains("-0.0000000 "));
    let out = spintop(&[
        "balance", "--dipole", "loop", "--times", "0,1", "--format", "csv",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4);
    assert!(lines[0].starts_with("t,dipole_x"));
    assert!(lines[3].starts_with("average,"));
    assert_eq!(lines[0].split(',').count(), lines[1].split(',').count());
}

#[test]
fn cli_balance_bad_input_exits_2_with_one_line() {
    for args in [
        &["balance", "--dipole", "spiral", "--times", "0"][..],
        &[
            "balance",
            "--dipole",
            "precessing",
            "--cone",
            "4",
            "--times",
            "0",
        ],
        &[
            "balance",
            "--dipole",
            "precessing",
            "--rate",
            "0",
            "--times",
            "0",
        ],
        &[
            "balance",
            "--dipole",
            "precessing",
            "--rate",
            "nan",
            "--times",
            "0",
        ],
        &["balance", "--dipole", "loop", "--cone", "1", "--times", "0"],
        &[
            "balance", "--dipole", "dumbbell", "--masses", "1,-1", "--times", "0",
        ],
        &[
            "balance",
            "--dipole",
            "dumbbell",
            "--charges",
            "1",
            "--times",
            "0",
        ],
        &["balance", "--dipole", "loop", "--times", "0,inf"],
        &["balance", "--dipole", "loop"],
    ] {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("spintop: error: "), "{err}");
        assert!(out.stdout.is_empty());
    }
}
