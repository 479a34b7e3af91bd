//! The global optimum of the rational cubic of a LAC segment (`fit_rational_cubic`),
//! checked on 1000 random segments against an exhaustive search of the same family.
//!
//! Cases: alpha uniform in [-5, 5], turning uniform in [5, 120] degrees, the base angle at
//! the high-curvature end uniform between half the turning and 0.98 of θ_lim (any split of
//! the turning between the ends), size log-uniform in [1e-3, 1e3], any rotation.
//!
//! Exhaustive search (independent of the library's optimiser; it uses only `construct`,
//! `LacSegment::sample`, `approximation_error` and the exact monotone test): the measure
//! `fit_rational_cubic` reports (distance to the segment's point of the same turning angle
//! over the arc length, rms at uniform t) on the segment tabulated densely in its own test
//! code; a 160 x 160 grid over (f0, f1) at 41 samples, restricted to curvature-monotone
//! cubics; along every grid row and column the valley floor near the row's best cell
//! (golden section, 201 samples: narrow valleys cross the grid lines); from the best
//! profile minima of up to eight distinct valleys, a golden-section search of the profile
//! (the minimum across the valley as a function of the position along it); the optimum's
//! rms then by the library's exact `approximation_error`. The optima are
//! committed in `tests/data/approx_sweep.csv`; regenerate them (a few minutes) with
//! `AECURVE_WRITE_DATA=1 cargo test --release -p aesthetic-curves --test integration approx_sweep::
//! -- --ignored`.

use aesthetic_curves::approx::{approximation_error, construct, fit_rational_cubic, ApproxOptions};
use aesthetic_curves::lac::LacSegment;
use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::samples::SplitMix64;
use aesthetic_curves::{Point, Vec2};
use rayon::prelude::*;

use crate::approx_cases::{read_optima, triangle, write_optima, OptimumRow};

const CASES: usize = 1000;
const SWEEP: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/approx_sweep.csv");

/// The cases: (alpha, turning, base angle, size, rotation).
fn cases() -> Vec<[f64; 5]> {
    cases_from(20261130, CASES)
}

/// `count` cases of the sweep's distribution from the generator seeded with `seed`.
fn cases_from(seed: u64, count: usize) -> Vec<[f64; 5]> {
    let mut rng = SplitMix64::new(seed);
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let alpha = rng.range(-5.0, 5.0);
        let td = rng.range(5f64.to_radians(), 120f64.to_radians());
        let lim = LacSegment::theta_lim(alpha, td).unwrap();
        let top = 0.98 * lim;
        let u = rng.range(0.0, 1.0);
        let size = 10f64.powf(rng.range(-3.0, 3.0));
        let rot = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
        if top <= 0.5 * td {
            continue;
        }
        let phi = 0.5 * td + u * (top - 0.5 * td);
        out.push([alpha, td, phi, size, rot]);
    }
    out
}

/// The segment tabulated at 4097 turning angles (exact points and curvatures from
/// `LacSegment::sample`), interpolated by cubic Hermite in the turning angle (dP/dτ =
/// T/|κ|): relative error below 1e-12 of the size, far below the optima's 1e-8 and up.
struct Table {
    p: Vec<Point>,
    d: Vec<Vec2>,
    h: f64,
    theta_d: f64,
    d0: Vec2,
    sign: f64,
    len: f64,
}

impl Table {
    fn new(seg: &LacSegment) -> Table {
        let m = 4097;
        let aesthetic_curves::Polyline {
            points: p,
            kappa: k,
        } = seg.sample(m).unwrap();
        let c = seg.control();
        let d0 = (c[1] - c[0]) / (c[1] - c[0]).hypot();
        let sign = (c[1] - c[0]).cross(c[2] - c[1]).signum();
        let h = seg.theta_d() / (m - 1) as f64;
        let d = k
            .iter()
            .enumerate()
            .map(|(i, kk)| {
                let a = sign * h * i as f64;
                let (sn, cs) = a.sin_cos();
                Vec2::new(d0.x * cs - d0.y * sn, d0.x * sn + d0.y * cs) / kk.abs()
            })
            .collect();
        Table {
            p,
            d,
            h,
            theta_d: seg.theta_d(),
            d0,
            sign,
            len: seg.arc_length().unwrap(),
        }
    }

