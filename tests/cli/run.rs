//! `spintop run`, `spintop scenes` and `spintop tui SCENE` as a user meets
//! them: the JSON contract of the matching command plus `chosen`, the
//! catalogue by name from any directory, and malformed scene files refused
//! with exit code 2 and one line naming the file, the line and what was
//! expected (never a panic, never a second line).

use crate::support;
use support::{Scratch, spintop};

use serde_json::Value;
use spintop::scene::Body;
use spintop::scene::catalogue::CATALOGUE;
use std::process::Command;

const HEAD: &str = "[scene]\nname = \"x\"\nkind = \"top\"\ndescription = \"d\"\n\n";
const SPHERE: &str = "[units]\nshape = \"sphere\"\nradius_nm = 50.0\ndensity_kg_m3 = 2200.0\ndipole_debye = 1e3\nspin_hz = 1e9\n";

const MOLECULE: &str = "[units]\nshape = \"molecule\"\nmoments_amu_a2 = [1.7923, 13.014, 14.8063]\ndipole_vector_debye = [2.33, 0.0, 0.0]\nomega_hz = [1.9e12, 7.0e11, 6.5e11]\n";

/// Malformed scene files: (file name, text, line of the fault, words the message must hold).
fn malformed() -> Vec<(&'static str, String, usize, &'static str)> {
    vec![
        ("unknown-key.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\nration = 0.4\n"), 8, "unknown key `ration`"),
        ("missing-key.toml", format!("{HEAD}[top]\nratio = 0.4\n"), 6, "missing the key model"),
        ("wrong-type.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\nratio = \"big\"\n"), 8, "[top] ratio: invalid type: string \"big\", expected a number"),
        ("ratio-out-of-range.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\nratio = 3.0\n"), 8, "0 < I3/I1 <= 2"),
        ("non-finite.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\nomega = [0.0, nan, 0.2]\n"), 8, "not a finite number"),
        ("infinite-ratio.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\nratio = inf\n"), 8, "not a finite number; expected I3/I1 in (0, 2]"),
        ("unknown-kind.toml", "[scene]\nname = \"x\"\nkind = \"spinner\"\ndescription = \"d\"\n".into(), 3, "expected one of top, balance, orbit, shell, stability"),
        ("unknown-method.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\n\n[solve]\nmethod = \"euler\"\n"), 10, "expected one of auto, exact, rk4"),
        ("bad-time-unit.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\n\n{SPHERE}time_unit = \"fortnight\"\n"), 15, "expected one of s, min, h, d, yr"),
        ("negative-radius.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\n\n{}", SPHERE.replace("50.0", "-50.0")), 11, "expected a positive radius"),
        ("units-with-ratio.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\nratio = 0.4\n\n{SPHERE}"), 8, "ratio follows from [units]"),
        ("units-general.toml", format!("{HEAD}[top]\nmodel = \"general\"\ninertia = [1.0, 1.0, 1.0]\ndipole = [0.0, 0.0, 1.0]\n\n{SPHERE}"), 8, "inertia follows from [units]"),
        ("units-sphere-general.toml", format!("{HEAD}[top]\nmodel = \"general\"\n\n{SPHERE}"), 9, "shape = \"sphere\" is a symmetric top"),
        ("measured-moments.toml", format!("{HEAD}[top]\nmodel = \"auto\"\n\n{MOLECULE}").replace("14.8063", "14.863"), 11, "inertia defect"),
        ("molecule-scalar-dipole.toml", format!("{HEAD}[top]\nmodel = \"auto\"\n\n{MOLECULE}dipole_debye = 2.0\n"), 14, "give dipole_vector_debye"),
        ("molecule-zero-dipole.toml", format!("{HEAD}[top]\nmodel = \"auto\"\n\n{MOLECULE}").replace("[2.33, 0.0, 0.0]", "[0.0, 0.0, 0.0]"), 9, "dipole"),
        ("ellipsoid-no-density.toml", format!("{HEAD}[top]\nmodel = \"auto\"\n\n[units]\nshape = \"ellipsoid\"\nsemi_axes_nm = [150.0, 60.0, 40.0]\ndipole_vector_debye = [0.0, 3e4, 4e4]\nomega_hz = [2e8, 5e8, 1e9]\n"), 9, "density_kg_m3"),
        ("molecule-full.toml", format!("{HEAD}[top]\nmodel = \"full\"\n\n{MOLECULE}"), 7, "cannot take [units]"),
        // The one rule of sim::Model::check_method and MethodOptions::for_choice, as the command line applies it.
        ("full-dop853.toml", format!("{HEAD}[top]\nmodel = \"full\"\n\n[solve]\nmethod = \"dop853\"\n"), 10, "[solve] method = \"dop853\": the full model (3.4) takes method auto"),
        ("rtol-below-double.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\n\n[solve]\nrtol = 1e-15\n"), 10, "[solve] rtol = 1e-15 is out of range; expected a relative tolerance in [1e-14, 1)"),
        ("step-not-rk4.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\n\n[solve]\nmethod = \"dop853\"\nstep = 0.1\n"), 11, "[solve] step sets the fixed step of method = \"rk4\" only; the adaptive methods take rtol"),
        ("auto-with-method.toml", format!("{HEAD}[top]\nmodel = \"auto\"\n\n[solve]\nmethod = \"dop853\"\n"), 10, "model = \"auto\" chooses the model and its method together"),
        ("times-decreasing.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\n\n[solve]\ntimes = [0.0, 5.0, 2.0]\n"), 10, "2 comes after 5"),
        ("times-and-t-end.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\n\n[solve]\ntimes = [0.0, 1.0]\nt_end = 5.0\n"), 11, "either times"),
        ("zero-samples.toml", format!("{HEAD}[top]\nmodel = \"truncated\"\n\n[solve]\nt_end = 5.0\nsamples = 0\n"), 11, "expected a whole number from 1 to 1000000"),
        ("empty.toml", String::new(), 1, "there is no [scene] section"),
        ("syntax.toml", "[scene\nname = \"x\"\n".into(), 1, "expected `]`"),
        ("missing-description.toml", "[scene]\nname = \"x\"\nkind = \"top\"\n\n[top]\nmodel = \"truncated\"\n".into(), 1, "missing the key description"),
        ("foreign-section.toml", "[scene]\nname = \"x\"\nkind = \"orbit\"\ndescription = \"d\"\n\n[orbit]\npotential = \"coulomb\"\ntau0 = 1e-3\n\n[solve]\ntimes = [0.0, 1.0]\n\n[top]\nmodel = \"reduced\"\n".into(), 13, "[top] does not belong"),
        ("orbit-method.toml", "[scene]\nname = \"x\"\nkind = \"orbit\"\ndescription = \"d\"\n\n[orbit]\npotential = \"harmonic\"\ntau0 = 1e-3\n\n[solve]\nmethod = \"rk4\"\ntimes = [0.0, 1.0]\n".into(), 11, "its method follows from force"),
        ("stability-row.toml", "[scene]\nname = \"x\"\nkind = \"stability\"\ndescription = \"d\"\n\n[stability]\nrow = 9\n".into(), 7, "expected a row number, 1 to 6"),
        ("foreign-balance-key.toml", "[scene]\nname = \"x\"\nkind = \"balance\"\ndescription = \"d\"\n\n[balance]\ndipole = \"loop\"\ncone = 0.5\n\n[solve]\ntimes = [0.0]\n".into(), 8, "cone belongs to dipole = \"precessing\""),
        ("eccentricity.toml", "[scene]\nname = \"x\"\nkind = \"orbit\"\ndescription = \"d\"\n\n[orbit]\npotential = \"coulomb\"\ntau0 = 1e-3\neccentricity = 1.5\n\n[solve]\ntimes = [0.0, 1.0]\n".into(), 9, "eccentricity = 1.5 is out of range"),
        ("forced-integrator.toml", format!("{HEAD}[top]\nmodel = \"reduced\"\n\n{SPHERE}time_unit = \"yr\"\n\n[solve]\nmethod = \"dop853\"\nt_end = 10.0\n"), 18, "more than the 1e7 allowed; the closed forms ([solve] method = \"auto\" or [solve] method = \"exact\") answer any time at once"),
    ]
}

