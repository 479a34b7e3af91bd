//! The G2 log-aesthetic spline against checks that do not share its code: the delivered
//! rational cubics evaluated here from their homogeneous Bernstein form (value and first
//! two derivatives by the test's own de Casteljau), curvature from those, and identities
//! (similarity, reversal, points on a circle).

use aesthetic_curves::lac_spline::{lac_spline, LacSpline, LacSplineOptions, SplinePieceKind};
use aesthetic_curves::samples::{random_walk, wavy_points, SplitMix64};
use aesthetic_curves::{CurvatureMonotone, Error, Point, Vec2};

/// Homogeneous point (w x, w y, w) and its first two derivatives of a rational cubic.
fn derivs(p: &[Point], w: &[f64], t: f64) -> [[f64; 3]; 3] {
    let h: Vec<[f64; 3]> = p
        .iter()
        .zip(w)
        .map(|(p, w)| [p.x * w, p.y * w, *w])
        .collect();
    let b = |k: usize, t: f64| -> f64 {
        let n = h.len() - 1;
        let c = [1.0, 3.0, 3.0, 1.0];
        debug_assert_eq!(n, 3);
        c[k] * t.powi(k as i32) * (1.0 - t).powi((n - k) as i32)
    };
    let mut out = [[0.0; 3]; 3];
    for d in 0..3 {
        out[0][d] = (0..4).map(|k| b(k, t) * h[k][d]).sum();
        // First and second derivatives from the differences of the homogeneous points.
        let d1: Vec<f64> = (0..3).map(|k| 3.0 * (h[k + 1][d] - h[k][d])).collect();
        let d2: Vec<f64> = (0..2).map(|k| 2.0 * (d1[k + 1] - d1[k])).collect();
        out[1][d] = d1[0] * (1.0 - t).powi(2) + 2.0 * d1[1] * t * (1.0 - t) + d1[2] * t * t;
        out[2][d] = d2[0] * (1.0 - t) + d2[1] * t;
    }
    out
}

/// Point, unit tangent and signed curvature of a rational cubic at t.
fn frame(p: &[Point], w: &[f64], t: f64) -> (Point, Vec2, f64) {
    let [h, h1, h2] = derivs(p, w, t);
    let x = Vec2::new(h[0] / h[2], h[1] / h[2]);
    // x' = (h1 - w' x)/w, x'' = (h2 - 2 w' x' - w'' x)/w.
    let v = (Vec2::new(h1[0], h1[1]) - x * h1[2]) / h[2];
    let a = (Vec2::new(h2[0], h2[1]) - v * (2.0 * h1[2]) - x * h2[2]) / h[2];
    let k = v.cross(a) / v.hypot().powi(3);
    (x.to_point(), v.normalize(), k)
}

fn ends(s: &LacSpline, i: usize) -> [(Point, Vec2, f64); 2] {
    let r = &s.pieces[i].rational;
    [
        frame(r.points(), r.weights(), 0.0),
        frame(r.points(), r.weights(), 1.0),
    ]
}

fn size(points: &[Point]) -> f64 {
    points
        .iter()
        .map(|p| (*p - points[0]).hypot())
        .fold(0.0, f64::max)
}