    fn at(&self, tau: f64) -> Point {
        let tau = tau.clamp(0.0, self.theta_d);
        let k = ((tau / self.h) as usize).min(self.p.len() - 2);
        let x = (tau - k as f64 * self.h) / self.h;
        let (x2, x3) = (x * x, x * x * x);
        let (p0, p1) = (self.p[k].to_vec2(), self.p[k + 1].to_vec2());
        (p0 * (2.0 * x3 - 3.0 * x2 + 1.0)
            + self.d[k] * (self.h * (x3 - 2.0 * x2 + x))
            + p1 * (3.0 * x2 - 2.0 * x3)
            + self.d[k + 1] * (self.h * (x3 - x2)))
            .to_point()
    }

    /// The rms of `approximation_error` (distance to the segment's point of the same
    /// turning angle, over the arc length) at `n` uniform t.
    fn rms(&self, c: &aesthetic_curves::RationalBezier, n: usize) -> f64 {
        use aesthetic_curves::PlanarCurve;
        let mut sum = 0.0;
        for i in 0..n {
            let t = i as f64 / (n - 1) as f64;
            let dv = c.derivs(t);
            let tau = (self.sign * self.d0.cross(dv.d1)).atan2(self.d0.dot(dv.d1));
            let e = (dv.p - self.at(tau)).hypot() / self.len;
            sum += e * e;
        }
        (sum / n as f64).sqrt()
    }
}

/// Golden-section minimisation of `f` on [lo, hi] to `tol` (infinite values allowed: the
/// constrained minimum on a boundary is approached from the finite side).
fn golden(f: &mut dyn FnMut(f64) -> f64, mut lo: f64, mut hi: f64, tol: f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut fa, mut fb) = (f(a), f(b));
    while hi - lo > tol {
        if fa <= fb {
            hi = b;
            (b, fb) = (a, fa);
            a = hi - r * (hi - lo);
            fa = f(a);
        } else {
            lo = a;
            (a, fa) = (b, fb);
            b = lo + r * (hi - lo);
            fb = f(b);
        }
    }
    if fa <= fb {
        (a, fa)
    } else {
        (b, fb)
    }
}

