//! Dev-only comparison: the same 1000 points through Spiro (Raph Levien's libspiro, Debian
//! package `libspiro-dev`) and through the pseudo-elastic spline in table mode. Spiro solves
//! a different curve (piecewise Euler spirals, G2, a global Newton solve); both interpolate
//! the points with a fair curve, which is the work compared.
//!
//! `apt-get install libspiro-dev && cargo bench -p aesthetic-curves --features spiro-bench --bench spiro_compare`

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

fn bench(c: &mut Criterion) {
    let pts = wavy_points(1000, 7);
    let n = pts.len();
    let cps: Vec<SpiroCp> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| SpiroCp {
            x: p.x,
            y: p.y,
            ty: if i == 0 {
                b'{'
            } else if i == n - 1 {
                b'}'
            } else {
                b'c'
            } as c_char,
        })
        .collect();
    assert!(spiro(&cps), "libspiro failed on the benchmark points");
    tables();
    let mut g = c.benchmark_group("spline_vs_spiro");
    g.bench_function("pseudo_elastic_table_open_1000", |b| {
        b.iter(|| pseudo_elastic(black_box(&pts), false, Mode::Table).unwrap())
    });
    g.bench_function("libspiro_open_1000", |b| b.iter(|| spiro(black_box(&cps))));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
