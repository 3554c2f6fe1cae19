//! The three parsers that take text from outside, fed arbitrary input
//! (proptest): a scene file (`spintop::scene::parse`), a bench session's CSV
//! (`spintop::workprecision::report::parse_csv`, what `bench --join` reads)
//! and the book server's request head (`Connection::next_request`, read
//! from a real loopback socket). Each must return, never panic, and either
//! accept the text whole or refuse it with one clear line: a scene with its
//! file and line, a CSV row with its line, a request as malformed (400).
//! Beside raw bytes, each gets text built from its own vocabulary (the
//! real keys, columns and headers with hostile values), which reaches the
//! checks behind the syntax.

use proptest::prelude::*;
use spintop::scene::{Body, parse};
use spintop::workprecision::report::{CSV_COLUMNS, parse_csv};

// ---------------------------------------------------------------- values

/// A TOML value for a key: numbers of every size and sign (and the ones a
/// double cannot be), strings, arrays of the right and the wrong length.
fn toml_value() -> impl Strategy<Value = String> {
    let number = prop_oneof![
        any::<f64>().prop_map(|x| format!("{x:?}")),
        (-20i32..20, 1u32..10).prop_map(|(e, m)| format!("{m}e{e}")),
        (-400i32..400).prop_map(|e| format!("1e{e}")),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("0.0".to_string()),
        Just("-0.0".to_string()),
        any::<i64>().prop_map(|n| n.to_string()),
    ];
    let word = prop_oneof![
        Just("truncated"),
        Just("reduced"),
        Just("general"),
        Just("full"),
        Just("auto"),
        Just("exact"),
        Just("rk4"),
        Just("dopri5"),
        Just("dop853"),
        Just("radau5"),
        Just("forward"),
        Just("sphere"),
        Just("cylinder"),
        Just("ellipsoid"),
        Just("molecule"),
        Just("paper"),
        Just("coulomb"),
        Just("harmonic"),
        Just("ll"),
        Just("al"),
        Just("al-forward"),
        Just("precessing"),
        Just("loop"),
        Just("dumbbell"),
        Just("yr"),
        Just("s"),
        Just(""),
    ]
    .prop_map(|w| format!("\"{w}\""));
    let array =
        prop::collection::vec(number.clone(), 0..5).prop_map(|v| format!("[{}]", v.join(", ")));
    prop_oneof![4 => number, 3 => word, 3 => array, 1 => "\\PC{0,12}".prop_map(|s| format!("{s:?}"))]
}

const SECTIONS: [(&str, &[&str]); 8] = [
    ("scene", &["name", "kind", "description"]),
    (
        "top",
        &[
            "model", "ratio", "inertia", "dipole", "omega", "euler", "frame",
        ],
    ),
    (
        "balance",
        &[
            "dipole", "cone", "rate", "b", "eps", "charges", "masses", "length",
        ],
    ),
    (
        "orbit",
        &["potential", "tau0", "force", "r0", "eccentricity"],
    ),
    ("shell", &["tau0", "delay"]),
    ("stability", &["row"]),
    (
        "solve",
        &["method", "rtol", "step", "times", "t_end", "samples"],
    ),
    (
        "units",
        &[
            "shape",
            "radius_nm",
            "length_nm",
            "density_kg_m3",
            "dipole_debye",
            "spin_hz",
            "spin_tilt_deg",
            "upright_deg",
            "time_unit",
            "moments_amu_a2",
            "semi_axes_nm",
            "dipole_vector_debye",
            "omega_hz",
        ],
    ),
];

/// A scene file made of the real sections and keys with hostile values,
/// always with a well-formed [scene] header so that validation runs deep.
fn scene_text() -> impl Strategy<Value = String> {
    let kind = prop_oneof![
        Just("top"),
        Just("balance"),
        Just("orbit"),
        Just("shell"),
        Just("stability"),
        Just("spinner"),
    ];
    let section = (
        0..SECTIONS.len(),
        prop::collection::vec((0..16usize, toml_value()), 0..7),
    );
    (kind, prop::collection::vec(section, 0..4)).prop_map(|(kind, sections)| {
        let mut text = format!(
            "[scene]\nname = \"fuzz\"\nkind = \"{kind}\"\ndescription = \"A fuzzed scene.\"\n"
        );
        let mut seen = vec!["scene"];
        for (s, keys) in sections {
            let (name, names) = SECTIONS[s];
            if seen.contains(&name) {
                continue;
            }
            seen.push(name);
            text.push_str(&format!("\n[{name}]\n"));
            let mut used = Vec::new();
            for (k, value) in keys {
                let key = names[k % names.len()];
                if !used.contains(&key) {
                    used.push(key);
                    text.push_str(&format!("{key} = {value}\n"));
                }
            }
        }
        text
    })
}