/// Every check of a result: the points hit, G1 and G2 at every smooth join (the seam of a
/// closed curve included) and every cubic proven monotone; returns the largest relative
/// curvature jump and the largest join angle.
fn check(points: &[Point], opts: &LacSplineOptions, s: &LacSpline) -> (f64, f64) {
    let n = points.len();
    let tol = 1e-12 * size(points);
    // Each span's pieces start at its point and end at the next.
    let spans = if opts.closed { n } else { n - 1 };
    for k in 0..spans {
        let mine: Vec<usize> = (0..s.pieces.len())
            .filter(|&i| s.pieces[i].span == k)
            .collect();
        assert!(!mine.is_empty(), "span {k} has no piece");
        let first = ends(s, mine[0])[0].0;
        let last = ends(s, *mine.last().unwrap())[1].0;
        assert!(
            (first - points[k]).hypot() <= tol,
            "span {k} starts off its point"
        );
        assert!(
            (last - points[(k + 1) % n]).hypot() <= tol,
            "span {k} ends off its point"
        );
    }
    let kmax = (0..s.pieces.len())
        .flat_map(|i| ends(s, i).map(|e| e.2.abs()))
        .fold(0.0, f64::max);
    let joins = if opts.closed {
        s.pieces.len()
    } else {
        s.pieces.len() - 1
    };
    let (mut jump, mut angle) = (0.0f64, 0.0f64);
    for j in 0..joins {
        let (a, b) = (j, (j + 1) % s.pieces.len());
        let corner =
            s.pieces[b].span != s.pieces[a].span && opts.corners.contains(&s.pieces[b].span);
        let (ea, eb) = (ends(s, a)[1], ends(s, b)[0]);
        assert!((ea.0 - eb.0).hypot() <= tol, "join {j} is not continuous");
        if corner {
            continue;
        }
        angle = angle.max(ea.1.cross(eb.1).abs());
        jump = jump.max((ea.2 - eb.2).abs() / kmax.max(1e-300));
    }
    for (i, p) in s.pieces.iter().enumerate() {
        let verdict = p.rational.is_curvature_monotone().unwrap();
        assert!(
            verdict && p.monotone,
            "piece {i} ({:?}) not monotone",
            p.kind
        );
    }
    assert!(s.all_monotone);
    (jump, angle)
}

/// G2 to 1e-10, or to the rounding of coordinates far from the origin (the cubic of a
/// nearly circular piece is tilted above it to be proven monotone: lac_spline/pieces.rs).
fn run(points: &[Point], opts: &LacSplineOptions) -> LacSpline {
    let reach = points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    run_within(
        points,
        opts,
        1e-10f64.max(1e3 * f64::EPSILON * reach / size(points)),
    )
}

fn run_within(points: &[Point], opts: &LacSplineOptions, bound: f64) -> LacSpline {
    let s = lac_spline(points, opts).unwrap_or_else(|e| panic!("{e}"));
    let (jump, angle) = check(points, opts, &s);
    assert!(jump < bound, "curvature jump {jump:e}");
    assert!(angle < 1e-9, "join angle {angle:e}");
    s
}

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

#[test]
fn open_curves_pass_through_the_points_g2_with_monotone_pieces() {
    for alpha in [-2.0, -1.0, -0.5] {
        for seed in 1..=5 {
            let pts = wavy_points(8, seed);
            let s = run(
                &pts,
                &LacSplineOptions {
                    alpha,
                    ..Default::default()
                },
            );
            // Every piece of shape α (the inflection halves' α is solved back from their
            // triangle: to rounding).
            for pc in &s.pieces {
                if let Some(a) = pc.alpha {
                    assert!((a - alpha).abs() < 1e-9, "{a} for {alpha}");
                }
            }
        }
    }
}

#[test]
fn positive_alphas_pass_through_the_points_g2() {
    // α >= 0 has no inflection-end segment: S-spans get clothoid-like halves; the bends
    // keep α where a segment of it exists.
    for alpha in [0.0, 1.0, 2.0] {
        let pts = [
            p(0.0, 0.0),
            p(3.0, 2.0),
            p(6.0, 2.5),
            p(9.0, 1.0),
            p(11.0, -1.5),
        ];
        let s = run(
            &pts,
            &LacSplineOptions {
                alpha,
                ..Default::default()
            },
        );
        assert!(s.pieces.iter().any(|pc| pc.alpha == Some(alpha)));
    }
}

#[test]
fn points_on_a_circle_give_the_circle() {
    for n in [3usize, 5, 8] {
        for closed in [true, false] {
            let r = 7.5;
            let c = p(3.0, -2.0);
            let count = if closed { n } else { n + 1 };
            let pts: Vec<Point> = (0..count)
                .map(|k| {
                    let a = 0.3
                        + 2.0 * std::f64::consts::PI * k as f64 / n as f64
                            * if closed { 1.0 } else { 0.6 };
                    c + Vec2::from_angle(a) * r
                })
                .collect();
            let s = run(
                &pts,
                &LacSplineOptions {
                    closed,
                    ..Default::default()
                },
            );
            for pc in &s.pieces {
                for i in 0..=20 {
                    let t = i as f64 / 20.0;
                    let (x, _, k) = frame(pc.rational.points(), pc.rational.weights(), t);
                    assert!(
                        ((x - c).hypot() - r).abs() < 1e-9 * r,
                        "n {n}: off the circle"
                    );
                    assert!((k * r - 1.0).abs() < 1e-9, "n {n}: curvature {k}");
                }
            }
        }
    }
}

