//! Straight stretches inside a curved run of a contour (a stage of [`super::contour`]).
//!
//! A rounded rectangle drawn in one stroke has no corners, but four of its stretches are
//! straight: they come back as lines, and the curves between them join each line G2 (the
//! curve leaves the line along it with zero curvature: [`super::SketchOptions::line_ends`]).
//!
//! A stretch of a run is straight when
//! 1. its points lie within the tolerance of their least-squares line, and a cubic explains
//!    them no better than that line does: the drop in the sum of squared residuals from the
//!    line to the cubic (in the line's frame) stays below [`BEND_CHI2`] σ² (a χ² of two
//!    degrees of freedom: a bow or an S hidden in the noise would show there);
//! 2. it is at least [`MIN_LENGTH_TOLERANCES`] tolerances and [`MIN_POINTS`] points long;
//! 3. it is straight *against its neighbours*: the curves on both sides bend the same way,
//!    and the fair spline (the sketch's, within [`FAIR_SHARE`] of the tolerance) is flat in
//!    its middle, its largest |κ| from 20 % to 80 % of the stretch at most [`FLAT_SHARE`]
//!    of its largest |κ| within half the stretch's length beyond each end. On a large arc
//!    the spline's curvature is the same inside and beyond; between opposite bends (the
//!    flank of an S or a wave, nearly straight as it may be) no stretch is a line.
//!
//! The stretches are found greedily from the start of the run: each as long as 1 allows
//! (doubling, then bisection; a later start kept where it runs further), at least
//! [`MIN_GAP`] points apart so that the curve between two lines has points to be fitted
//! to, neighbours that are one merged, and each end that meets a curve moved back from it
//! ([`Test::trimmed`]).

use super::constants::FAIR_SHARE;
use super::input::{arc_lengths, bbox_diagonal};
use kurbo::{Point, Vec2};

/// Upper bound of the drop in squared residuals from a line to a cubic, in units of σ²
/// (the 99.9 % point of χ² with two degrees of freedom).
pub(super) const BEND_CHI2: f64 = 13.8;

/// A straight stretch is at least this many tolerances long...
pub(super) const MIN_LENGTH_TOLERANCES: f64 = 10.0;

/// ... and this many points.
pub(super) const MIN_POINTS: usize = 10;

/// Points between two stretches, or between a stretch and a run's end that is not on it.
pub(super) const MIN_GAP: usize = 8;

/// The fair spline's largest |κ| inside a straight stretch is at most this share of its
/// largest just beyond it.
pub(super) const FLAT_SHARE: f64 = 0.15;

/// [`FLAT_SHARE`] for a hand's stroke ([`Test::allowing_bow`]).
pub(super) const HAND_FLAT_SHARE: f64 = 0.3;

/// A straight stretch: points `a..=b` of the run and their least-squares line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Stretch {
    pub(super) a: usize,
    pub(super) b: usize,
    /// A point of the line (the points' centroid).
    pub(super) centre: Point,
    /// Its unit direction, from `a` towards `b`.
    pub(super) dir: Vec2,
}

impl Stretch {
    /// The foot of `q` on the line.
    pub(super) fn foot(&self, q: Point) -> Point {
        self.centre + self.dir * (q - self.centre).dot(self.dir)
    }
}

/// A part of a run split at its straight stretches.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Part {
    /// A stretch as a line from `start` to `end`, and its points.
    Line {
        start: Point,
        end: Point,
        points: Vec<Point>,
    },
    /// The points between two stretches (or a stretch and an end of the run), starting and
    /// ending where the lines next to them end, and those lines' directions.
    Curve {
        points: Vec<Point>,
        line_ends: [Option<Vec2>; 2],
    },
}