/// The exhaustive optimum (rms, f0, f1); rms infinite when no cubic of the family has
/// monotone curvature. The reported rms is the library's exact measure at the optimum.
fn exhaustive(seg: &LacSegment) -> (f64, f64, f64) {
    let table = Table::new(seg);
    let rms = |f0: f64, f1: f64, n: usize| -> f64 {
        if !(f0 > 0.0 && f0 < 1.0 && f1 > 0.0 && f1 < 1.0) {
            return f64::INFINITY;
        }
        let Ok(c) = construct(seg, f0, f1) else {
            return f64::INFINITY;
        };
        if !c.is_curvature_monotone().unwrap_or(false) {
            return f64::INFINITY;
        }
        table.rms(&c, n)
    };
    // The point at x along the grid line s: f0 = s for axis 0, f1 = s for axis 1.
    let point = |axis: usize, s: f64, x: f64| if axis == 0 { (s, x) } else { (x, s) };
    let along = |axis: usize, s: f64, x: f64| {
        let (f0, f1) = point(axis, s, x);
        rms(f0, f1, 201)
    };
    // 1. The grid.
    let n = 160;
    let w = 1.0 / n as f64;
    let at = |i: usize| (i as f64 + 0.5) * w;
    let grid: Vec<f64> = (0..n * n).map(|k| rms(at(k / n), at(k % n), 41)).collect();
    if grid.iter().all(|v| !v.is_finite()) {
        return (f64::INFINITY, 0.5, 0.5);
    }
    // 2. Profiles: along every row and every column, the valley floor near the row's best
    // cell (golden section over two cells each side, at the reported 201 samples). Narrow
    // valleys cross the grid lines, so every valley shows up as profile minima.
    let mut cands: Vec<(f64, usize, f64, f64)> = Vec::new(); // (rms, axis, line value, x)
    for axis in 0..2 {
        for i in 0..n {
            let cell = |j: usize| {
                if axis == 0 {
                    grid[i * n + j]
                } else {
                    grid[j * n + i]
                }
            };
            let Some(j) = (0..n)
                .filter(|&j| cell(j).is_finite())
                .min_by(|&a, &b| cell(a).total_cmp(&cell(b)))
            else {
                continue;
            };
            let line = at(i);
            let mut f = |x: f64| along(axis, line, x);
            let (x, v) = golden(&mut f, at(j) - 2.0 * w, at(j) + 2.0 * w, 1e-10);
            let (x, v) = if v.is_finite() {
                (x, v)
            } else {
                (at(j), f(at(j)))
            };
            cands.push((v, axis, line, x));
        }
    }
    cands.sort_by(|a, b| a.0.total_cmp(&b.0));
    // 3. The best profile minima of distinct valleys, refined in two dimensions: golden
    // section along the line coordinate of the profile g(s) = min over the other one.
    let mut best = (f64::INFINITY, 0.5, 0.5);
    let mut used: Vec<(f64, f64)> = Vec::new();
    for &(v0, axis, line, x0) in &cands {
        if used.len() >= 8 || !v0.is_finite() {
            break;
        }
        let pt = point(axis, line, x0);
        if used
            .iter()
            .any(|u| (u.0 - pt.0).abs().max((u.1 - pt.1).abs()) < 3.0 * w)
        {
            continue;
        }
        used.push(pt);
        let mut floor = x0;
        let mut g = |s: f64| {
            let (x, v) = golden(
                &mut |x| along(axis, s, x),
                floor - 2.0 * w,
                floor + 2.0 * w,
                1e-11,
            );
            if v.is_finite() {
                floor = x;
            }
            v
        };
        let (s, v) = golden(&mut g, line - 1.5 * w, line + 1.5 * w, 1e-10);
        let (x, v2) = golden(
            &mut |x| along(axis, s, x),
            floor - 2.0 * w,
            floor + 2.0 * w,
            1e-11,
        );
        let (v, p) = if v2 <= v.min(v0) {
            (v2, point(axis, s, x))
        } else if v <= v0 {
            (v, point(axis, s, floor))
        } else {
            (v0, pt)
        };
        if v < best.0 {
            best = (v, p.0, p.1);
        }
    }
    if best.0.is_finite() {
        let c = construct(seg, best.1, best.2).unwrap();
        best.0 = approximation_error(seg, &c, 201).unwrap().rms;
    }
    best
}