#[test]
fn a_closed_curve_is_g2_at_its_seam() {
    let pts = [
        p(0.0, 0.0),
        p(4.0, -1.0),
        p(8.0, 1.0),
        p(7.0, 5.0),
        p(3.0, 6.0),
        p(-1.0, 3.0),
    ];
    let opts = LacSplineOptions {
        closed: true,
        ..Default::default()
    };
    let s = run(&pts, &opts);
    assert!(s.closed && s.pieces.last().unwrap().span == pts.len() - 1);
}

/// S2's example points taken as a closed curve: a thin zig-zag whose closing chord the
/// circles' tangents ask to turn 320° (once refused: "cannot start"). The
/// mended start (the closing span's ends taken from their short spans) converges to
/// libspiro's root (the spiro-oracle test compares them); here without libspiro: it passes
/// through the points G2 with proven pieces, and backwards and under a similarity (rotated,
/// scaled 1000 times, 1e6 away) it is the same curve: the same largest |κ| (over the
/// scale), the same inflections.
#[test]
fn a_thin_closed_zigzag_is_solved() {
    let pts = aesthetic_curves::samples::s2_points();
    let opts = LacSplineOptions {
        closed: true,
        ..Default::default()
    };
    let big = |s: &LacSpline| {
        s.pieces.iter().fold(0.0f64, |m, q| {
            m.max(q.end_curvatures.0.abs())
                .max(q.end_curvatures.1.abs())
        })
    };
    let forward = run(&pts, &opts);
    let mut back = pts.to_vec();
    back.reverse();
    let backward = run(&back, &opts);
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let moved: Vec<Point> = pts
        .iter()
        .map(|q| {
            p(
                1e6 + 1000.0 * (c * q.x - s * q.y),
                -1e6 + 1000.0 * (s * q.x + c * q.y),
            )
        })
        .collect();
    let similar = run(&moved, &opts);
    let k = big(&forward);
    assert!(
        (big(&backward) - k).abs() <= 1e-9 * k,
        "{} {k}",
        big(&backward)
    );
    assert!(
        (1000.0 * big(&similar) - k).abs() <= 1e-6 * k,
        "{} {k}",
        big(&similar)
    );
    for other in [&backward, &similar] {
        assert_eq!(other.inflections, forward.inflections);
    }
}

#[test]
fn corners_break_the_tangent_and_free_the_curvature() {
    // A closed contour with two corners: a lens-like shape with a bump.
    let pts = [
        p(0.0, 0.0),
        p(5.0, -2.0),
        p(10.0, 0.0),
        p(7.0, 3.0),
        p(3.0, 3.5),
    ];
    let opts = LacSplineOptions {
        closed: true,
        corners: vec![0, 2],
        ..Default::default()
    };
    let s = run(&pts, &opts);
    // The tangent turns at the corners.
    let into = |span: usize| {
        let i = s.pieces.iter().rposition(|pc| pc.span == span).unwrap();
        ends(&s, i)[1].1
    };
    let out = |span: usize| {
        let i = s.pieces.iter().position(|pc| pc.span == span).unwrap();
        ends(&s, i)[0].1
    };
    assert!(into(4).cross(out(0)).abs() > 0.1 && into(1).cross(out(2)).abs() > 0.1);
}