/// `run` split at its `stretches` (in order, [`MIN_GAP`] apart): each stretch a line from
/// its first point's foot on its least-squares line to its last's (at the run's own ends:
/// the run's end points, where the next run or a corner meets it), and between them curves
/// that start and end on those lines, along them. `closed_loop`: `run` is a closed loop
/// (its last point its first) that starts with the first stretch, so its last curve ends
/// where the first line starts.
pub(super) fn parts(run: &[Point], stretches: &[Stretch], closed_loop: bool) -> Vec<Part> {
    let last = run.len() - 1;
    let mut out = Vec::with_capacity(2 * stretches.len() + 1);
    // Where the previous part ended: point, index, and the line's direction there.
    let mut prev: (Point, usize, Option<Vec2>) = (run[0], 0, None);
    let mut first_dir = None;
    for s in stretches {
        let start = if s.a == 0 { run[0] } else { s.foot(run[s.a]) };
        let end = if s.b == last {
            run[last]
        } else {
            s.foot(run[s.b])
        };
        let dir = (end - start).normalize();
        if s.a > prev.1 {
            let mut points = vec![prev.0];
            points.extend_from_slice(&run[prev.1 + 1..s.a]);
            points.push(start);
            out.push(Part::Curve {
                points,
                line_ends: [prev.2, Some(dir)],
            });
        }
        out.push(Part::Line {
            start,
            end,
            points: run[s.a..=s.b].to_vec(),
        });
        first_dir = first_dir.or(Some(dir));
        prev = (end, s.b, Some(dir));
    }
    if prev.1 < last {
        let mut points = vec![prev.0];
        points.extend_from_slice(&run[prev.1 + 1..]);
        let end_dir = if closed_loop { first_dir } else { None };
        out.push(Part::Curve {
            points,
            line_ends: [prev.2, end_dir],
        });
    }
    out
}

impl<'a> Test<'a> {
    /// The test for a run's points (see the module documentation): `sigma` is the stroke's
    /// noise (σ), `tolerance` the contour's; the fair spline is fitted here, once for every
    /// setback tried. `None` where no fair spline is found.
    pub(super) fn of(
        points: &'a [Point],
        tolerance: f64,
        sigma: f64,
        closed_loop: bool,
    ) -> Option<Self> {
        // Exact samples have no noise: a floor that only rounding can pass.
        let sigma = sigma.max(1e-9 * bbox_diagonal(points));
        Some(Test {
            points,
            tolerance,
            sigma,
            bow: 0.0,
            kappa: fair_curvatures(points, tolerance)?,
            arc: arc_lengths(points),
            closed_loop,
        })
    }

    /// The test letting a stretch bow by up to `bow` root mean square (the drop of item 1 up
    /// to `bow² n` over `n` points): a hand's slow wobble bows a side drawn straight by a
    /// pixel or two, a bend that the χ² test, whose noise is the white noise of 15
    /// neighbours, finds in every long side. Item 3 still tells a large arc from a line.
    pub(super) fn allowing_bow(self, bow: f64) -> Self {
        Test { bow, ..self }
    }

    /// The straight stretches, each line ending `setback` radii before its curve
    /// ([`Test::trimmed`]).
    pub(super) fn stretches(&self, setback: f64) -> Vec<Stretch> {
        let (test, arc, n, tolerance) = (self, &self.arc, self.points.len(), self.tolerance);
        let mut out: Vec<Stretch> = Vec::new();
        let mut i = 0;
        while i + MIN_POINTS <= n {
            let mut b = test.longest_from(i);
            // A later start may run further (the first one is in a curve's tail): follow it
            // while it does.
            for _ in 0..8 {
                if b + 1 - i < MIN_POINTS {
                    break;
                }
                let (s, e) = test.longest_near(i, b);
                if (s, e) == (i, b) {
                    break;
                }
                (i, b) = (s, e);
            }
            let long_enough =
                b + 1 - i >= MIN_POINTS && arc[b] - arc[i] >= MIN_LENGTH_TOLERANCES * tolerance;
            if long_enough {
                let found = test.stretch(i, b).and_then(|s| {
                    let kappas = test.against_neighbours(&s)?;
                    test.trimmed(s, kappas, setback)
                });
                if let Some(s) = found {
                    out.push(s);
                    i = b + MIN_GAP;
                    continue;
                }
            }
            i += 1;
        }
        keep_room_at_ends(test, merge_collinear(test, out), n)
    }
}

