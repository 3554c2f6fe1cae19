//! Whole solves, one criterion benchmark each: the work-precision problems
//! (T = 200τ, 200 output points) by DOP853 and Dormand–Prince 5(4) at rtol
//! 1e-8 and 1e-12, and by the closed forms.
//!
//! ```sh
//! cargo bench --bench solves
//! ```
//!
//! Each solve is exactly a row of `spintop bench` (the same
//! `spintop::workprecision` entry), timed by criterion instead.

use criterion::{Criterion, criterion_group, criterion_main};
use spintop::workprecision::{Method, Problem, ProblemKind, Solver, Spintop, Target};
use std::hint::black_box;
use std::time::Duration;

fn solves(c: &mut Criterion) {
    for kind in [ProblemKind::Reduced, ProblemKind::General] {
        let problem = Problem::new(kind).expect("the problem and its reference");
        let mut g = c.benchmark_group(format!("solve {} T=200", kind.name()));
        for method in [Method::Dop853, Method::Dopri5] {
            let entry = Spintop {
                method,
                target: Target::Omega,
            };
            for rtol in [1e-8, 1e-12] {
                g.bench_function(format!("{} rtol {rtol:e}", method.name()), |b| {
                    b.iter(|| {
                        entry
                            .solve(black_box(&problem), Some(rtol))
                            .expect("a solve")
                    })
                });
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

criterion_group! {
    name = solve;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = solves
}
criterion_main!(solve);
