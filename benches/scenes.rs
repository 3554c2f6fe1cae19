//! Scenes answered whole, one criterion benchmark each: the nanoparticle
//! scenes, whose τΩ ~ 1e-26 and 1e-18 would need ~1e20 steps to integrate and
//! are answered from the closed forms (goal: under 100 ms), the asymmetric
//! real particles (a molecule, a nanoellipsoid; 10¹⁷ and 10²⁶ rad), answered by
//! the secular model (same goal), and Figure 2 for comparison (the reduced
//! orientation is integrated there).
//!
//! ```sh
//! cargo bench -p spintop-benches --bench scenes
//! ```

use criterion::{Criterion, criterion_group, criterion_main};
use spintop::scene::answer::answer;
use spintop::scene::catalogue::find;
use std::hint::black_box;

fn scenes(c: &mut Criterion) {
    let mut g = c.benchmark_group("spintop run");
    for name in [
        "nanoparticle-1e3-debye",
        "nanoparticle-1e7-debye",
        "formaldehyde-molecule",
        "nanoellipsoid-tumbling",
        "figure-2",
    ] {
        let scene = find(name)
            .expect("a catalogue scene")
            .scene()
            .expect("it parses");
        g.bench_function(name, |b| {
            b.iter(|| answer(black_box(&scene)).expect("an answer"))
        });
    }
    g.finish();
}

criterion_group!(benches, scenes);
criterion_main!(benches);
