use super::constants::{tame_curvatures, HOOK_FACTOR};
use super::slot::{rotate, segment_distance, slot_ends, triangle, Cut, EndPoints, Slot};

use super::track::Track;
use crate::bspline;
use crate::lac::{LacSegment, ALPHA_RANGE};
use crate::solve::line_search::brent;
use kurbo::Point;
use rayon::prelude::*;

/// Distance from `q` to a curve sampled at an odd number of points: each pair of
/// neighbouring chords is read as the parabola over its outer chord through its three
/// points (the middle sample at its own place along the chord, which need not be the
/// middle: samples even in turning angle are not even in length), which removes the
/// chord's sagitta from the distance; the nearest of all of them (no assumption that the
/// points advance along the curve).
pub(super) fn curve_distance(samples: &[Point], q: Point) -> f64 {
    let mut best = f64::INFINITY;
    let mut k = 0;
    while k + 2 < samples.len() {
        best = best.min(arc_distance(
            [samples[k], samples[k + 1], samples[k + 2]],
            q,
        ));
        k += 2;
    }
    best
}

/// Distance from `q` to the parabola over the chord `p0 p2` through `p1` (as a graph over
/// the chord), to first order in the parabola's slope; beyond the chord's ends, the
/// distance to the nearer end. A middle sample too close to an end for a parabola gives
/// the two chords.
fn arc_distance([p0, p1, p2]: [Point; 3], q: Point) -> f64 {
    let d = p2 - p0;
    let len = d.hypot();
    let chords = || segment_distance(q, p0, p1).min(segment_distance(q, p1, p2));
    if len <= 0.0 || !len.is_finite() {
        return chords();
    }
    let e = d / len;
    let n = kurbo::Vec2::new(-e.y, e.x);
    let x1 = (p1 - p0).dot(e) / len;
    if !(0.05..=0.95).contains(&x1) {
        return chords();
    }
    let h1 = (p1 - p0).dot(n);
    let (xq, yq) = ((q - p0).dot(e) / len, (q - p0).dot(n));
    if !(0.0..=1.0).contains(&xq) {
        return (q - p0).hypot().min((q - p2).hypot());
    }
    let c = h1 / (x1 * (1.0 - x1));
    let y = c * xq * (1.0 - xq);
    let slope = c * (1.0 - 2.0 * xq) / len;
    (yq - y).abs() / (1.0 + slope * slope).sqrt()
}

/// Sum of squared and largest distance of `pts` to the LAC segment of shape `alpha` in
/// `tri` (its end curvatures within `cap` and within
/// [`MAX_CURVATURE_RATIO`](super::constants::MAX_CURVATURE_RATIO) of each other), from 65 samples
/// read as parabolic arcs: within 5e-5 of the segment's size even where its curvature grows 26-fold
/// (tested; 129 samples gave 6e-6 and a sixth more time to a Prius line's fit). `None` where the
/// segment does not exist.
pub(super) fn lac_cost(alpha: f64, tri: [Point; 3], pts: &[Point], cap: f64) -> Option<(f64, f64)> {
    let seg = LacSegment::new(alpha, tri).ok()?;
    let (k0, k1) = seg.end_curvatures().ok()?;
    if k0.abs().max(k1.abs()) > cap || !tame_curvatures(k0, k1) {
        return None;
    }
    let poly = seg.sample(65).ok()?.points;
    let (mut sum, mut max) = (0.0, 0.0f64);
    // The nearest sample by descent from the previous point's (either way: points may step
    // back), then the parabolic arcs around it.
    let mut j = 0usize;
    for q in pts {
        while j + 1 < poly.len() && (poly[j + 1] - *q).hypot2() <= (poly[j] - *q).hypot2() {
            j += 1;
        }
        while j > 0 && (poly[j - 1] - *q).hypot2() < (poly[j] - *q).hypot2() {
            j -= 1;
        }
        // Arcs start at even samples: the ones holding j and its neighbours.
        let lo = (j.saturating_sub(2)) & !1;
        let hi = (j + 4).min(poly.len());
        let d = curve_distance(&poly[lo..hi], *q);
        sum += d * d;
        max = max.max(d);
    }
    Some((sum, max))
}

