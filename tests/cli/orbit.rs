//! `spintop orbit` as a user meets it: the JSON contract, the collapse and
//! crossing times, the runaway report, bad input refused with exit code 2 and
//! one line, and a run past the collapse stopped with exit code 3 and the time.

use crate::support;
use support::spintop;

use serde_json::Value;

fn json(args: &[&str]) -> Value {
    support::json("orbit", args)
}

fn check_samples(v: &Value, n: usize) {
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), n);
    for s in samples {
        assert_eq!(s["position"].as_array().unwrap().len(), 2);
        assert_eq!(s["velocity"].as_array().unwrap().len(), 2);
        for key in ["t", "r", "l", "energy"] {
            assert!(s[key].is_f64(), "{key}");
        }
    }
}

#[test]
fn cli_orbit_coulomb_collapse_contract() {
    let v = json(&[
        "--potential",
        "coulomb",
        "--tau0",
        "1e-3",
        "--times",
        "0,100,166.6",
    ]);
    check_samples(&v, 3);
    assert_eq!(v["force"], "ll");
    let s0 = &v["samples"][0];
    assert_eq!(s0["r"].as_f64(), Some(1.0));
    assert_eq!(s0["l"].as_f64(), Some(1.0));
    assert_eq!(s0["energy"].as_f64(), Some(-0.5));
    assert!((v["collapse_time"].as_f64().unwrap() - 1000.0 / 6.0).abs() < 1e-12);
    let crossings = v["first_crossing"].as_array().unwrap();
    let levels: Vec<f64> = crossings.iter().map(|c| c["r"].as_f64().unwrap()).collect();
    assert_eq!(levels, [0.5, 0.2, 0.1]);
    for c in crossings {
        let (t, avg) = (c["t"].as_f64().unwrap(), c["averaged"].as_f64().unwrap());
        assert!((t / avg - 1.0).abs() < 2e-3);
    }
}

#[test]
fn cli_orbit_eccentric_start_is_the_pericentre() {
    let v = json(&[
        "--potential",
        "coulomb",
        "--tau0",
        "1e-4",
        "--r0",
        "0.5",
        "--eccentricity",
        "0.6",
        "--times",
        "0",
    ]);
    // v_p = sqrt((1 + e)/r0) and E = −1/(2a) with a = r0/(1 − e).
    let s = &v["samples"][0];
    assert!((s["velocity"][1].as_f64().unwrap() - (1.6_f64 / 0.5).sqrt()).abs() < 1e-14);
    assert!((s["energy"].as_f64().unwrap() + 0.4 / 1.0).abs() < 1e-14);
    // Elliptic: no circular closed form for the crossings, but the averaged t_c.
    assert!(v["first_crossing"][0]["averaged"].is_null());
    assert!(v["collapse_time"].as_f64().unwrap() > 0.0);
}

#[test]
fn cli_orbit_harmonic_al_is_exact_and_reports_the_roots() {
    let v = json(&[
        "--potential",
        "harmonic",
        "--tau0",
        "0.1",
        "--force",
        "al",
        "--times",
        "0,1,2",
    ]);
    check_samples(&v, 3);
    assert_eq!(v["method"], "exact");
    assert!(v.get("collapse_time").is_none() && v.get("first_crossing").is_none());
    // The roots of τ₀s³ − s² − 1 = 0 (τ₀ = 0.1), checked in place: each is a
    // root, and together they satisfy Vieta's relations (sum 1/τ₀, product
    // 1/τ₀), so no other root is left: the runaway is 10.098067…, the
    // physical pair −0.049034 ± 0.993924i.
    let roots = &v["roots"];
    let tau0 = 0.1;
    let runaway = roots["runaway"].as_f64().unwrap();
    let (re, im) = (
        roots["abraham_lorentz"][0].as_f64().unwrap(),
        roots["abraham_lorentz"][1].as_f64().unwrap(),
    );
    let s = nalgebra::Complex::new(re, im);
    assert!((tau0 * runaway.powi(3) - runaway * runaway - 1.0).abs() < 1e-12);
    assert!((tau0 * s * s * s - s * s - 1.0).norm() < 1e-13);
    assert!((runaway + 2.0 * re - 1.0 / tau0).abs() < 1e-12);
    assert!((runaway * (re * re + im * im) - 1.0 / tau0).abs() < 1e-12);
    assert!((runaway - 10.098067).abs() < 1e-6 && (im - 0.993924).abs() < 1e-6);
}

