//! `spintop bench` as a user meets it: the quick sweep prints both charts and
//! the table, `--out` writes rows that read back and that `--join` accepts,
//! and bad input is refused with one line on stderr and exit code 2.

use crate::support;
use support::spintop;

use spintop::workprecision::{Row, report};
use std::path::{Path, PathBuf};

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_bench");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The quick sweep, then what `--join` makes of the file it wrote: alone,
/// beside a peer's file, and asked for a problem the file does not hold.
#[test]
fn bench_quick_prints_both_charts_the_table_and_writes_csv() {
    let csv = scratch("reduced.csv");
    let rows = quick_sweep_prints_and_writes(&csv);
    join_alone_names_the_fastest_integrator(&csv, &rows);
    join_with_a_peer_draws_its_curve(&csv, &rows);
    join_refuses_a_problem_the_files_do_not_hold(&csv);
}

/// `bench --quick` on the reduced model: both charts, every method, the
/// table, and rows in `csv` that read back.
fn quick_sweep_prints_and_writes(csv: &Path) -> Vec<Row> {
    let out = spintop(&[
        "bench",
        "--quick",
        "--model",
        "reduced",
        "--repeats",
        "1",
        "--out",
        csv.to_str().unwrap(),
    ]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(stdout.contains("reference: "), "{stdout}");
    assert!(stdout.contains("error of Ω against time"), "{stdout}");
    assert!(
        stdout.contains("error of Ω against RHS evaluations"),
        "{stdout}"
    );
    assert!(stdout.contains("8 dop853") && stdout.contains("C closed-form"));
    assert!(stdout.contains("[reduced]"), "{stdout}");
    for method in [
        "closed-form",
        "rk4",
        "dopri5",
        "dop853",
        "closed-form+dop853",
        "radau5",
        "rotation-damping",
        "taylor",
    ] {
        assert!(stdout.contains(method), "{method} missing:\n{stdout}");
    }
    assert!(stdout.contains("reduced: fastest: at 1e-8"), "{stdout}");
    let rows = report::parse_csv(&std::fs::read_to_string(csv).unwrap()).unwrap();
    assert!(rows.len() >= 20, "{}", rows.len());
    assert!(rows.iter().all(|r| r.ok() && r.model == "reduced"));
    assert!(rows.iter().all(|r| r.time_s.is_some_and(|t| t > 0.0)));
    rows
}

/// The join reads the file back (alone here: a run joined with itself,
/// ratio 1) and names the best integrator at 1e-12 the file's.
fn join_alone_names_the_fastest_integrator(csv: &Path, rows: &[Row]) {
    let out = spintop(&["bench", "--join", csv.to_str().unwrap()]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // The best integrator at 1e-12 is the one whose matched time is least
    // in the file (which one depends on the machine's timing that day: the
    // join must name the file's, whichever it is).
    let matched = report::matched(rows);
    let i = report::MATCHED_ERRORS
        .iter()
        .position(|&e| e == 1e-12)
        .unwrap();
    let fastest = matched
        .iter()
        .filter(|m| m.source == "spintop" && !m.method.starts_with("closed-form"))
        .filter(|m| m.time[i].is_some())
        .min_by(|a, b| a.time[i].unwrap().total_cmp(&b.time[i].unwrap()))
        .expect("a spintop method reaches 1e-12");
    assert!(
        stdout.contains("time @1e-8")
            && stdout.contains(&format!(
                "best integrator at 1e-12: spintop {} ",
                fastest.method
            )),
        "{stdout}"
    );
}

/// Joined with a peer's file, the chart draws the peer's curve beside
/// spintop's: here a copy of the DOP853 rows under another source's name,
/// twice as slow.
fn join_with_a_peer_draws_its_curve(csv: &Path, rows: &[Row]) {
    let mut peer: Vec<_> = rows
        .iter()
        .filter(|r| r.method == "dop853" && r.target == spintop::workprecision::Target::Omega)
        .cloned()
        .collect();
    assert!(!peer.is_empty());
    for r in &mut peer {
        r.source = "elsewhere".into();
        r.time_s = r.time_s.map(|t| 2.0 * t);
    }
    let peer_csv = scratch("elsewhere.csv");
    std::fs::write(&peer_csv, report::to_csv(&peer)).unwrap();
    let out = spintop(&[
        "bench",
        "--join",
        csv.to_str().unwrap(),
        peer_csv.to_str().unwrap(),
        "--width",
        "50",
    ]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        stdout.contains("reduced model, T = 200: max relative error of Ω against time")
            && stdout.contains("error of Ω against RHS evaluations"),
        "{stdout}"
    );
    let legend = stdout
        .lines()
        .find(|l| l.contains("8 dop853"))
        .expect("a legend");
    assert!(legend.contains("e elsewhere dop853"), "{legend}");
    peer_markers_sit_where_spintops_do(csv, &stdout);
    assert!(stdout.contains("elsewhere    dop853"), "{stdout}");
}

/// The lines of the time chart (the first chart) below its legend.
fn time_chart_lines(stdout: &str) -> Vec<&str> {
    stdout
        .split("against RHS evaluations")
        .next()
        .unwrap()
        .lines()
        .skip_while(|l| !l.contains("8 dop853"))
        .skip(1)
        .collect()
}

/// (row, column) of each character of the evaluations chart (the second
/// chart) that `mark` picks, on its plot lines.
fn evaluation_markers(text: &str, mark: fn(char) -> bool) -> Vec<(usize, usize)> {
    let chart = text.split_once("against RHS evaluations").unwrap().1;
    chart
        .lines()
        .skip_while(|l| !l.contains("8 dop853"))
        .skip(1)
        .take_while(|l| l.starts_with(|c| ('\u{2800}'..='\u{28FF}').contains(&c)))
        .filter(|l| !l.contains("1e"))
        .enumerate()
        .flat_map(|(row, l)| {
            l.chars()
                .enumerate()
                .filter(move |&(_, c)| mark(c))
                .map(move |(col, _)| (row, col))
        })
        .collect()
}

/// Where the peer's markers are drawn in `stdout` (the join of `csv` with
/// the peer's file): the peer's rows are spintop's DOP853 rows with the same
/// RHS evaluations, so on the evaluations chart every 'e' must sit exactly
/// where spintop's '8' sits when its file is charted alone (at the same
/// width; the evaluations set the same axis). On the time chart, twice the
/// time puts each 'e' log10(2) of a decade right of its '8' (about 4 columns
/// of this 50-column chart; the times are measured, so a marker may hide
/// another: at least two pairs must show it).
fn peer_markers_sit_where_spintops_do(csv: &Path, stdout: &str) {
    let alone = spintop(&["bench", "--join", csv.to_str().unwrap(), "--width", "50"]);
    let alone = text(&alone.stdout);
    // (Where two methods share a point one marker hides the other.)
    let peer = evaluation_markers(stdout, |c| c == 'e');
    let eights = evaluation_markers(&alone, |c| c == '8');
    let any = evaluation_markers(&alone, |c| c.is_ascii_alphanumeric());
    assert_eq!(peer.len(), 4, "one marker per tolerance:\n{stdout}");
    assert!(
        eights.iter().all(|p| peer.contains(p)) && peer.iter().all(|p| any.contains(p)),
        "peer {peer:?}, spintop's 8 {eights:?}\n{stdout}\n{alone}"
    );
    let time_chart = time_chart_lines(stdout);
    let time_lines: Vec<&str> = time_chart
        .iter()
        .copied()
        .filter(|l| !l.contains("1e-"))
        .collect();
    let pairs = time_lines
        .iter()
        .filter(|line| {
            let chars: Vec<char> = line.chars().collect();
            chars
                .iter()
                .position(|&c| c == 'e')
                .is_some_and(|e| (3..=5).any(|d| e >= d && chars[e - d] == '8'))
        })
        .count();
    assert!(
        pairs >= 2,
        "'e' about 4 columns right of '8':\n{}",
        time_lines.join("\n")
    );
    let time_chart: String = time_chart.concat();
    assert!(
        time_chart.contains('e') && time_chart.contains('8'),
        "{stdout}"
    );
}

/// A problem the files do not hold cannot be charted: one line, exit 2.
fn join_refuses_a_problem_the_files_do_not_hold(csv: &Path) {
    let out = spintop(&[
        "bench",
        "--join",
        csv.to_str().unwrap(),
        "--chart",
        "general",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("--chart general"), "{err}");
    assert!(out.stdout.is_empty(), "{}", text(&out.stdout));
}

#[test]
fn bench_json_out_is_one_object_with_rows() {
    let json = scratch("general.json");
    let out = spintop(&[
        "bench",
        "--quick",
        "--model",
        "general",
        "--repeats",
        "1",
        "--out",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert!(!rows.is_empty());
    for key in report::CSV_COLUMNS {
        assert!(rows[0].get(key).is_some(), "{key}");
    }
}

#[test]
fn bench_bad_input_exits_2_with_one_line() {
    let missing = scratch("does-not-exist.csv");
    let garbage = scratch("garbage.csv");
    std::fs::write(&garbage, "source,model\nspintop,reduced\n").unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["bench", "--out", "rows.txt"],
        vec!["bench", "--repeats", "0"],
        vec!["bench", "--model", "reduced", "--chart", "general"],
        vec!["bench", "--chart", "all"],
        vec!["bench", "--width", "5"],
        vec!["bench", "--model", "sideways"],
        vec!["bench", "--join", missing.to_str().unwrap()],
        vec!["bench", "--join", garbage.to_str().unwrap()],
        vec!["bench", "--join", garbage.to_str().unwrap(), "--quick"],
    ];
    for args in cases {
        let out = spintop(&args);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("spintop: error: "), "{err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// An `--out` that cannot be written is refused before the sweep: nothing
/// on stdout, exit 2 (it used to time every method, print the charts and
/// the table, and only then fail).
#[test]
fn bench_out_that_cannot_be_written_is_refused_before_the_sweep() {
    let dir = scratch("bench-out-folder").join("rows.csv");
    std::fs::create_dir_all(&dir).unwrap();
    let out = spintop(&["bench", "--quick", "--out", dir.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(out.stdout.is_empty(), "{}", text(&out.stdout));
    assert!(stderr.contains("cannot write --out"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}