#[test]
fn the_same_curve_under_a_similarity_and_backwards() {
    let pts = wavy_points(7, 11);
    let opts = LacSplineOptions::default();
    let s = run(&pts, &opts);
    // Rotation by 0.7, scale 1000, far from the origin.
    let (rot, scale, off) = (Vec2::from_angle(0.7), 1000.0, Vec2::new(1e6, -3e5));
    let map = |q: Point| {
        let v = q.to_vec2() * scale;
        (Vec2::new(rot.x * v.x - rot.y * v.y, rot.y * v.x + rot.x * v.y) + off).to_point()
    };
    let unmap = |q: Point| {
        let v = (q.to_vec2() - off) / scale;
        Point::new(rot.x * v.x + rot.y * v.y, -rot.y * v.x + rot.x * v.y)
    };
    let moved: Vec<Point> = pts.iter().map(|q| map(*q)).collect();
    let m = run(&moved, &opts);
    assert_eq!(m.pieces.len(), s.pieces.len());
    // Compared as point sets (a nearly circular piece's cubic can be parameterized
    // differently at another scale): every point of one within 1e-9 of the other, with the
    // curvature there scaled.
    for (a, b) in s.pieces.iter().zip(&m.pieces) {
        for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let (x, _, k) = frame(a.rational.points(), a.rational.weights(), t);
            let q: Vec<Point> = b.rational.points().iter().map(|q| unmap(*q)).collect();
            let (d, kk) = nearest(&q, b.rational.weights(), x);
            assert!(d < 1e-9, "similarity moved a point by {d:e}");
            assert!((k - kk).abs() < 1e-7 * k.abs().max(0.01), "{k} vs {kk}");
        }
    }
    // Backwards: the same points in reverse give the same curve traversed the other way.
    let back: Vec<Point> = pts.iter().rev().copied().collect();
    let r = run(&back, &opts);
    let n = s.pieces.len();
    assert_eq!(r.pieces.len(), n);
    for (i, a) in s.pieces.iter().enumerate() {
        let b = &r.pieces[n - 1 - i];
        for t in [0.0, 0.3, 0.6, 1.0] {
            let (x, _, k) = frame(a.rational.points(), a.rational.weights(), t);
            let (d, kk) = nearest(b.rational.points(), b.rational.weights(), x);
            assert!(d < 1e-9, "reversal moved a point by {d:e}");
            assert!(
                (k + kk).abs() < 1e-7 * k.abs().max(0.01),
                "reversal: curvature {k} vs {kk}"
            );
        }
    }
}

/// Distance from `x` to a rational cubic and the curvature at the nearest point: the best
/// of 64 samples, then Newton's method on (c(t) - x) · c'(t) = 0.
fn nearest(p: &[Point], w: &[f64], x: Point) -> (f64, f64) {
    let dist = |t: f64| (frame(p, w, t).0 - x).hypot();
    let mut t = (0..=64)
        .map(|i| i as f64 / 64.0)
        .min_by(|a, b| dist(*a).total_cmp(&dist(*b)))
        .unwrap();
    for _ in 0..30 {
        let h = 1e-6;
        let g = |t: f64| {
            let (c, v, _) = frame(p, w, t);
            (c - x).dot(v)
        };
        let d = (g(t + h) - g(t - h)) / (2.0 * h);
        t = (t - g(t) / d).clamp(0.0, 1.0);
    }
    (dist(t), frame(p, w, t).2)
}

#[test]
fn near_degenerate_points_are_normal_points() {
    // Collinear points: one line through them all.
    let line: Vec<Point> = (0..6).map(|k| p(3.0 * k as f64, 1.5 * k as f64)).collect();
    let s = run(&line, &LacSplineOptions::default());
    assert!(s.pieces.iter().all(|pc| pc.kind == SplinePieceKind::Line));
    // Integer coordinates far from the origin, tiny and huge scales.
    let base = [p(0.0, 0.0), p(40.0, 25.0), p(90.0, 30.0), p(130.0, 0.0)];
    for (scale, off) in [(1.0, 1e7), (1e-6, 0.0), (1e6, 0.0)] {
        let pts: Vec<Point> = base
            .iter()
            .map(|q| p(q.x * scale + off, q.y * scale + off))
            .collect();
        run(&pts, &LacSplineOptions::default());
    }
    // Nearly collinear: a bend of a few millionths of a radian. The curvature of a cubic
    // this flat is known from its f64 control points to a relative 1e-16 over its turning
    // (1e-10 here), so its arcs are tilted by some 1e-9 to be proven monotone: G2 to that.
    let bent = [p(0.0, 0.0), p(1.0, 1e-6), p(2.0, 0.0)];
    let s = run_within(&bent, &LacSplineOptions::default(), 1e-8);
    assert!(s
        .pieces
        .iter()
        .all(|pc| (pc.end_curvatures.0 + 2e-6).abs() < 1e-14));
}

