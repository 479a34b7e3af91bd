//! The sketch pipeline on points sampled from known G2 piecewise-LAC curves.

use aesthetic_curves::lac::{LacInflectionSegment, LacSegment};
use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::sketch::{fit_sketch, PieceKind, SketchOptions};
use aesthetic_curves::{Point, Vec2};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// Reflect `q` across the line through `o` with direction `d`.
fn mirror(q: Point, o: Point, d: Vec2) -> Point {
    let d = d / d.hypot();
    let v = q - o;
    o + d * (2.0 * v.dot(d)) - v
}

/// A symmetric bump: a LAC segment rising to its curvature peak, then its mirror image.
fn bump(alpha: f64, n: usize) -> Vec<Point> {
    // High-curvature end at control[2] (larger base angle there).
    let seg = LacSegment::new(alpha, [p(0.0, 0.0), p(6.0, 3.0), p(9.0, 0.5)]).unwrap();
    let (pts, _) = seg.sample(n).unwrap();
    let end = pts[n - 1];
    let (_, d) = seg.eval_turning(&[seg.theta_d]).unwrap();
    let normal = Vec2::new(-d[0].y, d[0].x);
    let mut out = pts.clone();
    for q in pts.iter().rev().skip(1) {
        out.push(mirror(*q, end, normal));
    }
    out
}

/// An S curve: an inflection-end segment and its point reflection through the inflection.
fn s_curve(n: usize) -> (Vec<Point>, f64) {
    let seg = LacInflectionSegment::new([p(0.0, 0.0), p(5.0, 0.0), p(7.0, 3.0)]).unwrap();
    let (pts, _) = seg.sample(n).unwrap();
    let mut out: Vec<Point> = pts.iter().rev().map(|q| p(-q.x, -q.y)).collect();
    out.extend(pts.iter().skip(1));
    (out, seg.alpha)
}

fn noisy(points: &[Point], amp: f64) -> Vec<Point> {
    // Deterministic pseudo-random noise.
    let mut s = 12345u64;
    let mut r = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    points
        .iter()
        .map(|q| p(q.x + amp * r(), q.y + amp * r()))
        .collect()
}

fn size(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for q in points {
        lo = p(lo.x.min(q.x), lo.y.min(q.y));
        hi = p(hi.x.max(q.x), hi.y.max(q.y));
    }
    (hi - lo).hypot()
}

fn check(name: &str, points: &[Point], tol: f64, truth: Option<&[f64]>) {
    check_g2(name, points, tol, truth, true)
}

fn check_g2(name: &str, points: &[Point], tol: f64, truth: Option<&[f64]>, want_g2: bool) {
    let t0 = std::time::Instant::now();
    let sk = fit_sketch(points, &SketchOptions::with_tolerance(tol)).unwrap();
    let dt = t0.elapsed();
    println!(
        "{name}: {} pieces, dev {:.3e} (tol {tol:.1e}), jump {:.2e}, fairing {:?}, {:?}",
        sk.pieces.len(),
        sk.max_deviation,
        sk.max_curvature_jump,
        sk.fairing,
        dt
    );
    println!(
        "   bspline dev {:.3e}, {} control points",
        sk.bspline_deviation,
        sk.bspline.control_points.len()
    );
    for pc in &sk.pieces {
        println!(
            "   rational k ({:.6e}, {:.6e})",
            pc.rational.kappa_start(),
            pc.rational.kappa_end()
        );
        println!(
            "   {:?} alpha {:.4} est {:?} k {:?} err {:.2e}",
            pc.kind, pc.alpha, pc.alpha_estimate, pc.end_curvatures, pc.rational_error
        );
    }
    assert!(sk.max_deviation <= tol, "{name}: deviation");
    if want_g2 {
        assert!(sk.max_curvature_jump < 1e-6, "{name}: G2");
    }
    for pc in &sk.pieces {
        // Independent check: the sampling test at 2000 divisions, and the exact test.
        assert!(
            pc.rational
                .curvature_monotone_sampled(2000)
                .unwrap()
                .monotone
        );
        assert!(pc.rational.is_curvature_monotone().unwrap());
    }
    if let Some(t) = truth {
        let lac: Vec<f64> = sk
            .pieces
            .iter()
            .filter(|p| p.kind == PieceKind::Lac || p.kind == PieceKind::LacInflection)
            .map(|p| p.alpha)
            .collect();
        for (a, b) in lac.iter().zip(t) {
            assert!((a - b).abs() < 0.15, "{name}: alpha {a} vs {b}");
        }
    }
}

#[test]
fn single_segments() {
    for alpha in [-1.0, 0.0, 0.5, 1.0, 2.0] {
        let seg = LacSegment::new(alpha, [p(0.0, 0.0), p(6.0, 3.0), p(9.0, 0.5)]).unwrap();
        let (pts, _) = seg.sample(300).unwrap();
        check(
            &format!("single {alpha}"),
            &pts,
            1e-3 * size(&pts),
            Some(&[alpha]),
        );
    }
}

#[test]
fn symmetric_bump() {
    for alpha in [-1.0, 0.5, 2.0] {
        let pts = bump(alpha, 200);
        check(
            &format!("bump {alpha}"),
            &pts,
            1e-3 * size(&pts),
            Some(&[alpha, alpha]),
        );
        let n = noisy(&pts, 2e-4 * size(&pts));
        check(&format!("noisy bump {alpha}"), &n, 3e-3 * size(&pts), None);
    }
}

#[test]
fn s_curve_through_an_inflection() {
    let (pts, alpha) = s_curve(200);
    check("s curve", &pts, 1e-3 * size(&pts), Some(&[alpha, alpha]));
    let n = noisy(&pts, 2e-4 * size(&pts));
    check("noisy s curve", &n, 3e-3 * size(&pts), None);
}

fn prius(i: usize) -> Vec<Point> {
    aesthetic_curves_data::PRIUS[i - 1]
        .points()
        .into_iter()
        .map(|[x, y]| p(x, y))
        .collect()
}

#[test]
fn prius_key_lines_at_0_3_mm() {
    for i in [1, 2, 3, 4, 5] {
        let pts = prius(i);
        check(&format!("prius {i}"), &pts, 0.3, None);
    }
}
