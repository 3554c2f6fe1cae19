//! `--spread FILE…` of the peers bench: several runs' `--h2h-out` files
//! side by side, each ratio's median per run and then across the runs.

use super::median;
use spintop::math::Real;
use spintop::numbers;
use std::collections::BTreeMap;

/// (model, error, source method).
type Key = (String, String, String);
/// One run: per key, the time of each round.
type Run = BTreeMap<Key, Vec<Real>>;

/// Read each `--h2h-out` file: `model,error,source,method,round,time_s`.
fn read_runs(files: &[String]) -> Result<Vec<Run>, String> {
    let mut runs = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(f).map_err(|e| format!("{f}: {e}"))?;
        let mut map = Run::new();
        for (n, line) in text.lines().enumerate().skip(1) {
            let c: Vec<&str> = line.split(',').collect();
            if c.len() != 6 {
                return Err(format!("{f}:{}: expected 6 fields", n + 1));
            }
            let t: Real = c[5].parse().map_err(|_| format!("{f}:{}: time", n + 1))?;
            map.entry((c[0].into(), c[1].into(), format!("{} {}", c[2], c[3])))
                .or_default()
                .push(t);
        }
        runs.push(map);
    }
    Ok(runs)
}

/// Each (model, error) any run holds, in the order first seen.
fn groups(runs: &[Run]) -> Vec<(String, String)> {
    let mut groups: Vec<(String, String)> = Vec::new();
    for run in runs {
        for (m, e, _) in run.keys() {
            if !groups.contains(&(m.clone(), e.clone())) {
                groups.push((m.clone(), e.clone()));
            }
        }
    }
    groups
}

/// One ratio's line: the median of the runs' medians, their extremes,
/// whether they agree within 10 %, and each run's.
fn report_ratio(model: &str, error: &str, label: String, per_run: Vec<Real>) {
    let lo = per_run.iter().copied().fold(Real::INFINITY, Real::min);
    let hi = per_run.iter().copied().fold(0.0, Real::max);
    let Some(m) = median(per_run.clone()) else {
        return;
    };
    let stable = if hi / lo < 1.1 {
        "stable"
    } else {
        "within noise"
    };
    let each: Vec<String> = per_run.iter().map(|r| numbers::fixed(*r, 2)).collect();
    println!(
        "{model:<9} {error:>6}  {label:<60} {m} [{lo}, {hi}]  {stable}  (runs: {})",
        each.join(" "),
        m = numbers::fixed(m, 2),
        lo = numbers::fixed(lo, 2),
        hi = numbers::fixed(hi, 2)
    );
}

/// The fastest finite time of round `r` among `names` in `run`.
fn best_of<'a>(
    run: &Run,
    model: &str,
    error: &str,
    names: impl Iterator<Item = &'a String>,
    r: usize,
) -> Real {
    names
        .filter_map(|n| {
            run.get(&(model.to_string(), error.to_string(), n.clone()))
                .and_then(|t| t.get(r).copied())
        })
        .filter(|t| t.is_finite())
        .fold(Real::INFINITY, Real::min)
}

/// The ratios of one (model, error): each peer over spintop's DOP853 and
/// over spintop's best, and the best Runge–Kutta method over Taylor.
fn report_group(runs: &[Run], model: &str, error: &str) {
    let mut names: Vec<String> = Vec::new();
    for run in runs {
        for (m, e, name) in run.keys() {
            if m == model && e == error && !names.contains(name) {
                names.push(name.clone());
            }
        }
    }
    let of = |run: &Run, name: &str| {
        run.get(&(model.to_string(), error.to_string(), name.to_string()))
            .cloned()
    };
    let ours = || names.iter().filter(|n| n.starts_with("spintop "));
    let peers = || names.iter().filter(|n| !n.starts_with("spintop "));
    // Each peer over spintop's DOP853 (the same method: the historical
    // ratio), round by round.
    for peer in peers() {
        let per_run: Vec<Real> = runs
            .iter()
            .filter_map(|run| {
                let (p, d) = (of(run, peer)?, of(run, "spintop dop853")?);
                median(p.iter().zip(&d).map(|(a, b)| a / b).collect())
            })
            .collect();
        report_ratio(model, error, format!("{peer} / spintop dop853"), per_run);
    }
    // Each peer over spintop's best, round by round.
    for peer in peers() {
        let per_run: Vec<Real> = runs
            .iter()
            .filter_map(|run| {
                let p = of(run, peer)?;
                let ratios = (0..p.len())
                    .map(|r| p[r] / best_of(run, model, error, ours(), r))
                    .collect();
                median(ratios)
            })
            .collect();
        report_ratio(model, error, format!("{peer} / spintop's best"), per_run);
    }
    // The best Runge–Kutta method of any crate over the Taylor method.
    let per_run: Vec<Real> = runs
        .iter()
        .filter_map(|run| {
            let t = of(run, "spintop taylor")?;
            let rk = || names.iter().filter(|n| *n != "spintop taylor");
            let ratios = (0..t.len())
                .map(|r| best_of(run, model, error, rk(), r) / t[r])
                .collect();
            median(ratios)
        })
        .collect();
    report_ratio(
        model,
        error,
        "best Runge-Kutta (any crate) / spintop taylor".into(),
        per_run,
    );
}

/// `--spread FILE…`: several runs' `--h2h-out` files side by side. For each
/// problem and matched error, each peer's ratio to spintop's best and the
/// best Runge–Kutta method's ratio to the Taylor method, as the median over
/// the rounds of each run, then across the runs: median [smallest, largest]
/// of the runs' medians, called stable when the largest run's median is
/// within 10 % of the smallest's. Each peer is given over spintop's DOP853
/// (the same method) and over spintop's best method in the same round.
pub fn spread_of_runs(files: &[String]) -> Result<(), String> {
    let runs = read_runs(files)?;
    println!(
        "# {} runs: per ratio, the median of each run (over its rounds), then across runs: median [smallest, largest]; 'stable' when the runs' medians differ by less than 10 %",
        runs.len()
    );
    for (model, error) in groups(&runs) {
        report_group(&runs, &model, &error);
    }
    Ok(())
}
