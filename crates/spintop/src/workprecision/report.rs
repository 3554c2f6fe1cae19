//! The sweep's rows as text: the table, the two log-log charts, CSV and JSON,
//! and the join of runs from different tools at matched error.
//!
//! Strings in, strings out: the command line and the peers bench do the
//! writing. The CSV columns are the contract that SciPy's script
//! (`benches/scipy_work_precision.py`) and the peers bench follow too:
//!
//! ```text
//! source,model,method,target,knob,value,omega_error,orientation_error,rhs_evals,steps,rejected,time_s,repeats,status
//! ```
//!
//! An unknown value is an empty cell.

use super::{KnobKind, Row, Target};
use crate::math::Real;
use crate::plot::{Marked, loglog_chart};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The CSV header, in order.
pub const CSV_COLUMNS: [&str; 14] = [
    "source",
    "model",
    "method",
    "target",
    "knob",
    "value",
    "omega_error",
    "orientation_error",
    "rhs_evals",
    "steps",
    "rejected",
    "time_s",
    "repeats",
    "status",
];

/// The matched errors of the join: where a student's question usually sits
/// (1e-8), and down to the last digits a double holds (1e-14), where the
/// methods part ways.
pub const MATCHED_ERRORS: [Real; 4] = [1e-8, 1e-10, 1e-12, 1e-14];

/// The index of `error` in [`MATCHED_ERRORS`].
pub fn matched_index(error: Real) -> Option<usize> {
    MATCHED_ERRORS.iter().position(|&e| e == error)
}

/// A count's cell, empty where there is none.
fn cell<T: ToString>(x: Option<T>) -> String {
    x.map(|v| v.to_string()).unwrap_or_default()
}

/// A number's cell (lossless, [`crate::numbers::csv`]), empty where there is none.
fn real_cell(x: Option<Real>) -> String {
    x.map(crate::numbers::csv).unwrap_or_default()
}

