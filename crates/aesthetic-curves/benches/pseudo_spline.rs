//! The pseudo-elastic spline (issue target: a 1000-point open curve in table mode under
//! 1 ms median), one table lookup, and one exact segment minimisation for scale.

use aesthetic_curves::pseudo_segment::optimal_segment;
use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
use aesthetic_curves::pseudo_table::tables;
use aesthetic_curves::samples::wavy_points;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let pts = wavy_points(1000, 7);
    tables(); // decoded once, outside the timing
    let mut g = c.benchmark_group("pseudo_spline");
    g.bench_function("table_open_1000", |b| {
        b.iter(|| pseudo_elastic(black_box(&pts), false, Mode::Table).unwrap())
    });
    g.bench_function("table_closed_1000", |b| {
        b.iter(|| pseudo_elastic(black_box(&pts), true, Mode::Table).unwrap())
    });
    g.bench_function("table_segment", |b| {
        b.iter(|| tables().segment(black_box(0.31), black_box(-0.52)).unwrap())
    });
    g.sample_size(10);
    g.bench_function("exact_segment", |b| {
        b.iter(|| optimal_segment(black_box(0.31), black_box(-0.52)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