/// Neighbouring stretches that are one (the longest window stops where noise, not a bend,
/// fails the test once) merged.
fn merge_collinear(test: &Test, found: Vec<Stretch>) -> Vec<Stretch> {
    let mut out: Vec<Stretch> = Vec::with_capacity(found.len());
    for s in found {
        if let Some(prev) = out.last_mut() {
            if let Some(both) = test.stretch(prev.a, s.b) {
                *prev = both;
                continue;
            }
        }
        out.push(s);
    }
    out
}

/// Stretches that stop a few points short of a run's end reach it (when still straight) or
/// leave it [`MIN_GAP`] points (a curve needs them); one that cannot is dropped.
fn keep_room_at_ends(test: &Test, mut out: Vec<Stretch>, n: usize) -> Vec<Stretch> {
    if let Some(first) = out.first().copied() {
        if first.a > 0 && first.a < MIN_GAP {
            match test.stretch(0, first.b) {
                Some(s) => out[0] = s,
                None => {
                    out.remove(0);
                }
            }
        }
    }
    if let Some(last) = out.last().copied() {
        let k = out.len() - 1;
        if last.b < n - 1 && last.b + MIN_GAP > n - 1 {
            match test.stretch(last.a, n - 1) {
                Some(s) => out[k] = s,
                None => {
                    out.pop();
                }
            }
        }
    }
    out
}

/// The straightness test of the module documentation, items 1 and 3, on a run's points.
pub(super) struct Test<'a> {
    pub(super) points: &'a [Point],
    tolerance: f64,
    sigma: f64,
    /// The root-mean-square bow item 1 lets pass whatever the noise ([`Test::allowing_bow`]).
    bow: f64,
    /// The fair spline's signed curvature at each point (item 3).
    kappa: Vec<f64>,
    /// Cumulative arc length at each point.
    arc: Vec<f64>,
    /// The points are a closed loop (the last is the first): neighbours go round.
    pub(super) closed_loop: bool,
}

