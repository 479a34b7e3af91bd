//! Criterion benchmarks of log-aesthetic curve evaluation (targets: 1000 samples of
//! a solved segment under 20 µs, the segment solve under 3 µs) and of the single-LAC fit
//! (`lac_fit/*`: a measured Prius line, and 20,000 points, target under 1 s).

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

fn bench_lac_fit(c: &mut Criterion) {
    use aesthetic_curves::lac_fit::{fit_lac, LacFitOptions};
    let mut g = c.benchmark_group("lac_fit");
    g.sample_size(10);
    let prius: Vec<Point> = aesthetic_curves_data::PRIUS[0].points_as::<Point>();
    g.bench_function("prius_ps_1", |b| {
        b.iter(|| fit_lac(black_box(&prius), LacFitOptions::default()).unwrap())
    });
    // 20,000 points along a shallow arc with a ripple (the protocol's largest lac.fit).
    let n = 20_000;
    let many: Vec<Point> = (0..n)
        .map(|i| {
            let u = i as f64 / (n - 1) as f64;
            Point::new(
                1500.0 * u,
                80.0 * (0.9 * std::f64::consts::PI * u).sin() + 0.2 * (1.7 * i as f64).sin(),
            )
        })
        .collect();
    g.bench_function("points_20000", |b| {
        b.iter(|| fit_lac(black_box(&many), LacFitOptions::default()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench_lac, bench_lac_fit);
criterion_main!(benches);