/// A hold-out check (slow: about a second per case per core): cases the optimiser was never
/// tuned on, from another seed (`AECURVE_SWEEP_SEED`, default 1; `AECURVE_SWEEP_CASES`,
/// default 200), each against the exhaustive search. Measured, 300 cases per seed: seeds
/// 1, 3, 5, 7 and 11 had five misses (by 2.4 % to 73 %, in long valleys) until the fit
/// walked valley floors (`approx/valley.rs`), none since; seeds 13 and 17, first run after
/// that change, none. The bound: every case within 1 % of the exhaustive optimum (it was:
/// at most 1 % of the cases outside, none by more than 5 %).
#[test]
#[ignore = "slow hold-out sweep on fresh cases"]
fn fresh_cases_near_the_exhaustive_optimum() {
    let var = |k: &str, d: u64| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let seed = var("AECURVE_SWEEP_SEED", 1);
    let count = var("AECURVE_SWEEP_CASES", 200) as usize;
    // The exhaustive optima are cached in the target's scratch folder (per seed and count):
    // a re-run after a change to the optimiser checks the fit alone.
    let cache = format!(
        "{}/approx_sweep_{seed}_{count}.csv",
        env!("CARGO_TARGET_TMPDIR")
    );
    let rows: Vec<OptimumRow> = if std::path::Path::new(&cache).exists() {
        read_optima(&cache)
    } else {
        let rows: Vec<OptimumRow> = cases_from(seed, count)
            .par_iter()
            .map(|&c| {
                let [alpha, td, phi, size, rot] = c;
                let seg = LacSegment::new(alpha, triangle(td, phi, size, rot)).unwrap();
                (c, exhaustive(&seg))
            })
            .collect();
        write_optima(
            &cache,
            "alpha,theta_d,phi,size,rotation,best_rms,f0,f1\n",
            &rows,
        );
        rows
    };
    use std::sync::atomic::Ordering::Relaxed;
    let worst = std::sync::atomic::AtomicU64::new(0);
    let failures: Vec<String> = rows
        .par_iter()
        .filter_map(|&([alpha, td, phi, size, rot], (best, b0, b1))| {
            let seg = LacSegment::new(alpha, triangle(td, phi, size, rot)).unwrap();
            let label = format!("alpha {alpha:?} td {td:?} phi {phi:?} size {size:?}");
            match fit_rational_cubic(&seg, &ApproxOptions::default()) {
                Ok(fit) if best.is_finite() => (fit.rms > 1.01 * best && fit.rms > best + 1e-15)
                    .then(|| {
                        let ratio = fit.rms / best;
                        worst.fetch_max((ratio * 1e6) as u64, Relaxed);
                        format!(
                            "{label}: {:e} vs exhaustive {best:e} at ({b0}, {b1}), ratio {ratio:.4}",
                            fit.rms
                        )
                    }),
                // The exhaustive grid's first cell centre is 1/320 from the square's edges:
                // a monotone region thinner than that (one seed-13 case: f0 = 0.0003) is
                // found by the fit alone. Its verdict, checked here by dense sampling, is the
                // judge.
                Ok(fit) => {
                    let sampled = fit.curve.curvature_monotone_sampled(20_000);
                    match sampled {
                        Ok(r) if r.monotone => {
                            println!(
                                "  {label}: rms {:e} at ({:.5}, {:.5}), monotone by dense \
                                 sampling; the exhaustive grid found none",
                                fit.rms, fit.f0, fit.f1
                            );
                            None
                        }
                        _ => Some(format!(
                            "{label}: rms {:e}, exhaustive found none and sampling disagrees",
                            fit.rms
                        )),
                    }
                }
                Err(_) if !best.is_finite() => None,
                Err(e) => Some(format!("{label}: {e}")),
            }
        })
        .collect();
    println!("seed {seed}: {} of {count} cases miss", failures.len());
    for f in &failures {
        println!("  {f}");
    }
    let worst = worst.into_inner() as f64 * 1e-6;
    assert!(
        failures.is_empty(),
        "{} of {count} cases miss the 1 % band (worst ratio {worst:.4})",
        failures.len()
    );
}

/// The committed rows: the case and its exhaustive optimum.
fn committed() -> Vec<([f64; 5], (f64, f64, f64))> {
    read_optima(SWEEP)
}

