//! Cubic Bézier paths (kurbo's [`BezPath`]) within an accuracy of the curves that are not
//! polynomial: log-aesthetic segments, inflection-end segments and rational Béziers (the
//! polynomial ones convert exactly: [`crate::Bezier::to_bezpath`]).
//!
//! **Algorithm.** kurbo's curve fitting ([`kurbo::fit_to_bezpath`]: each piece a cubic that
//! matches the source's area and moment, split where it is off by more than the accuracy)
//! over a parameterisation of the source: turning angle for a LAC segment, arc length for an
//! inflection-end segment (whose radius of curvature is infinite at the inflection), t for a
//! rational Bézier.
//!
//! **Contract.** The path starts and ends at the curve's ends and keeps its end tangents; its
//! distance from the curve is within `accuracy` as kurbo measures it (at sample points of
//! every piece); `tests` check it against 2,000 points of the curve. `accuracy` must be
//! positive, and at least 1e-9 of the curve's chord (finer asks f64 for more than it
//! holds): else [`Error::InvalidInput`]. A curve that cannot be evaluated (a segment too
//! extreme for f64) is an error, never a path of NaN.

use crate::bezier::{PlanarCurve, RationalBezier};
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment};
use kurbo::{fit_to_bezpath, BezPath, CurveFitSample, ParamCurveFit, Point, Shape, Vec2};
use std::ops::Range;

/// A curve given by its point and derivative at t in [0, 1] (evaluations checked beforehand).
struct Sampled<F: Fn(f64) -> Result<(Point, Vec2)>>(F);

impl<F: Fn(f64) -> Result<(Point, Vec2)>> ParamCurveFit for Sampled<F> {
    fn sample_pt_tangent(&self, t: f64, _sign: f64) -> CurveFitSample {
        let (p, tangent) = self.sample_pt_deriv(t);
        CurveFitSample { p, tangent }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        // Checked at 65 points before fitting; a failure in between gives NaN, which the
        // final check of the path turns into an error.
        (self.0)(t.clamp(0.0, 1.0)).unwrap_or((Point::new(f64::NAN, f64::NAN), Vec2::ZERO))
    }

    fn break_cusp(&self, _range: Range<f64>) -> Option<f64> {
        // The curves here are regular inside: no cusps or corners.
        None
    }
}

/// Fit `eval` (point and derivative at t in [0, 1]) within `accuracy`.
fn fit(eval: impl Fn(f64) -> Result<(Point, Vec2)>, accuracy: f64) -> Result<BezPath> {
    let (a, _) = eval(0.0)?;
    let (b, _) = eval(1.0)?;
    let size = (b - a).hypot().max(
        // A closed or nearly closed curve: its extent instead of the chord.
        (0..=16)
            .map(|i| eval(i as f64 / 16.0).map(|(p, _)| (p - a).hypot()))
            .try_fold(0.0f64, |m, d| d.map(|d| m.max(d)))?,
    );
    Error::check_positive("accuracy", accuracy)?;
    if accuracy < 1e-9 * size {
        return Err(Error::invalid(
            "accuracy",
            format!(
                "{accuracy:e} is below 1e-9 of the curve's size ({size:e}): f64 cannot hold it"
            ),
        ));
    }
    for i in 0..=64 {
        let (p, d) = eval(i as f64 / 64.0)?;
        if !(p.is_finite() && d.is_finite()) {
            return Err(Error::NoConvergence(
                "the curve cannot be evaluated in f64 everywhere".into(),
            ));
        }
    }
    let path = fit_to_bezpath(&Sampled(eval), accuracy);
    let finite = path.segments().all(|seg| seg.bounding_box().is_finite());
    if path.elements().is_empty() || !finite {
        return Err(Error::NoConvergence(
            "the curve fit produced no finite path".into(),
        ));
    }
    Ok(path)
}

/// Cubic Béziers within `accuracy` of a curve with [`PlanarCurve`] derivatives on [0, 1].
pub(crate) fn fit_planar(c: &impl PlanarCurve, accuracy: f64) -> Result<BezPath> {
    fit(
        |t| {
            let d = c.derivs(t);
            Ok((d.p, d.d1))
        },
        accuracy,
    )
}

impl LacSegment {
    /// Cubic Béziers within `accuracy` of this segment, from `control[0]` to `control[2]`
    /// (module documentation: [`crate::bezpath`]).
    pub fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
        let td = self.theta_d;
        fit(
            |t| {
                let at = self.eval_turning(&[t * td])?;
                Ok((at.points[0], at.derivative(0) * td))
            },
            accuracy,
        )
    }
}

impl LacInflectionSegment {
    /// Cubic Béziers within `accuracy` of this segment, from the inflection end `control[0]`
    /// to `control[2]` (module documentation: [`crate::bezpath`]).
    pub fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
        // Arc length: the standard form has θ = s^q, q = (α-1)/α, so s/L = t gives
        // τ = θ_d t^q and dP/dt = L T.
        let q = (self.alpha - 1.0) / self.alpha;
        let len = self.arc_length();
        let td = self.theta_d;
        fit(
            |t| {
                let at = self.eval_turning(&[td * t.powf(q)])?;
                Ok((at.points[0], at.tangents[0] * len))
            },
            accuracy,
        )
    }
}