#[test]
fn a_span_may_turn_past_a_half_turn() {
    // A spiral through points 200° apart: its spans turn by more than π each, built in two
    // halves of the same segment (no control triangle holds one).
    let pts: Vec<Point> = (0..5)
        .map(|k| {
            let a = (200.0f64 * k as f64).to_radians();
            (Vec2::from_angle(a) * (1.0 + 0.3 * k as f64)).to_point()
        })
        .collect();
    for alpha in [-1.0, -0.5] {
        let s = run(
            &pts,
            &LacSplineOptions {
                alpha,
                ..Default::default()
            },
        );
        let turn = |span: usize| -> f64 {
            s.pieces
                .iter()
                .filter(|pc| pc.span == span)
                .map(|pc| {
                    let c = pc.rational.points();
                    let (u, v) = ((c[1] - c[0]).normalize(), (c[3] - c[2]).normalize());
                    u.cross(v).atan2(u.dot(v)).abs()
                })
                .sum()
        };
        assert!(
            (0..4).filter(|&k| turn(k) > std::f64::consts::PI).count() >= 2,
            "alpha {alpha}: spans turn {:?}",
            (0..4).map(turn).collect::<Vec<_>>()
        );
    }
}

#[test]
fn bad_input_is_refused_by_name() {
    let pts = [p(0.0, 0.0), p(1.0, 1.0), p(1.0, 1.0), p(2.0, 0.0)];
    assert!(matches!(
        lac_spline(&pts, &LacSplineOptions::default()),
        Err(Error::Degenerate(_))
    ));
    let ok = [p(0.0, 0.0), p(1.0, 1.0), p(2.0, 0.0)];
    let bad_alpha = LacSplineOptions {
        alpha: f64::NAN,
        ..Default::default()
    };
    assert!(matches!(
        lac_spline(&ok, &bad_alpha),
        Err(Error::InvalidInput { .. })
    ));
    let bad_corner = LacSplineOptions {
        corners: vec![7],
        ..Default::default()
    };
    assert!(matches!(
        lac_spline(&ok, &bad_corner),
        Err(Error::InvalidInput { .. })
    ));
    let nan = [p(0.0, 0.0), p(f64::NAN, 1.0)];
    assert!(matches!(
        lac_spline(&nan, &LacSplineOptions::default()),
        Err(Error::InvalidInput { .. })
    ));
    assert!(lac_spline(&ok[..1], &LacSplineOptions::default()).is_err());
}

/// How often the solve fails on random point sets (turns between chords up to ±120°):
/// a sweep measured, and bounded.
#[test]
fn random_point_sets_converge() {
    const TURN: f64 = 1.2;
    let mut rng = SplitMix64::new(5);
    let (mut failed, total) = (0usize, 200usize);
    for _ in 0..total {
        let pts = random_walk(&mut rng, TURN);
        match lac_spline(&pts, &LacSplineOptions::default()) {
            Ok(s) => {
                let (jump, _) = check(&pts, &LacSplineOptions::default(), &s);
                assert!(jump < 1e-10, "{pts:?}: jump {jump:e}");
            }
            Err(e) => {
                eprintln!("{e}");
                failed += 1
            }
        }
    }
    eprintln!("random point sets: {failed} of {total} failed");
    assert!(failed * 20 <= total, "{failed} of {total} failed");
}

/// The harsh sets (5 to 16 points, chords 30 times apart, turns to ±149°), open
/// and closed. Where the spans' own family (each side of an S-span turning less than a
/// half turn) holds no solution from the circles' start, the solve goes on in the wider
/// family (a side up to 1.8 half turns, built as an inflection-end piece and a segment)
/// and by continuation from the points on a line or a circle, then with spans that wind
/// (a tangent past a half turn from its chord, a segment up to 1.95 half turns). With
/// the spans' own family alone, 11 of 150 open and 40 of 150 closed sets failed; with
/// the wider family and the continuation 2 and 9; now 1 and 1. Every result reported G2 (`g2()`, as
/// the sweep against libspiro counts) passes every check: the points hit, the segments G2 to 1e-10
/// and their cubics to 1e-8 (their own G2 as delivered: chords 30 times apart put the cubics' jumps
/// near 1e-10), every cubic proven monotone.
#[test]
fn harsh_point_sets_converge_in_the_wider_family() {
    use aesthetic_curves::samples::harsh_walk;
    let mut over = Vec::new();
    for (closed, seed, most) in [(false, 8, 2), (true, 10, 3)] {
        let mut rng = SplitMix64::new(seed);
        let opts = LacSplineOptions {
            closed,
            ..Default::default()
        };
        let mut failed = 0;
        for _ in 0..150 {
            let pts = harsh_walk(&mut rng, 2.6);
            match lac_spline(&pts, &opts) {
                Ok(s) if s.g2() => {
                    let (jump, angle) = check(&pts, &opts, &s);
                    assert!(s.max_curvature_jump <= 1e-10, "{pts:?}");
                    assert!(jump < 1e-8 && angle < 1e-9, "{pts:?}: {jump:e} {angle:e}");
                }
                _ => failed += 1,
            }
        }
        eprintln!("harsh sets, closed {closed}: {failed} of 150 failed");
        if failed > most {
            over.push(format!("closed {closed}: {failed} of 150 failed"));
        }
    }
    assert!(over.is_empty(), "{over:?}");
}

