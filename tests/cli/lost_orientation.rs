//! Past the phase a double resolves (`MAX_PHASE`, 1e9 rad of turning) the
//! full model's orientation is lost: no error of it is claimed (a claim of π
//! is no claim), and a warning says why and what still holds, in
//! `simulate`'s JSON and table and in a scene's answer alike.

use super::entry::{run, scene};
use spintop::sim::cost::{MAX_PHASE, turning_angle};

/// A fast symmetric top of the full model: Ω₃ = 1e7/τ turns it about 2e7
/// rad per τ (the claim's own bound, [`turning_angle`]).
const OMEGA: &str = "0.01,0,1e7";

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}: {out}"))
}

fn lost(v: &serde_json::Value) -> bool {
    v["warnings"].as_array().is_some_and(|w| {
        w.iter().any(|w| {
            let w = w.as_str().unwrap_or("");
            w.contains("orientation (phi, theta, psi) is lost") && w.contains("Omega, E, |L|")
        })
    })
}

fn simulate(t_end: &str, format: &str) -> Vec<String> {
    [
        "simulate",
        "--model",
        "full",
        "--omega",
        OMEGA,
        "--t-end",
        t_end,
        "--samples",
        "2",
        "--format",
        format,
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn past_the_phase_limit_the_full_models_orientation_is_reported_lost() {
    let model = spintop::sim::Model::Full(
        spintop::physics::symmetric_top::SymmetricTop::new(0.4, 1.0).unwrap(),
    );
    let w = spintop::math::Vec3::new(0.01, 0.0, 1e7);
    // Below the limit (about 2e8 rad): the orientation is claimed, under π.
    assert!(turning_angle(&model, &w, 10.0) < MAX_PHASE);
    let args = simulate("10", "json");
    let below = json(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let o = below["error"]["orientation"]
        .as_f64()
        .expect("an orientation claim");
    assert!(o < std::f64::consts::PI, "{o}");
    assert!(!lost(&below), "{}", below["warnings"]);
    // Past it (about 2e10 rad): no claim, the warning, Ω still claimed.
    assert!(turning_angle(&model, &w, 1000.0) > MAX_PHASE);
    let args = simulate("1000", "json");
    let past = json(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        past["error"].get("orientation").is_none(),
        "{}",
        past["error"]
    );
    assert!(past["error"]["omega"].as_f64().unwrap() < 1e-6);
    assert!(lost(&past), "{}", past["warnings"]);
    // The table: no orientation in the error line, the warning on stderr.
    let args = simulate("1000", "table");
    let (code, out, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "{err}");
    let line = out.lines().find(|l| l.starts_with("# error:")).expect(&out);
    assert!(!line.contains("orientation"), "{line}");
    assert!(
        err.contains("orientation (phi, theta, psi) is lost"),
        "{err}"
    );
    // A scene's answer says the same.
    let dir = std::env::temp_dir().join(format!("spintop-lost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = scene(
        &dir,
        0,
        "top",
        "model = \"full\"\nomega = [0.01, 0.0, 1e7]",
        "t_end = 1000.0\nsamples = 2",
    );
    let answer = json(&["run", &path, "--format", "json"]);
    let (code, table, err) = run(&["run", &path]);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(code, 0, "{err}");
    assert!(
        table.contains("# warning: the body turns") && table.contains("is lost"),
        "{table}"
    );
    assert!(
        answer["error"].get("orientation").is_none(),
        "{}",
        answer["error"]
    );
    assert!(lost(&answer), "{}", answer["warnings"]);
}
