//! Dense strokes thinned before the contour fit: a pen tablet's 200 events a second put
//! points a fraction of a pixel apart, tens to hundreds per tolerance, and every stage of
//! the fit (the straightness windows, the fair spline, the deviations) pays for each of
//! them. Points are averaged over bins of arc length half the tolerance long: the averages
//! follow the stroke to well within the tolerance (a bin's chord sags by w²/8R, 0.012 px
//! for w = 1.4 px on a radius of 20 px) and carry less of the sensor's noise. The
//! averages hide the noise's extremes, which the default tolerance must still reach: where
//! the curve misses a raw point, the raw points are fitted (a pen's 6,000-point S and wave
//! measured so, at 2 and 13 % more time; its circle and spiral 1.3 and 1.1 s instead of
//! 2.0 and 2.6 s).
//! The delivered curve is then measured against every raw point
//! ([`worst_distance`]); a curve that misses one by more than the tolerance is not
//! delivered (the caller fits the raw points instead).

use super::contour::Run;
use super::deviation::{project, Sampled};
use super::slot::segment_distance;
use crate::bezier::RationalBezier;
use kurbo::Point;
use rayon::prelude::*;

/// Bins are this share of the tolerance long.
pub(super) const THIN_SHARE: f64 = 0.5;

/// Strokes of fewer points are fitted as they are: thinning also smooths, and a stroke at
/// the edge of fairness can then pass the default's first rung where its raw points fail
/// it and go on to a looser, fairer rung (a trackpad's rounded rectangle of 1,000 points as
/// a file: 37 pieces at the default instead of 11 at twice it). The fit of 2,000 points
/// takes a second or more.
pub(super) const THIN_MIN_POINTS: usize = 2000;

/// A stroke is thinned only when the bins leave at most this share of its points.
const THIN_GAIN: f64 = 0.75;

/// A thinned stroke: the bins' averages, and the range of raw indices each one holds.
pub(super) struct Thinned {
    pub(super) points: Vec<Point>,
    pub(super) origin: Vec<(usize, usize)>,
}

impl Thinned {
    /// The raw point a thinned index stands for: its bin's middle one.
    pub(super) fn raw_index(&self, k: usize) -> usize {
        let (a, b) = self.origin[k];
        (a + b) / 2
    }

    /// How many raw points the first `kept` thinned ones hold.
    pub(super) fn raw_kept(&self, kept: usize) -> usize {
        kept.checked_sub(1).map_or(0, |k| self.origin[k].1 + 1)
    }
}

/// `points` averaged over bins of arc length `width` (the first and the last point kept
/// as they are: a stroke's ends are where it was put down and lifted); `None` for a short
/// stroke ([`THIN_MIN_POINTS`]) or one the bins would not thin by much ([`THIN_GAIN`]).
pub(super) fn thin(points: &[Point], width: f64) -> Option<Thinned> {
    let n = points.len();
    if n < THIN_MIN_POINTS || !(width > 0.0 && width.is_finite()) {
        return None;
    }
    let mut out = Thinned {
        points: vec![points[0]],
        origin: vec![(0, 0)],
    };
    let (mut start, mut along) = (1, 0.0);
    for k in 1..n - 1 {
        along += (points[k] - points[k - 1]).hypot();
        if along >= width {
            push_bin(&mut out, points, start, k);
            (start, along) = (k + 1, 0.0);
        }
    }
    if start < n - 1 {
        push_bin(&mut out, points, start, n - 2);
    }
    out.points.push(points[n - 1]);
    out.origin.push((n - 1, n - 1));
    (out.points.len() as f64 <= THIN_GAIN * n as f64).then_some(out)
}

/// The average of `points[a..=b]` as the next bin.
fn push_bin(out: &mut Thinned, points: &[Point], a: usize, b: usize) {
    let bin = &points[a..=b];
    let sum = bin.iter().fold(kurbo::Vec2::ZERO, |s, q| s + q.to_vec2());
    out.points.push((sum / bin.len() as f64).to_point());
    out.origin.push((a, b));
}

/// The largest distance from `points` to the nearest of the contour's `runs` (a line's
/// segment, or a curve's rational cubics, each a nearest-point projection), in parallel.
pub(super) fn worst_distance(points: &[Point], runs: &[Run]) -> f64 {
    let pieces: Vec<(&RationalBezier, Sampled)> = runs
        .iter()
        .filter_map(|r| match r {
            Run::Curve(s) => Some(s.pieces.iter()),
            Run::Line { .. } => None,
        })
        .flatten()
        .map(|p| (&p.rational, Sampled::new(p)))
        .collect();
    let lines: Vec<(Point, Point)> = runs
        .iter()
        .filter_map(|r| match r {
            Run::Line { start, end } => Some((*start, *end)),
            Run::Curve(_) => None,
        })
        .collect();
    points
        .par_iter()
        .with_min_len(64)
        .map(|q| {
            let mut best = lines
                .iter()
                .map(|(a, b)| segment_distance(*q, *a, *b))
                .fold(f64::INFINITY, f64::min);
            for (curve, sm) in &pieces {
                if sm.may_be_nearer(*q, best) {
                    best = best.min(project(curve, *q, &sm.samples).0);
                }
            }
            best
        })
        .reduce(|| 0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dense_stroke_is_averaged_over_bins_with_its_ends_kept() {
        // 3,001 points 0.01 apart along a line: bins of 0.25 hold 25 points each.
        let pts: Vec<Point> = (0..=3000)
            .map(|i| Point::new(0.01 * i as f64, 1.0))
            .collect();
        let t = thin(&pts, 0.25).expect("thinned");
        assert_eq!(t.points[0], pts[0]);
        assert_eq!(*t.points.last().unwrap(), pts[3000]);
        assert!(t.points.len() < 130, "{}", t.points.len());
        // Every raw point is in exactly one bin, in order.
        let mut next = 0;
        for &(a, b) in &t.origin {
            assert_eq!(a, next);
            next = b + 1;
        }
        assert_eq!(next, 3001);
        assert!(t.points.iter().all(|q| (q.y - 1.0).abs() < 1e-12));
        assert_eq!(t.raw_kept(t.points.len()), 3001);
        // A sparse stroke is left alone.
        let sparse: Vec<Point> = (0..4000).map(|i| Point::new(i as f64, 0.0)).collect();
        assert!(thin(&sparse, 0.25).is_none());
    }
}
