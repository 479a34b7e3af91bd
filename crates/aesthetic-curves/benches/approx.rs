//! Criterion benchmarks of the rational cubic approximation of a LAC segment (issue target:
//! one segment under 0.1 ms median; also 50 random shapes, with and without the table of
//! optima), of a segment with an inflection end (one cubic, and the
//! G2 spline within 1e-7 of the size that CAD exports use), and of the spline of a long
//! segment.

use aesthetic_curves::approx::{
    fit_inflection_cubic, fit_inflection_spline, fit_rational_cubic, fit_rational_spline,
    ApproxOptions,
};
use aesthetic_curves::lac::{LacInflectionSegment, LacSegment};
use aesthetic_curves::Point;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn bench_approx(c: &mut Criterion) {
    let mut g = c.benchmark_group("approx/segment");
    let tri = [
        Point::new(0.0, 0.0),
        Point::new(10.0, 0.0),
        Point::new(16.0, 9.0),
    ];
    let opts = ApproxOptions::default();
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let seg = LacSegment::new(alpha, tri).unwrap();
        g.bench_with_input(BenchmarkId::new("fit", alpha), &seg, |b, s| {
            b.iter(|| fit_rational_cubic(black_box(s), &opts).unwrap())
        });
    }
    g.finish();
    // 50 random shapes as in tests/approx_sweep.rs (alpha in [-5, 5], turning 5 to 120
    // degrees, base angle from the circle to 0.98 of theta_lim): the table's starts against
    // the search of the whole square.
    let segs = aesthetic_curves::samples::random_lac_segments(50, 17);
    let mut g = c.benchmark_group("approx/random50");
    g.sample_size(20);
    for table in [true, false] {
        let o = ApproxOptions {
            table,
            ..ApproxOptions::default()
        };
        let name = if table { "table" } else { "grid_search" };
        g.bench_function(name, |b| {
            b.iter(|| {
                segs.iter()
                    .filter(|s| fit_rational_cubic(black_box(s), &o).is_ok())
                    .count()
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("approx/cad");
    g.sample_size(10);
    let inflection = LacInflectionSegment::new([
        Point::new(0.0, 0.0),
        Point::new(6.0, 0.0),
        Point::new(9.0, 5.0),
    ])
    .unwrap();
    let size = 9f64.hypot(5.0);
    g.bench_function("inflection_cubic", |b| {
        b.iter(|| fit_inflection_cubic(black_box(&inflection), &opts).unwrap())
    });
    g.bench_function("inflection_spline_1e-7", |b| {
        b.iter(|| fit_inflection_spline(black_box(&inflection), 1e-7 * size, 64, &opts).unwrap())
    });
    let seg = LacSegment::new(-1.0, tri).unwrap();
    g.bench_function("lac_spline_1e-7", |b| {
        b.iter(|| fit_rational_spline(black_box(&seg), 1e-7 * 16f64.hypot(9.0), 64, &opts).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench_approx);
criterion_main!(benches);