/// The signed turning of span `k` (the sum of its pieces' turnings, each below a half
/// turn): past a half turn, the span winds.
fn span_turning(s: &LacSpline, k: usize) -> f64 {
    (0..s.pieces.len())
        .filter(|&i| s.pieces[i].span == k)
        .map(|i| {
            let [a, b] = ends(s, i);
            a.1.cross(b.1).atan2(a.1.dot(b.1))
        })
        .sum()
}

/// A closed set of sharp turns whose G2 curve (libspiro's too) has its closing span wind
/// 340° with its start tangent 168° from its chord: the deviations measured on the branch
/// of the start (past a half turn), the one segment turning up to 1.95 half turns.
/// A solve with every deviation wrapped into (-180°, 180°] stopped 0.69 of the
/// largest curvature short of G2 on it.
#[test]
fn a_closing_span_that_winds_nearly_a_full_turn_is_solved() {
    use aesthetic_curves::samples::harsh_walk;
    let mut rng = SplitMix64::new(9);
    let pts = (0..99).map(|_| harsh_walk(&mut rng, 2.1)).last().unwrap();
    let opts = LacSplineOptions {
        closed: true,
        ..Default::default()
    };
    let s = lac_spline(&pts, &opts).unwrap();
    assert!(s.g2(), "{:e} {:e}", s.max_curvature_jump, s.max_cubic_jump);
    let (jump, angle) = check(&pts, &opts, &s);
    assert!(jump < 1e-8 && angle < 1e-9, "{jump:e} {angle:e}");
    let last = pts.len() - 1;
    let turning = span_turning(&s, last);
    eprintln!("closing span turns {:.1} deg", turning.to_degrees());
    assert!(
        turning.abs() > 1.8 * std::f64::consts::PI,
        "{}",
        turning.to_degrees()
    );
    // Its start tangent leaves the chord by more than 160°.
    let chord = pts[0] - pts[last];
    let t = s.tangents[last];
    assert!(chord.normalize().dot(t) < (160f64).to_radians().cos());
}

