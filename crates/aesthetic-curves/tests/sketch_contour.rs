//! Pen strokes as contours (`sketch::contour`): straight strokes, corners, closed loops,
//! drawn with a fixed-seed hand jitter of ±1.5 px at the default tolerance; and the strokes
//! without corners (the jittery S, arc, spiral and wave, the Prius key lines) found to
//! have none.

use aesthetic_curves::sketch::contour::{fit_contour, ContourOptions, Run, SketchContour};
use aesthetic_curves::{Point, Vec2};
use std::f64::consts::PI;

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A hand's jitter: uniform in ±`amp` per coordinate, fixed seed.
struct Jitter(u64);

impl Jitter {
    fn next(&mut self, amp: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * amp
    }

    fn apply(&mut self, pts: &[Point], amp: f64) -> Vec<Point> {
        pts.iter()
            .map(|q| p(q.x + self.next(amp), q.y + self.next(amp)))
            .collect()
    }

    /// A Gaussian deviate of standard deviation `sigma` (Box–Muller).
    fn gaussian(&mut self, sigma: f64) -> f64 {
        let u = (self.next(0.5) + 0.5).max(1e-300);
        let v = self.next(0.5) + 0.5;
        sigma * (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

/// Points every `step` along the polyline through `corners` (as a pen samples a stroke).
fn along(corners: &[Point], step: f64) -> Vec<Point> {
    let mut out = vec![corners[0]];
    for w in corners.windows(2) {
        let n = ((w[1] - w[0]).hypot() / step).ceil().max(1.0) as usize;
        for k in 1..=n {
            out.push(w[0] + (w[1] - w[0]) * (k as f64 / n as f64));
        }
    }
    out
}

fn fit(pts: &[Point]) -> SketchContour {
    fit_contour(pts, &ContourOptions::default()).unwrap()
}

fn kinds(c: &SketchContour) -> Vec<&'static str> {
    c.runs.iter().map(Run::kind).collect()
}

fn assert_within_tolerance(name: &str, c: &SketchContour) {
    assert!(
        c.max_deviation <= c.tolerance,
        "{name}: deviation {} over the tolerance {}",
        c.max_deviation,
        c.tolerance
    );
}

/// The runs meet: each ends exactly where the next starts (closed: the last where the
/// first starts), at the corner between them.
fn assert_connected(name: &str, c: &SketchContour) {
    let n = c.runs.len();
    let joins = if c.closed { n } else { n - 1 };
    for k in 0..joins {
        let (a, b) = (c.runs[k].ends().1, c.runs[(k + 1) % n].ends().0);
        assert_eq!(
            a,
            b,
            "{name}: run {k} ends at {a:?}, run {} starts at {b:?}",
            k + 1
        );
        if let Some(corner) = c.corners.iter().find(|x| x.run == k) {
            assert_eq!(a, corner.point, "{name}: corner after run {k}");
        }
    }
}

#[test]
fn a_straight_stroke_is_one_line() {
    let clean = along(&[p(20.0, 30.0), p(420.0, 180.0)], 2.0);
    let jittery = Jitter(1).apply(&clean, 1.5);
    for (name, pts) in [("clean", &clean), ("jittery", &jittery)] {
        let c = fit(pts);
        assert_eq!(kinds(&c), ["line"], "{name}");
        assert!(c.corners.is_empty() && !c.closed, "{name}");
        assert_within_tolerance(name, &c);
    }
}

/// The default tolerance follows the hand: for a jitter of ±a px per
/// coordinate it is about twice the amplitude (at most 2.4a, and above a: a fair curve can
/// meet it, as the fits here show), whatever the stroke's size, direction and shape; for
/// precise points (sampled from the curve) it is 0.5 % of the size.
#[test]
fn the_default_tolerance_is_about_twice_the_jitter() {
    use aesthetic_curves::sketch::default_tolerance;
    let arc = |r: f64, n: usize| -> Vec<Point> {
        (0..n)
            .map(|i| {
                let a = PI * (0.1 + 0.8 * i as f64 / (n - 1) as f64);
                p(r * a.cos(), r * a.sin())
            })
            .collect()
    };
    let diagonal = |l: f64| along(&[p(0.0, 0.0), p(l, l)], 2.0);
    let wave: Vec<Point> = (0..140)
        .map(|i| {
            let t = i as f64 / 139.0;
            p(400.0 * t, 120.0 * (3.0 * PI * t).sin())
        })
        .collect();
    let mut seed = 10;
    for (name, clean) in [
        ("arc r 200", arc(200.0, 130)),
        ("arc r 800", arc(800.0, 500)),
        ("diagonal line", diagonal(300.0)),
        ("long diagonal line", diagonal(2000.0)),
        ("wave", wave),
    ] {
        for a in [0.5, 1.5, 3.0] {
            seed += 1;
            let pts = Jitter(seed).apply(&clean, a);
            let tol = default_tolerance(&pts);
            assert!(
                tol > a && tol <= 2.4 * a,
                "{name}, ±{a}: default tolerance {tol}"
            );
            let c = fit(&pts);
            assert_eq!(c.tolerance, tol, "{name}");
            assert_within_tolerance(name, &c);
            // Every run meets the next (the wave at ±3 px, its crests read as corners,
            // once left 2.96 px between two runs).
            assert_connected(name, &c);
        }
        let size = {
            let (lo, hi) = clean.iter().fold(
                (p(f64::MAX, f64::MAX), p(f64::MIN, f64::MIN)),
                |(lo, hi), q| {
                    (
                        p(lo.x.min(q.x), lo.y.min(q.y)),
                        p(hi.x.max(q.x), hi.y.max(q.y)),
                    )
                },
            );
            (hi - lo).hypot()
        };
        let precise = default_tolerance(&clean);
        assert!(
            (precise / size - 0.005).abs() < 1e-12,
            "{name}: precise {precise} of {size}"
        );
    }
}

/// `n` points of `curve` (over [0, 1]) with `noise(amp)` added to each coordinate.
fn sampled(
    curve: &dyn Fn(f64) -> Point,
    n: usize,
    mut noise: impl FnMut(f64) -> f64,
    amp: f64,
) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let q = curve(i as f64 / (n - 1) as f64);
            p(q.x + noise(amp), q.y + noise(amp))
        })
        .collect()
}

/// The largest distance from a point of `pts` to its nearest of `dense` (samples of the
/// true curve): how far the noise reaches.
fn farthest(pts: &[Point], dense: &[Point]) -> f64 {
    pts.iter()
        .map(|q| {
            dense
                .iter()
                .map(|d| (*d - *q).hypot())
                .fold(f64::MAX, f64::min)
        })
        .fold(0.0, f64::max)
}

