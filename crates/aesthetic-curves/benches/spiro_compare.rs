//! Dev-only comparison: the same points through Spiro (Raph Levien's libspiro, Debian
//! package `libspiro-dev`), through the pseudo-elastic spline in table mode, and through the
//! G2 log-aesthetic spline at α = -1 (the same curve as Spiro's). Spiro solves
//! a different curve (piecewise Euler spirals, G2, a global Newton solve); both interpolate
//! the points with a fair curve, which is the work compared.
//!
//! `apt-get install libspiro-dev && cargo bench -p aesthetic-curves --features spiro-bench --bench spiro_compare`

use aesthetic_curves::lac_spline::{lac_spline, lac_spline_tangents, LacSplineOptions};
use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
use aesthetic_curves::pseudo_table::tables;
use aesthetic_curves::samples::wavy_points;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::os::raw::{c_char, c_int, c_void};

#[repr(C)]
#[derive(Clone, Copy)]
struct SpiroCp {
    x: f64,
    y: f64,
    ty: c_char,
}

#[link(name = "spiro")]
extern "C" {
    fn run_spiro(src: *const SpiroCp, n: c_int) -> *mut c_void;
    fn free_spiro(s: *mut c_void);
}

fn spiro(cps: &[SpiroCp]) -> bool {
    // SAFETY: `cps` is a valid array of `cps.len()` control points for the call's duration;
    // the returned segment array is freed by the library's own function.
    unsafe {
        let s = run_spiro(cps.as_ptr(), cps.len() as c_int);
        let ok = !s.is_null();
        if ok {
            free_spiro(s);
        }
        ok
    }
}

/// Spiro control points through `pts`: open curves start with '{' and end with '}',
/// closed ones are all 'c' (G2 everywhere).
fn control_points(pts: &[aesthetic_curves::Point], closed: bool) -> Vec<SpiroCp> {
    let n = pts.len();
    pts.iter()
        .enumerate()
        .map(|(i, p)| SpiroCp {
            x: p.x,
            y: p.y,
            ty: if closed {
                b'c'
            } else if i == 0 {
                b'{'
            } else if i == n - 1 {
                b'}'
            } else {
                b'c'
            } as c_char,
        })
        .collect()
}

/// The point sets of issue 17's spline race (the same as `aecurve bench spline`): 15 and
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
    // (every piece's cubic fitted and proven monotone), on the sizes it takes (500 points).
    let circle100: Vec<aesthetic_curves::Point> = (0..100)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 100.0;
            aesthetic_curves::Point::new(a.cos(), a.sin())
        })
        .collect();
    let lac_sets = [
        ("open_15", wavy_points(15, 7), false),
        ("open_100", wavy_points(100, 7), false),
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