impl Test<'_> {
    /// The last index `b` such that `a..=b` is straight (at least `a + 1`).
    fn longest_from(&self, a: usize) -> usize {
        let n = self.points.len();
        let mut good = (a + 1).min(n - 1);
        let mut step = MIN_POINTS;
        // Doubling while straight, then bisection between the last good and the first bad.
        let mut bad = loop {
            let b = good + step;
            if b >= n {
                if self.stretch(a, n - 1).is_some() {
                    return n - 1;
                }
                break n - 1;
            }
            if self.stretch(a, b).is_none() {
                break b;
            }
            good = b;
            step *= 2;
        };
        while bad - good > 1 {
            let mid = (good + bad) / 2;
            if self.stretch(a, mid).is_some() {
                good = mid;
            } else {
                bad = mid;
            }
        }
        good
    }

    /// The longest straight window starting at `a` or at up to 16 later points before `b`
    /// (`a..=b` is straight): a window that starts in the tail of a rounded corner passes
    /// the test but stops early, tilted; one that starts on the side runs along it.
    fn longest_near(&self, a: usize, b: usize) -> (usize, usize) {
        let step = ((b - a) / 16).max(1);
        (a..b)
            .step_by(step)
            .map(|s| (s, if s == a { b } else { self.longest_from(s) }))
            .max_by_key(|&(s, e)| (e - s, usize::MAX - s))
            .unwrap_or((a, b))
    }

    /// Points `a..=b` as a stretch, when they pass item 1.
    fn stretch(&self, a: usize, b: usize) -> Option<Stretch> {
        let pts = &self.points[a..=b];
        if pts.len() < 3 {
            return None;
        }
        let (centre, dir) = line_of(pts)?;
        let off = pts
            .iter()
            .map(|q| (*q - centre).cross(dir).abs())
            .fold(0.0, f64::max);
        if off > self.tolerance {
            return None;
        }
        let drop = bend(pts, centre, dir)?;
        let allowed =
            (BEND_CHI2 * self.sigma * self.sigma).max(self.bow * self.bow * pts.len() as f64);
        (drop <= allowed).then_some(Stretch { a, b, centre, dir })
    }

    /// Item 3: the curves on both sides bend the same way (the fair spline's curvature at
    /// its largest |κ| within half the stretch's length beyond each end has one sign: a
    /// straight between two bends of a rounded shape; between opposite bends the flank of an
    /// S or a wave, nearly straight as it may be, is not taken for a line), and its largest
    /// |κ| over the middle of the stretch (from 20 % to 80 % of its length) is at most
    /// [`FLAT_SHARE`] of the smaller of theirs. Returns those two largest |κ| (before,
    /// after); `None` where the stretch is not straight by this test.
    fn against_neighbours(&self, s: &Stretch) -> Option<[f64; 2]> {
        let (kappa, arc) = (&self.kappa, &self.arc);
        let length = arc[s.b] - arc[s.a];
        let (from, to) = (arc[s.a] + 0.2 * length, arc[s.b] - 0.2 * length);
        let inside = (s.a..=s.b)
            .filter(|&k| arc[k] >= from && arc[k] <= to)
            .map(|k| kappa[k].abs())
            .fold(0.0, f64::max);
        let before = self.bend_beyond(s.a, false, 0.5 * length)?;
        let after = self.bend_beyond(s.b, true, 0.5 * length)?;
        let same_way = before.signum() == after.signum();
        let (kb, ka) = (before.abs(), after.abs());
        // A hand's side (a bow allowed): its fair spline carries the corners' curvature a
        // little further in, and the wobble's.
        let share = if self.bow > 0.0 {
            HAND_FLAT_SHARE
        } else {
            FLAT_SHARE
        };
        (same_way && inside <= share * kb.min(ka)).then_some([kb, ka])
    }

    /// The fair spline's signed curvature where |κ| is largest within `reach` of point
    /// `from`, going forward or back (round a closed loop, whose last point is its first);
    /// `None` where fewer than three points lie there.
    fn bend_beyond(&self, from: usize, forward: bool, reach: f64) -> Option<f64> {
        let n = self.points.len();
        let step = |k: usize| -> Option<usize> {
            match (forward, self.closed_loop) {
                (true, _) if k + 1 < n => Some(k + 1),
                (true, true) => Some(1),
                (false, _) if k > 0 => Some(k - 1),
                (false, true) => Some(n - 2),
                _ => None,
            }
        };
        let (mut k, mut along, mut seen, mut best) = (from, 0.0, 0, 0.0f64);
        while let Some(next) = step(k) {
            along += (self.points[next] - self.points[k]).hypot();
            if along > reach || next == from {
                break;
            }
            k = next;
            seen += 1;
            if self.kappa[k].abs() > best.abs() {
                best = self.kappa[k];
            }
        }
        (seen >= 3).then_some(best)
    }

    /// The stretch with each end that meets a curve moved back along it by the length over
    /// which that curve, of curvature `κ`, stays within the noise of the line's tangent
    /// (`κ p² / 2 = 2σ`), half as much again (the test of item 1 lets a stretch run that far
    /// into the curve), and by `setback / κ` more: a curve that leaves a line with zero
    /// curvature needs room to reach the curvature of a drawn arc (a line that ends where
    /// the arc begins leaves its inflection-end piece the base angles of a circle, at the
    /// edge of its existence region); `None` when too little is left.
    fn trimmed(&self, s: Stretch, kappas: [f64; 2], setback: f64) -> Option<Stretch> {
        let arc = &self.arc;
        let reach = |k: f64| {
            if k > 0.0 {
                1.5 * (4.0 * self.sigma / k).sqrt() + setback / k
            } else {
                0.0
            }
        };
        let (from, to) = (arc[s.a] + reach(kappas[0]), arc[s.b] - reach(kappas[1]));
        let a = if s.a == 0 && !self.closed_loop {
            0
        } else {
            s.a + arc[s.a..=s.b].partition_point(|&x| x < from)
        };
        let last = self.points.len() - 1;
        let at_end = s.b == last && !self.closed_loop;
        let b = if at_end {
            last
        } else {
            (s.a + arc[s.a..=s.b].partition_point(|&x| x <= to))
                .saturating_sub(1)
                .max(a)
        };
        if b < a + MIN_POINTS {
            return None;
        }
        self.stretch(a, b)
    }
}