/// `SketchOptions::line_ends`: a curve that leaves a line along it with zero curvature
/// (G2 to the line), at both ends, on a clean and a jittery rounded corner; and bad line
/// ends refused by name.
#[test]
fn line_ends_make_a_curve_leave_its_lines_g2() {
    use aesthetic_curves::sketch::{fit_sketch, PieceKind, SketchOptions};
    use aesthetic_curves::Error;
    // A corner of radius 40 between a line along +x and one along +y, 10 units of each.
    let mut corner: Vec<Point> = (0..5).map(|i| p(2.0 * i as f64, 0.0)).collect();
    for i in 0..=32 {
        let a = -PI / 2.0 + PI / 2.0 * i as f64 / 32.0;
        corner.push(p(10.0 + 40.0 * a.cos(), 40.0 + 40.0 * a.sin()));
    }
    corner.extend((1..=5).map(|i| p(50.0, 40.0 + 2.0 * i as f64)));
    let last = corner.len() - 1;
    let jittery: Vec<Point> = {
        let mut j = Jitter(21);
        let mut v = j.apply(&corner, 0.5);
        (v[0], v[last]) = (corner[0], corner[last]);
        v
    };
    let (dx, dy) = (Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0));
    for (name, pts, tol) in [("clean", &corner, 0.3), ("jittery", &jittery, 1.5)] {
        let opts = SketchOptions {
            line_ends: [Some(dx * 3.0), Some(dy)],
            ..SketchOptions::with_tolerance(tol)
        };
        let sk = fit_sketch(pts, &opts).unwrap();
        let (first, last) = (&sk.pieces[0], &sk.pieces[sk.pieces.len() - 1]);
        assert_eq!(first.kind, PieceKind::LacInflection, "{name}");
        assert_eq!(last.kind, PieceKind::LacInflection, "{name}");
        assert_eq!(first.end_curvatures.0, 0.0, "{name}");
        assert_eq!(last.end_curvatures.1, 0.0, "{name}");
        // The delivered cubics: they start and end on the given points, along the lines,
        // with zero curvature (the rational cubic's end curvature, in closed form).
        let (a, b) = (first.rational.points(), last.rational.points());
        assert_eq!(a[0], pts[0]);
        assert_eq!(b[3], pts[pts.len() - 1]);
        let (ta, tb) = ((a[1] - a[0]).normalize(), (b[3] - b[2]).normalize());
        assert!(
            ta.cross(dx).abs() < 1e-12 && ta.dot(dx) > 0.0,
            "{name}: {ta:?}"
        );
        assert!(
            tb.cross(dy).abs() < 1e-12 && tb.dot(dy) > 0.0,
            "{name}: {tb:?}"
        );
        let scale = sk
            .pieces
            .iter()
            .map(|q| q.end_curvatures.0.abs().max(q.end_curvatures.1.abs()))
            .fold(0.0, f64::max);
        assert!(first.rational.kappa_start().abs() < 1e-9 * scale, "{name}");
        assert!(last.rational.kappa_end().abs() < 1e-9 * scale, "{name}");
        assert!(
            sk.g2 && sk.all_monotone && sk.max_deviation <= tol,
            "{name}"
        );
        // On the exact corner (a circle straight after the line: G1, a curvature step) at
        // 0.3 the curvature overshoots twice with a dip between (0.029, 0.0225, 0.029 for
        // the circle's 0.025): a known limit of fitting G1 data tightly; the hand's corner
        // has one peak.
        let most = if name == "clean" { 3 } else { 1 };
        assert!(
            sk.curvature_extrema <= most,
            "{name}: {}",
            sk.curvature_extrema
        );
    }
    let closed = SketchOptions {
        closed: true,
        line_ends: [Some(dx), None],
        ..SketchOptions::with_tolerance(0.3)
    };
    let zero = SketchOptions {
        line_ends: [None, Some(Vec2::ZERO)],
        ..SketchOptions::with_tolerance(0.3)
    };
    for opts in [closed, zero] {
        let err = fit_sketch(&corner, &opts).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidInput { field, .. } if field.as_str() == "line_ends"),
            "{err:?}"
        );
    }
}

/// Gaussian noise has no bound: among a few hundred points some lie 3σ off, where a
/// tolerance of 3σ would leave no fair curve (the fair spline follows those points, and the
/// fit returns many pieces with false inflections). The default tolerance stays above the
/// noise's largest deviation from the true curve, measured here from the curve itself, and
/// the fit finds the true curve's inflections, G2 (a sine is no LAC: at σ 0.25 the S takes
/// 13 pieces, at σ 1.5 five); so does the README's example stroke (240
/// points with a noise of σ 0.034, whose default fell to 20 pieces with 6 inflections at 3σ).
#[test]
fn the_default_tolerance_clears_gaussian_extremes() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch, SketchOptions};
    let arc = |t: f64| {
        let a = PI * (0.1 + 0.8 * t);
        p(800.0 * a.cos(), 800.0 * a.sin())
    };
    let s_curve = |t: f64| p(250.0 + 150.0 * (2.0 * PI * t).sin(), 400.0 * t);
    for (name, curve, n, inflections) in [
        ("arc", &arc as &dyn Fn(f64) -> Point, 500, 0),
        ("S", &s_curve, 240, 1),
    ] {
        let dense: Vec<Point> = (0..=20_000).map(|i| curve(i as f64 / 20_000.0)).collect();
        for (seed, sigma) in [(41, 0.25), (42, 0.75), (43, 1.5)] {
            let mut jitter = Jitter(seed);
            let pts = sampled(curve, n, |a| jitter.gaussian(a), sigma);
            let off = farthest(&pts, &dense);
            let tol = default_tolerance(&pts);
            assert!(
                tol > 1.1 * off && tol < 6.0 * sigma,
                "{name}, σ {sigma}: tolerance {tol}, noise up to {off}"
            );
            let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol)).unwrap();
            println!(
                "{name}, σ {sigma}: tolerance {tol:.3} ({:.2}σ, {:.2} times the noise's largest \
                 deviation), {} pieces, {} inflections",
                tol / sigma,
                tol / off,
                sk.pieces.len(),
                sk.inflections
            );
            assert_eq!(sk.inflections, inflections, "{name}, σ {sigma}");
            assert!(
                sk.g2 && sk.pieces.len() <= 16,
                "{name}, σ {sigma}: {} pieces, jump {:e}, fairing {:?}",
                sk.pieces.len(),
                sk.max_curvature_jump,
                sk.fairing
            );
        }
    }
    let stroke: Vec<Point> = include_str!("../../../examples/sketch-stroke.csv")
        .lines()
        .skip(1)
        .map(|l| {
            let (x, y) = l.split_once(',').unwrap();
            p(x.trim().parse().unwrap(), y.trim().parse().unwrap())
        })
        .collect();
    let sk = fit_sketch(
        &stroke,
        &SketchOptions::with_tolerance(default_tolerance(&stroke)),
    )
    .unwrap();
    assert_eq!((sk.inflections, sk.curvature_extrema), (2, 1));
    assert!(sk.g2 && sk.pieces.len() <= 7, "{} pieces", sk.pieces.len());
}

/// A hand's tremor regular enough to read as noise (0.7 px at a 6-point period on a 120-point
/// stroke): the default tolerance sits inside it and the fit there fails (it once answered
/// "no triangle"). Without a tolerance the sketch and the contour escalate it to the
/// first G2 fit and on while that loses events: G2, at most one inflection (the stroke's
/// own shape has one), every point within the tolerance reported, by an oracle of the
/// test's own (the nearest of 2,001 samples per piece).
#[test]
fn a_tremor_read_as_noise_still_gets_a_fair_curve_by_default() {
    use aesthetic_curves::sketch::{
        default_tolerance, fit_sketch, fit_sketch_within, SketchOptions,
    };
    let stroke: Vec<Point> = (0..120)
        .map(|i| {
            let t = i as f64;
            p(
                60.0 * (0.03 * t).cos(),
                40.0 * (0.05 * t).sin() + 0.7 * (7.3 * t).sin(),
            )
        })
        .collect();
    let default = default_tolerance(&stroke);
    assert!(fit_sketch(&stroke, &SketchOptions::with_tolerance(default)).is_err());
    let (sk, tol) = fit_sketch_within(&stroke, None).unwrap();
    println!(
        "tremor: default {default:.3}, used {tol:.3}, {} pieces, {} inflections, {} extrema",
        sk.pieces.len(),
        sk.inflections,
        sk.curvature_extrema
    );
    assert!(tol > default && tol <= 2.0 * default, "{tol} {default}");
    assert!(
        sk.g2 && sk.inflections <= 1,
        "{} inflections",
        sk.inflections
    );
    let dense: Vec<Point> = (0..=sk.pieces.len() * 2000)
        .map(|i| sk.eval(i as f64 / 2000.0))
        .collect();
    assert!(farthest(&stroke, &dense) <= tol);
    let c = fit(&stroke);
    assert_within_tolerance("tremor", &c);
    assert!(c.runs.iter().all(|r| r.is_g2()), "contour not G2");
}

