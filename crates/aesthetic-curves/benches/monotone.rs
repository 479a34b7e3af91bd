//! Criterion benchmarks of the curvature-monotonicity tests (issue: exact test of a cubic under
//! 1 µs, at least 5x faster than sampling with 100 divisions). Each iteration runs the test
//! over a fixed set of random curves (the same set for every method); throughput is per curve.

use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::samples::{random_curves, random_rational_curves};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;

const CURVES: usize = 256;

/// The exact test (verdict alone, and with its extrema) and the sampling test at each of
/// `samplings` divisions, over one set of curves, in the group `name`.
fn bench_set<C: CurvatureMonotone>(
    c: &mut Criterion,
    name: &str,
    curves: &[C],
    samplings: &[usize],
) {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(curves.len() as u64));
    g.bench_function("exact", |b| {
        b.iter(|| {
            curves
                .iter()
                .filter(|c| black_box(c).is_curvature_monotone().unwrap_or(false))
                .count()
        })
    });
    g.bench_function("exact_with_extrema", |b| {
        b.iter(|| {
            curves
                .iter()
                .map(|c| {
                    black_box(c)
                        .curvature_monotone()
                        .map(|r| r.extrema.len())
                        .unwrap_or(0)
                })
                .sum::<usize>()
        })
    });
    for &n in samplings {
        g.bench_with_input(BenchmarkId::new("sampling", n), &n, |b, &n| {
            b.iter(|| {
                curves
                    .iter()
                    .filter(|c| {
                        black_box(c)
                            .curvature_monotone_sampled(n)
                            .map(|r| r.monotone)
                            .unwrap_or(false)
                    })
                    .count()
            })
        });
    }
    g.finish();
}

fn bench_polynomial(c: &mut Criterion) {
    for degree in [3usize, 4, 5] {
        let curves = random_curves(degree, CURVES, 42);
        bench_set(
            c,
            &format!("monotone/degree{degree}"),
            &curves,
            &[100, 200, 400],
        );
    }
}

fn bench_rational(c: &mut Criterion) {
    let curves = random_rational_curves(3, CURVES, 42);
    bench_set(c, "monotone/rational3", &curves, &[100]);
}

/// Near-degenerate cubics in integer font units that the floating-point filter cannot decide
/// (a collinear end with a long nearly parallel handle, retracted handles; kept only where
/// `MonotoneReport::exact` says big-integer arithmetic ran): the exact fallback's cost per
/// curve (target: under 100 µs).
fn bench_exact_fallback(c: &mut Criterion) {
    use aesthetic_curves::{Bezier, Point, RationalBezier};
    let mut curves = Vec::new();
    let mut state = 12345u64;
    let mut next = |m: i64| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as i64).rem_euclid(m)
    };
    while curves.len() < 64 {
        let (x0, y0) = (100 + next(1900), 100 + next(1900));
        let a = 1 + next(7);
        let p = [
            (x0, y0),
            (x0 + a, y0),
            (x0 + a + 1 + next(3), y0),
            (x0 + a + 5 + next(60), y0 + next(7) - 3),
        ];
        let mut pts: Vec<Point> = p
            .iter()
            .map(|&(x, y)| Point::new(x as f64, y as f64))
            .collect();
        if next(2) == 0 {
            pts[1] = pts[0];
        }
        let b = Bezier::new(pts.clone()).expect("cubic");
        if b.curvature_monotone().is_ok_and(|r| r.exact) {
            curves.push(b);
        }
    }
    let rational: Vec<RationalBezier> = curves
        .iter()
        .map(|b| {
            RationalBezier::new(b.points().to_vec(), vec![1.0, 2.0, 1.0, 3.0]).expect("weights")
        })
        .collect();
    let mut g = c.benchmark_group("monotone/exact_fallback");
    g.throughput(Throughput::Elements(curves.len() as u64));
    g.bench_function("polynomial_with_extrema", |b| {
        b.iter(|| {
            curves
                .iter()
                .filter(|c| black_box(c).curvature_monotone().is_ok_and(|r| r.monotone))
                .count()
        })
    });
    g.bench_function("rational_with_extrema", |b| {
        b.iter(|| {
            rational
                .iter()
                .filter(|c| black_box(c).curvature_monotone().is_ok_and(|r| r.monotone))
                .count()
        })
    });
    g.finish();
}

/// The space curves' exact verdicts (curvature, zero-curvature points, planarity and
/// torsion: `space::SpaceBezier::check`) over 256 random twisted curves of degree 3 and of
/// degree 5, polynomial and with weights from 1 to 3.
fn bench_space(c: &mut Criterion) {
    use aesthetic_curves::space::SpaceBezier;
    let mut g = c.benchmark_group("space/check");
    g.throughput(Throughput::Elements(CURVES as u64));
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut random = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0
    };
    for degree in [3usize, 5] {
        let curves: Vec<SpaceBezier> = (0..CURVES)
            .map(|_| {
                let p = (0..=degree)
                    .map(|_| [random(), random(), random()])
                    .collect();
                SpaceBezier::new(p).unwrap()
            })
            .collect();
        let rational: Vec<SpaceBezier> = (curves.iter())
            .map(|c| {
                let w = (0..=degree)
                    .map(|_| 1.0 + 0.01 * (random() + 100.0))
                    .collect();
                SpaceBezier::rational(c.points().to_vec(), w).unwrap()
            })
            .collect();
        g.bench_with_input(
            BenchmarkId::new("rational_degree", degree),
            &rational,
            |b, cs| {
                b.iter(|| {
                    (cs.iter())
                        .map(|c| black_box(c).check())
                        .filter(|r| r.curvature.monotone)
                        .count()
                })
            },
        );
        g.bench_with_input(BenchmarkId::new("degree", degree), &curves, |b, cs| {
            b.iter(|| {
                cs.iter()
                    .map(|c| black_box(c).check())
                    .filter(|r| r.curvature.monotone)
                    .count()
            })
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    bench_polynomial,
    bench_rational,
    bench_exact_fallback,
    bench_space
);
criterion_main!(benches);
