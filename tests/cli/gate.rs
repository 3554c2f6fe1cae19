//! The output gate (`src/cli/gate.rs`): every command's output passes one
//! checked path before it is written. Read from the sources, every command
//! listed by `spintop --help` takes the gate and nothing else to write its
//! output with; run, a result with a non-finite number, a run that stopped
//! early and a join of a file holding NaN each end with exit 3 or 2 and one
//! line, never with the number printed.

use crate::support::{Scratch, commands, spintop};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Why `source` (one command's file under `src/cli/`) could write its output
/// around the gate, if it could: its `execute` must take `&mut Gate` and no
/// other output, and nothing in it may reach stdout itself.
fn writes_around_the_gate(source: &str) -> Option<String> {
    let Some(at) = source.find("fn execute(") else {
        return Some("it has no `fn execute(`".into());
    };
    let signature = &source[at..at + source[at..].find('{').unwrap_or(0)];
    if !signature.contains("&mut Gate<'_>") {
        return Some(format!("its execute does not take the gate: {signature}"));
    }
    if signature.contains("out: &mut impl Write") || signature.contains("out: &mut dyn Write") {
        return Some(format!(
            "its execute takes a writer of its own: {signature}"
        ));
    }
    for (n, line) in source.lines().enumerate() {
        let code = without_strings(line.trim_start());
        if code.starts_with("//") {
            continue;
        }
        let code = code.replace("stdout().is_terminal()", "");
        let reaches = ["print!(", "println!(", "stdout()", "dbg!("]
            .iter()
            .any(|p| calls(&code, p));
        if reaches {
            return Some(format!(
                "line {} reaches stdout itself: {}",
                n + 1,
                line.trim()
            ));
        }
    }
    None
}

/// `line` with the insides of its string literals blanked (a snippet that
/// prints is text, not a call).
fn without_strings(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let (mut inside, mut escaped) = (false, false);
    for c in line.chars() {
        match (inside, escaped, c) {
            (true, false, '\\') => escaped = true,
            (true, true, _) => escaped = false,
            (_, false, '"') => {
                inside = !inside;
                out.push('"');
            }
            (true, false, _) => {}
            (false, _, c) => out.push(c),
        }
    }
    out
}

/// True when `code` calls `name` itself (`print!(`, not `eprint!(`).
fn calls(code: &str, name: &str) -> bool {
    code.match_indices(name).any(|(at, _)| {
        code[..at]
            .chars()
            .last()
            .is_none_or(|c| !(c.is_alphanumeric() || c == '_'))
    })
}

#[test]
fn every_command_writes_its_output_through_the_gate() {
    let dispatch = std::fs::read_to_string(root().join("src/cli.rs")).unwrap();
    let mut bad = Vec::new();
    for command in commands() {
        let file = root().join(format!("src/cli/{command}.rs"));
        let source = std::fs::read_to_string(&file)
            .unwrap_or_else(|e| panic!("{command}: {}: {e}", file.display()));
        if let Some(why) = writes_around_the_gate(&source) {
            bad.push(format!("{command}: {why}"));
        }
        // And the dispatcher hands it the gate, not stdout.
        if !dispatch.contains(&format!("{command}::execute(args, out")) {
            bad.push(format!("{command}: src/cli.rs does not hand it the gate"));
        }
    }
    assert!(
        bad.is_empty(),
        "commands that can skip the gate:\n{}",
        bad.join("\n")
    );
}

#[test]
fn the_gate_check_fails_on_each_way_around_it() {
    let good = "pub(crate) fn execute(args: A, out: &mut Gate<'_>) -> R {\n    writeln!(out, \"x\")?;\n    eprint!(\"progress\");\n    let code = \"fn main() { println!(1) }\";\n    if !io::stdout().is_terminal() {}\n}\n";
    assert_eq!(writes_around_the_gate(good), None);
    for bad in [
        "pub(crate) fn execute(args: A, out: &mut impl Write) -> R {\n}\n",
        "pub(crate) fn execute(args: A, out: &mut Gate<'_>) -> R {\n    println!(\"{}\", x);\n}\n",
        "pub(crate) fn execute(args: A, out: &mut Gate<'_>) -> R {\n    let mut s = std::io::stdout();\n}\n",
        "pub(crate) fn execute(args: A, out: &mut Gate<'_>) -> R {\n    dbg!(x);\n}\n",
        "pub(crate) fn run(args: A) -> R {\n}\n",
    ] {
        assert!(writes_around_the_gate(bad).is_some(), "{bad}");
    }
}

/// A result holding a number that is not finite is refused whole, with the
/// place it sits, exit 3 and one line; no NaN, inf or null reaches stdout.
#[test]
fn a_non_finite_result_is_refused_with_exit_3_and_nothing_written() {
    for format in ["json", "csv", "table"] {
        let args = [
            "balance",
            "--dipole",
            "precessing",
            "--rate",
            "1e120",
            "--times",
            "0",
            "--format",
            format,
        ];
        let out = spintop(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains("not a finite number at "), "{stderr}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// A forward run of (3.4) that runs away says so in every format, CSV
/// included, and exits 3.
#[test]
fn a_run_that_stopped_says_so_in_every_format() {
    for format in ["table", "csv", "json"] {
        let out = spintop(&[
            "simulate", "--model", "full", "--method", "forward", "--times", "0,1,2,50",
            "--format", format,
        ]);
        assert_eq!(out.status.code(), Some(3), "{format}");
        let stdout = String::from_utf8(out.stdout).unwrap();
        let said = match format {
            "json" => serde_json::from_str::<serde_json::Value>(&stdout).unwrap()["stopped"]
                .as_str()
                .is_some_and(|s| s.starts_with("runaway at t = ")),
            _ => stdout
                .lines()
                .last()
                .is_some_and(|l| l.starts_with("# stopped: runaway at t = ")),
        };
        assert!(said, "{format}: {stdout}");
    }
}

/// A non-finite number, an error or a time below zero, or a knob not above
/// it, is no measurement (a negative error was drawn at a log-log chart's
/// floor, as if it were the best): each refused in one line with the file,
/// the line and the column; and files that hold no row at all draw nothing.
#[test]
fn bench_join_refuses_a_row_that_is_no_measurement_with_the_file_and_the_line() {
    let dir = Scratch::new("gate-join");
    let head = "source,model,method,target,knob,value,omega_error,orientation_error,rhs_evals,steps,rejected,time_s,repeats,status\n";
    let good = "scipy,reduced,DOP853,omega,rtol,0.001,0.0007,,242,17,0,0.0017,5,ok\n";
    for (name, bad, column, why) in [
        (
            "nan-error.csv",
            "scipy,reduced,DOP853,omega,rtol,1e-6,nan,,242,17,0,0.0017,5,ok\n",
            "omega_error",
            "not a finite number",
        ),
        (
            "inf-time.csv",
            "scipy,reduced,DOP853,omega,rtol,1e-6,1e-7,,242,17,0,inf,5,ok\n",
            "time_s",
            "not a finite number",
        ),
        (
            "neg-inf-knob.csv",
            "scipy,reduced,DOP853,omega,rtol,-inf,1e-7,,242,17,0,0.1,5,ok\n",
            "value",
            "not a finite number",
        ),
        (
            "neg-error.csv",
            "scipy,reduced,DOP853,omega,rtol,1e-6,-1e-3,,242,17,0,0.0017,5,ok\n",
            "omega_error",
            "negative",
        ),
        (
            "neg-orientation.csv",
            "scipy,reduced,DOP853,omega,rtol,1e-6,1e-3,-1e-9,242,17,0,0.0017,5,ok\n",
            "orientation_error",
            "negative",
        ),
        (
            "neg-time.csv",
            "scipy,reduced,DOP853,omega,rtol,1e-6,1e-7,,242,17,0,-0.1,5,ok\n",
            "time_s",
            "negative",
        ),
        (
            "zero-knob.csv",
            "scipy,reduced,DOP853,omega,rtol,0,1e-7,,242,17,0,0.1,5,ok\n",
            "value",
            "zero",
        ),
    ] {
        let path = dir.write(name, &format!("{head}{good}{bad}"));
        let out = spintop(&["bench", "--join", &path]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(out.stdout.is_empty(), "{name}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(&path)
                && stderr.contains("line 3")
                && stderr.contains(column)
                && stderr.contains(why),
            "{name}: {stderr}"
        );
    }
    let empty = dir.write("header-only.csv", head);
    let out = spintop(&["bench", "--join", &empty, &empty]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(out.stdout.is_empty());
    assert!(stderr.contains("no row"), "{stderr}");
}

/// A cylinder 300 decades longer than wide passes every size check, but its
/// I₃/I₁ underflows to 0: the scene is refused as bad input, never a panic.
#[test]
fn a_particle_whose_moment_ratio_underflows_is_a_scene_error() {
    let dir = Scratch::new("gate-particle");
    let text = "[scene]\nname = \"needle\"\nkind = \"top\"\ndescription = \"A needle.\"\n\n[top]\nmodel = \"auto\"\n\n[units]\nshape = \"cylinder\"\nradius_nm = 1e-150\nlength_nm = 1e150\ndensity_kg_m3 = 2200.0\ndipole_debye = 1e3\nspin_hz = 1e9\n";
    let path = dir.write("needle.toml", text);
    for args in [vec!["run", path.as_str()], vec!["tui", path.as_str()]] {
        let out = spintop(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(&format!("{path}:9: [units]")) && stderr.contains("I3/I1 of the shape"),
            "{stderr}"
        );
    }
}

/// `spintop run` of a scene file holding `text`, written to a scratch folder
/// named `tag`: the output, its stdout and its stderr.
fn run_scene(tag: &str, text: &str) -> (std::process::Output, String, String) {
    let dir = Scratch::new(tag);
    let path = dir.write("scene.toml", text);
    let out = spintop(&["run", path.as_str()]);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out, stdout, stderr)
}

/// A molecule whose one moment outweighs the other two is refused with the
/// other two's real sum, in a few digits: beside a moment of 1e300 the sum
/// was taken as the total less that moment, which cancelled to 0, and the
/// moment was printed in 301 digits.
#[test]
fn a_molecule_refused_for_its_moments_names_their_sum_in_few_digits() {
    let text = "[scene]\nname = \"heavy\"\nkind = \"top\"\ndescription = \"One heavy axis.\"\n\n[top]\nmodel = \"auto\"\n\n[units]\nshape = \"molecule\"\nmoments_amu_a2 = [1e300, 1.0, 1.0]\ndipole_vector_debye = [2.33, 0.0, 0.0]\nomega_hz = [1e12, 1e12, 1e12]\n";
    let (out, _, stderr) = run_scene("gate-molecule", text);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("I1 = 1e300 exceeds the sum of the other two, 2,"),
        "{stderr}"
    );
}

/// A quantity that stops existing is absent, not a non-finite number: the
/// tumbling nanoellipsoid ends turning about one axis, where the free motion
/// has no period. Its scene passes the gate in every format: no `period` in
/// those JSON samples (never `null`), an empty CSV cell, `none` in the table.
#[test]
fn a_period_that_ends_is_absent_and_passes_the_gate() {
    let run = |format: &str| {
        let out = spintop(&["run", "nanoellipsoid-tumbling", "--format", format]);
        assert!(
            out.status.success(),
            "{format}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let json = run("json");
    assert!(!json.contains("null"), "{json}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let samples = v["samples"].as_array().unwrap();
    assert!(samples.iter().any(|s| s.get("period").is_none()));
    assert!(
        samples
            .iter()
            .any(|s| s["period"].as_f64().is_some_and(f64::is_finite))
    );
    assert!(run("csv").lines().any(|l| l.ends_with(',')));
    assert!(run("table").contains("none"));
}

/// A value as large as a run of a million samples, walked lazily: it counts
/// the samples a writer asked of it.
struct Lazy {
    samples: usize,
    walked: std::cell::Cell<usize>,
}

impl serde::Serialize for Lazy {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{SerializeSeq, SerializeStruct};
        struct Samples<'a>(&'a Lazy);
        impl serde::Serialize for Samples<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut seq = s.serialize_seq(Some(self.0.samples))?;
                for i in 0..self.0.samples {
                    self.0.walked.set(self.0.walked.get() + 1);
                    seq.serialize_element(&[i as f64; 8])?;
                }
                seq.end()
            }
        }
        let mut st = s.serialize_struct("Lazy", 2)?;
        st.serialize_field("model", "truncated")?;
        st.serialize_field("samples", &Samples(self))?;
        st.end()
    }
}

impl spintop::output::Output for Lazy {
    fn write_text(
        &self,
        _: &mut dyn std::io::Write,
        _: spintop::output::Format,
    ) -> std::io::Result<()> {
        Ok(())
    }
    fn advice(&self, _entry: spintop::output::Entry) -> String {
        String::new()
    }
}

/// A writer that takes `room` bytes and then fails, as a closed pipe does.
struct Full {
    room: usize,
}

impl std::io::Write for Full {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.room == 0 {
            return Err(std::io::ErrorKind::BrokenPipe.into());
        }
        let n = buf.len().min(self.room);
        self.room -= n;
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The JSON form is written as it is walked, never built whole in memory
/// first (a million samples took 2.2 GB that way): a reader that stops after
/// 4 kB has cost a few samples, not a million.
#[test]
fn json_output_streams_and_is_never_built_whole_first() {
    let value = Lazy {
        samples: 1_000_000,
        walked: std::cell::Cell::new(0),
    };
    let mut out = Full { room: 4096 };
    let result = spintop::output::write(&mut out, &value, spintop::output::Format::Json);
    assert!(result.is_err(), "the writer was full");
    assert!(
        value.walked.get() < 1000,
        "{} samples walked before 4 kB were written",
        value.walked.get()
    );
}

/// CSV cells are written by the one number module (`numbers::csv`): lossless
/// and short. A rate of 1e-300 used to fill a cell with 302 digits
/// (`to_string`), and the same value is read back exactly.
#[test]
fn csv_cells_are_short_and_read_back_exactly() {
    let out = spintop(&[
        "simulate",
        "--model",
        "truncated",
        "--omega",
        "1e-300,0,1e-300",
        "--times",
        "0,1",
        "--format",
        "csv",
    ]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    let mut rows = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<&str> = rows.next().unwrap().split(',').collect();
    let first: Vec<&str> = rows.next().unwrap().split(',').collect();
    for cell in text.lines().flat_map(|l| l.split(',')) {
        assert!(
            cell.len() <= 25,
            "a cell of {} characters: {cell}",
            cell.len()
        );
    }
    let column = head.iter().position(|h| *h == "omega1").expect("omega1");
    assert_eq!(first[column].parse::<f64>().unwrap(), 1e-300);
}

/// A scene's runaway is said by the run (its `runaway` record, its line, the
/// gate's `# stopped:`), not also as a warning: the table said it three times
/// and stderr twice.
#[test]
fn a_scenes_runaway_is_reported_once_not_also_as_a_warning() {
    let text = "[scene]\nname = \"fw\"\nkind = \"top\"\ndescription = \"d\"\n\n[top]\nmodel = \"full\"\n\n[solve]\nmethod = \"forward\"\nt_end = 100.0\n";
    let (out, stdout, stderr) = run_scene("gate-runaway", text);
    assert_eq!(out.status.code(), Some(3));
    assert!(!stdout.contains("# warning: runaway"), "{stdout}");
    assert!(!stderr.contains("warning: runaway"), "{stderr}");
    assert_eq!(stderr.matches("runaway at t = ").count(), 1, "{stderr}");
}