/// The rows as CSV with a header line (full precision, `.` decimal point).
pub fn to_csv(rows: &[Row]) -> String {
    let mut out = CSV_COLUMNS.join(",");
    out.push('\n');
    for r in rows {
        // NOTE: a failure message is free text; commas and line breaks would
        // break the columns, so they become semicolons and spaces.
        let status = r.status.replace(',', ";").replace(['\n', '\r'], " ");
        let fields = [
            r.source.clone(),
            r.model.clone(),
            r.method.clone(),
            r.target.name().to_string(),
            r.knob.name().to_string(),
            real_cell(r.value),
            real_cell(r.omega_error),
            real_cell(r.orientation_error),
            cell(r.rhs_evals),
            cell(r.steps),
            cell(r.rejected),
            real_cell(r.time_s),
            r.repeats.to_string(),
            status,
        ];
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    out
}

/// The rows as one JSON object `{"columns": [...], "rows": [...]}`.
pub fn to_json(rows: &[Row]) -> String {
    serde_json::json!({ "columns": CSV_COLUMNS, "rows": rows }).to_string()
}

/// Read rows written by [`to_csv`] (or by SciPy's script). Errors name the line.
pub fn parse_csv(text: &str) -> Result<Vec<Row>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err("the file is empty".into());
    };
    let names: Vec<&str> = header.trim().split(',').collect();
    let index = |col: &str| names.iter().position(|n| *n == col);
    let columns: Vec<usize> = CSV_COLUMNS
        .iter()
        .map(|c| index(c).ok_or_else(|| format!("the header has no column '{c}'")))
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for (n, line) in lines {
        let at = |line_no: usize, what: &str| format!("line {}: {what}", line_no + 1);
        let fields: Vec<&str> = line.trim_end_matches('\r').split(',').collect();
        if fields.len() != names.len() {
            return Err(at(
                n,
                &format!("{} fields for {} columns", fields.len(), names.len()),
            ));
        }
        let get = |i: usize| fields[columns[i]].trim();
        let real = |i: usize| -> Result<Option<Real>, String> {
            let s = get(i);
            if s.is_empty() {
                return Ok(None);
            }
            // NOTE: Python writes inf and nan, and Rust reads both; a row
            // holding one is refused, not charted as nothing (an empty cell
            // is how a run that measured nothing says so).
            match s.parse::<Real>() {
                Ok(x) if x.is_finite() => Ok(Some(x)),
                Ok(_) => Err(at(
                    n,
                    &format!("{} '{s}' is not a finite number", CSV_COLUMNS[i]),
                )),
                Err(_) => Err(at(n, &format!("{} '{s}' is not a number", CSV_COLUMNS[i]))),
            }
        };
        // An error or a time below zero, a tolerance or a step not above
        // it, is no measurement.
        let at_least = |i: usize, positive: bool| -> Result<Option<Real>, String> {
            match real(i)? {
                Some(x) if x < 0.0 || (positive && x == 0.0) => Err(at(
                    n,
                    &format!(
                        "{} '{}' is {}; expected a number {}",
                        CSV_COLUMNS[i],
                        get(i),
                        if x < 0.0 { "negative" } else { "zero" },
                        if positive { "above 0" } else { ">= 0" }
                    ),
                )),
                x => Ok(x),
            }
        };
        let count = |i: usize| -> Result<Option<u64>, String> {
            let s = get(i);
            if s.is_empty() {
                return Ok(None);
            }
            s.parse::<u64>()
                .map(Some)
                .map_err(|_| at(n, &format!("{} '{s}' is not a count", CSV_COLUMNS[i])))
        };
        let target = Target::from_name(get(3))
            .ok_or_else(|| at(n, &format!("unknown target '{}'", get(3))))?;
        let knob = KnobKind::from_name(get(4))
            .ok_or_else(|| at(n, &format!("unknown knob '{}'", get(4))))?;
        rows.push(Row {
            source: get(0).to_string(),
            model: get(1).to_string(),
            method: get(2).to_string(),
            target,
            knob,
            value: at_least(5, true)?,
            omega_error: at_least(6, false)?,
            orientation_error: at_least(7, false)?,
            rhs_evals: count(8)?,
            steps: count(9)?,
            rejected: count(10)?,
            time_s: at_least(11, false)?,
            // NOTE: a count past u32 is refused, not cut (`as` kept 4294967297 as 1).
            repeats: count(12)?
                .map(u32::try_from)
                .transpose()
                .map_err(|_| at(n, &format!("repeats '{}' is too large", get(12))))?
                .unwrap_or(0),
            status: get(13).to_string(),
        });
    }
    Ok(rows)
}

// The table's numbers are written by the crate's one number module.
pub use crate::numbers::{duration, sci};

fn knob_text(r: &Row) -> String {
    match (r.knob, r.value) {
        (KnobKind::None, _) | (_, None) => "-".into(),
        (KnobKind::Step, Some(h)) => format!("h={h}"),
        (k, Some(v)) => format!("{}={v:.0e}", k.name()),
    }
}

