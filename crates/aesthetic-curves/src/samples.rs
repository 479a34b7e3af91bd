//! Reproducible sets of curves for benchmarks, demos and tests.
//!
//! A small SplitMix64 generator (no dependency) drives two families in equal parts:
//! control polygons with points uniform in a box (mostly not curvature-monotone), and
//! "class A"-like spirals whose edges are scaled and rotated by a constant with a small
//! jitter (mostly monotone). The same seed always gives the same curves.

use crate::bezier::{Bezier, RationalBezier};
use kurbo::{Point, Vec2};

/// SplitMix64: a tiny, well-distributed, reproducible generator.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

fn polygon(rng: &mut SplitMix64, degree: usize) -> Vec<Point> {
    if rng.next_u64() & 1 == 0 {
        (0..=degree)
            .map(|_| Point::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0)))
            .collect()
    } else {
        let scale = rng.range(0.55, 1.0);
        let rot = rng.range(-0.7, 0.7);
        let mut e = Vec2::from_angle(rng.range(0.0, std::f64::consts::TAU)) * rng.range(1.0, 3.0);
        let mut p = Point::ZERO;
        let mut out = vec![p];
        for _ in 0..degree {
            p += e + Vec2::new(rng.range(-0.05, 0.05), rng.range(-0.05, 0.05));
            out.push(p);
            e = Vec2::from_angle(rot).rotate_scale(e) * scale;
        }
        out
    }
}

/// `count` polynomial Bézier curves of the given degree (1 to 20).
pub fn random_curves(degree: usize, count: usize, seed: u64) -> Vec<Bezier> {
    let mut rng = SplitMix64::new(seed ^ (degree as u64).wrapping_mul(0x1234_5678_9ABC));
    (0..count)
        .map(|_| Bezier::new(polygon(&mut rng, degree)).expect("valid degree"))
        .collect()
}

/// `count` rational Bézier curves of the given degree, weights in [0.25, 4].
pub fn random_rational_curves(degree: usize, count: usize, seed: u64) -> Vec<RationalBezier> {
    let mut rng = SplitMix64::new(seed ^ (degree as u64).wrapping_mul(0x9876_5432_1FED));
    (0..count)
        .map(|_| {
            let pts = polygon(&mut rng, degree);
            let w = (0..=degree)
                .map(|_| 4f64.powf(rng.range(-1.0, 1.0)))
                .collect();
            RationalBezier::new(pts, w).expect("valid degree and weights")
        })
        .collect()
}

/// S2's example points (`examples/spline-points.csv`): a thin zig-zag of six points, open
/// as the paper draws it, or closed (a closing span across the whole shape).
pub fn s2_points() -> Vec<Point> {
    [
        (0.0, 0.0),
        (2.0, 1.5),
        (4.0, 1.0),
        (6.0, 3.0),
        (8.0, 2.5),
        (10.0, 4.0),
    ]
    .into_iter()
    .map(|(x, y)| Point::new(x, y))
    .collect()
}

/// `n` points along a smooth wavy line (spacing about 1, irregular, chord turns up to about
/// 40°): the input of the spline benchmarks and comparisons. Same seed, same points.
pub fn wavy_points(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|k| {
            let t = k as f64 + 0.3 * (rng.next_f64() - 0.5);
            Point::new(t, 2.0 * (t / 3.0).sin() + 0.5 * (0.7 * t).sin())
        })
        .collect()
}

/// A random open polyline's points, the input of the spline sweeps (`tests/lac_spline.rs`,
/// `tests/spiro_oracle.rs`): 4 to 9 points from the origin, chords 0.5 to 2 long, each
/// turning from the last by up to ±`turn` radians. Draws from `rng`, so one generator gives
/// a reproducible sequence of sets.
pub fn random_walk(rng: &mut SplitMix64, turn: f64) -> Vec<Point> {
    let n = 4 + (rng.next_u64() % 6) as usize;
    walk(rng, n, turn, |rng| rng.range(0.5, 2.0))
}

