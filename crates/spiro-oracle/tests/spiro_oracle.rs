//! The log-aesthetic spline at α = -1 against libspiro (Raph Levien's Spiro, Debian package
//! `libspiro-dev`), an independent solver of the same equations: Spiro's G2 points ('c')
//! join clothoid segments (two parameters each: κ and dκ/ds) with continuous tangent and
//! curvature, and its open ends ('{', '}') and corners ('v') take a circular arc for the
//! span next to them (one parameter): exactly the spline of `lac_spline` with α = -1. The
//! two must agree on the curvature at every point.
//!
//! `apt-get install libspiro-dev && cargo test --release --workspace --features
//! spiro-oracle/libspiro --test spiro_oracle`

use aesthetic_curves::lac_spline::{lac_spline, LacSpline, LacSplineOptions};
use aesthetic_curves::samples::{harsh_walk, random_walk, s2_points, wavy_points, SplitMix64};
use aesthetic_curves::{Point, Vec2};

use spiro_oracle::ffi::{control_points, run, SpiroSeg};

/// Spiro's segments through `pts` (corners 'v' at `corners`), or None when it fails.
fn spiro(pts: &[Point], closed: bool, corners: &[usize]) -> Option<Vec<SpiroSeg>> {
    run(&control_points(pts, closed, corners))
}

/// A Spiro segment's signed curvature at its start and end, input units: its curvature in
/// the normalized arc length s in [-1/2, 1/2] is `ks0 + ks1 s + ks2 s²/2 + ks3 s³/6`, over
/// the length `seg_ch / ch` (ch the chord of the unit-length curve, integrated here by a
/// 64-point Gauss–Legendre rule on 16 panels).
fn spiro_ends(seg: &SpiroSeg) -> (f64, f64) {
    let k = seg.ks;
    let theta =
        |s: f64| k[0] * s + k[1] * s * s / 2.0 + k[2] * s.powi(3) / 6.0 + k[3] * s.powi(4) / 24.0;
    // 4-point Gauss–Legendre on 16 panels.
    let (x, w) = (
        [
            -0.861_136_311_594_052_6,
            -0.339_981_043_584_856_3,
            0.339_981_043_584_856_3,
            0.861_136_311_594_052_6,
        ],
        [
            0.347_854_845_137_453_9,
            0.652_145_154_862_546_1,
            0.652_145_154_862_546_1,
            0.347_854_845_137_453_9,
        ],
    );
    let mut c = Vec2::ZERO;
    let panels = 16;
    for p in 0..panels {
        let (a, b) = (
            -0.5 + p as f64 / panels as f64,
            -0.5 + (p + 1) as f64 / panels as f64,
        );
        for i in 0..4 {
            let s = 0.5 * (a + b) + 0.5 * (b - a) * x[i];
            c += Vec2::from_angle(theta(s)) * (0.5 * (b - a) * w[i]);
        }
    }
    let per_length = c.hypot() / seg.seg_ch;
    let at = |s: f64| (k[0] + k[1] * s + k[2] * s * s / 2.0 + k[3] * s.powi(3) / 6.0) * per_length;
    (at(-0.5), at(0.5))
}

/// libspiro's curvature variation ∫|dκ/ds| ds over its first `spans` segments, input
/// units: each segment's curvature polynomial sampled at 400 steps, scaled to its end
/// curvatures ([`spiro_ends`]).
fn spiro_variation(segs: &[SpiroSeg], spans: usize) -> f64 {
    let mut total = 0.0;
    for seg in segs.iter().take(spans) {
        let (a, b) = spiro_ends(seg);
        let k = seg.ks;
        let raw = |x: f64| k[0] + k[1] * x + k[2] * x * x / 2.0 + k[3] * x.powi(3) / 6.0;
        if raw(0.5) == raw(-0.5) {
            continue;
        }
        let scale = (b - a) / (raw(0.5) - raw(-0.5));
        let mut last = raw(-0.5);
        for i in 1..=400 {
            let v = raw(-0.5 + i as f64 / 400.0);
            total += ((v - last) * scale).abs();
            last = v;
        }
    }
    total
}

/// The spline's curvature variation: every piece is curvature-monotone (proven), so its
/// part is the difference of its end curvatures.
fn lac_variation(s: &LacSpline) -> f64 {
    s.pieces
        .iter()
        .map(|p| (p.end_curvatures.1 - p.end_curvatures.0).abs())
        .sum()
}

