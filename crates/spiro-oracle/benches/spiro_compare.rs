//! Dev-only comparison: the same points through Spiro (Raph Levien's libspiro, Debian
//! package `libspiro-dev`), through the pseudo-elastic spline in table mode, and through the
//! G2 log-aesthetic spline at α = -1 (the same curve as Spiro's). Spiro solves
//! a different curve (piecewise Euler spirals, G2, a global Newton solve); both interpolate
//! the points with a fair curve, which is the work compared.
//!
//! `apt-get install libspiro-dev && cargo bench -p spiro-oracle --features libspiro --bench
//! spiro_compare`

use aesthetic_curves::lac_spline::{lac_spline, lac_spline_tangents, LacSplineOptions};
use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
use aesthetic_curves::pseudo_table::tables;
use aesthetic_curves::samples::wavy_points;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

use spiro_ffi::SpiroCp;
use spiro_oracle::ffi as spiro_ffi;

/// libspiro solved `cps`.
fn spiro(cps: &[SpiroCp]) -> bool {
    spiro_ffi::run(cps).is_some()
}

/// Spiro control points through `pts`, no corners.
fn control_points(pts: &[aesthetic_curves::Point], closed: bool) -> Vec<SpiroCp> {
    spiro_ffi::control_points(pts, closed, &[])
}

/// The point sets of the spline race (the same as `aecurve bench spline`): 15 and
/// 1000 wavy points, 1000 points on a circle (closed), 100,000 wavy points; each through
/// both, in one run.
fn bench(c: &mut Criterion) {
    let circle: Vec<aesthetic_curves::Point> = (0..1000)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 1000.0;
            aesthetic_curves::Point::new(a.cos(), a.sin())
        })
        .collect();
    let sets = [
        ("open_15", wavy_points(15, 7), false),
        ("open_1000", wavy_points(1000, 7), false),
        ("circle_closed_1000", circle, true),
        ("open_100000", wavy_points(100_000, 7), false),
    ];
    tables();
    let mut g = c.benchmark_group("spline_vs_spiro");
    for (name, pts, closed) in sets {
        let cps = control_points(&pts, closed);
        assert!(spiro(&cps), "libspiro failed on the {name} points");
        if pts.len() > 10_000 {
            g.sample_size(10);
        }
        g.bench_function(format!("pseudo_elastic_table_{name}"), |b| {
            b.iter(|| pseudo_elastic(black_box(&pts), closed, Mode::Table).unwrap())
        });
        g.bench_function(format!("libspiro_{name}"), |b| {
            b.iter(|| spiro(black_box(&cps)))
        });
    }
    g.finish();
    // The G2 log-aesthetic spline at α = -1 solves Spiro's own equations (tests/spiro_oracle.rs:
    // the curvatures agree to 1e-10): its solve alone against libspiro's, and the whole spline
    // (every piece's cubic fitted and proven monotone), on the sizes it takes (up to 500 points).
    let circle100: Vec<aesthetic_curves::Point> = (0..100)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 100.0;
            aesthetic_curves::Point::new(a.cos(), a.sin())
        })
        .collect();
    let lac_sets = [
        ("open_15", wavy_points(15, 7), false),
        ("open_100", wavy_points(100, 7), false),
        ("open_500", wavy_points(500, 7), false),
        ("circle_closed_100", circle100, true),
    ];
    let mut g = c.benchmark_group("lac_spline_vs_spiro");
    g.sample_size(20);
    for (name, pts, closed) in lac_sets {
        let cps = control_points(&pts, closed);
        let opts = LacSplineOptions {
            closed,
            ..Default::default()
        };
        g.bench_function(format!("libspiro_{name}"), |b| {
            b.iter(|| spiro(black_box(&cps)))
        });
        g.bench_function(format!("lac_spline_solve_{name}"), |b| {
            b.iter(|| lac_spline_tangents(black_box(&pts), &opts).unwrap())
        });
        g.bench_function(format!("lac_spline_with_cubics_{name}"), |b| {
            b.iter(|| lac_spline(black_box(&pts), &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
