//! Identities the monotonicity test must respect: similarity invariance (translation,
//! rotation, uniform scaling, mirroring), reversal symmetry, invariance under degree
//! elevation and subdivision, and agreement with dense sampling away from the extrema.

use aesthetic_curves::monotone::{CurvatureMonotone, Trend};
use aesthetic_curves::samples::random_curves;
use aesthetic_curves::{Bezier, Error, PlanarCurve, Point, RationalBezier};
use proptest::prelude::*;

fn transform(pts: &[Point], angle: f64, scale: f64, dx: f64, dy: f64, mirror: bool) -> Vec<Point> {
    let (c, s) = (angle.cos(), angle.sin());
    pts.iter()
        .map(|p| {
            let y = if mirror { -p.y } else { p.y };
            Point::new(
                scale * (c * p.x - s * y) + dx,
                scale * (s * p.x + c * y) + dy,
            )
        })
        .collect()
}

fn arb_curve() -> impl Strategy<Value = Vec<Point>> {
    (3usize..=7).prop_flat_map(|n| {
        prop::collection::vec((-10.0f64..10.0, -10.0f64..10.0), n + 1)
            .prop_map(|v| v.into_iter().map(|(x, y)| Point::new(x, y)).collect())
    })
}

fn close_lists(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn similarity_invariance(pts in arb_curve(), angle in -3.2f64..3.2, scale in 0.01f64..100.0,
                             dx in -30f64..30.0, dy in -30f64..30.0, mirror in any::<bool>()) {
        // Translations in proportion to the size: a curve moved far from the origin loses
        // digits to rounding, and near-boundary verdicts may then legitimately differ.
        let (dx, dy) = (dx * scale, dy * scale);
        let a = Bezier::new(pts.clone()).unwrap().curvature_monotone();
        let b = Bezier::new(transform(&pts, angle, scale, dx, dy, mirror)).unwrap().curvature_monotone();
        match (a, b) {
            (Ok(a), Ok(b)) => {
                prop_assert_eq!(a.monotone, b.monotone);
                prop_assert!(close_lists(&a.extrema, &b.extrema, 1e-7), "{:?} {:?}", a.extrema, b.extrema);
                // A mirror flips the sign of curvature, hence the trend.
                if let (Some(ta), Some(tb)) = (a.trend, b.trend) {
                    let flipped = match ta { Trend::Increasing => Trend::Decreasing, Trend::Decreasing => Trend::Increasing, t => t };
                    prop_assert_eq!(tb, if mirror { flipped } else { ta });
                }
            }
            (Err(Error::Degenerate(_)), Err(Error::Degenerate(_))) => {}
            (a, b) => prop_assert!(false, "verdicts differ: {:?} vs {:?}", a, b),
        }
    }

    #[test]
    fn reversal_mirrors_the_extrema(pts in arb_curve()) {
        let rev: Vec<Point> = pts.iter().rev().copied().collect();
        let (fwd, back) = (Bezier::new(pts).unwrap(), Bezier::new(rev).unwrap());
        let a = fwd.curvature_monotone();
        let b = back.curvature_monotone();
        if let (Ok(a), Ok(b)) = (a, b) {
            prop_assert_eq!(a.monotone, b.monotone);
            let mirrored: Vec<f64> = b.extrema.iter().rev().map(|t| 1.0 - t).collect();
            prop_assert_eq!(a.extrema.len(), mirrored.len());
            // 1e-9, or what f64 allows: a root of K where |K'| is small (near a double root)
            // moves by up to the coefficients' rounding bound over |K'| (one case in a few
            // thousand: 1.6e-9 at |K'| = 158 against K's scale 2.5e9).
            let cv = (fwd.curvature_variation(), back.curvature_variation());
            let noise = |c: &aesthetic_curves::monotone::CurvatureVariation| {
                c.k_noise.iter().fold(0.0f64, |m, v| m.max(*v))
            };
            let bound = noise(&cv.0) + noise(&cv.1);
            for (x, y) in a.extrema.iter().zip(&mirrored) {
                let h = 1e-7;
                let slope = ((cv.0.k.eval(x + h) - cv.0.k.eval(x - h)) / (2.0 * h)).abs();
                let tol = 1e-9 + 2.0 * bound / slope;
                prop_assert!((x - y).abs() <= tol, "{:?} {:?} (tolerance {:e})", a.extrema, mirrored, tol);
            }
        }
    }

    #[test]
    fn elevation_keeps_the_verdict(pts in arb_curve()) {
        let b = Bezier::new(pts).unwrap();
        let e = b.elevate().unwrap();
        if let (Ok(x), Ok(y)) = (b.curvature_monotone(), e.curvature_monotone()) {
            prop_assert_eq!(x.monotone, y.monotone);
            prop_assert!(close_lists(&x.extrema, &y.extrema, 1e-8));
        }
    }

    #[test]
    fn rational_weights_scale_invariance(pts in arb_curve(), w in prop::collection::vec(0.2f64..5.0, 8), s in 0.01f64..100.0) {
        let n = pts.len();
        let w = w[..n].to_vec();
        let ws: Vec<f64> = w.iter().map(|v| v * s).collect();
        let a = RationalBezier::new(pts.clone(), w).unwrap().curvature_monotone();
        let b = RationalBezier::new(pts, ws).unwrap().curvature_monotone();
        if let (Ok(a), Ok(b)) = (a, b) {
            prop_assert_eq!(a.monotone, b.monotone);
            prop_assert!(close_lists(&a.extrema, &b.extrema, 1e-8));
        }
    }
}