/// The rows as an aligned table, one line per row, grouped by problem.
pub fn table(rows: &[Row]) -> String {
    let header = [
        "source", "method", "target", "knob", "err Ω", "err O", "evals", "steps", "rej", "time",
    ];
    let mut lines: Vec<(&str, Vec<String>, &str)> = Vec::new();
    for r in rows {
        let cells = vec![
            r.source.clone(),
            r.method.clone(),
            r.target.name().to_string(),
            knob_text(r),
            sci(r.omega_error),
            sci(r.orientation_error),
            cell(r.rhs_evals),
            cell(r.steps),
            cell(r.rejected),
            duration(r.time_s),
        ];
        lines.push((&r.model, cells, &r.status));
    }
    let mut width: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for (_, cells, _) in &lines {
        for (w, c) in width.iter_mut().zip(cells) {
            *w = (*w).max(c.chars().count());
        }
    }
    let render = |cells: &[String]| {
        let mut s = String::new();
        for (i, (c, w)) in cells.iter().zip(&width).enumerate() {
            let pad = w - c.chars().count();
            // Text columns to the left, numbers to the right.
            if i < 4 {
                s.push_str(c);
                s.push_str(&" ".repeat(pad));
            } else {
                s.push_str(&" ".repeat(pad));
                s.push_str(c);
            }
            s.push_str("  ");
        }
        s.trim_end().to_string()
    };
    let mut out = String::new();
    let mut model = None;
    for (m, cells, status) in &lines {
        if model != Some(*m) {
            let _ = writeln!(out, "\n[{m}]");
            let head: Vec<String> = header.iter().map(|h| h.to_string()).collect();
            let _ = writeln!(out, "{}", render(&head));
            model = Some(*m);
        }
        let failed = if *status == "ok" {
            String::new()
        } else {
            format!("  failed: {status}")
        };
        let _ = writeln!(out, "{}{failed}", render(cells));
    }
    out
}

/// The horizontal axis of a chart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CostAxis {
    /// Median wall time of a solve.
    Time,
    /// Right-hand-side evaluations of a solve.
    Evals,
}

/// An error of exactly 0 (the reference itself) is drawn here.
pub const ERROR_FLOOR: Real = 1e-17;

/// The marker of a method in the charts.
pub fn marker(source: &str, method: &str) -> char {
    match (source, method) {
        ("spintop", "closed-form") => 'C',
        ("spintop", "closed-form+dop853") => 'c',
        ("spintop", "rk4") => '4',
        ("spintop", "dopri5") => '5',
        ("spintop", "dop853") => '8',
        ("spintop", "taylor") => 't',
        ("spintop", "physical") => 'P',
        // Reserved for the methods being added (see `Method`).
        ("spintop", "radau5") => 'I',
        ("spintop", "strang") => 'S',
        ("spintop", "yoshida4") => 'Y',
        ("spintop", "rotation-damping") => 'X',
        ("ode_solvers", "Dopri5") => 'd',
        ("ode_solvers", "Dop853") => 'D',
        ("ode_solvers", "Dop853 (t<200)") => 'x',
        ("differential-equations", "dop853") => 'e',
        ("differential-equations", "rkv988e") => 'V',
        ("diffsol", "tsit45") => 'T',
        ("scipy", "RK45") => 'r',
        ("scipy", "DOP853") => 's',
        ("scipy", "Radau") => 'R',
        ("scipy", "LSODA") => 'L',
        ("scipy", "odeint") => 'O',
        ("scipy", "cvode-adams") => 'A',
        ("scipy", "cvode-bdf") => 'B',
        // Another source's method: its source's initial (a clash within
        // one chart is resolved by `curves`).
        _ => source.chars().next().unwrap_or('?'),
    }
}

/// Markers for curves whose own marker another curve of the chart already has.
const MARKER_POOL: &str = "abfghjkmnpqtuvwyzEFGHJKMNQUWZ0123679*#@%&";

