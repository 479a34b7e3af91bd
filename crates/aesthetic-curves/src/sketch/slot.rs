//! A piece's place on the fair spline (a slot): its parameter range, what ends it, its α,
//! and the control triangle of its end points and tangents.

use super::track::Track;
use crate::lcg::{fit_line, lcg_point};
use kurbo::{Point, Vec2};

/// What ends a piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Cut {
    End,
    Inflection,
    /// An end of the curve that joins a line ([`super::SketchOptions::line_ends`]): zero
    /// curvature like an inflection, and the piece there must be an inflection-end one.
    Line,
    /// A curvature maximum of precise input: a feature of the data, never merged across.
    Peak,
    Other,
}

impl Cut {
    /// Zero curvature there: an inflection or a line's end.
    pub(super) fn zero(self) -> bool {
        matches!(self, Cut::Inflection | Cut::Line)
    }
}

/// A piece's place on the B-spline, with its end tangents (unit vectors).
#[derive(Clone, Debug)]
pub(super) struct Slot {
    pub(super) ua: f64,
    pub(super) ub: f64,
    pub(super) cut_a: Cut,
    pub(super) cut_b: Cut,
    /// α of the piece: least squares against the input points, or the B-spline's LCG
    /// slope where that fit has not run or found no segment.
    pub(super) alpha: Option<f64>,
    /// Whether the least-squares fit of α ran.
    pub(super) fitted: bool,
    /// Tangent at the curve's start or end fitted with α (end slots only): replaces the
    /// spline's there.
    pub(super) dir_a: Option<Vec2>,
    /// As `dir_a`, at the slot's end.
    pub(super) dir_b: Option<Vec2>,
}

/// The slot over `a..b` with the cuts given, its α from the LCG (not fitted yet).
pub(super) fn slot(track: &Track, a: (f64, Cut), b: (f64, Cut)) -> Slot {
    Slot {
        ua: a.0,
        ub: b.0,
        cut_a: a.1,
        cut_b: b.1,
        alpha: lcg_alpha(track, a.0, b.0),
        fitted: false,
        dir_a: None,
        dir_b: None,
    }
}

/// α of the B-spline over [ua, ub] from the least-squares line of its LCG; `None` where the
/// curvature barely varies.
pub(super) fn lcg_alpha(track: &Track, ua: f64, ub: f64) -> Option<f64> {
    let n = 64;
    let mut graph = Vec::with_capacity(n);
    let (mut kmin, mut kmax) = (f64::INFINITY, 0.0f64);
    for i in 0..n {
        let u = ua + (ub - ua) * (i as f64 + 0.5) / n as f64;
        let d = track.derivs(u);
        let k = d.kappa().abs();
        kmin = kmin.min(k);
        kmax = kmax.max(k);
        if let Some(p) = lcg_point(d.kappa(), d.dkappa_ds()) {
            graph.push(p);
        }
    }
    if kmax.is_nan() || kmax <= 0.0 || (kmax - kmin) < 0.01 * kmax {
        return None;
    }
    fit_line(graph).ok().map(|f| f.alpha.clamp(-5.0, 5.0))
}

/// The curve's end points: the first and last input points.
pub(super) type EndPoints = (Point, Point);

/// Where slot `s` starts and ends: on the track, or at the curve's end points.
pub(super) fn slot_ends(track: &Track, s: &Slot, ends: EndPoints) -> (Point, Point) {
    let a = if s.cut_a == Cut::End || s.ua <= track.breaks[0] {
        ends.0
    } else {
        track.point(s.ua)
    };
    let b = if s.cut_b == Cut::End || s.ub >= track.breaks[track.breaks.len() - 1] {
        ends.1
    } else {
        track.point(s.ub)
    };
    (a, b)
}

/// The distance from `q` to the segment from `a` to `b` (kurbo's nearest point on a line;
/// a zero-length segment is its point).
pub(super) fn segment_distance(q: Point, a: Point, b: Point) -> f64 {
    use kurbo::ParamCurveNearest;
    kurbo::Line::new(a, b).nearest(q, 0.0).distance_sq.sqrt()
}

impl Slot {
    /// One of its ends joins a line ([`Cut::Line`]).
    pub(super) fn at_line(&self) -> bool {
        self.cut_a == Cut::Line || self.cut_b == Cut::Line
    }
}

/// The control triangle of a piece from its end points and unit end tangents; `None` when
/// the tangent lines do not meet ahead of the start and behind the end.
pub(super) fn triangle(pa: Point, da: Vec2, pb: Point, db: Vec2) -> Option<[Point; 3]> {
    let den = da.cross(db);
    if den.abs() < 1e-12 {
        return None;
    }
    let s = (pb - pa).cross(db) / den;
    // Apex = pb + t' db with t' = (pb - pa) x da / den, which must be behind pb.
    let t = -(pb - pa).cross(da) / den;
    if !(s > 0.0 && t > 0.0) {
        return None;
    }
    Some([pa, pa + da * s, pb])
}

/// `v` turned by `a` radians.
pub(super) fn rotate(v: Vec2, a: f64) -> Vec2 {
    let (s, c) = a.sin_cos();
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_needs_tangents_that_meet_ahead() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(10.0, 0.0));
        let up = Vec2::from_angle(0.5);
        let down = Vec2::from_angle(-0.5);
        let t = triangle(a, up, b, down).expect("the tangents meet above the chord");
        assert!(
            (t[1] - Point::new(5.0, 5.0 * 0.5f64.tan())).hypot() < 1e-12,
            "{t:?}"
        );
        assert!(triangle(a, up, b, up).is_none(), "parallel tangents");
        assert!(triangle(a, up, b, -down).is_none(), "apex behind the end");
    }
}