#[test]
fn dense_sampling_agrees_where_it_can_see() {
    // With 20000 divisions, sampling only misses extrema of tiny amplitude; count both ways.
    let mut checked = 0;
    for degree in [3, 4, 5, 7] {
        for c in random_curves(degree, 200, 9) {
            let Ok(exact) = c.curvature_monotone() else {
                continue;
            };
            let s = c.curvature_monotone_sampled(20000).unwrap();
            if exact.monotone {
                assert!(
                    s.monotone,
                    "exact says monotone, dense sampling not: {:?}",
                    c.points()
                );
            } else if !s.monotone {
                checked += 1;
            }
        }
    }
    assert!(checked > 300, "{checked}");
}

#[test]
fn every_degree_up_to_20_works_and_subdivision_locates_extrema() {
    for degree in 1..=20 {
        for c in random_curves(degree, 20, 3) {
            let Ok(r) = c.curvature_monotone() else {
                continue;
            };
            assert_eq!(
                r.test_degree,
                if degree >= 3 {
                    4 * degree - 7
                } else if degree == 2 {
                    1
                } else {
                    0
                }
            );
            // At each reported extremum dkappa/ds changes sign.
            for &t in &r.extrema {
                let h = 1e-6;
                let (a, b) = (c.dkappa_ds((t - h).max(0.0)), c.dkappa_ds((t + h).min(1.0)));
                assert!(
                    a * b <= 0.0 || a.abs().min(b.abs()) < 1e-6 * a.abs().max(b.abs()),
                    "degree {degree}: no sign change of dkappa/ds around {t}: {a} {b}"
                );
            }
        }
    }
}

#[test]
fn huge_and_tiny_coordinates_give_the_same_verdicts() {
    for c in random_curves(4, 100, 11) {
        let big = Bezier::new(
            c.points()
                .iter()
                .map(|p| Point::new(p.x * 1e12, p.y * 1e12))
                .collect(),
        )
        .unwrap();
        let small = Bezier::new(
            c.points()
                .iter()
                .map(|p| Point::new(p.x * 1e-12, p.y * 1e-12))
                .collect(),
        )
        .unwrap();
        let (a, b, d) = (
            c.curvature_monotone(),
            big.curvature_monotone(),
            small.curvature_monotone(),
        );
        if let (Ok(a), Ok(b), Ok(d)) = (a, b, d) {
            assert_eq!(a.monotone, b.monotone);
            assert_eq!(a.monotone, d.monotone);
        }
    }
}

#[test]
fn fast_verdict_agrees_with_the_full_analysis() {
    // `is_curvature_monotone` takes shortcuts (value-only pass, a loose global rounding
    // bound); it must never disagree with the full per-coefficient analysis.
    for degree in 2..=12 {
        for c in random_curves(degree, if degree <= 7 { 400 } else { 60 }, 77) {
            match (c.curvature_monotone(), c.is_curvature_monotone()) {
                (Ok(full), Ok(fast)) => assert_eq!(full.monotone, fast, "{:?}", c.points()),
                (Err(_), Err(_)) => {}
                (a, b) => panic!("degree {degree}: {a:?} vs {b:?}"),
            }
        }
    }
}

/// Scaled by 2^1021 (exact: a power of two), curves whose control points differ by more
/// than the largest double keep their verdict, their extrema and their end curvatures
/// (divided by the scale): the differences of the coordinates overflowed before, and the end
/// curvatures came out infinite or NaN (`null` in `check --json`).
#[test]
fn curves_at_the_top_of_the_range_keep_verdicts_and_end_curvatures() {
    let s = 2f64.powi(1021);
    let mut overflowing = 0;
    let scale = |p: &[Point]| -> Option<Vec<Point>> {
        let q: Vec<Point> = p.iter().map(|p| Point::new(p.x * s, p.y * s)).collect();
        q.iter()
            .all(|p| p.x.is_finite() && p.y.is_finite())
            .then_some(q)
    };
    let check = |a: aesthetic_curves::monotone::MonotoneReport,
                 b: aesthetic_curves::monotone::MonotoneReport| {
        assert_eq!(a.monotone, b.monotone);
        assert_eq!(a.extrema.len(), b.extrema.len());
        for (x, y) in a.extrema.iter().zip(&b.extrema) {
            assert!((x - y).abs() < 1e-12, "{x} {y}");
        }
        for (e, f) in a.ends.iter().zip(&b.ends) {
            let (Some(k), Some(kb)) = (e.value(), f.value()) else {
                assert_eq!(e.value().is_none(), f.value().is_none(), "{e:?} {f:?}");
                continue;
            };
            assert!(kb.is_finite(), "{f:?}");
            let back = kb * s;
            assert!((back - k).abs() <= 1e-9 * k.abs() + 1e-15, "{k} vs {back}");
        }
    };
    for degree in [2, 3, 4, 5] {
        for c in random_curves(degree, 60, 5) {
            let Some(q) = scale(c.points()) else { continue };
            let spread = q
                .iter()
                .any(|a| q.iter().any(|b| (a.x - b.x).is_infinite()));
            overflowing += spread as usize;
            let big = Bezier::new(q).unwrap();
            if let (Ok(a), Ok(b)) = (c.curvature_monotone(), big.curvature_monotone()) {
                check(a, b);
            }
        }
        for c in aesthetic_curves::samples::random_rational_curves(degree, 30, 6) {
            let Some(q) = scale(c.points()) else { continue };
            let big = RationalBezier::new(q, c.weights().to_vec()).unwrap();
            if let (Ok(a), Ok(b)) = (c.curvature_monotone(), big.curvature_monotone()) {
                check(a, b);
            }
        }
    }
    assert!(
        overflowing > 20,
        "{overflowing} curves whose differences overflow"
    );
}