/// The Ω rows of one problem as one curve per (source, method), in cost order.
fn curves(rows: &[Row], model: &str, target: Target, axis: CostAxis) -> Vec<Marked> {
    let mut groups: BTreeMap<(String, String), Vec<(Real, Real)>> = BTreeMap::new();
    let mut order: Vec<(String, String)> = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.ok() && r.model == model && r.target == target)
    {
        let cost = match axis {
            CostAxis::Time => r.time_s,
            CostAxis::Evals => r.rhs_evals.map(|n| n as Real),
        };
        // A closed form does no evaluations: it has no place on a log axis of them.
        let (Some(cost), Some(err)) = (cost.filter(|c| *c > 0.0), r.omega_error) else {
            continue;
        };
        let key = (r.source.clone(), r.method.clone());
        if !groups.contains_key(&key) {
            order.push(key.clone());
        }
        groups
            .entry(key)
            .or_default()
            .push((cost, err.max(ERROR_FLOOR)));
    }
    let mut used: Vec<char> = Vec::new();
    order
        .into_iter()
        .filter_map(|key| {
            let mut points = groups.remove(&key)?;
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let label = if key.0 == "spintop" {
                key.1.clone()
            } else {
                format!("{} {}", key.0, key.1)
            };
            // Two curves of one chart never share a marker.
            let mut mark = marker(&key.0, &key.1);
            if used.contains(&mark) {
                mark = MARKER_POOL
                    .chars()
                    .find(|c| !used.contains(c))
                    .unwrap_or('?');
            }
            used.push(mark);
            Some(Marked {
                label,
                marker: mark,
                points,
            })
        })
        .collect()
}

/// The log-log chart of Ω's error against cost for one problem (its
/// [`Target::Omega`] rows); `None` when no row has both numbers.
pub fn chart(rows: &[Row], model: &str, axis: CostAxis, width: u32, height: u32) -> Option<String> {
    let curves = curves(rows, model, Target::Omega, axis);
    if curves.iter().all(|c| c.points.is_empty()) {
        return None;
    }
    let (x_label, what) = match axis {
        CostAxis::Time => ("wall time per solve [s]", "time"),
        CostAxis::Evals => ("RHS evaluations per solve", "RHS evaluations"),
    };
    let title = format!("{model} model, T = 200: max relative error of Ω against {what}");
    Some(loglog_chart(
        &title, x_label, "error", &curves, width, height,
    ))
}

// ANCHOR: cost_at
/// The cost needed to reach `error`, read off a method's (cost, error) points
/// by straight lines in log-log.
///
/// Walking from the cheapest point up, the answer lies on the first segment
/// that crosses below `error`: a method that reaches an error only by luck at
/// one loose tolerance and then loses it again does not get credit for it.
/// `None` when no point reaches `error`; the cheapest point when it already
/// does (no extrapolation).
pub fn cost_at(points: &[(Real, Real)], error: Real) -> Option<Real> {
    let mut pts: Vec<(Real, Real)> = points
        .iter()
        .copied()
        .filter(|(c, e)| c.is_finite() && *c > 0.0 && e.is_finite())
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let first = pts.iter().position(|p| p.1 <= error)?;
    if first == 0 {
        return Some(pts[0].0);
    }
    let (c0, e0) = pts[first - 1];
    let (c1, e1) = pts[first];
    let (l0, l1) = (e0.max(ERROR_FLOOR).log10(), e1.max(ERROR_FLOOR).log10());
    let s = (error.log10() - l0) / (l1 - l0);
    let log_cost = c0.log10() + s * (c1.log10() - c0.log10());
    Some((10.0 as Real).powf(log_cost))
}
// ANCHOR_END: cost_at

/// One method's cost at the matched errors.
#[derive(Clone, Debug, PartialEq)]
pub struct Matched {
    /// The problem.
    pub model: String,
    /// Whose implementation.
    pub source: String,
    /// The method.
    pub method: String,
    /// Wall time at each of [`MATCHED_ERRORS`].
    pub time: [Option<Real>; MATCHED_ERRORS.len()],
    /// RHS evaluations at each of [`MATCHED_ERRORS`].
    pub evals: [Option<Real>; MATCHED_ERRORS.len()],
}