/// α of the LAC segment in `tri` closest to `pts` in the least-squares sense (point-to-curve
/// distances), and the largest distance of all `pts`: a scan over [`ALPHA_RANGE`] (its 21
/// values in parallel) then Brent's refinement to 1e-4 (parabolic steps: about half the
/// evaluations of golden sections) between the grid's neighbours of its best α, on at
/// most 64 of the points (evenly spread; the largest distance is measured on all). Where a
/// neighbour gives no segment (the triangle's existence region, or the hook cap, ends
/// there) the refinement stops at that edge, found by bisection: the least-squares α
/// may lie on it. `None` when no α of the range gives a segment.
pub(super) fn fit_alpha(tri: [Point; 3], all: &[Point], cap: f64) -> Option<(f64, f64)> {
    let sub = spread(all, 64);
    let pts = &sub[..];
    let (lo, hi) = ALPHA_RANGE;
    let steps = 20;
    // The grid's costs in parallel (in order: the same minimum in any run).
    let grid: Vec<(f64, f64)> = (0..=steps)
        .into_par_iter()
        .filter_map(|k| {
            let a = lo + (hi - lo) * k as f64 / steps as f64;
            lac_cost(a, tri, pts, cap).map(|c| (a, c.0))
        })
        .collect();
    let &(a0, c0) = grid.iter().min_by(|x, y| x.1.total_cmp(&y.1))?;
    let h = (hi - lo) / steps as f64;
    let f = |a: f64| lac_cost(a, tri, pts, cap).map_or(f64::INFINITY, |c| c.0);
    let a = feasible_edge(&f, a0, (a0 - h).max(lo));
    let b = feasible_edge(&f, a0, (a0 + h).min(hi));
    let refined = brent(&mut |x| f(x), a.0, b.0, 1e-4);
    // The best of the refined point, the edges and the grid's (the refinement never loses
    // it), each valued once.
    let (best, _) = [refined, a, b, (a0, c0)]
        .into_iter()
        .filter(|c| c.1.is_finite())
        .min_by(|x, y| x.1.total_cmp(&y.1))?;
    lac_cost(best, tri, all, cap).map(|c| (best, c.1))
}

/// The α values around `alpha` (within [`ALPHA_RANGE`]) whose segment in `tri` fits `pts`
/// as closely as the points can tell: its largest distance within twice `alpha`'s own
/// or within `alpha`'s own plus 3 times the input's `noise` (σ), and never over
/// `tolerance` (an infinite `noise`, unknown, leaves the whole tolerance). Exact samples
/// pin α to their own fit; noisy points of a nearly circular or straight piece leave a
/// wide range. Each edge is walked to in steps of [`RANGE_STEP`],
/// then bisected to 1e-4; it stops where a segment stops existing.
pub(super) fn alpha_range(
    tri: [Point; 3],
    pts: &[Point],
    alpha: f64,
    noise: f64,
    tolerance: f64,
) -> (f64, f64) {
    let cost = |a: f64| lac_cost(a, tri, pts, f64::INFINITY).map(|c| c.1);
    let Some(own) = cost(alpha) else {
        return (alpha, alpha);
    };
    let limit = (2.0 * own).max(own + 3.0 * noise).min(tolerance.max(own));
    let fits = |a: f64| cost(a).is_some_and(|d| d <= limit);
    let edge = |to: f64| -> f64 {
        let mut good = alpha;
        while good != to {
            let next = if (to - good).abs() <= RANGE_STEP {
                to
            } else {
                good + RANGE_STEP.copysign(to - good)
            };
            if !fits(next) {
                let mut bad = next;
                while (bad - good).abs() > 1e-4 {
                    let mid = 0.5 * (good + bad);
                    if fits(mid) {
                        good = mid;
                    } else {
                        bad = mid;
                    }
                }
                return good;
            }
            good = next;
        }
        to
    };
    (edge(ALPHA_RANGE.0), edge(ALPHA_RANGE.1))
}

/// The step of [`alpha_range`]'s walk to its edges.
const RANGE_STEP: f64 = 0.25;

