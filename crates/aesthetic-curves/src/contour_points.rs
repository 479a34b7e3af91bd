//! A font's contour as a list of points (the UFO's and fontTools' point-pen structure:
//! on-curve points typed `move`, `line`, `curve` or `qcurve`, off-curve points between
//! them) read into segments of lines and cubics, each control point with its index in the
//! list, so that a repair can be written back point for point. `aecurve fix` reads norad's
//! points through it, and the Python package ufoLib2's and defcon's.

use crate::{Error, Point, Result};

/// A point's kind in the list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointKind {
    /// The start of an open contour.
    Move,
    /// The end of a line.
    Line,
    /// The end of a cubic (after two off-curve points).
    Curve,
    /// The end of a quadratic (TrueType).
    QCurve,
    /// A control point.
    OffCurve,
}

/// One point of the list.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ListPoint {
    /// Where it is.
    pub at: Point,
    /// Its kind.
    pub kind: PointKind,
    /// The designer's smooth flag (on-curve points).
    pub smooth: bool,
}

/// The segments of a contour with the indices of their points.
#[derive(Clone, Debug, PartialEq)]
pub struct IndexedContour {
    /// Control points per segment (2: a line, 4: a cubic).
    pub segments: Vec<Vec<Point>>,
    /// For each control point, its index in the list.
    pub indices: Vec<Vec<usize>>,
    /// Closed (no `move` point).
    pub closed: bool,
    /// Per join (after segment j): the smooth flag of its on-curve point.
    pub smooth: Vec<bool>,
}

/// Why a contour is not one of lines and cubics.
fn not_cubic(why: impl Into<String>) -> Error {
    Error::invalid("contour", why)
}

/// Read a point list: an open contour from its `move`, a closed one from its first
/// on-curve point. Errors name why it is not a contour of lines and cubics (quadratics,
/// off-curve points only, three or more off-curve points in a row, a dangling end).
pub fn index_contour(points: &[ListPoint]) -> Result<IndexedContour> {
    use PointKind as K;
    let n = points.len();
    if n < 2 {
        return Err(not_cubic("fewer than two points"));
    }
    let open = points[0].kind == K::Move;
    let start = if open {
        0
    } else {
        points
            .iter()
            .position(|q| q.kind != K::OffCurve)
            .ok_or_else(|| {
                not_cubic("off-curve points only (implied quadratics): not a cubic outline")
            })?
    };
    let at = |k: usize| (start + k) % n;
    let mut out = IndexedContour {
        segments: Vec::new(),
        indices: Vec::new(),
        closed: !open,
        smooth: Vec::new(),
    };
    let mut current = vec![at(0)];
    let steps = if open { n - 1 } else { n };
    for k in 1..=steps {
        let i = at(k);
        let q = &points[i];
        current.push(i);
        match q.kind {
            K::OffCurve => continue,
            K::QCurve => {
                return Err(not_cubic(
                    "a quadratic (qcurve) segment: fix works on cubic outlines",
                ))
            }
            _ => {}
        }
        match current.len() {
            2 | 4 => {}
            3 => {
                return Err(not_cubic(
                    "a curve with one off-curve point (a quadratic): fix works on cubic outlines",
                ))
            }
            m => {
                return Err(not_cubic(format!(
                    "a curve point after {} off-curve points (at most 2)",
                    m - 2
                )))
            }
        }
        out.segments
            .push(current.iter().map(|&j| points[j].at).collect());
        out.indices.push(std::mem::replace(&mut current, vec![i]));
        out.smooth.push(q.smooth);
    }
    if current.len() > 1 {
        return Err(not_cubic(
            "off-curve points after the last on-curve point of an open contour",
        ));
    }
    // An open contour has no join after its last segment.
    if open {
        out.smooth.pop();
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: f64, y: f64, kind: PointKind) -> ListPoint {
        ListPoint {
            at: Point::new(x, y),
            kind,
            smooth: kind == PointKind::Curve,
        }
    }

    #[test]
    fn a_closed_contour_starts_at_its_first_on_curve_point_and_quadratics_are_named() {
        use PointKind::{Curve, Line, OffCurve, QCurve};
        // Off-curve points first: the contour starts at index 2.
        let pts = [
            pt(0.0, 10.0, OffCurve),
            pt(5.0, 12.0, OffCurve),
            pt(10.0, 10.0, Curve),
            pt(10.0, 0.0, Line),
            pt(0.0, 0.0, Line),
        ];
        let c = index_contour(&pts).unwrap();
        assert!(c.closed);
        assert_eq!(c.indices, vec![vec![2, 3], vec![3, 4], vec![4, 0, 1, 2]]);
        assert_eq!(c.segments[2][0], Point::new(0.0, 0.0));
        assert_eq!(c.smooth, vec![false, false, true]);
        let q = [
            pt(0.0, 0.0, QCurve),
            pt(1.0, 0.0, OffCurve),
            pt(1.0, 1.0, QCurve),
        ];
        assert!(index_contour(&q)
            .unwrap_err()
            .to_string()
            .contains("quadratic"));
        let off = [pt(0.0, 0.0, OffCurve), pt(1.0, 0.0, OffCurve)];
        assert!(index_contour(&off)
            .unwrap_err()
            .to_string()
            .contains("off-curve points only"));
        let open = [
            pt(0.0, 0.0, PointKind::Move),
            pt(1.0, 0.0, Line),
            pt(2.0, 0.0, OffCurve),
        ];
        assert!(index_contour(&open)
            .unwrap_err()
            .to_string()
            .contains("after the last"));
    }
}