/// The largest difference, over the largest curvature, between the two splines' curvature
/// at the start and the end of every span.
fn compare(pts: &[Point], closed: bool, corners: &[usize]) -> Option<f64> {
    let segs = spiro(pts, closed, corners)?;
    let opts = LacSplineOptions {
        closed,
        corners: corners.to_vec(),
        ..Default::default()
    };
    let ours = lac_spline(pts, &opts).ok()?;
    Some(difference(&segs, &ours))
}

/// [`compare`]'s measure of the two solved splines: one libspiro segment per span of
/// `ours`.
fn difference(segs: &[SpiroSeg], ours: &LacSpline) -> f64 {
    let spans = ours.pieces.last().map_or(0, |p| p.span + 1);
    let mut big = 0.0f64;
    let mut worst = 0.0f64;
    for (k, seg) in segs.iter().enumerate().take(spans) {
        let first = ours.pieces.iter().find(|p| p.span == k).unwrap();
        let last = ours.pieces.iter().rev().find(|p| p.span == k).unwrap();
        let (a, b) = (first.end_curvatures.0, last.end_curvatures.1);
        let (sa, sb) = spiro_ends(seg);
        big = big.max(a.abs()).max(b.abs());
        worst = worst.max((a - sa).abs()).max((b - sb).abs());
    }
    worst / big.max(1e-300)
}

#[test]
fn the_clothoid_spline_is_spiros() {
    let p = Point::new;
    let cases: Vec<(Vec<Point>, bool, Vec<usize>)> = vec![
        (wavy_points(8, 3), false, vec![]),
        (wavy_points(15, 7), false, vec![]),
        (s2_points(), false, vec![]),
        // S2's example points taken as a closed curve: a thin zig-zag whose closing chord
        // the circles' tangents ask to turn 320° (once refused).
        (s2_points(), true, vec![]),
        (
            vec![
                p(0.0, 0.0),
                p(4.0, -1.0),
                p(8.0, 1.0),
                p(7.0, 5.0),
                p(3.0, 6.0),
                p(-1.0, 3.0),
            ],
            true,
            vec![],
        ),
        (
            vec![
                p(0.0, 0.0),
                p(5.0, -2.0),
                p(10.0, 0.0),
                p(7.0, 3.0),
                p(3.0, 3.5),
            ],
            true,
            vec![0, 2],
        ),
    ];
    for (pts, closed, corners) in cases {
        let d = compare(&pts, closed, &corners).expect("both solve");
        eprintln!("{} points, closed {closed}: {d:.2e}", pts.len());
        assert!(
            d < 1e-7,
            "{pts:?}: curvatures differ by {d:e} of the largest"
        );
    }
}

/// On random point sets (4 to 9 points, chords 0.5 to 2, turns between chords up to
/// ±`turn`): how many each solver fails on, and the largest difference where both solve.
fn sweep(turn: f64, seed: u64) -> (usize, usize, usize, usize, f64) {
    let mut rng = SplitMix64::new(seed);
    let (mut both, mut spiro_failed, mut ours_failed, mut both_failed) = (0, 0, 0, 0);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let pts = random_walk(&mut rng, turn);
        let s = spiro(&pts, false, &[]).is_some();
        let o = lac_spline(&pts, &LacSplineOptions::default()).is_ok();
        match (s, o) {
            (true, true) => {
                worst = worst.max(compare(&pts, false, &[]).unwrap());
                both += 1;
            }
            (false, true) => spiro_failed += 1,
            (true, false) => ours_failed += 1,
            (false, false) => both_failed += 1,
        }
    }
    (both, spiro_failed, ours_failed, both_failed, worst)
}

#[test]
fn random_point_sets_agree_with_spiro() {
    for (turn, seed) in [(1.2, 5), (1.2, 6), (2.1, 5), (2.1, 6), (2.6, 5)] {
        let (both, s, o, n, worst) = sweep(turn, seed);
        eprintln!(
            "turns to ±{:.0}°, seed {seed}: both solve {both} (largest difference {worst:.1e}), \
             only lac_spline {s}, only libspiro {o}, neither {n}",
            turn.to_degrees()
        );
        assert_eq!(o + n, 0, "lac_spline failed where libspiro did not");
    }
}

