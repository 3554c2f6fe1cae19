//! Whole solves, one criterion benchmark each: the work-precision problems
//! (T = 200τ, 200 output points) by DOP853, Dormand–Prince 5(4) and the
//! Taylor method at rtol 1e-8 and 1e-12 (DOP853 and Taylor also at 1e-14),
//! and by the closed forms.
//!
//! ```sh
//! cargo bench -p spintop-benches --bench solves
//! ```
//!
//! Each solve is exactly a row of `spintop bench` (the same
//! `spintop::workprecision` entry), timed by criterion instead. Beside the
//! DOP853 rows, "bare Dop853" runs the stepper itself with a plain closure on
//! the same problem, options and output times: the product path should cost
//! what the stepper costs (issue goal: within 5 %).

use criterion::{Criterion, criterion_group, criterion_main};
use spintop::integrate::{self, AdaptiveOptions, Composition, Dop853, Splitting};
use spintop::math::{Real, State};
use spintop::physics::symmetric_top::{reduced_ale_rhs, reduced_closed_form_many};
use spintop::sim::Model;
use spintop::sim::split::ReducedFlow;
use spintop::workprecision::{Method, Problem, ProblemKind, Solver, Spintop, Target};
use std::hint::black_box;
use std::time::Duration;

fn solves(c: &mut Criterion) {
    for kind in [ProblemKind::Reduced, ProblemKind::General] {
        let problem = Problem::new(kind).expect("the problem and its reference");
        let mut g = c.benchmark_group(format!("solve {} T=200", kind.name()));
        for method in [Method::Dop853, Method::Dopri5, Method::Taylor] {
            let entry = Spintop {
                method,
                target: Target::Omega,
            };
            let rtols: &[Real] = if method == Method::Dopri5 {
                &[1e-8, 1e-12]
            } else {
                &[1e-8, 1e-12, 1e-14]
            };
            for &rtol in rtols {
                g.bench_function(format!("{} rtol {rtol:e}", entry.method()), |b| {
                    b.iter(|| {
                        entry
                            .solve(black_box(&problem), Some(rtol))
                            .expect("a solve")
                    })
                });
            }
        }
        for rtol in [1e-8, 1e-12] {
            let y0 = problem.initial().omega;
            let opts = AdaptiveOptions::new(rtol, problem.atol(rtol)).expect("valid tolerances");
            let times = problem.times();
            match *problem.model() {
                Model::Reduced(top) => {
                    g.bench_function(format!("bare Dop853 closure rtol {rtol:e}"), |b| {
                        b.iter(|| {
                            let mut s = Dop853::new(0.0, black_box(y0), opts).expect("a start");
                            let f = |_t: Real, w: &State<3>| reduced_ale_rhs(&top, w);
                            integrate::solve(&mut s, &f, times).expect("a solve")
                        })
                    });
                }
                Model::General(top) => {
                    g.bench_function(format!("bare Dop853 closure rtol {rtol:e}"), |b| {
                        b.iter(|| {
                            let mut s = Dop853::new(0.0, black_box(y0), opts).expect("a start");
                            let f = |_t: Real, w: &State<3>| top.truncated_ale_rhs(w);
                            integrate::solve(&mut s, &f, times).expect("a solve")
                        })
                    });
                }
                _ => {}
            }
        }
        let closed = Spintop {
            method: Method::ClosedForm,
            target: Target::Omega,
        };
        if closed.applies_to(&problem) {
            g.bench_function("closed form, 200 points", |b| {
                b.iter(|| closed.solve(black_box(&problem), None).expect("a solve"))
            });
        }
        g.finish();
    }
}

/// Cost against the horizon T (10 … 10⁶) with 200 evenly spaced outputs on
/// the reduced problem: the closed form (its recurrence), the Lie–Trotter
/// splitting of rotation and damping (exact flows) with step 0.5, and DOP853
/// at rtol 1e-10. `benches/results/horizon-*.csv` holds the medians, and the
/// book's speed chapter charts them (`workprecision::report::horizon_figure`).
fn horizon(c: &mut Criterion) {
    let problem = Problem::new(ProblemKind::Reduced).expect("the reduced problem");
    let Model::Reduced(top) = *problem.model() else {
        unreachable!("the reduced problem")
    };
    let y0 = problem.initial().omega;
    let rtol = 1e-10;
    let opts = AdaptiveOptions::new(rtol, problem.atol(rtol)).expect("valid tolerances");
    let mut g = c.benchmark_group("cost vs horizon");
    g.sample_size(10);
    for t_end in [1e1, 1e2, 1e3, 1e4, 1e5, 1e6] {
        let times: Vec<Real> = (0..200).map(|j| t_end * j as Real / 199.0).collect();
        g.bench_function(format!("closed form T={t_end:e}"), |b| {
            b.iter(|| reduced_closed_form_many(&top, &y0, black_box(&times)))
        });
        g.bench_function(format!("splitting h=0.5 T={t_end:e}"), |b| {
            b.iter(|| {
                let mut split =
                    Splitting::new(ReducedFlow(top), Composition::LieTrotter, 0.0, y0, 0.5)
                        .expect("a splitting");
                black_box(&times)
                    .iter()
                    .map(|&t| {
                        split.advance_to(t).expect("a step");
                        *split.state()
                    })
                    .collect::<Vec<_>>()
            })
        });
        g.bench_function(format!("dop853 rtol 1e-10 T={t_end:e}"), |b| {
            b.iter(|| {
                let mut s = Dop853::new(0.0, black_box(y0), opts).expect("a start");
                let f = |_t: Real, w: &State<3>| reduced_ale_rhs(&top, w);
                integrate::solve(&mut s, &f, &times).expect("a solve")
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = solve;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = solves, horizon
}
criterion_main!(solve);