/// Point sets a designer clicks or types, over the α range the editor offers: random open
/// walks of 4 to 9 points turning up to 75° between chords at integer pixels, closed
/// polygons of 4 to 9 integer points around a centre, and typed waves of round
/// coordinates; `n_per_alpha` of each kind at each α of -5, -3, -2, -1, -0.5, 0, 0.5, 1,
/// 2, 3, 5. Every answer must be the checked spline (through the points, G2 and every
/// cubic proven monotone, by the test's own evaluator); where the requested α could not
/// be held, the spans that took another α are named and every other span has the
/// requested one. Returns (answered, asked, relaxed spans, spans).
fn alpha_sweep(seed: u64, n_per_alpha: usize) -> (usize, usize, usize, usize) {
    let mut rng = SplitMix64::new(seed);
    let mut uniform = |lo: f64, hi: f64| lo + (hi - lo) * rng.next_f64();
    let alphas = [-5.0, -3.0, -2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 3.0, 5.0];
    let (mut answered, mut asked, mut relaxed, mut spans) = (0, 0, 0, 0);
    for &alpha in &alphas {
        for case in 0..3 * n_per_alpha {
            let n = 4 + (uniform(0.0, 6.0) as usize).min(5);
            let (pts, closed): (Vec<Point>, bool) = match case % 3 {
                0 => {
                    let mut pts = vec![p(0.0, 0.0)];
                    let mut heading = uniform(-std::f64::consts::PI, std::f64::consts::PI);
                    for _ in 1..n {
                        heading += uniform(-75.0, 75.0).to_radians();
                        let l = uniform(20.0, 120.0);
                        let last = *pts.last().unwrap();
                        let next = p(
                            (last.x + l * heading.cos()).round(),
                            (last.y + l * heading.sin()).round(),
                        );
                        if next != last {
                            pts.push(next);
                        }
                    }
                    (pts, false)
                }
                1 => {
                    let pts = (0..n)
                        .map(|k| {
                            let t =
                                std::f64::consts::TAU * k as f64 / n as f64 + uniform(-0.3, 0.3);
                            let r = uniform(60.0, 140.0);
                            p((r * t.cos()).round(), (r * t.sin()).round())
                        })
                        .collect();
                    (pts, true)
                }
                _ => {
                    // A wave typed in round numbers: x every 3 units, y a rounded sine
                    // of a random phase and amplitude.
                    let (amp, phase) = (uniform(1.0, 4.0), uniform(0.0, std::f64::consts::TAU));
                    let pts = (0..n + 2)
                        .map(|i| {
                            let y = 5.0 + amp * (phase + i as f64 * 1.3).sin();
                            p(1.0 + 3.0 * i as f64, y.round())
                        })
                        .collect();
                    (pts, false)
                }
            };
            if pts.len() < 3 {
                continue;
            }
            asked += 1;
            let opts = LacSplineOptions {
                alpha,
                closed,
                ..Default::default()
            };
            let s = match lac_spline(&pts, &opts) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("alpha {alpha} kind {} {pts:?}: {e}", case % 3);
                    continue;
                }
            };
            if !(s.g2() && s.all_monotone) {
                // Answered, and said to be short of G2 or of a proof: not counted.
                eprintln!(
                    "alpha {alpha} kind {} {pts:?}: reported not G2 or not proven",
                    case % 3
                );
                continue;
            }
            let (jump, angle) = check(&pts, &opts, &s);
            if !(jump < 1e-8 && angle < 1e-9) {
                eprintln!(
                    "alpha {alpha} kind {} {pts:?}: jump {jump:e} angle {angle:e}",
                    case % 3
                );
                continue;
            }
            answered += 1;
            spans += s.span_alphas.len();
            relaxed += s.relaxed_spans.len();
            for (k, a) in s.span_alphas.iter().enumerate() {
                assert!(
                    *a == alpha || s.relaxed_spans.contains(&k),
                    "span {k} got alpha {a} without being named"
                );
            }
        }
    }
    (answered, asked, relaxed, spans)
}

/// [`alpha_sweep`] asserted: at least 96 % of the sets answered, at most a quarter of the
/// spans at another α than the requested one.
fn assert_sweep(seed: u64, n_per_alpha: usize) {
    let (answered, asked, relaxed, spans) = alpha_sweep(seed, n_per_alpha);
    eprintln!(
        "alpha sweep: {answered} of {asked} answered G2 and monotone; {relaxed} of {spans} \
         spans took another alpha than the requested one"
    );
    assert!(answered * 100 >= asked * 96, "{answered} of {asked}");
    assert!(relaxed * 4 <= spans, "{relaxed} of {spans} spans relaxed");
}

/// The sweep of [`alpha_sweep`], 8 sets of each kind at each α (264 sets). Before the
/// spans could take the nearest α they hold, 35 to 85 % of the sets at α >= 0 failed and
/// half of the waves at every α; 20 sets of each kind (660) answer 644 (97.6 %): the rest
/// are solved but their cubics not G2 to 1e-8 as delivered (mostly α <= -2, jumps of
/// 1e-8 to 1e-3), and three typed waves at α >= 2 with no solution found.
#[test]
fn the_spline_answers_at_every_alpha() {
    assert_sweep(67, 8);
}

/// The sweep with 40 sets of each kind at each α (1,320 sets, another seed).
#[test]
#[ignore = "slow: about two minutes (run by CI's slow oracles)"]
fn the_spline_answers_at_every_alpha_on_1320_sets() {
    assert_sweep(1067, 40);
}