/// How often each solver fails on 300 [`harsh_walk`]s, open or closed: libspiro (it
/// returns no path where its Newton iteration did not converge, FontForge's "Spiros did
/// not converge") and `lac_spline` (an error, or a spline not G2); the counts (both, only
/// libspiro, only `lac_spline`, neither), the largest difference of their curvatures where
/// both solve, how many of those differ by more than 1e-6 (another solution of the same
/// equations) and in how many of those the spline's curvature varies less (∫|dκ/ds| ds).
fn harsh_sweep(turn: f64, closed: bool, seed: u64) -> ([usize; 4], f64, [usize; 2]) {
    let mut rng = SplitMix64::new(seed);
    let mut counts = [0usize; 4];
    let mut worst = 0.0f64;
    let mut other = [0usize; 2];
    let opts = LacSplineOptions {
        closed,
        ..Default::default()
    };
    let spans = |n: usize| if closed { n } else { n - 1 };
    for _ in 0..300 {
        let pts = harsh_walk(&mut rng, turn);
        let segs = spiro(&pts, closed, &[]);
        let ours = lac_spline(&pts, &opts).ok().filter(|sp| sp.g2());
        let (s, o) = (segs.is_some(), ours.is_some());
        if let (Some(segs), Some(ours)) = (&segs, &ours) {
            let d = difference(segs, ours);
            worst = worst.max(d);
            if d > 1e-6 {
                other[0] += 1;
                let fairer = lac_variation(ours) < spiro_variation(segs, spans(pts.len()));
                other[1] += usize::from(fairer);
            }
        }
        counts[usize::from(!s) * 2 + usize::from(!o)] += 1;
    }
    (counts, worst, other)
}

/// Point sets harsher than [`random_point_sets_agree_with_spiro`]'s (the target: "converges
/// where libspiro does not", FontForge's "Spiros did not converge"). Open sets with turns
/// up to ±120° give the same curve from both, asserted, and `lac_spline` must solve at
/// least 1,150 of the 1,200. The rest is measured: libspiro solved 1,197, `lac_spline`
/// with its spans' own family alone 1,055 (that family held no solution near libspiro's:
/// one side of an S-span winds past a half turn); with the wider family and the
/// continuation as fallbacks, 1,178, one of them one libspiro did not solve; then,
/// with spans that wind (a tangent past a half turn from its chord, measured on the
/// branch of the start; a segment up to 1.95 half turns) as the last fallbacks, and the
/// cubics' end curvatures read from their f64 coordinates repaired (lac_spline/joins.rs;
/// three sets had jumps of 3e-8 to 4e-7 there): 1,196.
/// Some of the sets both solve are another solution of the same equations than
/// libspiro's (curvatures apart by up to 1.6 of the largest): an open defect.
#[test]
fn harsh_point_sets_against_libspiro() {
    let mut total = [0usize; 4];
    let mut others = [0usize; 2];
    for (turn, closed, seed) in [
        (2.1, false, 7),
        (2.6, false, 8),
        (2.1, true, 9),
        (2.6, true, 10),
    ] {
        let ([both, only_spiro, only_ours, neither], worst, other) =
            harsh_sweep(turn, closed, seed);
        eprintln!(
            "harsh, turns to ±{:.0}°, {}: both solve {both} (largest difference {worst:.1e}, \
             {} other solutions, the spline's fairer in {}), only lac_spline {only_ours}, \
             only libspiro {only_spiro}, neither {neither}",
            turn.to_degrees(),
            if closed { "closed" } else { "open" },
            other[0],
            other[1]
        );
        others[0] += other[0];
        others[1] += other[1];
        if turn < 2.2 && !closed {
            assert!(worst < 1e-6, "the two differ by {worst:e}");
        }
        for (t, c) in total.iter_mut().zip([both, only_spiro, only_ours, neither]) {
            *t += c;
        }
    }
    eprintln!(
        "harsh: both solve {}, only libspiro {}, only lac_spline {}, neither {}",
        total[0], total[1], total[2], total[3]
    );
    let ours = total[0] + total[2];
    assert!(ours >= 1190, "lac_spline solved {ours} of 1,200");
    // Where the two reach different solutions, the spline's is the fairer by the fairness
    // measure (∫|dκ/ds| ds) in most (measured: 51 of 57).
    eprintln!(
        "other solutions: {}, the spline's curvature varying less in {}",
        others[0], others[1]
    );
    assert!(
        others[1] * 4 >= others[0] * 3,
        "the spline fairer in {} of {}",
        others[1],
        others[0]
    );
}
