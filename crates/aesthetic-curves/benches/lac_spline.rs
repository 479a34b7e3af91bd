//! Criterion benchmark of the editor's spline mode: a drag redraws the G2 log-aesthetic
//! spline through 20 points at the slider's α (target: under 30 ms of server time). Ten
//! sets of wavy points (`samples::wavy_points(20, seed)`, seeds 0 to 9) per iteration, so
//! a time over ten is the mean redraw; the whole spline, cubics proven monotone, as the
//! editor draws it.

use aesthetic_curves::lac_spline::{lac_spline, LacSplineOptions};
use aesthetic_curves::samples::wavy_points;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn bench_drag(c: &mut Criterion) {
    let sets: Vec<_> = (0..10).map(|seed| wavy_points(20, seed)).collect();
    let mut g = c.benchmark_group("lac_spline_drag_20_points_x10");
    g.sample_size(10);
    for alpha in [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0] {
        let opts = LacSplineOptions {
            alpha,
            ..Default::default()
        };
        g.bench_with_input(BenchmarkId::new("alpha", alpha), &opts, |b, o| {
            b.iter(|| {
                for pts in &sets {
                    black_box(lac_spline(black_box(pts), o).expect("the spline answers"));
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_drag);
criterion_main!(benches);