fn check_scene(text: &str) -> Result<(), TestCaseError> {
    match parse(text, "fuzz.toml") {
        Ok(scene) => {
            // Accepted whole: what it will run on is finite.
            if let Body::Top(top) = &scene.body {
                prop_assert!(top.times.iter().all(|t| t.is_finite() && *t >= 0.0));
                prop_assert!(top.initial.omega.iter().all(|w| w.is_finite()));
            }
        }
        Err(e) => {
            prop_assert_eq!(&e.file, "fuzz.toml");
            prop_assert!(!e.message.contains('\n'), "two lines: {}", e.message);
            prop_assert!(!e.message.trim().is_empty());
            let lines = text.lines().count().max(1);
            prop_assert!(
                e.line >= 1 && e.line <= lines + 1,
                "line {} of {lines}",
                e.line
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn scene_parser_refuses_any_text_in_one_line_or_accepts_it(text in "\\PC{0,300}") {
        check_scene(&text)?;
    }

    #[test]
    fn scene_parser_refuses_hostile_values_of_real_keys_in_one_line(text in scene_text()) {
        check_scene(&text)?;
    }
}

// ---------------------------------------------------------------- bench CSV

/// One CSV field: a number of any kind (the ones Python writes for NaN and
/// infinities too), a count, a name, empty, or junk.
fn csv_field() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| x.to_string()),
        prop_oneof![
            Just("nan"),
            Just("inf"),
            Just("-inf"),
            Just("NaN"),
            Just("")
        ]
        .prop_map(String::from),
        any::<u64>().prop_map(|n| n.to_string()),
        any::<i64>().prop_map(|n| n.to_string()),
        prop_oneof![
            Just("omega"),
            Just("omega+orientation"),
            Just("rtol"),
            Just("step"),
            Just("none"),
            Just("ok"),
            Just("spintop"),
            Just("reduced"),
        ]
        .prop_map(String::from),
        "[^,\\n\\r]{0,8}",
    ]
}

/// A valid field for column `i` of [`CSV_COLUMNS`].
fn valid_field(i: usize) -> BoxedStrategy<String> {
    match CSV_COLUMNS[i] {
        "target" => prop_oneof![Just("omega"), Just("omega+orientation")]
            .prop_map(String::from)
            .boxed(),
        "knob" => prop_oneof![Just("rtol"), Just("h"), Just("")]
            .prop_map(String::from)
            .boxed(),
        "value" | "omega_error" | "orientation_error" | "time_s" => prop_oneof![
            (1e-300..1e300f64).prop_map(|x| x.to_string()),
            Just(String::new()),
        ]
        .boxed(),
        "rhs_evals" | "steps" | "rejected" | "repeats" => prop_oneof![
            (0u32..100_000).prop_map(|n| n.to_string()),
            Just(String::new()),
        ]
        .boxed(),
        _ => "[a-z0-9+-]{1,8}".boxed(),
    }
}

/// A session file: the real header (maybe shuffled, maybe short a column),
/// then rows that are valid but for, often, one hostile field (NaN, an
/// infinity, junk), and sometimes a field too many or too few.
fn csv_text() -> impl Strategy<Value = String> {
    let n = CSV_COLUMNS.len();
    let row = (
        (0..n).map(valid_field).collect::<Vec<_>>(),
        prop::option::of((0..n, csv_field())),
        prop_oneof![8 => Just(0i8), 1 => Just(1), 1 => Just(-1)],
    );
    let order = Just((0..n).collect::<Vec<usize>>()).prop_shuffle();
    (order, any::<bool>(), prop::collection::vec(row, 0..6)).prop_map(
        move |(order, shuffled, rows)| {
            let order: Vec<usize> = if shuffled { order } else { (0..n).collect() };
            let mut text = order
                .iter()
                .map(|&i| CSV_COLUMNS[i])
                .collect::<Vec<_>>()
                .join(",")
                + "\n";
            for (mut fields, hostile, extra) in rows {
                if let Some((i, value)) = hostile {
                    fields[i] = value;
                }
                let mut cells: Vec<String> = order.iter().map(|&i| fields[i].clone()).collect();
                match extra {
                    1 => cells.push("x".into()),
                    -1 => {
                        cells.pop();
                    }
                    _ => {}
                }
                text.push_str(&cells.join(","));
                text.push('\n');
            }
            text
        },
    )
}

fn check_csv(text: &str) -> Result<(), TestCaseError> {
    match parse_csv(text) {
        Ok(rows) => {
            // Accepted whole: every number a chart would draw is finite.
            for r in &rows {
                for x in [r.value, r.omega_error, r.orientation_error, r.time_s]
                    .into_iter()
                    .flatten()
                {
                    prop_assert!(x.is_finite(), "{x} accepted");
                }
            }
        }
        Err(e) => {
            prop_assert!(!e.contains('\n'), "two lines: {e}");
            prop_assert!(!e.trim().is_empty());
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn bench_csv_parser_refuses_any_text_in_one_line_or_accepts_it(text in "\\PC{0,300}") {
        check_csv(&text)?;
    }

    #[test]
    fn bench_csv_parser_refuses_hostile_rows_in_one_line(text in csv_text()) {
        check_csv(&text)?;
    }

    /// Rows with nothing hostile in them are read back, value for value.
    #[test]
    fn bench_csv_parser_reads_every_valid_row(
        rows in prop::collection::vec((0..CSV_COLUMNS.len()).map(valid_field).collect::<Vec<_>>(), 1..5)
    ) {
        let mut text = CSV_COLUMNS.join(",") + "\n";
        for row in &rows {
            text.push_str(&row.join(","));
            text.push('\n');
        }
        let parsed = parse_csv(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(parsed.len(), rows.len());
        for (r, fields) in parsed.iter().zip(&rows) {
            prop_assert_eq!(r.value, fields[5].parse::<f64>().ok());
            prop_assert_eq!(r.time_s, fields[11].parse::<f64>().ok());
        }
    }
}

#[test]
fn bench_csv_refusals_name_the_line() {
    let head = CSV_COLUMNS.join(",");
    let row = "scipy,reduced,DOP853,omega,rtol,1e-6,nan,,242,17,0,0.1,5,ok";
    let e = parse_csv(&format!("{head}\n{row}\n")).unwrap_err();
    assert_eq!(e, "line 2: omega_error 'nan' is not a finite number");
}

// ---------------------------------------------------------------- request head
