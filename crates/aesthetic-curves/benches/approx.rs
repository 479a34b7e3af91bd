//! Criterion benchmarks of the rational cubic approximation of a LAC segment (issue target:
//! one segment under 1 ms median).

use aesthetic_curves::approx::{fit_rational_cubic, ApproxOptions};
use aesthetic_curves::lac::LacSegment;
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
}

criterion_group!(benches, bench_approx);
criterion_main!(benches);
