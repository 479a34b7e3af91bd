//! Criterion benchmarks of the editor's shaded regions (target: an interaction is
//! answered in under 16 ms of server time). One thread, so the numbers are per core; the
//! editor uses half the cores. Grid 100 x 70 cells, about what a 1000 x 700 view shows at
//! one cell per 10 pixels.

use aesthetic_curves::region::{bezier_monotone, inflection_existence, lac_existence, Grid};
use aesthetic_curves::Point;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn bench_region(c: &mut Criterion) {
    let grid = Grid::new(-2.0, -3.0, 18.0, 11.0, 100, 70).unwrap();
    let (p0, p1) = (Point::new(0.0, 0.0), Point::new(10.0, 0.0));
    let mut g = c.benchmark_group("region");
    for alpha in [-1.0, 0.5, 2.0] {
        g.bench_with_input(BenchmarkId::new("lac_100x70", alpha), &alpha, |b, &a| {
            b.iter(|| lac_existence(black_box(a), p0, p1, grid, 1).unwrap())
        });
    }
    g.bench_function("inflection_100x70", |b| {
        b.iter(|| inflection_existence(black_box(p0), p1, grid, 1).unwrap())
    });
    let cubic = [
        Point::new(0.0, 0.0),
        Point::new(6.0, 0.0),
        Point::new(12.0, 3.0),
        Point::new(16.0, 9.0),
    ];
    for block in [1usize, 4] {
        g.bench_with_input(
            BenchmarkId::new("bezier_cubic_100x70_block", block),
            &block,
            |b, &blk| b.iter(|| bezier_monotone(black_box(&cubic), None, 2, grid, blk, 1).unwrap()),
        );
    }
    let quintic = [
        Point::new(0.0, 0.0),
        Point::new(4.0, 0.0),
        Point::new(8.0, 0.5),
        Point::new(11.0, 2.0),
        Point::new(14.0, 5.0),
        Point::new(16.0, 9.0),
    ];
    g.bench_function("bezier_quintic_100x70_block4", |b| {
        b.iter(|| bezier_monotone(black_box(&quintic), None, 3, grid, 4, 1).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench_region);
criterion_main!(benches);