/// The generator (slow: minutes). With `AECURVE_WRITE_DATA=1` it
/// writes `tests/data/approx_sweep.csv`; without, it recomputes the first 24 cases and
/// checks them against the committed file (`.ci/run` runs that).
#[test]
#[ignore = "slow generator of tests/data/approx_sweep.csv"]
fn generate_exhaustive_optima() {
    let write = std::env::var_os("AECURVE_WRITE_DATA").is_some();
    let all = cases();
    let todo = if write { &all[..] } else { &all[..24] };
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<([f64; 5], (f64, f64, f64))> = todo
        .par_iter()
        .map(|&c| {
            let [alpha, td, phi, size, rot] = c;
            let seg = LacSegment::new(alpha, triangle(td, phi, size, rot)).unwrap();
            let r = exhaustive(&seg);
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if k % 50 == 0 {
                eprintln!("{k} / {}", todo.len());
            }
            (c, r)
        })
        .collect();
    if write {
        write_optima(
            SWEEP,
            "# Exhaustive optimum of the rational cubic family for 1000 random LAC segments\n\
             # (tests/approx_sweep.rs: a 160 x 160 grid at 41 samples over the curvature-monotone\n\
             # cubics, valley floors along every grid line and golden-section searches along the\n\
             # best eight valleys at 201 samples). best_rms = inf: no monotone cubic.\n\
             alpha,theta_d,phi,size,rotation,best_rms,f0,f1\n",
            &rows,
        );
        return;
    }
    let old = committed();
    for ((c, b), (oc, ob)) in rows.iter().zip(&old) {
        assert_eq!(c, oc, "the case generator changed: regenerate the file");
        assert!(
            // Below 1e-15 absolute (relative to the arc length) the rms is rounding,
            // whatever its relative size.
            b.0 == ob.0 || (b.0 - ob.0).abs() <= 1e-9 * ob.0 + 1e-15,
            "{c:?}: {b:?} vs committed {ob:?}"
        );
    }
}

/// Every committed case: `fit_rational_cubic` within 1 % of the exhaustive optimum (in
/// rms), or `NoSegment` exactly where the exhaustive search found no monotone cubic; the
/// misses are listed (see the bound at the end).
#[test]
fn within_one_percent_of_the_exhaustive_optimum_on_1000_segments() {
    let rows = committed();
    assert_eq!(rows.len(), CASES);
    let results: Vec<Result<f64, String>> = rows
        .par_iter()
        .map(|&([alpha, td, phi, size, rot], (best, b0, b1))| {
            let seg = LacSegment::new(alpha, triangle(td, phi, size, rot)).unwrap();
            let label = format!(
                "alpha {alpha:?} td {td:?} phi {phi:?} size {size:?}: exhaustive {best:e} at ({b0}, {b1})"
            );
            match fit_rational_cubic(&seg, &ApproxOptions::default()) {
                Ok(fit) if best.is_finite() => {
                    let ratio = fit.rms / best;
                    if ratio <= 1.01 || fit.rms <= best + 1e-15 {
                        Ok(ratio)
                    } else {
                        Err(format!("{label}: rms {:e} at ({}, {}), ratio {ratio:.4}", fit.rms, fit.f0, fit.f1))
                    }
                }
                Ok(fit) => Err(format!("{label}: returned rms {:e}, but no monotone cubic was found", fit.rms)),
                Err(_) if !best.is_finite() => Ok(1.0),
                Err(e) => Err(format!("{label}: {e}")),
            }
        })
        .collect();
    let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
    let worst = results
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .fold(0.0f64, |m, &r| m.max(r));
    let none = rows.iter().filter(|r| !r.1 .0.is_finite()).count();
    println!(
        "{} cases ({none} without a monotone cubic): worst rms / exhaustive {worst:.5}, {} failures",
        rows.len(),
        failures.len()
    );
    for f in failures.iter().take(40) {
        println!("  {f}");
    }
    // Every case within 1 % (the target). The last four misses were near-exact fits next to
    // the circle whose optimum is a twin minimum a few thousandths from another in the same
    // hairline valley; the table's starts there are no longer skipped or abandoned.
    assert!(
        failures.is_empty(),
        "{} of {} cases miss the exhaustive optimum by more than 1 %",
        failures.len(),
        rows.len()
    );
}