/// Every (problem, source, method) of the [`Target::Omega`] rows, with its
/// cost at the matched errors.
pub fn matched(rows: &[Row]) -> Vec<Matched> {
    let mut keys: Vec<(String, String, String)> = Vec::new();
    for r in rows.iter().filter(|r| r.target == Target::Omega) {
        let key = (r.model.clone(), r.source.clone(), r.method.clone());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .map(|(model, source, method)| {
            let of = |cost: fn(&Row) -> Option<Real>| -> Vec<(Real, Real)> {
                rows.iter()
                    .filter(|r| {
                        r.ok()
                            && r.target == Target::Omega
                            && r.model == model
                            && r.source == source
                            && r.method == method
                    })
                    .filter_map(|r| Some((cost(r)?, r.omega_error?)))
                    .collect()
            };
            let time = of(|r| r.time_s);
            let evals = of(|r| r.rhs_evals.map(|n| n as Real));
            Matched {
                time: MATCHED_ERRORS.map(|e| cost_at(&time, e)),
                evals: MATCHED_ERRORS.map(|e| cost_at(&evals, e)),
                model,
                source,
                method,
            }
        })
        .collect()
}

/// The fastest integrator of `source` on `model` at matched error `i` (the
/// closed forms are not integrators: they are the limit, shown on their own).
pub fn best<'a>(m: &'a [Matched], model: &str, source: &str, i: usize) -> Option<&'a Matched> {
    m.iter()
        .filter(|x| {
            x.model == model
                && x.source == source
                && !x.method.starts_with("closed-form")
                && x.time[i].is_some()
        })
        .min_by(|a, b| {
            a.time[i]
                .unwrap_or(Real::INFINITY)
                .total_cmp(&b.time[i].unwrap_or(Real::INFINITY))
        })
}

/// The side-by-side table of a join: every method's time and evaluations at
/// each of [`MATCHED_ERRORS`], and per problem each source's best against
/// spintop's best (how many times longer it takes).
pub fn join_table(rows: &[Row]) -> String {
    let m = matched(rows);
    let mut out = String::new();
    let mut models: Vec<&str> = Vec::new();
    for x in &m {
        if !models.contains(&x.model.as_str()) {
            models.push(&x.model);
        }
    }
    let mut sources: Vec<&str> = Vec::new();
    for x in &m {
        if !sources.contains(&x.source.as_str()) {
            sources.push(&x.source);
        }
    }
    let fmt_evals = |e: Option<Real>| e.map(|v| format!("{v:.0}")).unwrap_or("-".into());
    for model in models {
        let _ = writeln!(
            out,
            "\n[{model}] cost at matched max relative error of Ω (interpolated in log-log; - = not reached)"
        );
        let mut head = format!("{:<12} {:<20}", "source", "method");
        for e in MATCHED_ERRORS {
            let _ = write!(head, " {:>12}", format!("time @{e:.0e}"));
        }
        for e in MATCHED_ERRORS {
            let _ = write!(head, " {:>11}", format!("evals {e:.0e}"));
        }
        let _ = writeln!(out, "{head}");
        for x in m.iter().filter(|x| x.model == model) {
            let mut line = format!("{:<12} {:<20}", x.source, x.method);
            for t in x.time {
                let _ = write!(line, " {:>12}", duration(t));
            }
            for e in x.evals {
                let _ = write!(line, " {:>11}", fmt_evals(e));
            }
            let _ = writeln!(out, "{line}");
        }
        for (i, e) in MATCHED_ERRORS.iter().enumerate() {
            let Some(ours) = best(&m, model, "spintop", i) else {
                continue;
            };
            let mut parts = vec![format!(
                "spintop {} {}",
                ours.method,
                duration(ours.time[i])
            )];
            for source in sources.iter().filter(|s| **s != "spintop") {
                if let Some(theirs) = best(&m, model, source, i) {
                    let ratio =
                        theirs.time[i].unwrap_or(Real::NAN) / ours.time[i].unwrap_or(Real::NAN);
                    parts.push(format!(
                        "{source} {} {} ({ratio:.1}x)",
                        theirs.method,
                        duration(theirs.time[i])
                    ));
                }
            }
            let _ = writeln!(out, "best integrator at {e:.0e}: {}", parts.join(" | "));
        }
    }
    out
}