/// How much better a cubic explains the points than a line, in the line's frame: the drop
/// in the sum of squared residuals (normal offsets against the position along the line).
/// One pass gathers the power sums (positions scaled to [-1, 1]); each least-squares fit
/// explains `cᵀr` of the offsets' squares (`r` the moments of the offsets, `c` the fit's
/// coefficients), so the drop is the cubic's explained part less the line's, with no
/// residual sums to take apart.
fn bend(pts: &[Point], centre: Point, dir: Vec2) -> Option<f64> {
    let half = pts
        .iter()
        .fold(0.0f64, |m, q| m.max((*q - centre).dot(dir).abs()))
        .max(f64::MIN_POSITIVE);
    // x^0..x^6 and y x^0..y x^3.
    let (mut sx, mut sy) = ([0.0f64; 7], [0.0f64; 4]);
    for q in pts {
        let (x, y) = ((*q - centre).dot(dir) / half, (*q - centre).cross(dir));
        let mut p = 1.0;
        for (i, v) in sx.iter_mut().enumerate() {
            *v += p;
            if i < 4 {
                sy[i] += p * y;
            }
            p *= x;
        }
    }
    let line = explained::<2>(&sx, &sy)?;
    let cubic = explained::<4>(&sx, &sy)?;
    Some((cubic - line).max(0.0))
}

/// The part of the offsets' sum of squares that the least-squares polynomial with `K`
/// coefficients explains, from the power sums of [`bend`].
fn explained<const K: usize>(sx: &[f64; 7], sy: &[f64; 4]) -> Option<f64> {
    let m = nalgebra::SMatrix::<f64, K, K>::from_fn(|i, j| sx[i + j]);
    let r = nalgebra::SVector::<f64, K>::from_fn(|i, _| sy[i]);
    let c = m.cholesky()?.solve(&r);
    Some(c.dot(&r))
}

/// The least-squares line of the points: their centroid and the principal axis of their
/// scatter, pointing from the first point towards the last.
pub(super) fn line_of(pts: &[Point]) -> Option<(Point, Vec2)> {
    line_through(pts.iter().copied())
}

/// [`line_of`] for points given one by one (a window of a stroke by its indices).
pub(super) fn line_through(pts: impl Iterator<Item = Point> + Clone) -> Option<(Point, Vec2)> {
    let (c, sxx, sxy, syy) = scatter(pts.clone());
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let axis = Vec2::new(angle.cos(), angle.sin());
    let (first, last) = (pts.clone().next()?, pts.last()?);
    let dot = axis.dot(last - first);
    if dot == 0.0 || !dot.is_finite() {
        return None;
    }
    Some((c, if dot > 0.0 { axis } else { -axis }))
}

