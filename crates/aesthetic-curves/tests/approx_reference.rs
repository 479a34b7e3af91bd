//! The rational cubic approximation of LAC segments against an exhaustive search of the
//! same family, with independent checks of the ends and of curvature monotonicity.

use aesthetic_curves::approx::{approximation_error, construct, fit_rational_cubic, ApproxOptions};
use aesthetic_curves::lac::LacSegment;
use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::samples::SplitMix64;
use aesthetic_curves::PlanarCurve;

use crate::approx_cases::{read_optima, triangle, write_optima};

/// The best rms of the family over a grid (exact error, 201 samples, exact monotone test),
/// refined by a shrinking pattern search around the best monotone cell.
fn exhaustive_best(seg: &LacSegment, n: usize) -> (f64, f64, f64) {
    let eval = |f0: f64, f1: f64| -> Option<f64> {
        let c = construct(seg, f0, f1).ok()?;
        if !c.is_curvature_monotone().ok()? {
            return None;
        }
        approximation_error(seg, &c, 201).ok().map(|e| e.rms)
    };
    let mut best = (f64::INFINITY, 0.5, 0.5);
    for i in 0..n {
        for j in 0..n {
            let (f0, f1) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            if let Some(e) = eval(f0, f1) {
                if e < best.0 {
                    best = (e, f0, f1);
                }
            }
        }
    }
    let mut h = 0.5 / n as f64;
    while h > 1e-7 {
        let mut moved = false;
        for (d0, d1) in [
            (h, 0.0),
            (-h, 0.0),
            (0.0, h),
            (0.0, -h),
            (h, h),
            (-h, -h),
            (h, -h),
            (-h, h),
        ] {
            if let Some(e) = eval(best.1 + d0, best.2 + d1) {
                if e < best.0 {
                    best = (e, best.1 + d0, best.2 + d1);
                    moved = true;
                }
            }
        }
        if !moved {
            h *= 0.5;
        }
    }
    best
}

/// The random cases of the global-optimum check: (alpha, turning, base angle, scale,
/// rotation). The exhaustive optimum of each is committed in
/// `tests/data/approx_exhaustive.csv` (regenerate with
/// `cargo test --release -p aesthetic-curves --test integration approx_reference:: -- --ignored`).
fn random_cases(count: usize) -> Vec<[f64; 5]> {
    let mut rng = SplitMix64::new(20261122);
    (0..count)
        .map(|_| {
            let alpha = rng.range(-3.0, 3.0);
            let td = rng.range(30f64.to_radians(), 100f64.to_radians());
            let lim = LacSegment::theta_lim(alpha, td).unwrap();
            let phi = 0.5 * td + rng.range(0.05, 0.98) * (lim - 0.5 * td);
            [alpha, td, phi, rng.range(0.1, 100.0), rng.range(-3.0, 3.0)]
        })
        .collect()
}

const CASES: usize = 16;
const EXHAUSTIVE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/approx_exhaustive.csv"
);

/// The committed rows: the case and its exhaustive optimum (rms, f0, f1; rms `inf` when no
/// monotone cubic exists).
fn committed() -> Vec<([f64; 5], (f64, f64, f64))> {
    read_optima(EXHAUSTIVE)
}

/// Slow oracle (about 20 s): recompute the exhaustive optima and compare with the
/// committed file; with `AECURVE_WRITE_DATA=1` write the file instead.
#[test]
#[ignore = "slow oracle: recomputes tests/data/approx_exhaustive.csv; .ci/run runs it"]
fn committed_exhaustive_optima_are_current() {
    let mut rows = Vec::new();
    for c in random_cases(CASES) {
        let [alpha, td, phi, scale, rot] = c;
        let seg = LacSegment::new(alpha, triangle(td, phi, scale, rot)).unwrap();
        rows.push((c, exhaustive_best(&seg, 80)));
    }
    if std::env::var_os("AECURVE_WRITE_DATA").is_some() {
        write_optima(
            EXHAUSTIVE,
            "# Exhaustive optimum of the rational cubic family for random LAC segments: an 80 x 80\n\
             # grid over (f0, f1) of the exact rms (201 samples, exact monotone test), refined by a\n\
             # shrinking pattern search to 1e-7 (tests/approx_reference.rs, exhaustive_best).\n\
             alpha,theta_d,phi,scale,rotation,best_rms,f0,f1\n",
            &rows,
        );
        return;
    }
    let old = committed();
    assert_eq!(old.len(), rows.len());
    for ((c, b), (oc, ob)) in rows.iter().zip(&old) {
        assert_eq!(c, oc);
        // The rms is relative to the arc length and computed from distances known to a
        // few units of 1e-16 of the size: below 1e-15 absolute it is rounding, whatever
        // its relative size (a Λ solved to the last bit by another root finder moves a
        // 6e-8 optimum by 3e-9 of itself).
        assert!(
            (b.0 == ob.0) || (b.0 - ob.0).abs() <= 1e-9 * ob.0 + 1e-15,
            "{c:?}: {b:?} vs committed {ob:?}"
        );
    }
}