/// `to` when `f` is finite there, else the last α from `from` (where it is finite) towards
/// `to` where it still is, to 1e-4 (bisection); with its value.
fn feasible_edge(f: &dyn Fn(f64) -> f64, from: f64, to: f64) -> (f64, f64) {
    let at_to = f(to);
    if at_to.is_finite() {
        return (to, at_to);
    }
    let b = crate::solve::roots::bisect_by(
        |x| {
            let v = f(x);
            v.is_finite().then_some(v)
        },
        from,
        to,
        |a, b| 0.5 * (a + b),
        |a, b| (a - b).abs() < 1e-4,
        30,
    );
    (b.inside, b.value.unwrap_or_else(|| f(b.inside)))
}

/// At most `n` of `pts`, evenly spread (every k-th), for the searches; results are measured
/// on all of them.
pub(super) fn spread(pts: &[Point], n: usize) -> Vec<Point> {
    pts.iter()
        .step_by(pts.len().div_ceil(n).max(1))
        .copied()
        .collect()
}

/// The input points whose foot parameters lie in [ua, ub].
pub(super) fn points_in(fit: &bspline::BSplineFit, ua: f64, ub: f64) -> Vec<Point> {
    fit.points
        .iter()
        .zip(&fit.params)
        .filter(|(_, u)| **u >= ua && **u <= ub)
        .map(|(q, _)| *q)
        .collect()
}

