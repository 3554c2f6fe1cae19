//! The innermost costs, one criterion benchmark each: one right-hand-side
//! evaluation per model, one step per method, one closed-form evaluation.
//!
//! ```sh
//! cargo bench -p spintop-benches --bench kernels
//! ```
//!
//! The states are those of the work-precision problems (Ω₀ = (0, 0.1, 0.2),
//! I₃/I₁ = 0.4, τ = 1). A step is timed from a stepper that has already taken
//! one step, so its first stage is cached (FSAL) as it is in a run.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use spintop::integrate::taylor::{GeneralTruncated, SymmetricReduced};
use spintop::integrate::{AdaptiveOptions, Dop853, Dopri5, Rk4, Stepper, Taylor};
use spintop::math::{Mat3, State, Vec3};
use spintop::physics::full_ale::{general_full_ale_rhs, symmetric_full_ale_rhs};
use spintop::physics::general_top::GeneralTop;
use spintop::physics::symmetric_top::{
    SymmetricTop, reduced_ale_rhs, reduced_closed_form, reduced_closed_form_many,
    truncated_ale_rhs, truncated_closed_form, truncated_orientation,
};
use spintop::workprecision::problem::{GENERAL_DIPOLE, GENERAL_INERTIA, OMEGA0, RATIO};
use std::hint::black_box;
use std::time::Duration;

fn top() -> SymmetricTop {
    SymmetricTop::new(RATIO, 1.0).expect("the figure top")
}

fn rhs(c: &mut Criterion) {
    let top = top();
    let general = GeneralTop::new(Vec3::from(GENERAL_INERTIA), Vec3::from(GENERAL_DIPOLE))
        .expect("the general top");
    let omega = Vec3::from(OMEGA0);
    let mut g = c.benchmark_group("rhs");
    g.bench_function("truncated (4.2)-(4.4)", |b| {
        b.iter(|| truncated_ale_rhs(black_box(&top), black_box(&omega)))
    });
    g.bench_function("reduced (4.12)-(4.14)", |b| {
        b.iter(|| reduced_ale_rhs(black_box(&top), black_box(&omega)))
    });
    g.bench_function("general (3.3)", |b| {
        b.iter(|| black_box(&general).truncated_ale_rhs(black_box(&omega)))
    });
    let y4 = State::<4>::new(0.0, 0.1, -0.01, 0.0);
    g.bench_function("full ALE (3.4), symmetric", |b| {
        b.iter(|| symmetric_full_ale_rhs(black_box(&top), black_box(0.2), black_box(&y4)))
    });
    let y6 = State::<6>::new(0.0, 0.1, 0.2, -0.01, 0.0, 0.0);
    g.bench_function("full ALE (3.4), general", |b| {
        b.iter(|| general_full_ale_rhs(black_box(&general), black_box(&y6)))
    });
    g.finish();
}

fn step(c: &mut Criterion) {
    let top = top();
    let f = move |_t: f64, y: &State<3>| reduced_ale_rhs(&top, y);
    let y0 = Vec3::from(OMEGA0);
    let opts = AdaptiveOptions::new(1e-8, 1e-15).expect("valid tolerances");
    let mut g = c.benchmark_group("step (reduced model, rtol 1e-8)");
    g.bench_function("rk4 (4 evaluations)", |b| {
        b.iter(|| Rk4::step_once(&f, black_box(0.0), black_box(&y0), black_box(0.5)))
    });
    let mut dp5 = Dopri5::new(0.0, y0, opts).expect("a stepper");
    dp5.step(&f, 1e9).expect("a first step");
    g.bench_function("dopri5 (6 evaluations)", |b| {
        b.iter_batched(
            || dp5.clone(),
            |mut s| {
                s.step(&f, 1e9).expect("a step");
                s
            },
            BatchSize::SmallInput,
        )
    });
    let mut dop853 = Dop853::new(0.0, y0, opts).expect("a stepper");
    dop853.step(&f, 1e9).expect("a first step");
    let before = dop853.stats();
    let mut probe = dop853.clone();
    probe.step(&f, 1e9).expect("a step");
    assert_eq!(
        probe.stats().rejected,
        before.rejected,
        "the timed step is accepted"
    );
    g.bench_function("dop853 (12 evaluations)", |b| {
        b.iter_batched(
            || dop853.clone(),
            |mut s| {
                s.step(&f, 1e9).expect("a step");
                s
            },
            BatchSize::SmallInput,
        )
    });
    g.finish();
    // One Taylor step: the series to order p by recurrence, the step size
    // from its last two coefficients, the polynomial at the step's end.
    let general = GeneralTop::new(Vec3::from(GENERAL_INERTIA), Vec3::from(GENERAL_DIPOLE))
        .expect("the general top");
    let mut g = c.benchmark_group("taylor step");
    for rtol in [1e-8, 1e-14] {
        let opts = AdaptiveOptions::new(rtol, 1e-6 * rtol * y0.norm()).expect("valid tolerances");
        let reduced = Taylor::new(SymmetricReduced(top), 0.0, y0, opts).expect("a stepper");
        let p = reduced.order();
        g.bench_function(
            format!("reduced (4.12)-(4.14), rtol {rtol:e}, order {p}"),
            |b| {
                b.iter_batched(
                    || reduced.clone(),
                    |mut s| {
                        s.advance(1e9).expect("a step");
                        s
                    },
                    BatchSize::SmallInput,
                )
            },
        );
        let general = Taylor::new(GeneralTruncated(general), 0.0, y0, opts).expect("a stepper");
        g.bench_function(format!("general (3.3), rtol {rtol:e}, order {p}"), |b| {
            b.iter_batched(
                || general.clone(),
                |mut s| {
                    s.advance(1e9).expect("a step");
                    s
                },
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

fn closed_form(c: &mut Criterion) {
    let top = top();
    let omega0 = Vec3::from(OMEGA0);
    let o0 = Mat3::identity();
    let mut g = c.benchmark_group("closed form, one time");
    g.bench_function("truncated Ω (4.7)", |b| {
        b.iter(|| truncated_closed_form(black_box(&top), black_box(&omega0), black_box(100.0)))
    });
    g.bench_function("reduced Ω (4.15)-(4.16)", |b| {
        b.iter(|| reduced_closed_form(black_box(&top), black_box(&omega0), black_box(100.0)))
    });
    g.bench_function("truncated O(t) (4.9)-(4.11)", |b| {
        b.iter(|| {
            truncated_orientation(
                black_box(&top),
                black_box(&omega0),
                black_box(&o0),
                black_box(100.0),
            )
        })
    });
    g.finish();
    // 200 evenly spaced times on T = 200: per point, divide by 200.
    let times: Vec<f64> = (0..200).map(|j| 200.0 * j as f64 / 199.0).collect();
    let mut g = c.benchmark_group("closed form, 200 even points");
    g.bench_function("reduced Ω one by one", |b| {
        b.iter(|| {
            black_box(&times)
                .iter()
                .map(|&t| reduced_closed_form(&top, &omega0, t))
                .collect::<Vec<_>>()
        })
    });
    g.bench_function("reduced Ω by recurrence", |b| {
        b.iter(|| reduced_closed_form_many(black_box(&top), black_box(&omega0), black_box(&times)))
    });
    g.finish();
}

criterion_group! {
    name = kernels;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = rhs, step, closed_form
}
criterion_main!(kernels);