/// A tolerance typed inside the noise (below the default): either a fair curve within it
/// (G2, no inflection or curvature extremum that the fit at the default tolerance does not
/// have, every point within the typed tolerance by an oracle outside the fit: the nearest of
/// 2,001 samples per piece), or a typed error on the tolerance whose suggested value, typed,
/// gives such a curve. Never dozens of pieces, and never another error. Arcs (radius 250)
/// and S curves with Gaussian noise σ 1.5 and a hand's ±1.5 px jitter, at 50 to 85 % of the
/// default.
#[test]
fn a_tolerance_inside_the_noise_gets_a_fair_curve_or_the_tolerance_that_does() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch, Sketch, SketchOptions};
    use aesthetic_curves::Error;
    let arc = |t: f64| {
        let a = PI * 0.8 * t;
        p(250.0 * a.cos(), 250.0 * a.sin())
    };
    let s_curve = |t: f64| p(250.0 + 150.0 * (2.0 * PI * t).sin(), 400.0 * t);
    // Each point's nearest of the samples, refined by golden sections between its two
    // neighbours (the samples alone overstate the distance by up to 6e-4 here).
    let within = |sk: &Sketch, pts: &[Point]| {
        let m = sk.pieces.len() * 2000;
        let dense: Vec<Point> = (0..=m).map(|i| sk.eval(i as f64 / 2000.0)).collect();
        let refined = |q: Point| {
            let i = (0..=m)
                .min_by(|&a, &b| (dense[a] - q).hypot().total_cmp(&(dense[b] - q).hypot()))
                .unwrap();
            let d = |t: f64| (sk.eval(t) - q).hypot();
            let (mut a, mut b) = (
                i.saturating_sub(1) as f64 / 2000.0,
                (i + 1).min(m) as f64 / 2000.0,
            );
            for _ in 0..60 {
                let (x, y) = (b - 0.618 * (b - a), a + 0.618 * (b - a));
                if d(x) < d(y) {
                    b = y;
                } else {
                    a = x;
                }
            }
            d(0.5 * (a + b)).min((dense[i] - q).hypot())
        };
        pts.iter().map(|&q| refined(q)).fold(0.0, f64::max)
    };
    let (mut fitted, mut refused) = (0, 0);
    for (name, curve) in [("arc", &arc as &dyn Fn(f64) -> Point), ("S", &s_curve)] {
        for seed in 0..3u64 {
            let mut noise = Jitter(100 + seed);
            let gaussian = sampled(curve, 300, |a| noise.gaussian(a), 1.5);
            let hand = sampled(curve, 300, |a| noise.next(a), 1.5);
            for (kind, pts) in [("gaussian", &gaussian), ("hand", &hand)] {
                let default = default_tolerance(pts);
                let reference = fit_sketch(pts, &SketchOptions::with_tolerance(default)).unwrap();
                let fair = |sk: &Sketch, typed: f64| {
                    let off = within(sk, pts);
                    assert!(
                        sk.g2
                            && sk.inflections <= reference.inflections
                            && sk.curvature_extrema <= reference.curvature_extrema
                            && off <= typed * (1.0 + 1e-9),
                        "{name} {kind} {seed} at {typed}: {} pieces, g2 {}, events {} {} \
                         (default: {} {}), off {off}",
                        sk.pieces.len(),
                        sk.g2,
                        sk.inflections,
                        sk.curvature_extrema,
                        reference.inflections,
                        reference.curvature_extrema
                    );
                };
                for share in [0.5, 0.7, 0.85] {
                    let typed = share * default;
                    match fit_sketch(pts, &SketchOptions::with_tolerance(typed)) {
                        Ok(sk) => {
                            fair(&sk, typed);
                            fitted += 1;
                        }
                        Err(Error::InvalidInput { field, message }) if field == "tolerance" => {
                            let at_least: f64 = message
                                .split("a tolerance of at least ")
                                .nth(1)
                                .and_then(|r| r.split_whitespace().next())
                                .and_then(|v| v.parse().ok())
                                .unwrap_or_else(|| panic!("no tolerance in: {message}"));
                            assert!(at_least > typed && at_least < default, "{message}");
                            let opts = SketchOptions::with_tolerance(at_least);
                            fair(&fit_sketch(pts, &opts).unwrap(), at_least);
                            refused += 1;
                        }
                        Err(e) => panic!("{name} {kind} {seed} at {typed}: {e}"),
                    }
                }
            }
        }
    }
    println!("inside the noise: {fitted} fitted, {refused} refused with a tolerance that fits");
    assert!(fitted > 0 && refused > 0, "{fitted} {refused}");
}

/// The default tolerance over 240 strokes: an arc, an S, a spiral and a wave, each with
/// uniform jitter (a hand) and Gaussian noise of three sizes, ten seeds each. Against the
/// true curve (an oracle outside the fit: the points' largest distance to 20,001 samples of
/// it), the tolerance clears the noise's largest deviation on every stroke, and stays within
/// 2.4 amplitudes of a hand's jitter wherever the jitter, not the local cubics' own error on
/// a tight crest, is what the estimate sees (the wave at ±0.3 px: 3.0). A result is unfair
/// when its inflections are not the curve's or it is not G2: 7 of the 240 (six waves, whose
/// quarter sines no LAC piece follows, and an S; none fails), against 108 with the default of 3σ
/// and the fit that delivered non-G2 results. Slow in debug: run with `--release`.
#[test]
#[ignore]
fn the_default_tolerance_over_240_strokes() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch, SketchOptions};
    type Shape = (&'static str, usize, usize, Box<dyn Fn(f64) -> Point>);
    let shapes: Vec<Shape> = vec![
        (
            "arc",
            300,
            0,
            Box::new(|t| {
                let a = PI * (0.1 + 0.8 * t);
                p(400.0 * a.cos(), 400.0 * a.sin())
            }),
        ),
        (
            "S",
            200,
            1,
            Box::new(|t| p(250.0 + 150.0 * (2.0 * PI * t).sin(), 400.0 * t)),
        ),
        (
            "spiral",
            200,
            0,
            Box::new(|t| {
                let a = 3.5 * PI * t;
                let r = 40.0 + 160.0 * t;
                p(r * a.cos(), r * a.sin())
            }),
        ),
        (
            "wave",
            160,
            2,
            Box::new(|t| p(400.0 * t, 120.0 * (3.0 * PI * t).sin())),
        ),
    ];
    let (mut unfair, mut failed, mut pieces, mut on_bound) = (0, 0, 0, 0);
    for (name, n, inflections, curve) in &shapes {
        let dense: Vec<Point> = (0..=20_000).map(|i| curve(i as f64 / 20_000.0)).collect();
        for gaussian in [false, true] {
            for amp in [0.3, 1.0, 2.5] {
                for seed in 0..10u64 {
                    let mut j = Jitter(1000 + seed);
                    let noise = |a: f64| if gaussian { j.gaussian(a) } else { j.next(a) };
                    let pts = sampled(curve, *n, noise, amp);
                    let off = farthest(&pts, &dense);
                    let tol = default_tolerance(&pts);
                    let case = format!("{name}, gaussian {gaussian}, {amp}, seed {seed}");
                    assert!(
                        tol > 1.05 * off,
                        "{case}: tolerance {tol}, noise up to {off}"
                    );
                    if !gaussian {
                        let most = if *name == "wave" && amp < 1.0 {
                            3.0
                        } else {
                            2.4
                        };
                        assert!(tol <= most * amp, "{case}: tolerance {tol}");
                    }
                    let got = fit_sketch(&pts, &SketchOptions::with_tolerance(tol));
                    if let Ok(sk) = &got {
                        pieces += sk.pieces.len();
                        on_bound += sk.pieces.iter().filter(|q| q.alpha_at_bound).count();
                    }
                    match got {
                        Ok(sk) if sk.g2 && sk.inflections == *inflections => {}
                        Ok(sk) => {
                            unfair += 1;
                            println!(
                                "unfair: {case}: G2 {}, {} inflections, {} pieces",
                                sk.g2,
                                sk.inflections,
                                sk.pieces.len()
                            );
                        }
                        Err(e) => {
                            failed += 1;
                            println!("failed: {case}: {e}");
                        }
                    }
                }
            }
        }
    }
    println!(
        "{unfair} of 240 strokes unfair, {failed} failed; {pieces} pieces, {on_bound} on their α \
         bound"
    );
    assert!(failed == 0, "{failed} of 240 strokes failed");
    assert!(unfair <= 10, "{unfair} of 240 strokes unfair");
}

#[test]
fn an_l_is_two_lines_and_one_corner() {
    let clean = along(&[p(50.0, 50.0), p(50.0, 400.0), p(400.0, 400.0)], 2.0);
    let pts = Jitter(2).apply(&clean, 1.5);
    let c = fit(&pts);
    assert_eq!(kinds(&c), ["line", "line"]);
    assert_eq!(c.corners.len(), 1);
    let k = c.corners[0];
    assert!((k.point - p(50.0, 400.0)).hypot() < 6.0, "{k:?}");
    assert!((k.angle.to_degrees() - 90.0).abs() < 10.0, "{k:?}");
    assert!(!c.closed);
    assert_connected("L", &c);
    assert_within_tolerance("L", &c);
}