/// `n` points from the origin, each chord `chord(rng)` long and turning from the last by
/// up to ±`turn` radians (the turn drawn before the chord).
fn walk(
    rng: &mut SplitMix64,
    n: usize,
    turn: f64,
    chord: impl Fn(&mut SplitMix64) -> f64,
) -> Vec<Point> {
    let mut pts = vec![Point::new(0.0, 0.0)];
    let mut dir = 0.0f64;
    for _ in 1..n {
        dir += rng.range(-turn, turn);
        let last = *pts.last().expect("one point at least");
        pts.push(last + kurbo::Vec2::from_angle(dir) * chord(rng));
    }
    pts
}

/// A harsher random polyline (the harsh sweep against libspiro, `tests/spiro_oracle.rs`,
/// and `tests/lac_spline.rs`): 5 to 16 points, chords log-uniform in 0.1 to 3 (a
/// thirtyfold spread), each turning from the last by up to ±`turn` radians.
pub fn harsh_walk(rng: &mut SplitMix64, turn: f64) -> Vec<Point> {
    let n = 5 + (rng.next_u64() % 12) as usize;
    walk(rng, n, turn, |rng| rng.range(0.1f64.ln(), 3f64.ln()).exp())
}

/// `count` LAC segments of random shape, the distribution of the rational-cubic sweep
/// (`tests/approx_sweep.rs`): α uniform in [-5, 5], turning uniform in 5° to 120°, the base
/// angle at the high-curvature end uniform between the circle's and 0.98 of θ_lim; start
/// (0, 0), tangent intersection (1, 0). Same seed, same segments.
pub fn random_lac_segments(count: usize, seed: u64) -> Vec<crate::lac::LacSegment> {
    use crate::lac::LacSegment;
    let mut rng = SplitMix64::new(seed);
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let alpha = rng.range(-5.0, 5.0);
        let td = rng.range(5f64.to_radians(), 120f64.to_radians());
        let Ok(lim) = LacSegment::theta_lim(alpha, td) else {
            continue;
        };
        let phi = 0.5 * td + rng.range(0.0, 1.0) * (0.98 * lim - 0.5 * td).max(0.0);
        let d = phi.sin() / (td - phi).sin();
        let tri = [
            Point::ZERO,
            Point::new(1.0, 0.0),
            Point::new(1.0 + d * td.cos(), d * td.sin()),
        ];
        if let Ok(seg) = LacSegment::new(alpha, tri) {
            out.push(seg);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::monotone::CurvatureMonotone;

    #[test]
    fn the_generator_is_reproducible_and_uniform() {
        // SplitMix64's published first output for seed 0 (Vigna's reference code).
        assert_eq!(SplitMix64::new(0).next_u64(), 0xE220_A839_7B1D_CDAF);
        let mut rng = SplitMix64::new(7);
        let v: Vec<f64> = (0..20_000).map(|_| rng.next_f64()).collect();
        assert!(v.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        // The mean of 20,000 uniforms: 0.5 with a standard deviation of 0.002.
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        let mut r = SplitMix64::new(7);
        assert!((0..100).all(|_| (-3.0..5.0).contains(&r.range(-3.0, 5.0))));
    }

    #[test]
    fn the_sets_are_what_they_say() {
        // Same seed, same curves; both families present (some monotone, some not).
        let a = random_curves(5, 40, 3);
        assert_eq!(a, random_curves(5, 40, 3));
        assert!(a.iter().all(|c| c.degree() == 5));
        let monotone = a
            .iter()
            .filter(|c| c.is_curvature_monotone().unwrap_or(false))
            .count();
        assert!(monotone > 0 && monotone < 40, "{monotone}");
        let r = random_rational_curves(3, 30, 3);
        assert!(r
            .iter()
            .all(|c| c.weights().iter().all(|w| (0.25..=4.0).contains(w))));
        let w = wavy_points(50, 1);
        assert!(w.windows(2).all(|p| p[1].x > p[0].x));
        for seg in random_lac_segments(30, 5) {
            let alpha = seg.alpha();
            let td = seg.theta_d().to_degrees();
            assert!((-5.0..5.0).contains(&alpha) && (5.0..120.0).contains(&td));
        }
    }
}