impl RationalBezier {
    /// Cubic Béziers within `accuracy` of this curve (module documentation:
    /// [`crate::bezpath`]).
    pub fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
        fit_planar(self, accuracy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurveNearest, PathSeg};

    /// The largest distance from `pts` to the path.
    fn deviation(path: &BezPath, pts: &[Point]) -> f64 {
        let segs: Vec<PathSeg> = path.segments().collect();
        pts.iter()
            .map(|p| {
                segs.iter()
                    .map(|s| s.nearest(*p, 1e-12).distance_sq)
                    .fold(f64::INFINITY, f64::min)
                    .sqrt()
            })
            .fold(0.0, f64::max)
    }

    fn ends(path: &BezPath) -> (Point, Point) {
        let segs: Vec<PathSeg> = path.segments().collect();
        use kurbo::ParamCurve;
        (segs[0].start(), segs[segs.len() - 1].end())
    }

    #[test]
    fn lac_segments_within_the_accuracy_everywhere() {
        let p = Point::new;
        let tri = [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)];
        for alpha in [-2.0, -1.0, 0.0, 0.5, 1.0, 2.0, 4.0] {
            let seg = LacSegment::new(alpha, tri).unwrap();
            let taus: Vec<f64> = (0..2000).map(|i| seg.theta_d * i as f64 / 1999.0).collect();
            let pts = seg.eval_turning(&taus).unwrap().points;
            for acc in [1e-2, 1e-4, 1e-7] {
                let path = seg.to_bezpath(acc).unwrap();
                let dev = deviation(&path, &pts);
                assert!(dev <= 1.5 * acc, "alpha {alpha} accuracy {acc}: {dev:e}");
                let (a, b) = ends(&path);
                assert!((a - tri[0]).hypot() < 1e-9 && (b - tri[2]).hypot() < 1e-9);
            }
            // Finer asks for more pieces.
            let coarse = seg.to_bezpath(1e-2).unwrap().segments().count();
            let fine = seg.to_bezpath(1e-7).unwrap().segments().count();
            assert!(fine > coarse, "alpha {alpha}: {coarse} vs {fine}");
        }
    }

    #[test]
    fn segments_near_their_limit_too() {
        // 1e-3 rad below θ_lim: the radius of curvature nearly vanishes at one end (α = 2) or
        // the curve nearly reaches its inflection (α = -1).
        for alpha in [-1.0, 2.0] {
            let td = std::f64::consts::FRAC_PI_2;
            let phi = LacSegment::theta_lim(alpha, td).unwrap() - 1e-3;
            let d = phi.sin() / (td - phi).sin();
            let end = Point::new(1.0 + d * td.cos(), d * td.sin());
            let seg =
                LacSegment::new(alpha, [Point::new(0.0, 0.0), Point::new(1.0, 0.0), end]).unwrap();
            let taus: Vec<f64> = (0..2000).map(|i| seg.theta_d * i as f64 / 1999.0).collect();
            let pts = seg.eval_turning(&taus).unwrap().points;
            let path = seg.to_bezpath(1e-6).unwrap();
            let dev = deviation(&path, &pts);
            assert!(dev <= 1.5e-6, "alpha {alpha}: {dev:e}");
        }
    }

    #[test]
    fn inflection_segments_and_rational_curves_too() {
        let p = Point::new;
        let inf = LacInflectionSegment::new([p(0.0, 0.0), p(5.0, 0.0), p(7.0, 4.0)]).unwrap();
        let taus: Vec<f64> = (0..2000).map(|i| inf.theta_d * i as f64 / 1999.0).collect();
        let pts = inf.eval_turning(&taus).unwrap().points;
        let path = inf.to_bezpath(1e-5).unwrap();
        assert!(deviation(&path, &pts) <= 1.5e-5);
        // A quarter circle as a rational quadratic: every point of the path within the
        // accuracy of the unit circle (an independent reference).
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let arc = RationalBezier::new(
            vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
            vec![1.0, s, 1.0],
        )
        .unwrap();
        let path = arc.to_bezpath(1e-6).unwrap();
        for seg in path.segments() {
            for i in 0..=100 {
                let r = kurbo::ParamCurve::eval(&seg, i as f64 / 100.0)
                    .to_vec2()
                    .hypot();
                assert!((r - 1.0).abs() <= 1.5e-6, "{r}");
            }
        }
    }

    #[test]
    fn bad_accuracy_is_refused() {
        let p = Point::new;
        let seg = LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)]).unwrap();
        for acc in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-12] {
            assert!(
                matches!(seg.to_bezpath(acc), Err(Error::InvalidInput { .. })),
                "{acc}"
            );
        }
    }
}