/// The methods the book's work-precision figure draws, (source, method): the
/// Taylor method, spintop's two explicit pairs, and each compiled peer's best
/// Runge–Kutta method (`ode_solvers`' Dop853 with its extrapolated last value
/// replaced, its own accuracy). `spintop bench --join` charts everything.
pub const FIGURE_METHODS: [(&str, &str); 6] = [
    ("spintop", "taylor"),
    ("spintop", "dop853"),
    ("spintop", "dopri5"),
    ("ode_solvers", "Dop853 (t<200)"),
    ("differential-equations", "rkv988e"),
    ("diffsol", "tsit45"),
];

/// The book's work-precision figure from the rows of a peers run (`cargo
/// bench -p spintop-benches --bench peers -- --out FILE.csv`): one panel per
/// first-order problem, log₁₀ of the median time of one solve against log₁₀
/// of its error, one curve per method of [`FIGURE_METHODS`]. `None` when no
/// row has both numbers.
pub fn work_precision_figure(rows: &[Row]) -> Option<String> {
    let mut panels = Vec::new();
    for model in ["truncated", "reduced", "general"] {
        let mut curves = Vec::new();
        for (source, method) in FIGURE_METHODS {
            let mut points: Vec<(Real, Real)> = rows
                .iter()
                .filter(|r| r.ok() && r.target == Target::Omega && r.model == model)
                .filter(|r| r.source == source && r.method == method)
                .filter_map(|r| {
                    let err = r.omega_error?.max(ERROR_FLOOR);
                    Some((err.log10(), (r.time_s? * 1e6).log10()))
                })
                .collect();
            if points.is_empty() {
                continue;
            }
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let label = if source == "spintop" {
                method.to_string()
            } else {
                format!("{source} {method}")
            };
            curves.push((label, points));
        }
        if !curves.is_empty() {
            panels.push(crate::plot::panels::Panel {
                caption: format!("{model} model"),
                x_label: "log10 max relative error of Omega".into(),
                y_label: "log10 time of one solve [us]".into(),
                curves,
            });
        }
    }
    if panels.is_empty() {
        return None;
    }
    // The curves fall from the upper left (tight errors, slow) to the lower
    // right: the upper right corner is free for the legend.
    Some(crate::plot::panels::panels_svg_legend(
        "Work against precision, T = 200 tau, 200 outputs: the time of one solve against its error",
        &panels,
        plotters::prelude::SeriesLabelPosition::UpperRight,
    ))
}

/// The book's cost-against-horizon chart from the medians of `cargo bench -p
/// spintop-benches --bench solves -- "cost vs horizon"`, as CSV rows `method,t_end,median_us`
/// (lines starting with `#` are comments): log₁₀ of the time against log₁₀ T,
/// one curve per method. `None` if a row does not parse.
pub fn horizon_figure(csv: &str) -> Option<String> {
    let mut curves: Vec<(String, Vec<(Real, Real)>)> = Vec::new();
    for line in csv.lines().skip(1) {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let mut cells = line.split(',');
        let method = cells.next()?.trim().to_string();
        let t_end: Real = cells.next()?.trim().parse().ok()?;
        let micros: Real = cells.next()?.trim().parse().ok()?;
        if !(t_end > 0.0 && micros > 0.0) {
            return None;
        }
        let point = (t_end.log10(), micros.log10());
        match curves.iter_mut().find(|(m, _)| *m == method) {
            Some((_, points)) => points.push(point),
            None => curves.push((method, vec![point])),
        }
    }
    if curves.is_empty() {
        return None;
    }
    Some(crate::plot::panels::panels_svg(
        "The reduced model, 200 evenly spaced outputs on [0, T]: time of one solve",
        &[crate::plot::panels::Panel {
            caption: "log10 of the median time in microseconds against log10 T".into(),
            x_label: "log10 T [tau]".into(),
            y_label: "log10 time [us]".into(),
            curves,
        }],
    ))
}
