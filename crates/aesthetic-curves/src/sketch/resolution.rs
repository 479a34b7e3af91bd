//! What a hand's stroke holds beyond its points' own noise: the device's resolution (a
//! mouse's whole pixels, a tablet's steps) and the hand's slow wobble.
//!
//! A mouse delivers whole pixels (in the editor: whole pixels over the view's scale, plus
//! its offset). A local estimate of the noise over 15 points does not see that: where the
//! hand is slow, 15 points span a few pixels and sit on a staircase of one-pixel steps, and
//! a tolerance of a fraction of a pixel makes the fit follow the stairs. [`quantum`] finds
//! the step all coordinates share; the default tolerance is then never below
//! [`QUANTUM_TOLERANCE`] of them.
//!
//! A hand drifts by a pixel or two over a second, slowly enough that 15 points see a
//! smooth curve. [`wobble`] reads it at a longer scale: the points resampled at equal arc
//! length, [`WOBBLE_SAMPLES`] along the stroke, and the residuals of local cubics over
//! `2 WOBBLE_HALF + 1` of them (about a fifteenth of the stroke: a shape a designer draws
//! is smooth at that scale, so what is left is the hand's).

/// The default tolerance is at least this many device steps.
pub(super) const QUANTUM_TOLERANCE: f64 = 3.0;

/// A stroke is a device's when its typical step is at most this many quanta (a typed
/// polygon on whole numbers has steps of many units: its points are meant exactly).
const QUANTUM_STEPS: f64 = 16.0;

/// At least this many points are needed to read a quantum: a hand's stroke is a second
/// or more of a device's events (60 to 200 a second); points typed on whole numbers are
/// fewer, and meant exactly.
const QUANTUM_MIN_POINTS: usize = 60;

/// A quantum below this share of the stroke's size is rounding, not a device.
const QUANTUM_MIN_SHARE: f64 = 1e-5;

/// The points of the stroke resampled for [`wobble`].
const WOBBLE_SAMPLES: usize = 160;

/// The half window of [`wobble`]'s local cubics, in resampled points.
const WOBBLE_HALF: usize = 5;

use super::input::{arc_lengths, sigma_of_residuals};
use kurbo::Point;

/// The step every coordinate difference of consecutive points is a whole multiple of (to
/// 1e-7 of the stroke's size) in at least 3 sizes, when the stroke has
/// [`QUANTUM_MIN_POINTS`] points or more,
/// moves by a few such steps at a time (its median step at most [`QUANTUM_STEPS`] of them)
/// and the step is at least [`QUANTUM_MIN_SHARE`] of its size; else 0.
pub(super) fn quantum(points: &[Point], size: f64) -> f64 {
    if points.len() < QUANTUM_MIN_POINTS || size.is_nan() || size <= 0.0 {
        return 0.0;
    }
    let eps = 1e-7 * size;
    let steps: Vec<f64> = points
        .windows(2)
        .flat_map(|w| [(w[1].x - w[0].x).abs(), (w[1].y - w[0].y).abs()])
        .filter(|d| *d > eps)
        .collect();
    if steps.is_empty() {
        return 0.0;
    }
    let mut q = steps[0];
    for &d in &steps[1..] {
        q = approximate_gcd(q, d, eps);
        if q < QUANTUM_MIN_SHARE * size {
            return 0.0;
        }
    }
    // Every step a whole multiple of q, and of at least 3 sizes: a device's steps vary
    // with the hand's speed; a curve sampled at a regular step (a line's samples, all one
    // step) is precise, not quantized.
    let mut multiples = Vec::new();
    for d in &steps {
        let m = d / q;
        if (m - m.round()).abs() * q > 2.0 * eps {
            return 0.0;
        }
        let m = m.round() as u64;
        if !multiples.contains(&m) && multiples.len() < 3 {
            multiples.push(m);
        }
    }
    if multiples.len() < 3 {
        return 0.0;
    }
    let mut lengths: Vec<f64> = points
        .windows(2)
        .map(|w| (w[1] - w[0]).hypot())
        .filter(|d| *d > eps)
        .collect();
    lengths.sort_unstable_by(f64::total_cmp);
    let median = lengths[lengths.len() / 2];
    if median <= QUANTUM_STEPS * q {
        q
    } else {
        0.0
    }
}

/// The greatest common step of `a` and `b`, remainders within `eps` taken as zero.
fn approximate_gcd(mut a: f64, mut b: f64, eps: f64) -> f64 {
    if a < b {
        std::mem::swap(&mut a, &mut b);
    }
    for _ in 0..64 {
        if b <= eps {
            return a;
        }
        let mut r = a % b;
        if b - r <= eps {
            r = 0.0;
        }
        a = b;
        b = r;
    }
    a
}

/// The hand's slow wobble (σ, as [`super::estimated_noise`]) read over a fifteenth of the
/// stroke (see the module documentation); 0 for fewer than 40 points.
pub(super) fn wobble(points: &[Point]) -> f64 {
    if points.len() < 40 {
        return 0.0;
    }
    let even = resampled(points, WOBBLE_SAMPLES);
    sigma_of_residuals(&even, WOBBLE_HALF)
}

/// `n` points at equal arc length along the polyline through `points`.
fn resampled(points: &[Point], n: usize) -> Vec<Point> {
    let s = arc_lengths(points);
    let total = s[s.len() - 1];
    let mut out = Vec::with_capacity(n);
    let mut i = 1;
    for k in 0..n {
        let target = total * k as f64 / (n - 1) as f64;
        while i < s.len() - 1 && s[i] < target {
            i += 1;
        }
        let span = s[i] - s[i - 1];
        let t = if span > 0.0 {
            ((target - s[i - 1]) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        out.push(points[i - 1].lerp(points[i], t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_pixels_over_a_scale_have_their_quantum() {
        let scale = 37.0;
        let pts: Vec<Point> = (0..200)
            .map(|k| {
                let a = k as f64 * 0.02;
                let px = (
                    (300.0 * a.cos()).round() + 0.5,
                    (300.0 * a.sin()).round() - 3.0,
                );
                Point::new((px.0 - 411.3) / scale, (px.1 - 97.1) / scale)
            })
            .collect();
        let size = super::super::input::bbox_diagonal(&pts);
        let q = quantum(&pts, size);
        assert!((q * scale - 1.0).abs() < 1e-6, "{q}");
    }

    #[test]
    fn typed_points_and_floats_have_none() {
        // Typed on whole numbers, small steps: fewer points than a hand's second.
        let typed: Vec<Point> = (0..40)
            .map(|k| Point::new(k as f64 * 3.0, ((k * 7) % 11) as f64 * 2.0))
            .collect();
        assert_eq!(quantum(&typed, 130.0), 0.0);
        let floats: Vec<Point> = (0..200)
            .map(|k| {
                let a = k as f64 * 0.031;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        assert_eq!(quantum(&floats, 2.0), 0.0);
    }
}