#[test]
fn malformed_scene_files_exit_2_with_the_file_the_line_and_what_was_expected() {
    let dir = Scratch::new("bad");
    let cases = malformed();
    assert!(cases.len() >= 10);
    for (name, text, line, words) in cases {
        let path = dir.write(name, &text);
        let out = spintop(&["run", &path]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(out.stdout.is_empty(), "{name}: no output on failure");
        assert_eq!(err.lines().count(), 1, "{name}: one line, got {err}");
        let prefix = format!("spintop: error: {path}:{line}: ");
        assert!(
            err.starts_with(&prefix),
            "{name}: expected {prefix}…, got {err}"
        );
        assert!(err.contains(words), "{name}: expected '{words}' in {err}");
    }
}

/// A run that stops inside a scene says what to change in the scene's own
/// keys, never in flags of the command line the scene does not have: the
/// general top spun so fast that (3.4) has no slow manifold (the same run as
/// `simulate` with flags names `--omega`, tests/cli/simulate.rs).
#[test]
fn a_numerical_failure_in_a_scene_names_the_scenes_keys() {
    let dir = Scratch::new("keys");
    let path = dir.write(
        "fast.toml",
        &format!(
            "{HEAD}[top]\nmodel = \"full\"\ninertia = [1.0, 2.0, 2.5]\ndipole = [1.0, 0.5, 0.2]\nomega = [5.0, 3.0, 1.0]\n\n[solve]\nt_end = 10.0\n"
        ),
    );
    let out = spintop(&["run", &path]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("no slow manifold")
            && err.contains("[top] omega")
            && err.contains("[top] dipole")
            && err.contains("[top] model = \"reduced\""),
        "{err}"
    );
    assert!(!err.contains("--"), "a flag in a scene's advice: {err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn unknown_scene_and_csv_stability_are_refused_with_exit_2() {
    let out = spintop(&["run", "no-such-scene"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("spintop scenes"));
    let out = spintop(&["run", "stability-row-5", "--format", "csv"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not csv"));
}

#[test]
fn scenes_lists_the_catalogue_one_line_each() {
    let out = spintop(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), CATALOGUE.len());
    for (line, entry) in lines.iter().zip(CATALOGUE) {
        assert!(line.starts_with(entry.name), "{line}");
        let scene = entry.scene().unwrap();
        assert!(line.contains(scene.kind().name()));
        assert!(
            line.trim_end().ends_with('.'),
            "a whole first sentence: {line}"
        );
    }
}

/// The catalogue is compiled in: names work from any directory, and the JSON
/// is the `simulate` contract plus `scene`, `chosen` and `warnings`.
#[test]
fn run_by_name_from_elsewhere_gives_the_simulate_contract_and_chosen() {
    let elsewhere = Scratch::new("cwd");
    let out = Command::new(env!("CARGO_BIN_EXE_spintop"))
        .args(["run", "figure-1", "--format", "json"])
        .current_dir(&elsewhere.0)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "model",
        "method",
        "method_detail",
        "parameters",
        "stats",
        "samples",
    ] {
        assert!(!v[key].is_null(), "simulate's key {key}");
    }
    assert_eq!(v["scene"]["name"], "figure-1");
    assert_eq!(v["scene"]["kind"], "top");
    assert_eq!(v["chosen"]["method"], "exact");
    assert_eq!(v["chosen"]["method"], v["method"]);
    assert!(
        v["chosen"]["reason"]
            .as_str()
            .unwrap()
            .contains("closed form")
    );
    assert_eq!(v["warnings"].as_array().unwrap().len(), 0);
    assert_eq!(v["samples"].as_array().unwrap().len(), 11);
    for key in ["rotation", "euler", "l_lab", "tilt"] {
        assert!(!v["samples"][3][key].is_null(), "sample key {key}");
    }
}

#[test]
fn run_a_real_particle_reports_units_milestones_and_the_skipped_orientation() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/crates/spintop/scenes/nanoparticle-1e7-debye.toml"
    );
    let v = support::json("run", &[path]);
    let u = &v["units"];
    // τ in SI units, computed here from the scene's numbers: a silica sphere
    // of radius 50 nm and 2200 kg/m³ (I₁ = (2/5)mr²) with a dipole of 10⁷ D,
    // τ = d²/(6πε₀I₁c³) (the Gaussian 2d²/(3I₁c³)): 2.148e-28 s.
    let (r, rho) = (50e-9_f64, 2200.0);
    let mass = rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let i1 = 0.4 * mass * r * r;
    let (debye, eps0, c) = (3.335_640_95e-30, 8.854_187_812_8e-12, 299_792_458.0_f64);
    let d = 1e7 * debye;
    let tau = d * d / (6.0 * std::f64::consts::PI * eps0 * i1 * c.powi(3));
    assert!(
        (u["tau_s"].as_f64().unwrap() / tau - 1.0).abs() < 1e-6,
        "{tau:e}"
    );
    assert!((tau / 2.148e-28 - 1.0).abs() < 5e-4);
    assert_eq!(u["time_unit"], "yr");
    assert!(
        u["conversion"]
            .as_str()
            .unwrap()
            .starts_with("tau = 2 d^2/(3 I1 c^3)")
    );
    // Upright (tilt below 1°) in the reduced model: tan(tilt) = Ω⊥/k, and a
    // sphere spun 45° from its dipole starts with Ω⊥₀ = k, so by (4.16)
    // Φ² = e^{−s}/(2 − e^{−s}) with s = 2τk²t reaches x = tan²(1°) at
    // s = ln((1 + x)/(2x)): 27.67 years (of 365.25 days).
    let k = 2.0 * std::f64::consts::PI * 1e9 * (0.25 * std::f64::consts::PI).sin();
    let x = 1f64.to_radians().tan().powi(2);
    let years = ((1.0 + x) / (2.0 * x)).ln() / (2.0 * tau * k * k) / (365.25 * 86400.0);
    let upright = u["milestones"]["reduced_upright"]["unit"].as_f64().unwrap();
    assert!((upright / years - 1.0).abs() < 1e-6, "{upright} vs {years}");
    assert!((upright - 27.67).abs() < 0.01, "{upright}");
    assert!(u["milestones"]["reduced_half_spin"].is_null(), "never");
    assert!(v["orientation_skipped"].as_str().unwrap().contains("steps"));
    assert_eq!(v["stats"]["rhs_evals"], 0);
    let s = &v["samples"][3];
    assert_eq!(s["t_unit"], 27.7);
    assert!(
        s["rotation"].is_null() && s["euler"].is_null(),
        "no orientation in the samples"
    );
    // The table speaks in years and Hz.
    let out = spintop(&["run", path]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("t [yr]") && text.contains("f [Hz]"), "{text}");
    assert!(text.contains("falls below 1 deg after 27.6"), "{text}");
}

#[test]
fn csv_warnings_go_to_stderr() {
    let out = spintop(&["run", "euler-pole", "--format", "csv"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("spintop: warning: ") && err.contains("pole"),
        "{err}"
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("t,omega1,"), "{text}");
}

/// Every kind runs under the same JSON contract as its command.
#[test]
fn every_kind_keeps_its_commands_json_keys() {
    let cases: [(&str, &[&str]); 4] = [
        (
            "precessing-dipole",
            &["dipole", "period", "samples", "period_average"],
        ),
        (
            "coulomb-collapse",
            &["potential", "force", "method", "samples", "collapse_time"],
        ),
        (
            "appendix-convergence",
            &["tau0", "delay", "regime", "samples"],
        ),
        ("stability-row-2", &["rows"]),
    ];
    for (name, keys) in cases {
        let v = support::json("run", &[name]);
        for key in keys {
            assert!(!v[key].is_null(), "{name}: {key}");
        }
        assert!(v["chosen"]["method"].is_string() && v["chosen"]["reason"].is_string());
    }
}

/// The live view opens every top scene of the catalogue (headless: the
/// settings it would start from): the symmetric ones in two columns, a
/// general top in three ((3.3), reduced, physical (3.4)). Scenes of other
/// kinds are refused with a reason.
#[test]
fn tui_opens_every_top_scene() {
    for entry in CATALOGUE {
        let scene = entry.scene().unwrap();
        let got = spintop_app::live::Settings::for_scene(&scene, None);
        match &scene.body {
            Body::Top(top) => {
                let (settings, note) = got.unwrap_or_else(|e| panic!("{}: {e}", entry.name));
                assert_eq!(settings.omega0(), <[f64; 3]>::from(top.initial.omega));
                assert!(note.starts_with(&format!("scene {}", entry.name)));
                let general = top.model.name().starts_with("general");
                assert_eq!(settings.is_general(), general, "{}", entry.name);
                if general && top.general_units.is_some() {
                    assert!(note.contains("a real particle, τ_f ="), "{note}");
                } else if general {
                    assert!(note.contains("a general top under (3.3)"), "{note}");
                }
                let app = spintop_app::live::App::new(settings).unwrap();
                assert_eq!(app.columns().len(), if general { 3 } else { 2 });
            }
            _ => assert!(got.is_err(), "{}", entry.name),
        }
    }
    let out = spintop(&["tui", "precessing-dipole"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("opens top scenes"));
    let out = spintop(&["tui", "figure-1", "--ratio", "0.5"]);
    assert_eq!(out.status.code(), Some(2), "a scene and --ratio conflict");
}
