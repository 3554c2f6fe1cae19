//! The book's figures drawn by code: the paper's figures by `spintop
//! figure`, and the speed chapter's charts from the committed benchmark runs,
//! with the numbers the chapter gives from them.

use super::{book_src, figure_is_current, root, summary_chapters};
use std::collections::BTreeMap;
use std::fs;

/// The paper's figures in the book are what `spintop figure N --svg FILE`
/// draws now, and a chapter embeds each of them.
#[test]
fn book_figures_are_what_spintop_figure_draws_now() {
    let update = std::env::var_os("UPDATE_BOOK").is_some();
    let mut problems = Vec::new();
    for n in ["1", "2"] {
        let fresh_path = std::env::temp_dir().join(format!(
            "spintop-book-figure-{n}-{}.svg",
            std::process::id()
        ));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_spintop"))
            .args(["figure", n, "--svg"])
            .arg(&fresh_path)
            .output()
            .expect("the binary runs");
        assert!(
            out.status.success(),
            "spintop figure {n}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let fresh = fs::read_to_string(&fresh_path).expect("the SVG was written");
        fs::remove_file(&fresh_path).unwrap();
        let name = format!("figures/figure-{n}.svg");
        let shown = book_src().join(&name);
        if update {
            fs::create_dir_all(shown.parent().unwrap()).unwrap();
            fs::write(&shown, &fresh).unwrap();
        } else if fs::read_to_string(&shown).unwrap_or_default() != fresh {
            problems.push(format!(
                "the book's {name} is not what `spintop figure {n} --svg` draws now; run UPDATE_BOOK=1 cargo test -p spintop-app --test app project::"
            ));
        }
        let embedded = summary_chapters().iter().any(|c| {
            fs::read_to_string(book_src().join(c))
                .unwrap_or_default()
                .contains(&format!("]({name})"))
        });
        assert!(embedded, "no chapter embeds {name}");
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The speed chapter's cost-against-horizon chart is drawn by code from the
/// committed benchmark medians (benches/results/horizon-2026-11-25.csv).
#[test]
fn book_cost_horizon_figure_is_drawn_from_the_committed_medians() {
    let csv = fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("benches/results/horizon-2026-11-25.csv"),
    )
    .unwrap();
    let fresh = spintop::workprecision::report::horizon_figure(&csv).expect("the medians parse");
    figure_is_current(
        "figures/cost-horizon.svg",
        &fresh,
        "speed-accuracy.md",
        "horizon_figure (from the CSV)",
    );
    // The closed form's cost does not grow with T; DOP853's does.
    let rows: Vec<(String, f64, f64)> = csv
        .lines()
        .skip(1)
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (
                c[0].to_string(),
                c[1].parse().unwrap(),
                c[2].parse().unwrap(),
            )
        })
        .collect();
    let of = |m: &str| -> Vec<f64> {
        rows.iter()
            .filter(|r| r.0.starts_with(m))
            .map(|r| r.2)
            .collect()
    };
    let (closed, dop) = (of("closed form"), of("DOP853"));
    assert!(
        closed.iter().cloned().fold(0.0, f64::max)
            < 1.5 * closed.iter().cloned().fold(f64::INFINITY, f64::min)
    );
    assert!(dop.last().unwrap() > &(100.0 * dop[0]));
}