/// A forward run of (2.5) runs away: every format writes the samples before
/// it and says that it stopped (the JSON's `stopped`, a `# stopped:` line
/// after the table or the CSV rows), and the command exits 3 with one line.
#[test]
fn cli_orbit_forward_abraham_lorentz_reports_the_runaway() {
    let args = [
        "orbit",
        "--potential",
        "harmonic",
        "--tau0",
        "0.01",
        "--force",
        "al-forward",
        "--times",
        "0,0.05,1,2",
    ];
    let run = |format: &str| {
        let mut all = args.to_vec();
        all.extend(["--format", format]);
        let out = spintop(&all);
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(3), "{format}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains("runaway at t = ") && stderr.contains("2 of 4 samples omitted"),
            "{stderr}"
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let v: Value = serde_json::from_str(&run("json")).expect("one JSON object");
    let r = &v["runaway"];
    let t = r["t"].as_f64().unwrap();
    assert!(t > 0.05 && t < 0.2, "{t}");
    let rate = r["growth_rate"].as_f64().unwrap();
    assert!((rate / r["predicted_rate"].as_f64().unwrap() - 1.0).abs() < 5e-3);
    check_samples(&v, 2);
    assert_eq!(v["samples_omitted"].as_u64(), Some(2));
    assert!(
        v["stopped"]
            .as_str()
            .unwrap()
            .contains("2 later sample(s) omitted")
    );
    let csv = run("csv");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4, "{csv}");
    assert!(lines[0].starts_with("t,x,y"));
    assert!(
        lines[3].starts_with("# stopped: runaway at t = ")
            && lines[3].contains("2 later sample(s) omitted"),
        "{csv}"
    );
    let table = run("table");
    assert!(table.contains("RUNAWAY at t = "), "{table}");
    assert!(
        table
            .trim_end()
            .lines()
            .last()
            .unwrap()
            .starts_with("# stopped: runaway")
    );
}

#[test]
fn cli_orbit_bad_input_exits_2_with_one_line() {
    for args in [
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "0",
            "--times",
            "0",
        ][..],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "-1e-3",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "nan",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-3",
            "--r0",
            "0",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-3",
            "--r0",
            "-2",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-3",
            "--eccentricity",
            "1",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "harmonic",
            "--tau0",
            "1e-3",
            "--eccentricity",
            "-0.1",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "yukawa",
            "--tau0",
            "1e-3",
            "--times",
            "0",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-3",
            "--times",
            "2,1",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-3",
            "--times",
            "-1",
        ],
        &[
            "orbit",
            "--potential",
            "coulomb",
            "--tau0",
            "1e-9",
            "--force",
            "al",
            "--times",
            "0,100",
        ],
    ] {
        let out = spintop(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("spintop: error: "), "{err}");
    }
}

#[test]
fn cli_orbit_past_the_collapse_exits_3_with_the_time() {
    let out = spintop(&[
        "orbit",
        "--potential",
        "coulomb",
        "--tau0",
        "1e-3",
        "--times",
        "0,200",
    ]);
    assert_eq!(out.status.code(), Some(3));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1);
    assert!(
        err.contains("at t = 166.") && err.contains("t_c = 166.6666667"),
        "{err}"
    );
    assert!(!err.contains("NaN"));
}

/// Nothing lost: the rows before the collapse are printed, then the stop
/// (`# stopped:` in the table and the CSV, `stopped` in the JSON), and the
/// exit code is still 3, as `simulate` does before a runaway.
#[test]
fn cli_orbit_keeps_the_rows_before_the_collapse() {
    let base = [
        "orbit",
        "--potential",
        "coulomb",
        "--tau0",
        "1e-3",
        "--times",
        "0,50,100,200",
    ];
    for format in ["table", "csv", "json"] {
        let mut args = base.to_vec();
        args.extend(["--format", format]);
        let out = spintop(&args);
        assert_eq!(out.status.code(), Some(3), "{format}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("t_c = 166.6666667"), "{err}");
        let text = String::from_utf8(out.stdout).unwrap();
        if format == "json" {
            let v: Value = serde_json::from_str(&text).unwrap();
            let ts: Vec<f64> = v["samples"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s["t"].as_f64().unwrap())
                .collect();
            assert_eq!(ts, [0.0, 50.0, 100.0], "{text}");
            assert_eq!(v["samples_omitted"].as_u64(), Some(1), "{text}");
            assert!(
                v["stopped"].as_str().unwrap().contains("at t = 166."),
                "{text}"
            );
        } else {
            // Three rows of numbers (t = 0, 50, 100), then the stop.
            let rows = text
                .lines()
                .filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()))
                .count();
            assert_eq!(rows, 3, "{text}");
            let last = text.lines().last().unwrap();
            assert!(
                last.starts_with("# stopped: ") && last.contains("at t = 166."),
                "{text}"
            );
        }
    }
}