#[test]
fn optimum_is_global_and_checked() {
    let rows = committed();
    assert_eq!(rows.len(), CASES);
    let mut worst_ratio = 0.0f64;
    let mut checked = 0;
    for ([alpha, td, phi, scale, rot], (best, b0, b1)) in rows {
        let tri = triangle(td, phi, scale, rot);
        let seg = match LacSegment::new(alpha, tri) {
            Ok(s) => s,
            Err(e) => panic!("alpha {alpha} td {td} phi {phi}: {e}"),
        };
        let fit = match fit_rational_cubic(&seg, &ApproxOptions::default()) {
            Ok(f) => f,
            // No monotone cubic at all: the exhaustive search must agree.
            Err(e) => {
                assert_eq!(best, f64::INFINITY, "{alpha} {td}: {e}");
                continue;
            }
        };
        checked += 1;
        let ratio = fit.rms / best;
        worst_ratio = worst_ratio.max(ratio);
        assert!(
            ratio <= 1.01,
            "alpha {alpha:?} td {td:?} phi {phi:?}: rms {:e} at ({}, {}) vs exhaustive {best:e} at ({b0}, {b1})",
            fit.rms, fit.f0, fit.f1
        );
        // Ends: points, tangent directions and curvatures of the segment.
        let c = &fit.curve;
        let size = (tri[1] - tri[0]).hypot();
        let (k0, k1) = seg.end_curvatures().unwrap();
        assert!((c.eval(0.0) - tri[0]).hypot() < 1e-12 * size);
        assert!((c.eval(1.0) - tri[2]).hypot() < 1e-12 * size);
        let (t0, t1) = (c.eval_d(0.0), c.eval_d(1.0));
        assert!(t0.cross(tri[1] - tri[0]).abs() < 1e-12 * t0.hypot() * size);
        assert!(t1.cross(tri[2] - tri[1]).abs() < 1e-12 * t1.hypot() * size);
        assert!((c.kappa(0.0) - k0).abs() < 1e-10 * k0.abs());
        assert!((c.kappa(1.0) - k1).abs() < 1e-10 * k1.abs());
        assert!(c.weights().iter().all(|w| *w > 0.0));
        // Curvature monotone by an independent check: dense sampling, one direction only.
        let ks: Vec<f64> = (0..=20000).map(|i| c.kappa(i as f64 / 20000.0)).collect();
        let up = ks
            .windows(2)
            .filter(|w| w[1] > w[0] + 1e-12 * w[0].abs())
            .count();
        let down = ks
            .windows(2)
            .filter(|w| w[1] < w[0] - 1e-12 * w[0].abs())
            .count();
        assert!(
            up == 0 || down == 0,
            "alpha {alpha}: curvature not monotone ({up} up, {down} down)"
        );
    }
    assert!(checked >= 12, "only {checked} cases had a monotone cubic");
    println!("worst rms / exhaustive best over {checked} cases: {worst_ratio:.6}");
}

/// While the end point slides, the returned error varies continuously: a local optimiser
/// that jumps between basins shows a spike in the change of the error (a jump to a worse
/// basin and back), where the global optimum only ever switches basins at a tie.
#[test]
fn error_varies_continuously_while_a_point_slides() {
    let td = 90f64.to_radians();
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let lim = LacSegment::theta_lim(alpha, td).unwrap();
        let steps = 80;
        let mut rms = Vec::new();
        let mut segs = Vec::new();
        for k in 0..=steps {
            let phi = 0.5 * td + (0.02 + 0.9 * k as f64 / steps as f64) * (lim - 0.5 * td);
            let seg = LacSegment::new(alpha, triangle(td, phi, 1.0, 0.0)).unwrap();
            match fit_rational_cubic(&seg, &ApproxOptions::default()) {
                Ok(fit) => {
                    rms.push(fit.rms);
                    segs.push(seg);
                }
                Err(e) => {
                    let (best, b0, b1) = exhaustive_best(&seg, 60);
                    assert_eq!(
                        best,
                        f64::INFINITY,
                        "alpha {alpha} step {k}: {e}, but ({b0}, {b1}) is monotone"
                    );
                    break;
                }
            }
        }
        if rms.len() < 3 {
            continue;
        }
        let max = rms.iter().copied().fold(0.0, f64::max);
        let d: Vec<f64> = rms.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
        for k in 1..d.len() - 1 {
            if d[k] <= 4.0 * d[k - 1].max(d[k + 1]) + 0.02 * max {
                continue;
            }
            // A jump is allowed only where the global optimum itself jumps: both sides must
            // then be the exhaustive optimum.
            let ex: Vec<_> = [k, k + 1]
                .iter()
                .map(|&i| exhaustive_best(&segs[i], 80))
                .collect();
            let on_both = rms[k] <= 1.01 * ex[0].0 && rms[k + 1] <= 1.01 * ex[1].0;
            assert!(
                on_both,
                "exhaustive {ex:?}; alpha {alpha} step {k}: error jumps {:e} -> {:e} (neighbouring changes {:e}, {:e})",
                rms[k],
                rms[k + 1],
                d[k - 1],
                d[k + 1]
            );
        }
    }
}