/// The speed chapter's work-precision figure (time of a solve against its
/// error, the Taylor method beside the Runge–Kutta methods of every crate)
/// is drawn by code from a committed peers run, and the numbers the chapter
/// gives from that run are the run's: the best Runge–Kutta method's time
/// over the Taylor method's at matched errors 1e-8 and 1e-14 in its
/// interleaved head-to-head (median over the rounds), spintop's DOP853 being
/// that best method in most rounds at 1e-14, whether the 2× goal on the
/// general top is met, and where DOP853 is the faster at loose tolerances
/// in the sweep.
#[test]
fn book_work_precision_figure_is_drawn_from_the_committed_peers_run() {
    use spintop::workprecision::{Target, report};
    let read = |file: &str| fs::read_to_string(root().join(file)).unwrap();
    let rows = report::parse_csv(&read(TAYLOR_PEERS_RUN)).expect("the run parses");
    let fresh = report::work_precision_figure(&rows).expect("rows to draw");
    let chapter = figure_is_current(
        "figures/work-precision.svg",
        &fresh,
        "speed-accuracy.md",
        &format!("work_precision_figure (from {TAYLOR_PEERS_RUN})"),
    );
    // The claims are read across line breaks.
    let chapter = chapter.split_whitespace().collect::<Vec<_>>().join(" ");
    for file in [TAYLOR_PEERS_RUN, TAYLOR_H2H_RUN] {
        assert!(chapter.contains(file), "the chapter names {file}");
    }
    // The head-to-head: (model, error, "source method") -> time per round.
    let mut h2h: BTreeMap<(String, String, String), Vec<f64>> = BTreeMap::new();
    for line in read(TAYLOR_H2H_RUN).lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let key = (
            c[0].to_string(),
            c[1].to_string(),
            format!("{} {}", c[2], c[3]),
        );
        h2h.entry(key).or_default().push(c[5].parse().unwrap());
    }
    // The best Runge–Kutta time over the Taylor method's, median over the
    // rounds, and how often each method was the best Runge–Kutta method.
    let versus_rk = |model: &str, error: &str| -> (f64, BTreeMap<String, usize>) {
        let at =
            |name: &str| h2h[&(model.to_string(), error.to_string(), name.to_string())].clone();
        let taylor = at("spintop taylor");
        let others: Vec<(&String, &Vec<f64>)> = h2h
            .iter()
            .filter(|((m, e, n), _)| m == model && e == error && n != "spintop taylor")
            .map(|((_, _, n), t)| (n, t))
            .collect();
        let mut best_names = BTreeMap::new();
        let mut ratios: Vec<f64> = (0..taylor.len())
            .map(|r| {
                let (name, best) = others
                    .iter()
                    .map(|(n, t)| (n, t[r]))
                    .filter(|(_, t)| t.is_finite())
                    .fold(
                        (&others[0].0, f64::INFINITY),
                        |a, b| if b.1 < a.1 { b } else { a },
                    );
                *best_names.entry(name.to_string()).or_insert(0) += 1;
                best / taylor[r]
            })
            .collect();
        ratios.sort_by(f64::total_cmp);
        (ratios[ratios.len() / 2], best_names)
    };
    let models = ["truncated model", "reduced model", "general top"];
    for (error, words) in [("1e-14", "an error of 10⁻¹⁴"), ("1e-8", "an error of 10⁻⁸")] {
        let ratios: Vec<String> = ["truncated", "reduced", "general"]
            .iter()
            .map(|m| format!("{:.1}×", versus_rk(m, error).0))
            .collect();
        let claim = format!(
            "at {words} {} on the {}, {} on the {} and {} on the {}",
            ratios[0], models[0], ratios[1], models[1], ratios[2], models[2]
        );
        assert!(chapter.contains(&claim), "the chapter should say: {claim}");
    }
    for model in ["truncated", "reduced", "general"] {
        let names = versus_rk(model, "1e-14").1;
        let most = names
            .iter()
            .max_by_key(|(_, n)| **n)
            .map(|(m, _)| m.as_str());
        assert_eq!(most, Some("spintop dop853"), "{model}: {names:?}");
    }
    let goal = versus_rk("general", "1e-14").0 >= 2.0;
    let verdict = if goal {
        "the goal of 2× on the general top is met"
    } else {
        "the goal of 2× on the general top is missed"
    };
    assert!(
        chapter.contains(verdict),
        "the chapter should say: {verdict}"
    );
    // Loose tolerances, in the sweep: DOP853's time at a matched error of
    // 1e-5 (interpolated in log-log as the join does) against the Taylor
    // method's, per problem, as the chapter words it.
    let at_1e5 = |model: &str, method: &str| {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.ok() && r.target == Target::Omega && r.model == model)
            .filter(|r| r.source == "spintop" && r.method == method)
            .filter_map(|r| Some((r.time_s?, r.omega_error?)))
            .collect();
        report::cost_at(&points, 1e-5).unwrap()
    };
    let dop853_faster: Vec<&str> = ["truncated", "reduced", "general"]
        .into_iter()
        .filter(|m| at_1e5(m, "dop853") < at_1e5(m, "taylor"))
        .collect();
    let claim = match dop853_faster[..] {
        [] => {
            "at an error of 10⁻⁵ the Taylor method is the faster on all three problems".to_string()
        }
        [m] => format!("at an error of 10⁻⁵ DOP853 is the faster on the {m} problem"),
        [a, b] => format!("at an error of 10⁻⁵ DOP853 is the faster on the {a} and {b} problems"),
        _ => "at an error of 10⁻⁵ DOP853 is the faster on all three problems".to_string(),
    };
    assert!(chapter.contains(&claim), "the chapter should say: {claim}");
}

/// The peers run the speed chapter's work-precision figure is drawn from,
/// and the interleaved head-to-head of the same run.
const TAYLOR_PEERS_RUN: &str = "benches/results/peers-2026-11-26-taylor.csv";
const TAYLOR_H2H_RUN: &str = "benches/results/peers-h2h-2026-11-26-run3.csv";