#[test]
fn a_sharp_v_and_a_zigzag_have_their_corners() {
    let v = along(&[p(0.0, 0.0), p(150.0, 400.0), p(300.0, 0.0)], 2.0);
    let z = along(
        &[p(0.0, 0.0), p(100.0, 200.0), p(200.0, 0.0), p(300.0, 200.0)],
        2.0,
    );
    for (name, clean, want) in [("V", &v, 1), ("zigzag", &z, 2)] {
        let c = fit(&Jitter(3).apply(clean, 1.5));
        assert_eq!(c.corners.len(), want, "{name}: {:?}", c.corners);
        assert!(kinds(&c).iter().all(|k| *k == "line"), "{name}");
        assert_connected(name, &c);
        assert_within_tolerance(name, &c);
    }
}

/// Strokes of a few points each (clicked, or a pen sampled far apart: every step longer
/// than the corner window), at the default tolerance: a polygon's turns of 80° and more
/// are corners, points along an arc or a wave turn less and stay one curve; every point
/// within the tolerance. Before the corner window, the zigzag came back as one curve looping
/// 114,000 units away, the three-point L as one line 70 units from its corner, and 13
/// points around a circle as an error.
#[test]
fn sparse_strokes_are_polygons_or_curves_within_the_tolerance() {
    let ring = |n: usize, to: usize, turn: f64| -> Vec<Point> {
        (0..=to)
            .map(|k| {
                let a = turn * k as f64 / n as f64;
                p(100.0 * a.cos(), 100.0 * a.sin())
            })
            .collect()
    };
    let wave: Vec<Point> = (0..13)
        .map(|t| p(100.0 * (0.5 * t as f64).sin(), 30.0 * t as f64))
        .collect();
    let zigzag = [(0., 0.), (100., 5.), (0., 10.), (100., 15.), (0., 20.)].map(|(x, y)| p(x, y));
    let rect = [(0., 0.), (100., 0.), (100., 50.), (0., 50.), (0., 0.)].map(|(x, y)| p(x, y));
    let tri = [(0., 0.), (100., 0.), (50., 80.), (0., 0.)].map(|(x, y)| p(x, y));
    let l3 = [(0., 0.), (0., 100.), (100., 100.)].map(|(x, y)| p(x, y));
    // (name, points, closed, corners; None: one curve)
    let cases: Vec<(&str, Vec<Point>, bool, Option<usize>)> = vec![
        ("zigzag", zigzag.to_vec(), false, Some(3)),
        ("L of 3 points", l3.to_vec(), false, Some(1)),
        ("rectangle of 5 points", rect.to_vec(), true, Some(4)),
        ("triangle of 4 points", tri.to_vec(), true, Some(3)),
        ("half circle of 6 points", ring(5, 5, PI), false, None),
        ("wave of 13 points", wave, false, None),
        ("circle of 7 points", ring(6, 6, 2.0 * PI), true, None),
        ("circle of 9 points", ring(8, 8, 2.0 * PI), true, None),
        ("circle of 13 points", ring(12, 12, 2.0 * PI), true, None),
    ];
    // As one G2 curve (`sketch.fit`) the zigzag turns back at every point: a typed error
    // that names the place and points to the contour fit, not a curve 114,000 units out.
    match aesthetic_curves::sketch::fit_sketch_within(&zigzag, None) {
        Err(aesthetic_curves::Error::Degenerate(m)) => assert!(m.contains("sketch.contour"), "{m}"),
        other => panic!("zigzag as one curve: {other:?}"),
    }
    for (name, pts, closed, corners) in cases {
        let c = fit(&pts);
        assert_eq!(c.closed, closed, "{name}");
        assert_within_tolerance(name, &c);
        assert_connected(name, &c);
        match corners {
            Some(want) => {
                assert_eq!(c.corners.len(), want, "{name}: {:?}", c.corners);
                assert!(kinds(&c).iter().all(|k| *k == "line"), "{name}");
            }
            None => {
                assert!(c.corners.is_empty(), "{name}: {:?}", c.corners);
                assert_eq!(kinds(&c), ["curve"], "{name}");
                let Run::Curve(s) = &c.runs[0] else {
                    unreachable!()
                };
                assert!(s.g2 && s.all_monotone, "{name}");
                // The curve stays by its points: within a third of the points' spread
                // of their bounding box (the zigzag's loop went 1,000 times out).
                let (lo, hi) = pts.iter().fold(
                    (p(f64::MAX, f64::MAX), p(f64::MIN, f64::MIN)),
                    |(lo, hi), q| {
                        (
                            p(lo.x.min(q.x), lo.y.min(q.y)),
                            p(hi.x.max(q.x), hi.y.max(q.y)),
                        )
                    },
                );
                let margin = 0.35 * (hi - lo).hypot();
                for piece in &s.pieces {
                    for q in piece.rational.points() {
                        assert!(
                            q.x > lo.x - margin
                                && q.x < hi.x + margin
                                && q.y > lo.y - margin
                                && q.y < hi.y + margin,
                            "{name}: control point {q:?} far from the points"
                        );
                    }
                }
            }
        }
    }
}

