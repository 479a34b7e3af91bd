//! Rational B-spline curves (NURBS) in the plane: the form CAD systems import.
//!
//! [`Nurbs`] holds a degree, a clamped knot vector, control points and positive weights, and
//! evaluates by de Boor's algorithm on homogeneous coordinates. Rational Bézier curves and
//! the G2 piecewise splines of [`crate::approx`] are one (no resampling), so an exporter
//! needs only this one type.

use crate::bezier::RationalBezier;
use crate::error::{Error, Result};
use kurbo::Point;

/// A planar rational B-spline curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Nurbs {
    /// Polynomial degree p >= 1.
    pub degree: usize,
    /// Non-decreasing knots, `control_points.len() + degree + 1` of them, clamped
    /// (first and last values repeated p + 1 times).
    pub knots: Vec<f64>,
    /// Control points.
    pub control_points: Vec<Point>,
    /// One positive weight per control point.
    pub weights: Vec<f64>,
}

impl Nurbs {
    /// Check the invariants; errors name what is wrong.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        control_points: Vec<Point>,
        weights: Vec<f64>,
    ) -> Result<Nurbs> {
        let n = control_points.len();
        if degree == 0 || n < degree + 1 {
            return Err(Error::invalid(
                "degree",
                format!(
                    "degree {degree} needs at least {} control points",
                    degree + 1
                ),
            ));
        }
        if knots.len() != n + degree + 1 {
            return Err(Error::invalid(
                "knots",
                format!("need {} knots, got {}", n + degree + 1, knots.len()),
            ));
        }
        if knots.windows(2).any(|w| w[1] < w[0]) || knots.iter().any(|k| !k.is_finite()) {
            return Err(Error::invalid("knots", "must be finite and non-decreasing"));
        }
        let p = degree;
        if knots[..=p].iter().any(|k| *k != knots[0])
            || knots[n..].iter().any(|k| *k != knots[n + p])
            || knots[p] >= knots[n]
        {
            return Err(Error::invalid(
                "knots",
                "must be clamped with a non-empty range",
            ));
        }
        if weights.len() != n || weights.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(Error::invalid(
                "weights",
                "one finite positive weight per point",
            ));
        }
        if control_points.iter().any(|p| !p.is_finite()) {
            return Err(Error::invalid("control_points", "must be finite"));
        }
        Ok(Nurbs {
            degree,
            knots,
            control_points,
            weights,
        })
    }

    /// A rational Bézier curve as a one-span NURBS on [0, 1].
    pub fn from_bezier(c: &RationalBezier) -> Nurbs {
        let p = c.degree();
        let mut knots = vec![0.0; p + 1];
        knots.extend(vec![1.0; p + 1]);
        Nurbs {
            degree: p,
            knots,
            control_points: c.points().to_vec(),
            weights: c.weights().to_vec(),
        }
    }

    /// Rational Bézier curves of one degree joined end to end (each end point equal to the
    /// next start within 1e-9 of the size) as one NURBS: span i on [i, i+1], interior knots
    /// of multiplicity `degree`, each piece's weights scaled (which keeps its curve) so the
    /// shared control point has one weight.
    pub fn from_beziers(pieces: &[RationalBezier]) -> Result<Nurbs> {
        let breaks: Vec<f64> = (0..=pieces.len()).map(|i| i as f64).collect();
        Nurbs::from_beziers_at(pieces, &breaks)
    }

    /// [`Nurbs::from_beziers`] with span i on [`breaks[i]`, `breaks[i + 1]`] (increasing,
    /// one more than the pieces): for example the pieces' arc-length fractions.
    pub fn from_beziers_at(pieces: &[RationalBezier], breaks: &[f64]) -> Result<Nurbs> {
        let first = pieces
            .first()
            .ok_or_else(|| Error::invalid("pieces", "need at least one"))?;
        if breaks.len() != pieces.len() + 1
            || breaks
                .windows(2)
                .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
            || breaks.iter().any(|b| !b.is_finite())
        {
            return Err(Error::invalid(
                "breaks",
                "one more than the pieces, finite and increasing",
            ));
        }
        let p = first.degree();
        let mut control_points = vec![first.points()[0]];
        let mut weights = vec![first.weights()[0]];
        let mut knots = vec![breaks[0]; p + 1];
        let size = pieces
            .iter()
            .flat_map(|c| c.points().iter())
            .map(|q| q.to_vec2().hypot())
            .fold(0.0, f64::max)
            .max(1.0);
        for (i, c) in pieces.iter().enumerate() {
            if c.degree() != p {
                return Err(Error::invalid("pieces", "all pieces need the same degree"));
            }
            let last = *control_points.last().unwrap();
            if (c.points()[0] - last).hypot() > 1e-9 * size {
                return Err(Error::invalid(
                    format!("pieces[{i}]"),
                    "does not start where the previous piece ends",
                ));
            }
            let f = weights.last().unwrap() / c.weights()[0];
            control_points.extend_from_slice(&c.points()[1..]);
            weights.extend(c.weights()[1..].iter().map(|w| w * f));
            if i > 0 {
                knots.extend(vec![breaks[i]; p]);
            }
        }
        knots.extend(vec![breaks[pieces.len()]; p + 1]);
        Nurbs::new(p, knots, control_points, weights)
    }

    /// Parameter range [first knot, last knot].
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// The point at parameter `u` (clamped to the domain), by de Boor's algorithm.
    pub fn eval(&self, u: f64) -> Point {
        crate::bspline::de_boor(
            self.degree,
            &self.knots,
            &self.control_points,
            Some(&self.weights),
            u,
        )
    }

    /// The same curve with the knot `u` (strictly inside the domain) inserted once (Boehm's
    /// algorithm on the homogeneous control points).
    pub fn insert_knot(&self, u: f64) -> Nurbs {
        let p = self.degree;
        let n = self.control_points.len();
        // The span k with knots[k] <= u < knots[k + 1], k in p..n.
        let k = (p..n).rev().find(|&k| self.knots[k] <= u).unwrap_or(p);
        let hom = |i: usize| {
            let w = self.weights[i];
            (
                self.control_points[i].x * w,
                self.control_points[i].y * w,
                w,
            )
        };
        let mut pts = Vec::with_capacity(n + 1);
        let mut ws = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let (x, y, w) = if i + p <= k {
                hom(i)
            } else if i > k {
                hom(i - 1)
            } else {
                let a = (u - self.knots[i]) / (self.knots[i + p] - self.knots[i]);
                let (x0, y0, w0) = hom(i - 1);
                let (x1, y1, w1) = hom(i);
                (
                    (1.0 - a) * x0 + a * x1,
                    (1.0 - a) * y0 + a * y1,
                    (1.0 - a) * w0 + a * w1,
                )
            };
            pts.push(Point::new(x / w, y / w));
            ws.push(w);
        }
        let mut knots = self.knots.clone();
        knots.insert(k + 1, u);
        Nurbs {
            degree: p,
            knots,
            control_points: pts,
            weights: ws,
        }
    }

    /// The Bézier spans (between distinct knots) as rational Bézier curves: interior knots
    /// are first raised to multiplicity `degree` by knot insertion (the curve is unchanged).
    /// `None` only if a span's control points do not form a valid curve.
    pub fn bezier_spans(&self) -> Option<Vec<RationalBezier>> {
        let p = self.degree;
        let n = self.control_points.len();
        let (lo, hi) = (self.knots[p], self.knots[n]);
        let mut c = self.clone();
        let mut i = p + 1;
        while i < c.knots.len() && c.knots[i] < hi {
            let u = c.knots[i];
            let mult = c.knots.iter().filter(|k| **k == u).count();
            if u > lo && mult < p {
                c = c.insert_knot(u);
                continue;
            }
            i += 1;
        }
        c.bezier_spans_of_full_multiplicity()
    }

    fn bezier_spans_of_full_multiplicity(&self) -> Option<Vec<RationalBezier>> {
        let p = self.degree;
        let n = self.control_points.len();
        if (n - 1) % p != 0 {
            return None;
        }
        let spans = (n - 1) / p;
        for i in 1..spans {
            let at = p + 1 + (i - 1) * p;
            if self.knots[at..at + p].iter().any(|k| *k != self.knots[at]) {
                return None;
            }
        }
        (0..spans)
            .map(|i| {
                RationalBezier::new(
                    self.control_points[i * p..=(i + 1) * p].to_vec(),
                    self.weights[i * p..=(i + 1) * p].to_vec(),
                )
                .ok()
            })
            .collect()
    }

    /// The diagonal of the control points' bounding box: the size of the curve for
    /// tolerances.
    pub fn size(&self) -> f64 {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for q in &self.control_points {
            x0 = x0.min(q.x);
            x1 = x1.max(q.x);
            y0 = y0.min(q.y);
            y1 = y1.max(q.y);
        }
        (x1 - x0).hypot(y1 - y0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlanarCurve;

    /// A clamped spline with simple interior knots (degree 2, 3 and 5, rational) splits into
    /// Bézier spans that trace the same curve.
    #[test]
    fn simple_knots_split_into_the_same_curve() {
        for (p, n) in [(2usize, 6usize), (3, 7), (5, 9)] {
            let pts: Vec<Point> = (0..n)
                .map(|i| Point::new(i as f64, ((i * 7) % 5) as f64 - 2.0))
                .collect();
            let w: Vec<f64> = (0..n).map(|i| 1.0 + 0.4 * ((i * 3) % 4) as f64).collect();
            let inner = n - p - 1;
            let mut knots = vec![0.0; p + 1];
            // Uneven interior knots.
            knots.extend((1..=inner).map(|i| (i as f64 / (inner + 1) as f64).powf(1.3)));
            knots.extend(vec![1.0; p + 1]);
            let c = Nurbs::new(p, knots.clone(), pts, w).unwrap();
            let spans = c.bezier_spans().expect("spans");
            assert_eq!(spans.len(), inner + 1, "degree {p}");
            let mut breaks = vec![0.0];
            breaks.extend_from_slice(&knots[p + 1..p + 1 + inner]);
            breaks.push(1.0);
            for (s, b) in spans.iter().zip(breaks.windows(2)) {
                for j in 0..=10 {
                    let t = j as f64 / 10.0;
                    let u = b[0] + (b[1] - b[0]) * t;
                    let d = (s.eval(t) - c.eval(u)).hypot();
                    assert!(d < 1e-12, "degree {p}: {d}");
                }
            }
        }
    }

    #[test]
    fn beziers_join_at_given_breaks() {
        // Two quarter circles (exact rational quadratics) joined on [0, 0.3] and [0.3, 1]:
        // every point of the joined spline lies on the unit circle, the interior knot
        // sits at the break, and bad breaks are refused.
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let q1 = RationalBezier::new(
            vec![
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            vec![1.0, w, 1.0],
        )
        .unwrap();
        let q2 = RationalBezier::new(
            vec![
                Point::new(0.0, 1.0),
                Point::new(-1.0, 1.0),
                Point::new(-1.0, 0.0),
            ],
            vec![2.0, 2.0 * w, 2.0],
        )
        .unwrap();
        let n = Nurbs::from_beziers_at(&[q1.clone(), q2.clone()], &[0.0, 0.3, 1.0]).unwrap();
        assert_eq!(n.knots, vec![0.0, 0.0, 0.0, 0.3, 0.3, 1.0, 1.0, 1.0]);
        assert_eq!(n.weights, vec![1.0, w, 1.0, w, 1.0]);
        for i in 0..=50 {
            let r = n.eval(i as f64 / 50.0).to_vec2().hypot();
            assert!((r - 1.0).abs() < 1e-15, "{r}");
        }
        assert!((n.eval(0.3) - Point::new(0.0, 1.0)).hypot() < 1e-15);
        for bad in [&[0.0, 1.0][..], &[0.0, 0.5, 0.5], &[0.0, f64::NAN, 1.0]] {
            assert!(Nurbs::from_beziers_at(&[q1.clone(), q2.clone()], bad).is_err());
        }
    }

    #[test]
    fn bezier_round_trip_and_validation() {
        let c = RationalBezier::new(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(3.0, 2.0),
                Point::new(4.0, 0.0),
            ],
            vec![1.0, 0.7, 1.3, 0.9],
        )
        .unwrap();
        let n = Nurbs::from_bezier(&c);
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            assert!((n.eval(t) - c.eval(t)).hypot() < 1e-14);
        }
        assert_eq!(n.bezier_spans().unwrap()[0], c);
        assert!(Nurbs::new(3, vec![0.0; 7], n.control_points.clone(), n.weights.clone()).is_err());
        assert!(Nurbs::new(
            3,
            n.knots.clone(),
            n.control_points.clone(),
            vec![1.0, -1.0, 1.0, 1.0]
        )
        .is_err());
        assert!(Nurbs::new(
            3,
            n.knots.clone(),
            n.control_points.clone(),
            n.weights.clone()
        )
        .is_ok());
    }
}
