//! `spintop shell` as a user meets it: the JSON contract, a stable run that
//! follows the Abraham–Lorentz motion, an unstable run announced on stderr
//! before any output, bad input refused with exit code 2 and one line, and an
//! overflowing runaway stopped with exit code 3.

use serde_json::Value;
use std::process::{Command, Output};

fn spintop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn json(args: &[&str]) -> (Value, String) {
    let mut all = vec!["shell"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--format", "json"]);
    let out = spintop(&all);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{stderr}");
    (
        serde_json::from_slice(&out.stdout).expect("one JSON object"),
        stderr,
    )
}

fn pair(v: &Value) -> [f64; 2] {
    let a = v.as_array().expect("an array [re, im]");
    assert_eq!(a.len(), 2);
    [a[0].as_f64().unwrap(), a[1].as_f64().unwrap()]
}

#[test]
fn cli_shell_json_contract_stable_run() {
    let (v, stderr) = json(&["--tau0", "1e-3", "--delay", "0.03", "--times", "0,5,20"]);
    assert!(
        stderr.is_empty(),
        "a stable run prints no warning: {stderr}"
    );
    let (m0, m_em) = (v["m0"].as_f64().unwrap(), v["m_em"].as_f64().unwrap());
    assert!((m_em - 1.0 / 30.0).abs() < 1e-15 && (m0 + m_em - 1.0).abs() < 1e-15);
    assert_eq!(v["stable"], Value::Bool(true));
    assert!(
        v.get("growth_rate").is_none(),
        "growth_rate only when unstable"
    );
    let root = pair(&v["root_near_al"]);
    assert!(
        (root[0] + 5e-4).abs() < 1e-6 && (root[1] - 1.0).abs() < 1e-5,
        "{root:?}"
    );
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 3);
    for s in samples {
        for key in ["t", "l", "j", "l_minus_j"] {
            assert!(s[key].is_f64(), "{key}");
        }
        for key in ["z", "z_dot", "z_minus_z_al"] {
            pair(&s[key]);
        }
    }
    let s0 = &samples[0];
    assert_eq!(pair(&s0["z"]), [1.0, 0.0]);
    assert_eq!(pair(&s0["z_minus_z_al"]), [0.0, 0.0]);
    // At t = 20 the phase has slipped by about tau0 * delay * t / 4 = 1.5e-4.
    let d = pair(&samples[2]["z_minus_z_al"]);
    let slip = d[0].hypot(d[1]);
    assert!((slip / 1.5e-4 - 1.0).abs() < 0.05, "{slip}");
    // L - J is the Schott term -tau0^2 L, and J - J(0) equals the exact flux.
    let s2 = &samples[2];
    let (l, lmj) = (s2["l"].as_f64().unwrap(), s2["l_minus_j"].as_f64().unwrap());
    assert!((lmj / (-1e-6 * l) - 1.0).abs() < 0.01, "{lmj}");
    let res = s2["j_change"].as_f64().unwrap() - s2["flux_exact"].as_f64().unwrap();
    assert!(res.abs() < 1e-10);
}

#[test]
fn cli_shell_unstable_run_warns_on_stderr_before_any_output() {
    let (v, stderr) = json(&["--tau0", "0.06", "--delay", "0.1", "--times", "0,1,2"]);
    assert_eq!(v["stable"], Value::Bool(false));
    assert_eq!(v["regime"], "growing-oscillation");
    let rate = v["growth_rate"].as_f64().unwrap();
    assert!((rate - 4.0788).abs() < 1e-3, "{rate}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("warning") && stderr.contains("4.07875"),
        "{stderr}"
    );

    // "Before": with stdout closed, the warning has already been written.
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args([
            "shell", "--tau0", "1e-3", "--delay", "5e-4", "--times", "0,0.01",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(child.wait().unwrap().success());
    assert!(
        err.starts_with("spintop: warning:") && err.contains("runaway"),
        "{err}"
    );
}

#[test]
fn cli_shell_warning_precedes_stdout_in_a_merged_stream() {
    // One pipe for both streams: the order written is the order seen.
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "{} shell --tau0 0.06 --delay 0.1 --times 0,1 2>&1",
            env!("CARGO_BIN_EXE_spintop")
        ))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("spintop: warning:"), "{text}");
    assert!(text.lines().nth(1).unwrap().starts_with("# spintop shell"));
}

#[test]
fn cli_shell_runaway_overflow_exits_3_with_one_line() {
    let out = spintop(&[
        "shell", "--tau0", "1e-3", "--delay", "5e-4", "--times", "0,1",
    ]);
    assert_eq!(out.status.code(), Some(3));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    // The error line says the model is unstable and how fast it grows: the
    // warning a run that succeeds gets first is not said twice.
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].contains("finite range")
            && lines[0].contains("unstable")
            && lines[0].contains("1386"),
        "{err}"
    );
}

#[test]
fn cli_shell_bad_input_exits_2_with_one_line() {
    for args in [
        &["--tau0", "1e-3", "--delay", "0", "--times", "1"][..],
        &["--tau0", "1e-3", "--delay", "-0.1", "--times", "1"],
        &["--tau0", "0", "--delay", "0.1", "--times", "1"],
        &["--tau0", "-1e-3", "--delay", "0.1", "--times", "1"],
        &["--tau0", "inf", "--delay", "0.1", "--times", "1"],
        &["--tau0", "1e-3", "--delay", "nan", "--times", "1"],
        &["--tau0", "1e-3", "--delay", "1e-3", "--times", "1"],
        &["--tau0", "1e-3", "--delay", "0.1", "--times", "2,1"],
        &["--tau0", "1e-3", "--delay", "0.1", "--times", "-1"],
        &["--tau0", "1e-3", "--delay", "0.1", "--times", "x"],
        &["--tau0", "1e-3", "--delay", "1e-5", "--times", "1000"],
        &["--tau0", "1e-3", "--delay", "0.1"],
    ] {
        let mut all = vec!["shell"];
        all.extend_from_slice(args);
        let out = spintop(&all);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("spintop: error:"), "{err}");
    }
}

#[test]
fn cli_shell_table_and_csv() {
    let out = spintop(&[
        "shell", "--tau0", "1e-3", "--delay", "0.1", "--times", "0,1", "--format", "csv",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3);
    assert!(lines[0].starts_with("t,x,y,vx,vy,l,j,l_minus_j"));
    assert_eq!(lines[1].split(',').count(), lines[0].split(',').count());
    let out = spintop(&[
        "shell", "--tau0", "1e-3", "--delay", "0.1", "--times", "0,1",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("regime: stable"), "{text}");
    assert!(text.contains("exact flux integral"), "{text}");
}