/// The largest distance from a point of `curve` (sampled) to the polyline through `pts`.
fn excursion(pts: &[Point], curve: &[Point]) -> f64 {
    let seg = |q: Point, a: Point, b: Point| {
        let d = b - a;
        let t = ((q - a).dot(d) / d.hypot2().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (q - (a + d * t)).hypot()
    };
    curve
        .iter()
        .map(|&q| {
            pts.windows(2)
                .map(|w| seg(q, w[0], w[1]))
                .fold(f64::MAX, f64::min)
        })
        .fold(0.0, f64::max)
}

/// Sparse smooth strokes (8 to 20 points 20 to 80 apart, each turning up to 57° from the
/// last) through `sketch.fit` at the default tolerance: every one fitted, G2, its pieces
/// proven monotone, and the curve no farther from the points' polyline than the
/// tolerance and the longest step, nearly all within half of it (a fair curve bulges
/// between sparse points, a loop goes far out: 12 such points came back with control
/// points 9,000 away).
#[test]
fn sparse_smooth_strokes_are_fitted_near_their_points() {
    use aesthetic_curves::sketch::fit_sketch_within;
    use aesthetic_curves::PlanarCurve;
    let mut rng = Jitter(38);
    let (mut worst, mut over_half, mut over_step): (f64, usize, usize) = (0.0, 0, 0);
    let (mut failed, mut unfair) = (0, 0);
    for k in 0..40 {
        let n = 8 + (rng.next(0.5) + 0.5).mul_add(12.0, 0.0) as usize;
        let (mut a, mut pts) = (0.0f64, vec![p(0.0, 0.0)]);
        for _ in 1..n {
            a += rng.next(1.0);
            let l = 50.0 + rng.next(30.0);
            let q = *pts.last().unwrap();
            pts.push(p(q.x + l * a.cos(), q.y + l * a.sin()));
        }
        let Ok((s, tol)) = fit_sketch_within(&pts, None) else {
            failed += 1;
            continue;
        };
        unfair += usize::from(!(s.g2 && s.all_monotone));
        assert!(s.max_deviation <= tol, "stroke {k}");
        let curve: Vec<Point> = s
            .pieces
            .iter()
            .flat_map(|piece| (0..=32).map(|i| piece.rational.eval(i as f64 / 32.0)))
            .collect();
        let step = pts
            .windows(2)
            .map(|w| (w[1] - w[0]).hypot())
            .fold(0.0, f64::max);
        let out = excursion(&pts, &curve);
        worst = worst.max(out / step);
        over_half += usize::from(out > tol + 0.5 * step);
        over_step += usize::from(out > tol + step);
    }
    println!(
        "sparse smooth strokes: {failed} failed, {unfair} not G2 or not proven monotone; \
         worst excursion {worst:.3} steps, {over_half} beyond half a step, {over_step} beyond one"
    );
    // Measured when the sparse strokes were fixed: 2 refused (no spline near their points within
    // the tolerance), 2 unfair, 3 beyond half a step (an end overshooting between two sparse
    // points), none beyond one. Before it: 12-point strokes looped 9,000 units out.
    assert!(
        failed <= 2 && unfair <= 2,
        "{failed} failed, {unfair} unfair"
    );
    assert!(
        over_step == 0 && over_half <= 3,
        "{over_step} beyond a step, {over_half} beyond half"
    );
}

#[test]
fn a_square_and_a_triangle_in_one_stroke_come_back_closed_with_their_corners() {
    // Started in the middle of a side, ended back there with a small overshoot.
    let square = along(
        &[
            p(250.0, 50.0),
            p(450.0, 50.0),
            p(450.0, 450.0),
            p(50.0, 450.0),
            p(50.0, 50.0),
            p(262.0, 50.0),
        ],
        2.0,
    );
    let triangle = along(
        &[
            p(100.0, 400.0),
            p(250.0, 100.0),
            p(400.0, 400.0),
            p(100.0, 400.0),
        ],
        2.0,
    );
    for (name, clean, want) in [("square", &square, 4), ("triangle", &triangle, 3)] {
        let c = fit(&Jitter(4).apply(clean, 1.5));
        assert!(c.closed, "{name}");
        assert_eq!(c.corners.len(), want, "{name}: {:?}", c.corners);
        assert_eq!(c.runs.len(), want, "{name}");
        assert!(
            kinds(&c).iter().all(|k| *k == "line"),
            "{name}: {:?}",
            kinds(&c)
        );
        assert_connected(name, &c);
        assert_within_tolerance(name, &c);
    }
}

#[test]
fn a_circle_in_one_stroke_comes_back_closed_without_corners() {
    let clean: Vec<Point> = (0..=420)
        .map(|i| {
            // A little past the start, as a hand overshoots.
            let a = 2.0 * PI * i as f64 / 400.0;
            p(250.0 + 200.0 * a.cos(), 250.0 + 200.0 * a.sin())
        })
        .collect();
    let c = fit(&Jitter(5).apply(&clean, 1.5));
    assert!(c.closed && c.corners.is_empty(), "{:?}", c.corners);
    assert!(c.trimmed > 0, "the overshoot is trimmed");
    assert_eq!(kinds(&c), ["curve"]);
    let Run::Curve(s) = &c.runs[0] else {
        unreachable!()
    };
    assert!(
        s.g2 && s.all_monotone && s.pieces.len() <= 8,
        "{} pieces",
        s.pieces.len()
    );
    assert_connected("circle", &c);
    assert_within_tolerance("circle", &c);
    // G2 across the seam: one tangent, the curvature jump faired like every joint's.
    let seam = c.seam.unwrap();
    println!("circle seam {seam:?}, {} pieces", s.pieces.len());
    assert!(seam.angle < 1e-9 && seam.curvature_jump < 1e-6, "{seam:?}");
}

/// Strokes that are one fair curve have no corner: the jittery strokes of the sketch tests
/// and the measured Prius key lines.
#[test]
fn fair_strokes_have_no_corners() {
    let mut j = Jitter(7);
    type Shape = (&'static str, usize, Box<dyn Fn(f64) -> Point>);
    let shapes: Vec<Shape> = vec![
        (
            "wave",
            140,
            Box::new(|t| p(50.0 + 400.0 * t, 250.0 + 120.0 * (3.0 * PI * t).sin())),
        ),
        (
            "s",
            120,
            Box::new(|t| p(250.0 + 150.0 * (2.0 * PI * t).sin(), 50.0 + 400.0 * t)),
        ),
        (
            "arc",
            130,
            Box::new(|t| {
                let a = PI * (0.1 + 0.8 * t);
                p(250.0 + 200.0 * a.cos(), 60.0 + 200.0 * a.sin())
            }),
        ),
        (
            "spiral",
            160,
            Box::new(|t| {
                let a = 3.5 * PI * t;
                let r = 40.0 + 160.0 * t;
                p(250.0 + r * a.cos(), 250.0 + r * a.sin())
            }),
        ),
    ];
    for (name, n, f) in &shapes {
        let clean: Vec<Point> = (0..*n).map(|i| f(i as f64 / (*n - 1) as f64)).collect();
        let c = fit(&j.apply(&clean, 1.5));
        assert!(c.corners.is_empty(), "{name}: {:?}", c.corners);
        assert!(!c.closed, "{name}");
        assert_eq!(kinds(&c), ["curve"], "{name}");
        assert_within_tolerance(name, &c);
    }
    let strokes: serde_json::Value =
        serde_json::from_str(include_str!("data/editor-strokes.json")).unwrap();
    for (name, pts) in strokes["strokes"].as_object().unwrap() {
        let pts: Vec<Point> = pts
            .as_array()
            .unwrap()
            .iter()
            .map(|q| p(q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
            .collect();
        let c = fit(&pts);
        assert!(c.corners.is_empty(), "editor {name}: {:?}", c.corners);
        assert_eq!(kinds(&c), ["curve"], "editor {name}");
    }
    for (i, line) in aesthetic_curves_data::PRIUS.iter().enumerate() {
        let pts: Vec<Point> = line.points().into_iter().map(|[x, y]| p(x, y)).collect();
        let opts = ContourOptions {
            tolerance: Some(0.3),
            ..Default::default()
        };
        let c = fit_contour(&pts, &opts).unwrap();
        assert!(c.corners.is_empty(), "prius {}: {:?}", i + 1, c.corners);
        assert!(!c.closed, "prius {}", i + 1);
    }
}

/// A similarity (rotation, scale 1000, a far translation) and the reversal of the stroke
/// give the same corners (moved, or in reverse order) and runs of the same kinds.
#[test]
fn corners_are_similarity_and_reversal_invariant() {
    let clean = along(
        &[
            p(50.0, 50.0),
            p(50.0, 400.0),
            p(400.0, 400.0),
            p(300.0, 100.0),
        ],
        2.0,
    );
    let pts = Jitter(8).apply(&clean, 1.5);
    let c = fit(&pts);
    assert_eq!(c.corners.len(), 2);
    let (rot, scale, shift) = (0.7f64, 1000.0, Vec2::new(3.0e7, -1.0e7));
    let moved: Vec<Point> = pts
        .iter()
        .map(|q| {
            let (s, co) = rot.sin_cos();
            p((co * q.x - s * q.y) * scale, (s * q.x + co * q.y) * scale) + shift
        })
        .collect();
    let m = fit_contour(
        &moved,
        &ContourOptions {
            tolerance: Some(c.tolerance * scale),
            ..Default::default()
        },
    )
    .unwrap();
    let idx = |c: &SketchContour| c.corners.iter().map(|k| k.index).collect::<Vec<_>>();
    assert_eq!(idx(&m), idx(&c));
    assert_eq!(kinds(&m), kinds(&c));
    let rev: Vec<Point> = pts.iter().rev().copied().collect();
    let r = fit_contour(
        &rev,
        &ContourOptions {
            tolerance: Some(c.tolerance),
            ..Default::default()
        },
    )
    .unwrap();
    let n = pts.len() - 1;
    let mut back: Vec<usize> = idx(&r).iter().map(|i| n - i).collect();
    back.sort();
    // The same corners within a sample or two (the window test's maximum on noise).
    assert_eq!(back.len(), 2);
    for (a, b) in back.iter().zip(idx(&c)) {
        assert!(a.abs_diff(b) <= 2, "{back:?} vs {:?}", idx(&c));
    }
}

#[test]
fn bad_strokes_get_typed_errors() {
    let o = ContourOptions::default();
    assert!(fit_contour(&[p(0.0, 0.0)], &o).is_err());
    assert!(fit_contour(&[p(0.0, 0.0), p(f64::NAN, 1.0)], &o).is_err());
    let same = vec![p(3.0, 3.0); 10];
    assert_eq!(fit_contour(&same, &o).unwrap_err().kind(), "degenerate");
    let bad = ContourOptions {
        tolerance: Some(-1.0),
        ..Default::default()
    };
    assert!(fit_contour(&[p(0.0, 0.0), p(1.0, 1.0)], &bad).is_err());
    // Two points: a line.
    let c = fit_contour(&[p(0.0, 0.0), p(10.0, 5.0)], &o).unwrap();
    assert_eq!(kinds(&c), ["line"]);
}

/// A rectangle with rounded corners (radius 40) drawn in one stroke.
fn rounded_rectangle() -> Vec<Point> {
    let mut pts = Vec::new();
    let (x0, y0, x1, y1, r) = (50.0, 50.0, 450.0, 350.0, 40.0);
    let centres = [
        (x1 - r, y0 + r),
        (x1 - r, y1 - r),
        (x0 + r, y1 - r),
        (x0 + r, y0 + r),
    ];
    for (k, (cx, cy)) in centres.iter().enumerate() {
        let a0 = -PI / 2.0 + k as f64 * PI / 2.0;
        for i in 0..=20 {
            let a = a0 + PI / 2.0 * i as f64 / 20.0;
            pts.push(p(cx + r * a.cos(), cy + r * a.sin()));
        }
    }
    pts.push(pts[0]);
    Jitter(9).apply(&along(&pts, 2.0), 1.5)
}

/// Its rounded corners are not corners (a fair curve follows them), and it closes.
#[test]
fn a_rounded_rectangle_closes_and_has_no_corners() {
    use aesthetic_curves::sketch::contour::{closes, corners};
    use aesthetic_curves::sketch::default_tolerance;
    let pts = rounded_rectangle();
    let tol = default_tolerance(&pts);
    let (closed, kept) = closes(&pts, tol, None);
    assert!(closed);
    let found = corners(
        &pts[..kept],
        true,
        tol,
        ContourOptions::default().corner_angle,
    );
    assert!(found.is_empty(), "{found:?}");
}

/// The rounded rectangle drawn in one stroke: closed, its four straight sides
/// lines and its four rounded corners fair curves, each joining the lines next to it G2
/// (leaving the line along it with zero curvature), within the tolerance. It took 54
/// pieces, 5 s and a seam whose curvature jumped by 0.6 when the stroke was one curve.
#[test]
fn a_rounded_rectangle_comes_back_as_four_lines_and_four_fair_corners() {
    let t0 = std::time::Instant::now();
    let c = fit(&rounded_rectangle());
    println!(
        "rounded rectangle: {:?}, {} pieces in {:?}, smooth joins {:?}",
        kinds(&c),
        c.pieces(),
        t0.elapsed(),
        c.smooth_joins
    );
    assert!(c.closed && c.corners.is_empty() && c.seam.is_none());
    assert_eq!(kinds(&c), ["line", "curve"].repeat(4));
    assert_within_tolerance("rounded rectangle", &c);
    assert_connected("rounded rectangle", &c);
    // The sides along the rectangle's (x0, y0, x1, y1) = (50, 50, 450, 350), most of their
    // length (the corners' radius is 40).
    for run in &c.runs {
        match run {
            Run::Line { start, end } => {
                let d = *end - *start;
                assert!(d.hypot() > 150.0, "{start:?} {end:?}");
                let off_axis = (d.x.abs().min(d.y.abs()) / d.hypot()).asin().to_degrees();
                assert!(off_axis < 1.0, "{start:?} {end:?}");
            }
            Run::Curve(s) => {
                println!(
                    "curve: {:?}",
                    s.pieces
                        .iter()
                        .map(|q| (q.kind, q.end_curvatures))
                        .collect::<Vec<_>>()
                );
                assert!(s.g2 && s.all_monotone, "{:?}", s.fairing);
                assert!(s.pieces.len() <= 4, "{} pieces", s.pieces.len());
                assert_eq!(s.inflections, 0);
            }
        }
    }
    // Every join is smooth: one tangent and no curvature jump, to rounding; the last one
    // closes the contour.
    assert_eq!(c.smooth_joins.len(), 8);
    for (k, j) in c.smooth_joins.iter().enumerate() {
        assert_eq!(j.run, k);
        assert!(j.angle < 1e-9 && j.curvature_jump < 1e-9, "{j:?}");
        assert_eq!(j.point, c.runs[k].ends().1);
        assert_eq!(j.point, c.runs[(k + 1) % 8].ends().0);
    }
    // The delivered curve, as one: G1 at every join (the tangents of its rational cubics).
    let curve = c.as_curve().unwrap();
    assert!(curve.0.len() == c.pieces());
}

/// A stadium and a rounded triangle drawn by hand: lines for their straight sides, G2
/// everywhere; strokes that are one fair curve (a circle, the jittery S, wave, arc and
/// spiral: `fair_strokes_have_no_corners`) get no line.
#[test]
fn a_stadium_and_a_rounded_triangle_have_their_straight_sides() {
    let stadium = {
        let mut v = Vec::new();
        for (cx, a0) in [(400.0, -PI / 2.0), (100.0, PI / 2.0)] {
            for i in 0..=30 {
                let a = a0 + PI * i as f64 / 30.0;
                v.push(p(cx + 60.0 * a.cos(), 200.0 + 60.0 * a.sin()));
            }
        }
        v.push(v[0]);
        v
    };
    let triangle = {
        let mut v = Vec::new();
        let corners = [p(100.0, 100.0), p(400.0, 120.0), p(230.0, 380.0)];
        for k in 0..3 {
            let (a, b, c) = (corners[(k + 2) % 3], corners[k], corners[(k + 1) % 3]);
            // A rounded corner at b: an arc of radius 30 tangent to both sides.
            let (u, w) = ((a - b).normalize(), (c - b).normalize());
            let half = 0.5 * u.dot(w).acos();
            let centre = b + (u + w).normalize() * (30.0 / half.sin());
            let (t0, t1) = (b + u * (30.0 / half.tan()), b + w * (30.0 / half.tan()));
            let (a0, mut a1) = ((t0 - centre).atan2(), (t1 - centre).atan2());
            let sweep = {
                let d = a1 - a0;
                let d = (d + PI).rem_euclid(2.0 * PI) - PI;
                a1 = a0 + d;
                d
            };
            for i in 0..=12 {
                let a = a0 + sweep * i as f64 / 12.0;
                v.push(centre + kurbo::Vec2::from_angle(a) * 30.0);
            }
            let _ = a1;
        }
        v.push(v[0]);
        v
    };
    for (name, ring, sides) in [("stadium", &stadium, 2), ("rounded triangle", &triangle, 3)] {
        let pts = Jitter(12).apply(&along(ring, 2.0), 1.0);
        let c = fit(&pts);
        println!(
            "{name}: {:?}, {} pieces, smooth joins {}",
            kinds(&c),
            c.pieces(),
            c.smooth_joins.len()
        );
        assert!(c.closed && c.corners.is_empty(), "{name}");
        assert_eq!(kinds(&c), ["line", "curve"].repeat(sides), "{name}");
        assert_within_tolerance(name, &c);
        assert_connected(name, &c);
        assert!(c
            .smooth_joins
            .iter()
            .all(|j| j.angle < 1e-9 && j.curvature_jump < 1e-9));
    }
}

/// A clean sine sampled densely, at the default tolerance (0.5 % of its size, as large as
/// its amplitude): straight runs next to curved ones share their corner points, so the
/// contour joins into one curve (a line's end moved to its foot left a gap there).
#[test]
fn straight_runs_next_to_curved_ones_share_their_corners() {
    let pts: Vec<Point> = (0..4000)
        .map(|i| Point::new(i as f64 * 0.01, (i as f64 * 0.01).sin()))
        .collect();
    let c = fit(&pts);
    let runs = c.runs.len();
    for w in c.runs.windows(2) {
        let (a, b) = (w[0].ends().1, w[1].ends().0);
        assert!(
            (a - b).hypot() < 1e-9,
            "runs of {runs} meet: {a:?} vs {b:?}"
        );
    }
    c.as_curve().expect("one curve");
}

/// The jittery S the editor's end-to-end test draws (its stroke as the page sent it, in
/// world units): the piece after the upper turn's curvature peak was a sliver on its α
/// bound (-5) whose curvature fell from 3.3 to 1.2 within 2 % of the length, a step on the
/// curvature plot. No piece on its α bound may now fall by half the largest |κ|, and a
/// piece that falls by half from the largest |κ| does so with |α| at most 1.5 (it was
/// -2.11, falling 3.17 → 0.48 over 4 % of the length, at a split at the clamped half
/// turning: still a shoulder on the plot).
#[test]
fn a_jittery_s_has_no_step_after_its_peak() {
    let stroke: Vec<Point> = include_str!("data/jittery-s-stroke.csv")
        .lines()
        .skip(1)
        .map(|l| {
            let (x, y) = l.split_once(',').unwrap();
            p(x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    let c = fit(&stroke);
    assert_within_tolerance("S", &c);
    let Run::Curve(sk) = &c.runs[0] else {
        panic!("not a curve: {:?}", kinds(&c))
    };
    assert!(
        sk.g2 && sk.inflections == 1,
        "{} inflections",
        sk.inflections
    );
    let big = sk.pieces.iter().fold(0.0f64, |m, q| {
        m.max(q.end_curvatures.0.abs())
            .max(q.end_curvatures.1.abs())
    });
    for q in &sk.pieces {
        let fall = (q.end_curvatures.0 - q.end_curvatures.1).abs();
        assert!(
            !(q.alpha_at_bound && fall > 0.5 * big),
            "a piece on its α bound ({}) falls from {:?}",
            q.alpha,
            q.end_curvatures
        );
        let (ka, kb) = (q.end_curvatures.0.abs(), q.end_curvatures.1.abs());
        if ka.max(kb) > 0.99 * big && (ka - kb).abs() > 0.5 * big {
            assert!(
                q.alpha.abs() <= 1.5,
                "the fall from the peak {:?} has α {}",
                q.end_curvatures,
                q.alpha
            );
        }
    }
}

/// The wave of the 240-stroke test (ending at inflections, in flat stretches) at ±1 px:
/// three of its seeds failed with "a piece of the curve has end tangents that form no
/// triangle". The curve's end had the tangent of the flat stretch's last sign change, and a
/// piece cut at that sign change had the same tangent at both ends; splitting it ran into
/// the end. Now each is fitted, G2.
#[test]
fn a_wave_that_ends_flat_is_fitted() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch, SketchOptions};
    let wave = |t: f64| p(400.0 * t, 120.0 * (3.0 * PI * t).sin());
    for seed in [0, 2, 5] {
        let mut j = Jitter(1000 + seed);
        let pts = sampled(&wave, 160, |a| j.next(a), 1.0);
        let tol = default_tolerance(&pts);
        let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol))
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        assert!(sk.g2 && sk.max_deviation <= tol, "seed {seed}");
        assert!(sk.inflections >= 2, "seed {seed}: {}", sk.inflections);
    }
}

/// An arc (radius 400, 300 points) with Gaussian noise of σ 1 at its default tolerance
/// (3.82, its largest deviation 2.83): the fair spline at 3/4 of the tolerance had to pass
/// within 2.87 of that point and followed the noise: 21 pieces, 6 inflections. With room
/// left above the noise's extremes: no inflection, a few pieces.
#[test]
fn an_arc_with_gaussian_noise_has_no_inflection() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch, SketchOptions};
    let arc = |t: f64| {
        let a = PI * (0.1 + 0.8 * t);
        p(400.0 * a.cos(), 400.0 * a.sin())
    };
    let mut j = Jitter(1004);
    let pts = sampled(&arc, 300, |a| j.gaussian(a), 1.0);
    let tol = default_tolerance(&pts);
    let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol)).unwrap();
    assert!(
        sk.g2 && sk.inflections == 0 && sk.pieces.len() <= 4,
        "{} pieces, {} inflections",
        sk.pieces.len(),
        sk.inflections
    );
}

