//! A Bézier curve, polynomial or rational, as a request or a command line gives it (the
//! protocol's `bezier.curvature_monotone`, `aecurve monotone`, `aecurve lcg --bezier`, the
//! plots).

use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::{Bezier, Error, Point, RationalBezier};

/// A polynomial or rational Bézier curve.
pub enum AnyBezier {
    /// Polynomial.
    Poly(Bezier),
    /// Rational.
    Rational(RationalBezier),
}

impl AnyBezier {
    /// From control points and optional weights.
    pub fn new(points: Vec<Point>, weights: Option<Vec<f64>>) -> Result<Self, Error> {
        Ok(match weights {
            Some(w) => AnyBezier::Rational(RationalBezier::new(points, w)?),
            None => AnyBezier::Poly(Bezier::new(points)?),
        })
    }
    /// The curve as the monotonicity trait object.
    pub fn as_monotone(&self) -> &dyn CurvatureMonotone {
        match self {
            AnyBezier::Poly(b) => b,
            AnyBezier::Rational(r) => r,
        }
    }
    /// The curve as the library's curve trait object.
    pub fn as_curve(&self) -> &dyn aesthetic_curves::Curve {
        match self {
            AnyBezier::Poly(b) => b,
            AnyBezier::Rational(r) => r,
        }
    }
    /// Signed curvature at t.
    pub fn kappa(&self, t: f64) -> f64 {
        self.as_monotone().kappa(t)
    }
    /// Point at t.
    pub fn eval(&self, t: f64) -> Point {
        self.as_monotone().eval(t)
    }
}