/// The LAC piece of slot `s` (not an inflection piece) fitted to its input points: α by
/// least squares in the triangle of its end points and the track's tangents; with
/// `free_ends`, the tangent at an end of the whole curve is fitted too (Nelder–Mead over α
/// and the tangent angles, from the α of the fixed triangle). Returns the largest distance,
/// or `None` when the slot has no triangle or no segment.
pub(super) fn fit_slot_alpha(
    track: &Track,
    fit: &bspline::BSplineFit,
    s: &mut Slot,
    ends: EndPoints,
    free_ends: bool,
) -> Option<f64> {
    if s.cut_a.zero() || s.cut_b.zero() {
        return None;
    }
    let (pa, pb) = slot_ends(track, s, ends);
    let (da, db) = (track.direction(s.ua), track.direction(s.ub));
    let tri = triangle(pa, da, pb, db)?;
    let pts = points_in(fit, s.ua, s.ub);
    if pts.len() < 3 {
        return None;
    }
    s.fitted = true;
    // No hooks: the segment's end curvatures stay within HOOK_FACTOR of the fair spline's
    // largest over the piece (near the edge of its existence region a segment's end
    // curvature grows without bound while its shape, and the distances, barely change).
    let cap = HOOK_FACTOR
        * (0..=32)
            .map(|k| track.abs_kappa(s.ua + (s.ub - s.ua) * k as f64 / 32.0))
            .fold(0.0, f64::max);
    let (alpha, max) = fit_alpha(tri, &pts, cap)?;
    s.alpha = Some(alpha);
    let (free_a, free_b) = (
        free_ends && s.cut_a == Cut::End,
        free_ends && s.cut_b == Cut::End,
    );
    if !(free_a || free_b) {
        return Some(max);
    }
    let sub = spread(&pts, 64);
    // Unknowns: α, then the turn of each free end tangent (only those).
    let ib = if free_a { 2 } else { 1 };
    let make = |x: &[f64]| {
        let a = if free_a { rotate(da, x[1]) } else { da };
        let b = if free_b { rotate(db, x[ib]) } else { db };
        (a, b)
    };
    let mut cost = |x: &[f64]| -> f64 {
        let (a, b) = make(x);
        triangle(pa, a, pb, b)
            .and_then(|t| lac_cost(x[0].clamp(ALPHA_RANGE.0, ALPHA_RANGE.1), t, &sub, cap))
            .map_or(f64::INFINITY, |c| c.0)
    };
    let n = 1 + usize::from(free_a) + usize::from(free_b);
    let start = [alpha, 0.0, 0.0];
    let step = [0.25, 0.01, 0.01];
    let scale = cost(&start[..n]);
    // Stopped on the cost alone (its values within 1e-6 of the start's): the cost is flat
    // along α where the data do not pin α down, and asking the simplex to shrink there
    // too (1e-4) took about twice the evaluations for results within 1e-4 of the
    // tolerance on the Prius lines (for speed).
    let m = crate::solve::minimize::nelder_mead(
        &mut cost,
        &start[..n],
        &step[..n],
        crate::solve::minimize::NelderMead {
            f_tol: 1e-6 * scale,
            x_tol: f64::INFINITY,
            max_evaluations: 150,
            ..Default::default()
        },
    );
    if m.value.partial_cmp(&scale) != Some(std::cmp::Ordering::Less) {
        return Some(max);
    }
    let (a, b) = make(&m.x);
    let alpha = m.x[0].clamp(ALPHA_RANGE.0, ALPHA_RANGE.1);
    let tri = triangle(pa, a, pb, b)?;
    let (_, max) = lac_cost(alpha, tri, &pts, cap)?;
    s.alpha = Some(alpha);
    s.dir_a = free_a.then_some(a);
    s.dir_b = free_b.then_some(b);
    Some(max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Samples even in turning angle of a clothoid whose curvature grows 26-fold are 10
    /// times further apart at its flat end: the middle sample of a pair sits off the chord's
    /// middle there. Points on the curve (denser samples of it, an oracle of their own)
    /// are within 1e-5 of its size of the parabolic arcs; reading the middle sample as the
    /// chord's middle (as this measure did before) put them up to 6e-3 of the size off,
    /// which moved the least-squares α of such a piece by 0.08.
    #[test]
    fn curve_distance_is_exact_on_unevenly_spaced_samples() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(6.0, 3.0),
            Point::new(9.0, 0.5),
        ];
        let seg = LacSegment::new(-1.0, tri).unwrap();
        let poly = seg.sample(129).unwrap().points;
        let gaps: Vec<f64> = poly.windows(2).map(|w| (w[1] - w[0]).hypot()).collect();
        assert!(gaps[0] > 8.0 * gaps[gaps.len() - 1]);
        let worst = seg
            .sample(1000)
            .unwrap()
            .points
            .iter()
            .map(|q| curve_distance(&poly, *q))
            .fold(0.0, f64::max);
        assert!(worst < 1e-4, "{worst:e}");
        // The fit's own measure, from 65 samples: within 5e-5 of the size (about 10).
        let (sum, max) = lac_cost(-1.0, tri, &seg.sample(200).unwrap().points, 1e9).unwrap();
        assert!(max < 5e-4 && sum < 1e-6, "{max:e} {sum:e}");
    }

    /// The least-squares α of a segment's own points is its α, including where the grid's
    /// best α borders one that gives no segment (the refinement stops at that edge).
    #[test]
    fn fit_alpha_recovers_alpha_next_to_the_existence_edge() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(6.0, 3.0),
            Point::new(9.0, 0.5),
        ];
        // This triangle admits α from about -1.1 to 2.2 only.
        assert!(LacSegment::new(-1.5, tri).is_err() && LacSegment::new(2.5, tri).is_err());
        for alpha in [-1.0, -0.5, 0.0, 1.0, 2.0] {
            let pts = LacSegment::new(alpha, tri)
                .unwrap()
                .sample(150)
                .unwrap()
                .points;
            let (a, max) = fit_alpha(tri, &pts, 1e9).unwrap();
            assert!((a - alpha).abs() < 2e-3, "{alpha}: {a}");
            assert!(max < 5e-4, "{alpha}: {max:e}");
        }
    }

    #[test]
    fn curve_distance_removes_the_sagitta() {
        // Unit circle sampled coarsely: points on it are at distance ~0, the centre at 1.
        let samples: Vec<Point> = (0..=8)
            .map(|k| {
                let a = k as f64 * std::f64::consts::FRAC_PI_2 / 8.0;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let on = Point::new(0.3f64.cos(), 0.3f64.sin());
        let chord_only = polyline_like(&samples, on);
        assert!(curve_distance(&samples, on) < 0.05 * chord_only);
        assert!((curve_distance(&samples, Point::ZERO) - 1.0).abs() < 1e-3);
    }

    /// Distance to the chords alone, for comparison.
    fn polyline_like(poly: &[Point], q: Point) -> f64 {
        poly.windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                let t = ((q - w[0]).dot(d) / d.hypot2()).clamp(0.0, 1.0);
                (w[0] + d * t - q).hypot()
            })
            .fold(f64::INFINITY, f64::min)
    }
}