/// A few points, too few for a noise estimate (fewer than 15), are taken as precise; where
/// they are not (an arc measured at 13 points with noise of 1 % of its radius), the default
/// tolerance goes on past the usual ladder (to 8 times its first value); these all meet
/// 4 times it at most (2 % of the size), asserted.
/// Before, 13 points of an arc of radius 12 and noise σ 0.12 (below) failed at every rung
/// as a curve and as a contour, and so did seed 58's contour (2.38 left at 1.06). Taken as
/// precise, a quarter of these arcs come back with inflections that follow the noise:
/// that is what the default assumes of a dozen clicks; a tolerance given says otherwise.
#[test]
fn a_few_noisy_points_get_a_fair_curve_by_default() {
    let measured = [
        (11.751566298880475, -0.1163033025691039),
        (12.084358738426996, 0.5511601262840434),
        (12.199386197799253, 1.0151041711945255),
        (11.941033887421781, 1.6053729160700039),
        (11.746021845595251, 2.2638632942292234),
        (11.528566702256896, 2.8023400199757535),
        (11.485423044029863, 3.4221220999270865),
        (11.092171811787678, 4.1094529505015815),
        (11.071662157038894, 4.566137947649553),
        (10.695119147069402, 5.053498305006714),
        (10.362369981971698, 5.577369290129783),
        (10.395410815147564, 5.743481160737574),
        (9.734728744816335, 6.420505392691224),
    ];
    let mut strokes = vec![measured.iter().map(|&(x, y)| p(x, y)).collect::<Vec<_>>()];
    for seed in 0..60u64 {
        let mut j = Jitter(2000 + seed);
        let r = [12.0, 150.0, 400.0][seed as usize % 3];
        let span = 0.5 + 0.1 * seed as f64;
        let arc = |i: usize| {
            let a = span * i as f64 / 12.0;
            (r * a.cos(), r * a.sin())
        };
        strokes.push(
            (0..13)
                .map(|i| {
                    p(
                        arc(i).0 + j.gaussian(0.01 * r),
                        arc(i).1 + j.gaussian(0.01 * r),
                    )
                })
                .collect(),
        );
    }
    let mut failed = Vec::new();
    for (k, pts) in strokes.iter().enumerate() {
        let (lo, hi) = pts
            .iter()
            .fold(((f64::MAX, f64::MAX), (f64::MIN, f64::MIN)), |b, q| {
                (
                    (b.0 .0.min(q.x), b.0 .1.min(q.y)),
                    (b.1 .0.max(q.x), b.1 .1.max(q.y)),
                )
            });
        let size = (hi.0 - lo.0).hypot(hi.1 - lo.1);
        failed.extend(fair_by_default(k, pts, 0.02 * size * (1.0 + 1e-12)));
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// No piece outside the bound α shares with every fit. An inflection piece takes
/// its α from its control triangle, and a base angle near half the piece's turning asks for
/// α towards -∞: sparse smooth walks (6 to 24 points 20 to 80 apart, turning up to 57° a
/// step) came back with inflection pieces of α -7.5 to -7,024, one not proven monotone.
/// 200 such walks through `fit_sketch_within` and `fit_contour`: every delivered piece's α
/// within [`ALPHA_RANGE`](aesthetic_curves::lac::ALPHA_RANGE).
#[test]
fn no_piece_is_returned_with_alpha_beyond_the_bound() {
    use aesthetic_curves::lac::ALPHA_RANGE;
    use aesthetic_curves::sketch::{fit_sketch_within, SketchPiece};
    let mut rng = Jitter(3500);
    let (mut pieces, mut fitted) = (0usize, 0usize);
    let mut beyond = Vec::new();
    let mut check = |name: String, ps: &[SketchPiece]| {
        pieces += ps.len();
        for q in ps {
            if !(ALPHA_RANGE.0..=ALPHA_RANGE.1).contains(&q.alpha) {
                beyond.push(format!("{name}: {:?} piece with alpha {}", q.kind, q.alpha));
            }
        }
    };
    for k in 0..200 {
        let n = 6 + ((rng.next(0.5) + 0.5) * 19.0) as usize;
        let (mut a, mut pts) = (rng.next(PI), vec![p(0.0, 0.0)]);
        for _ in 1..n {
            a += rng.next(1.0);
            let l = 50.0 + rng.next(30.0);
            let q = *pts.last().unwrap();
            pts.push(p(q.x + l * a.cos(), q.y + l * a.sin()));
        }
        if let Ok((s, _)) = fit_sketch_within(&pts, None) {
            fitted += 1;
            check(format!("walk {k}"), &s.pieces);
        }
        if let Ok(c) = fit_contour(&pts, &ContourOptions::default()) {
            for run in &c.runs {
                if let Run::Curve(s) = run {
                    check(format!("walk {k}, contour"), &s.pieces);
                }
            }
        }
    }
    println!(
        "alpha bound: {fitted} of 200 walks fitted, {pieces} pieces, {} beyond",
        beyond.len()
    );
    assert!(fitted >= 180, "only {fitted} of 200 walks fitted");
    assert!(beyond.is_empty(), "{beyond:#?}");
}

/// Stroke `k` at the default tolerance, as a curve and as a contour: each within its
/// tolerance, which is at most `most`, the curve G2 and monotone, the contour connected;
/// the failures, each a line.
fn fair_by_default(k: usize, pts: &[Point], most: f64) -> Vec<String> {
    use aesthetic_curves::sketch::fit_sketch_within;
    let mut failed = Vec::new();
    match fit_sketch_within(pts, None) {
        Ok((sk, tol)) => {
            assert!(sk.max_deviation <= tol && tol <= most, "stroke {k}: {tol}");
            if !(sk.g2 && sk.all_monotone) {
                failed.push(format!("stroke {k}: a curve that is not G2 and monotone"));
            }
        }
        Err(e) => failed.push(format!("stroke {k}: {e}")),
    }
    match fit_contour(pts, &ContourOptions::default()) {
        Ok(c) => {
            let name = format!("stroke {k}");
            assert_within_tolerance(&name, &c);
            assert_connected(&name, &c);
            assert!(c.tolerance <= most, "{name}: {}", c.tolerance);
        }
        Err(e) => failed.push(format!("stroke {k}: contour: {e}")),
    }
    failed
}

/// Noisier still: 9 points of an arc with noise of 2 to 3 % of its radius, too few for a
/// noise estimate. The default's ladder for such strokes goes on to 8 times its first
/// value (4 % of the size) while nothing is G2; up to 4 times, two fuzzed arcs (below) and
/// one of these 40 seeded arcs failed at every rung, as a curve and as a contour (6 of 84
/// requests).
#[test]
fn nine_noisy_points_of_an_arc_get_a_fair_curve_by_default() {
    let fuzzed: [&[(f64, f64)]; 2] = [
        &[
            (133.317195, 1.782216),
            (138.365772, 11.575355),
            (135.674187, 22.209545),
            (132.415698, 36.674754),
            (127.637171, 43.406853),
            (124.704441, 50.407012),
            (125.187089, 61.511685),
            (112.727346, 70.609162),
            (106.988452, 81.060921),
        ],
        &[
            (463.867721, -7.277638),
            (454.424741, 130.943755),
            (372.528039, 233.869093),
            (307.047953, 355.161484),
            (176.026457, 437.852853),
            (68.883050, 498.925760),
            (-73.929123, 459.697471),
            (-216.731717, 428.134943),
            (-315.821226, 336.267288),
        ],
    ];
    let mut strokes: Vec<Vec<Point>> = fuzzed
        .iter()
        .map(|s| s.iter().map(|&(x, y)| p(x, y)).collect())
        .collect();
    for seed in 0..40u64 {
        let mut j = Jitter(4100 + seed);
        let r = [20.0, 130.0, 500.0][seed as usize % 3];
        let span = 0.6 + 0.06 * seed as f64;
        let sigma = (0.02 + 0.00025 * seed as f64) * r;
        strokes.push(
            (0..9)
                .map(|i| {
                    let a = span * i as f64 / 8.0;
                    p(
                        r * a.cos() + j.gaussian(sigma),
                        r * a.sin() + j.gaussian(sigma),
                    )
                })
                .collect(),
        );
    }
    let mut failed = Vec::new();
    for (k, pts) in strokes.iter().enumerate() {
        let size = pts
            .iter()
            .flat_map(|a| pts.iter().map(move |b| (*a - *b).hypot()))
            .fold(0.0, f64::max);
        failed.extend(fair_by_default(k, pts, 0.04 * 1.5 * size));
    }
    println!(
        "nine noisy points: {} of {} failed",
        failed.len(),
        2 * strokes.len()
    );
    assert!(failed.is_empty(), "{failed:#?}");
}

/// Clicks, not a pen: 15 to 30 points along an arc of 115° to 190° (radius 150 to 400),
/// each off by up to ±1 to ±4 px. The default tolerance stays about twice the jitter's
/// amplitude a here too (1.9a on average, asserted 2.1a; at most 2.9a, asserted 3a: a
/// dozen clicks estimate their noise less surely than a pen's hundreds): 15 such points span so
/// much of the arc that the noise read over 15 of them was the cubics missing the arc (σ 4.9 for a
/// true 1.7); the stroke of 15 clicks at ±3.2 px got a default of 31.9 px and its curve strayed 8.3
/// px from the clicks. Each fit is G2, proven monotone, without an inflection.
#[test]
fn clicked_arcs_get_a_default_tolerance_near_twice_the_jitter() {
    use aesthetic_curves::sketch::{default_tolerance, fit_sketch_within};
    let mut rng = Jitter(4700);
    let (mut worst, mut sum) = (0.0f64, 0.0);
    for k in 0..40 {
        let n = [15, 18, 23, 30][k % 4];
        let r = 275.0 + rng.next(125.0);
        let span = 2.65 + rng.next(0.65);
        let a = 2.5 + rng.next(1.5);
        let pts: Vec<Point> = (0..n)
            .map(|i| {
                let t = span * i as f64 / (n - 1) as f64;
                p(r * t.cos() + rng.next(a), r * t.sin() + rng.next(a))
            })
            .collect();
        let tol = default_tolerance(&pts);
        worst = worst.max(tol / a);
        sum += tol / a;
        assert!(
            tol <= 3.0 * a,
            "stroke {k} (n {n}, ±{a:.2}): default tolerance {tol:.2}"
        );
        let (s, used) = fit_sketch_within(&pts, None).unwrap_or_else(|e| panic!("stroke {k}: {e}"));
        assert!(s.max_deviation <= used, "stroke {k}");
        assert!(
            s.g2 && s.all_monotone && s.inflections == 0,
            "stroke {k}: {} inflections",
            s.inflections
        );
    }
    println!(
        "clicked arcs: default tolerance {:.2} times the jitter on average, at most {worst:.2}",
        sum / 40.0
    );
    assert!(
        sum / 40.0 <= 2.1,
        "on average {:.2} times the jitter",
        sum / 40.0
    );
}

/// Random clicks (4 to 30 points anywhere in 800 × 600) as contours at the default
/// tolerance: every one fitted, within its tolerance and connected. A run that turns back
/// and forth, which no G2 curve follows within the tolerance, gets a corner at its
/// sharpest point until every run fits: before, 4 of 1,600 such strokes sent through the
/// protocol failed ("these 11 points need more than 15 pieces as one G2 curve", or a
/// tolerance "inside the stroke's noise" the user never typed). And a straight stretch's
/// line, its ends set back along the curves beside it, is checked against the tolerance:
/// stroke 269 here came back 465 from its points at a tolerance of 437.
#[test]
fn random_clicks_come_back_as_contours() {
    let mut rng = Jitter(5200);
    let mut failed = Vec::new();
    for k in 0..300 {
        let n = 4 + ((rng.next(0.5) + 0.5) * 26.99) as usize;
        let pts: Vec<Point> = (0..n)
            .map(|_| p(400.0 + rng.next(400.0), 300.0 + rng.next(300.0)))
            .collect();
        match fit_contour(&pts, &ContourOptions::default()) {
            Ok(c) => {
                let name = format!("stroke {k}");
                assert_within_tolerance(&name, &c);
                assert_connected(&name, &c);
            }
            Err(e) => failed.push(format!("stroke {k} ({n} points): {e}")),
        }
    }
    println!("random clicks: {} of 300 failed", failed.len());
    assert!(failed.len() <= 1, "{failed:#?}");
}

/// A random walk of 7 points (from the protocol fuzz, seed 2, stroke 148) whose
/// default fit had an inflection piece of α -0.013 turning from zero to its largest
/// curvature over a thin triangle: no cubic of its family was proven monotone, and the
/// piece was delivered with the family centre's cubic, reported not monotone. An
/// inflection piece without a monotone cubic now asks for a split, as a LAC piece does:
/// every piece proven, the curve G2 and within its tolerance.
#[test]
fn an_inflection_piece_without_a_proven_cubic_is_split() {
    use aesthetic_curves::monotone::CurvatureMonotone;
    use aesthetic_curves::sketch::fit_sketch_within;
    let pts = [
        p(0.0, 0.0),
        p(-32.26347974087439, 6.0665280133593384),
        p(-24.415467201093563, 22.117008518142804),
        p(-51.16223720105158, 14.078234232345189),
        p(-70.62093046519628, -19.464141095349426),
        p(-82.60913627409664, -56.19909535707844),
        p(-69.12432925072645, -16.417754873211955),
    ];
    let (s, tol) = fit_sketch_within(&pts, None).unwrap();
    for (i, q) in s.pieces.iter().enumerate() {
        let proven = q.rational.is_curvature_monotone().unwrap();
        assert!(
            proven && q.monotone,
            "piece {i} ({:?}, alpha {})",
            q.kind,
            q.alpha
        );
    }
    assert!(s.all_monotone && s.g2, "{}", s.max_curvature_jump);
    assert!(s.max_deviation <= tol, "{} > {tol}", s.max_deviation);
    println!(
        "{} pieces, deviation {:.3} within {tol:.3}",
        s.pieces.len(),
        s.max_deviation
    );
}
