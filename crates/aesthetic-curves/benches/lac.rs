//! Criterion benchmarks of log-aesthetic curve evaluation (issue target: 1000 samples of a
//! solved segment under 100 µs).

use aesthetic_curves::lac::{LacSegment, LacStandard};
use aesthetic_curves::Point;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;

fn bench_lac(c: &mut Criterion) {
    let mut g = c.benchmark_group("lac/standard");
    for (alpha, lambda) in [(-1.0, 0.3), (0.5, 0.3), (1.0, 0.5), (2.0, 0.5)] {
        let curve = LacStandard::new(alpha, lambda).unwrap();
        let thetas: Vec<f64> = (0..1000).map(|i| i as f64 * 1.5 / 999.0).collect();
        g.bench_with_input(BenchmarkId::new("point", alpha), &curve, |b, c| {
            b.iter(|| c.eval(black_box(1.5)).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("samples1000", alpha), &curve, |b, c| {
            b.iter(|| c.eval_many(black_box(&thetas)).unwrap())
        });
    }
    g.finish();
    let mut g = c.benchmark_group("lac/segment");
    let tri = [
        Point::new(0.0, 0.0),
        Point::new(10.0, 0.0),
        Point::new(16.0, 9.0),
    ];
    for alpha in [-1.0, 0.5, 1.0, 2.0] {
        g.bench_with_input(BenchmarkId::new("solve", alpha), &alpha, |b, &a| {
            b.iter(|| LacSegment::new(black_box(a), tri).unwrap())
        });
        let seg = LacSegment::new(alpha, tri).unwrap();
        g.bench_with_input(BenchmarkId::new("sample1000", alpha), &seg, |b, s| {
            b.iter(|| s.sample(black_box(1000)).unwrap())
        });
    }
    // Triangles near the edge of the existence region (base angle 1e-3 rad below θ_lim),
    // where Λ approaches Λ_max and the curve nears its singular end.
    for alpha in [-1.0, 2.0] {
        let td = std::f64::consts::FRAC_PI_2;
        let phi = LacSegment::theta_lim(alpha, td).unwrap() - 1e-3;
        let other = td - phi;
        // Start (0,0), tangent intersection (1,0); the end on the ray at angle td from P1,
        // at the distance that gives base angle `phi` at the start.
        let d = phi.sin() / other.sin();
        let end = Point::new(1.0 + d * td.cos(), d * td.sin());
        let tri = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), end];
        g.bench_with_input(
            BenchmarkId::new("solve_near_limit", alpha),
            &alpha,
            |b, &a| b.iter(|| LacSegment::new(black_box(a), tri).unwrap()),
        );
    }
    g.finish();
}

criterion_group!(benches, bench_lac);
criterion_main!(benches);