/// The centroid of the points and their scatter about it: (centroid, sxx, sxy, syy).
pub(super) fn scatter(pts: impl Iterator<Item = Point> + Clone) -> (Point, f64, f64, f64) {
    let (sum, m) = pts
        .clone()
        .fold((Vec2::ZERO, 0.0), |(a, m), q| (a + q.to_vec2(), m + 1.0));
    let c = (sum / m).to_point();
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for q in pts {
        let d = q - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    (c, sxx, sxy, syy)
}

/// The point of a loop (its last point its first) where the fair spline's |κ| is largest;
/// `None` where no fair spline is found.
pub(super) fn sharpest(points: &[Point], tolerance: f64) -> Option<usize> {
    let kappa = fair_curvatures(points, tolerance)?;
    (0..points.len() - 1).max_by(|&a, &b| kappa[a].abs().total_cmp(&kappa[b].abs()))
}

/// The signed curvature at each point of the smoothest spline within [`FAIR_SHARE`] of the tolerance (the
/// sketch's fair spline: it follows no noise), at the point's parameter; `None` where no
/// such spline is found.
fn fair_curvatures(points: &[Point], tolerance: f64) -> Option<Vec<f64>> {
    let fit = crate::bspline::smoothing_fit(points, FAIR_SHARE * tolerance).ok()?;
    let track = super::track::Track::new(&fit.spline).ok()?;
    // The fit drops consecutive duplicates: a repeated point takes its twin's parameter.
    let mut out = Vec::with_capacity(points.len());
    let mut j = 0;
    for (i, q) in points.iter().enumerate() {
        if i > 0 && *q != points[i - 1] {
            j += 1;
        }
        out.push(track.derivs(*fit.params.get(j)?).kappa());
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A stadium sampled every 2 units: straight sides 200 long, semicircles of radius
    /// 40, closed (the last point the first), starting in the middle of its right end.
    fn stadium() -> Vec<Point> {
        let mut v = Vec::new();
        let arc = |v: &mut Vec<Point>, cx: f64, a0: f64, a1: f64| {
            let n = ((a1 - a0).abs() * 40.0 / 2.0).ceil() as usize;
            for i in 0..n {
                let a = a0 + (a1 - a0) * i as f64 / n as f64;
                v.push(Point::new(cx + 40.0 * a.cos(), 40.0 * a.sin()));
            }
        };
        arc(&mut v, 200.0, 0.0, PI / 2.0);
        v.extend((0..100).map(|i| Point::new(200.0 - 2.0 * i as f64, 40.0)));
        arc(&mut v, 0.0, PI / 2.0, 1.5 * PI);
        v.extend((0..100).map(|i| Point::new(2.0 * i as f64, -40.0)));
        arc(&mut v, 200.0, 1.5 * PI, 2.0 * PI);
        v.push(v[0]);
        v
    }

    #[test]
    fn the_sides_of_a_stadium_are_straight_and_an_arc_is_not() {
        let pts = stadium();
        let found = Test::of(&pts, 0.5, 0.0, true).unwrap().stretches(0.15);
        assert_eq!(found.len(), 2, "{found:?}");
        // The top side runs from x = 200 to 0 (y = 40), the bottom one back; each stops
        // short of its semicircles.
        for (s, dir, y) in [(found[0], -1.0, 40.0), (found[1], 1.0, -40.0)] {
            assert!((s.dir.x - dir).abs() < 1e-9, "{s:?}");
            for q in [pts[s.a], pts[s.b]] {
                assert!(
                    (q.y - y).abs() < 1e-9 && q.x > -1e-9 && q.x < 200.0 + 1e-9,
                    "{q:?}"
                );
            }
            assert!((pts[s.a] - pts[s.b]).hypot() > 150.0, "{s:?}");
        }
        // A large arc, sampled exactly: no straight stretch however flat.
        let arc: Vec<Point> = (0..400)
            .map(|i| {
                let a = 0.3 + 0.6 * i as f64 / 399.0;
                Point::new(2000.0 * a.cos(), 2000.0 * a.sin())
            })
            .collect();
        assert!(Test::of(&arc, 1.0, 0.0, false)
            .unwrap()
            .stretches(0.15)
            .is_empty());
    }
}
