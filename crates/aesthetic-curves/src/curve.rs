//! The one interface of the library's curves: [`Curve`], implemented by polynomial and
//! rational Béziers, NURBS, log-aesthetic segments (with and without an inflection end), the
//! pseudo-elastic spline and a sketch fit.
//!
//! Every implementation answers the same questions with the same names: where the curve
//! starts and ends ([`Curve::ends`]), its signed curvature there
//! ([`Curve::end_curvatures`]), its arc length ([`Curve::arc_length`]), the point, first and
//! second derivatives, signed curvature and dκ/ds at a value of its parameter
//! ([`Curve::at`] over [`Curve::domain`]: t for a Bézier, the arc length for a
//! log-aesthetic segment, piece index plus the piece's own parameter for pieces), points with unit
//! tangent and signed curvature along it ([`Curve::curve_points`]: what a curvature comb or
//! a curvature plot draws), cubic Béziers within an accuracy ([`Curve::to_bezpath`]), and
//! one NURBS for CAD, exact where the curve is rational and within an accuracy otherwise
//! ([`Curve::to_nurbs`]).
//! A piecewise curve (NURBS, spline, sketch) answers for all its pieces in order.
//!
//! Signed curvature is positive where the curve turns counter-clockwise (kurbo's has the
//! opposite sign). A point where the parameterisation stops (a zero first derivative, as
//! at a Bézier whose first two control points coincide) takes its tangent and curvature
//! from 1e-7 inside: the limit along the curve.

use crate::bezier::{Bezier, Derivs, PlanarCurve, RationalBezier};
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment};
use crate::nurbs::Nurbs;
use crate::pseudo_spline::PseudoSpline;
use crate::quadrature::{integrate, QuadOptions};
use crate::sketch::Sketch;
use kurbo::{BezPath, Point, Vec2};

/// A point of a curve with its unit tangent and signed curvature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// The point.
    pub p: Point,
    /// The unit tangent, in the direction of travel.
    pub tangent: Vec2,
    /// Signed curvature (positive: turning counter-clockwise).
    pub kappa: f64,
}

/// A curve at one value of its parameter ([`Curve::at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveEval {
    /// The point.
    pub p: Point,
    /// First derivative with respect to the curve's parameter.
    pub d1: Vec2,
    /// Second derivative.
    pub d2: Vec2,
    /// Signed curvature (positive: turning counter-clockwise); where the parameterisation
    /// stops (a zero first derivative), the limit from 1e-7 inside.
    pub kappa: f64,
    /// The derivative of the curvature in arc length (the same limit).
    pub dkappa_ds: f64,
}

impl CurvePoint {
    /// The unit left normal (the tangent turned by +90°): where the curve bends for κ > 0.
    pub fn normal(&self) -> Vec2 {
        self.tangent.turn_90()
    }
}

/// The interface every curve type of the library implements (module documentation).
pub trait Curve {
    /// The start and end points (an error only for a [`Pieces`] without pieces).
    fn ends(&self) -> Result<(Point, Point)>;
    /// Signed curvature at the start and at the end.
    fn end_curvatures(&self) -> Result<(f64, f64)>;
    /// The arc length (to about 1e-14 of itself, or as the type states).
    fn arc_length(&self) -> Result<f64>;
    /// `n >= 2` points per piece, from the start to the end, evenly spaced in each piece's
    /// own parameter (turning angle for log-aesthetic segments, t for Béziers); the shared
    /// end of consecutive pieces appears once.
    fn curve_points(&self, n: usize) -> Result<Vec<CurvePoint>>;
    /// Cubic Béziers within `accuracy` of the curve (exact for polynomial pieces of degree 3
    /// or less).
    fn to_bezpath(&self, accuracy: f64) -> Result<BezPath>;
    /// The interval of the curve's parameter ([`Curve::at`]): [0, 1] for a Bézier curve,
    /// the arc length [0, L] for a log-aesthetic segment (from `control[0]`), [0, n] for
    /// n pieces (piece i on [i, i + 1], in its own parameter scaled to unit length).
    fn domain(&self) -> Result<(f64, f64)>;
    /// The curve at parameter `u` (finite; clamped into [`Curve::domain`]): point, first and
    /// second derivative, signed curvature and its arc-length derivative.
    fn at(&self, u: f64) -> Result<CurveEval>;
    /// The curve as one NURBS (what CAD exports write): exact for the rational types
    /// (Béziers, NURBS, the spline, a sketch: `accuracy` unused); for a log-aesthetic
    /// segment, G2 rational cubics within `accuracy` (largest distance, in the curve's
    /// units), each proven curvature-monotone ([`crate::approx::fit_rational_spline`], at
    /// most [`MAX_NURBS_PIECES`] of them).
    fn to_nurbs(&self, accuracy: f64) -> Result<Nurbs>;
    /// The curve as one NURBS, exactly: for the rational types (Béziers, NURBS, splines,
    /// sketches, pieces). A log-aesthetic segment has no exact NURBS: an
    /// [`crate::Error::InvalidInput`] asks for [`Curve::to_nurbs`]'s accuracy.
    fn to_exact_nurbs(&self) -> Result<Nurbs> {
        self.to_nurbs(0.0)
    }
}

/// Most rational cubics a log-aesthetic segment's [`Curve::to_nurbs`] uses.
pub const MAX_NURBS_PIECES: usize = 64;

/// `u` clamped into `domain` (an error when it is not finite).
fn parameter(u: f64, domain: (f64, f64)) -> Result<f64> {
    if !u.is_finite() {
        return Err(Error::invalid("u", "the parameter must be finite"));
    }
    Ok(u.clamp(domain.0, domain.1))
}

/// A log-aesthetic point at an arc length, with the derivatives of that parameter.
fn arc_eval(q: crate::lac::ArcPoint) -> CurveEval {
    CurveEval {
        p: q.p,
        d1: q.tangent,
        d2: q.tangent.turn_90() * q.kappa,
        kappa: q.kappa,
        dkappa_ds: q.dkappa_ds,
    }
}

fn check_n(n: usize) -> Result<()> {
    if n < 2 {
        return Err(Error::invalid("samples", "need at least 2 per piece"));
    }
    if n > 10_000_000 {
        return Err(Error::invalid("samples", "at most 10,000,000 per piece"));
    }
    Ok(())
}

/// Derivatives at `t`, from 1e-7 inside where the first derivative vanishes.
fn regular(c: &impl PlanarCurve, t: f64) -> Result<Derivs> {
    let d = c.derivs(t);
    if d.is_regular() {
        return Ok(d);
    }
    let inner = if t < 0.5 { t + 1e-7 } else { t - 1e-7 };
    let e = c.derivs(inner);
    if !e.is_regular() {
        return Err(Error::Degenerate(
            "the curve does not move: its first derivative vanishes".into(),
        ));
    }
    Ok(Derivs { p: d.p, ..e })
}

fn point_of(c: &impl PlanarCurve, t: f64) -> Result<CurvePoint> {
    let d = regular(c, t)?;
    let kappa = d.kappa();
    if !kappa.is_finite() {
        return Err(Error::Degenerate(format!(
            "the curvature at t = {t} is not finite"
        )));
    }
    Ok(CurvePoint {
        p: d.p,
        tangent: d.d1 / d.d1.hypot(),
        kappa,
    })
}

fn bezier_points(c: &impl PlanarCurve, n: usize) -> Result<Vec<CurvePoint>> {
    check_n(n)?;
    (0..n)
        .map(|i| point_of(c, i as f64 / (n - 1) as f64))
        .collect()
}

/// ∫ |x'(t)| dt over [0, 1] by adaptive Gauss–Kronrod to 1e-14 of the control polygon's
/// length.
fn bezier_length(c: &impl PlanarCurve, polygon: &[Point]) -> Result<f64> {
    let scale: f64 = polygon.windows(2).map(|w| (w[1] - w[0]).hypot()).sum();
    let v = integrate(
        |t| Vec2::new(c.derivs(t).d1.hypot(), 0.0),
        0.0,
        1.0,
        QuadOptions {
            accuracy: (1e-14 * scale).max(f64::MIN_POSITIVE),
            max_panels: 4000,
        },
    )?;
    Ok(v.x)
}

/// The [`Curve`] of a Bézier type (points from [`PlanarCurve`]; `$path`: its `to_bezpath`;
/// `$rational`: the curve as a rational Bézier).
macro_rules! bezier_curve {
    ($ty:ty, $path:expr, $rational:expr) => {
        impl Curve for $ty {
            fn ends(&self) -> Result<(Point, Point)> {
                let p = self.points();
                Ok((p[0], p[p.len() - 1]))
            }
            fn end_curvatures(&self) -> Result<(f64, f64)> {
                Ok((point_of(self, 0.0)?.kappa, point_of(self, 1.0)?.kappa))
            }
            fn arc_length(&self) -> Result<f64> {
                bezier_length(self, self.points())
            }
            fn curve_points(&self, n: usize) -> Result<Vec<CurvePoint>> {
                bezier_points(self, n)
            }
            fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
                let path: fn(&$ty, f64) -> Result<BezPath> = $path;
                path(self, accuracy)
            }
            fn domain(&self) -> Result<(f64, f64)> {
                Ok((0.0, 1.0))
            }
            fn at(&self, u: f64) -> Result<CurveEval> {
                let t = parameter(u, (0.0, 1.0))?;
                let d = self.derivs(t);
                // Curvature from 1e-7 inside where the parameterisation stops.
                let r = if d.is_regular() { d } else { regular(self, t)? };
                Ok(CurveEval {
                    p: d.p,
                    d1: d.d1,
                    d2: d.d2,
                    kappa: r.kappa(),
                    dkappa_ds: r.dkappa_ds(),
                })
            }
            fn to_nurbs(&self, _accuracy: f64) -> Result<Nurbs> {
                let rational: fn(&$ty) -> RationalBezier = $rational;
                Ok(Nurbs::from_bezier(&rational(self)))
            }
        }
    };
}

// Exact for degree 3 or less; kurbo's curve fitting above.
bezier_curve!(
    Bezier,
    |c, accuracy| {
        if c.degree() <= 3 {
            Bezier::to_bezpath(std::slice::from_ref(c))
        } else {
            crate::bezpath::fit_planar(c, accuracy)
        }
    },
    Bezier::to_rational
);
bezier_curve!(
    RationalBezier,
    RationalBezier::to_bezpath,
    RationalBezier::clone
);

/// Unit tangents at turning angles `taus` from a start direction `d0`, turning with `sign`.
fn turned(d0: Vec2, sign: f64, taus: impl Iterator<Item = f64>) -> Vec<Vec2> {
    let u = d0 / d0.hypot();
    taus.map(|t| {
        let (s, c) = (sign * t).sin_cos();
        Vec2::new(u.x * c - u.y * s, u.x * s + u.y * c)
    })
    .collect()
}

/// Points of a turning-angle sampled curve: `sample` gives n points and curvatures evenly in
/// turning angle over [0, θ_d], the tangents turn from the first leg of the triangle.
fn turning_points(
    control: &[Point; 3],
    theta_d: f64,
    crate::lac::Polyline { points: pts, kappa }: crate::lac::Polyline,
) -> Vec<CurvePoint> {
    let n = pts.len();
    let (d0, d1) = (control[1] - control[0], control[2] - control[1]);
    let sign = if d0.cross(d1) >= 0.0 { 1.0 } else { -1.0 };
    let tangents = turned(
        d0,
        sign,
        (0..n).map(|i| theta_d * i as f64 / (n - 1) as f64),
    );
    pts.into_iter()
        .zip(tangents)
        .zip(kappa)
        .map(|((p, tangent), kappa)| CurvePoint { p, tangent, kappa })
        .collect()
}

/// The [`Curve`] of a log-aesthetic type (both have `control`, `theta_d`, `sample`,
/// `at_arc_length` and `to_bezpath`): `$ends` its end curvatures, `$length` its arc length,
/// `$spline` its rational spline within a tolerance.
macro_rules! lac_curve {
    ($ty:ty, $ends:expr, $length:expr, $spline:path) => {
        impl Curve for $ty {
            fn ends(&self) -> Result<(Point, Point)> {
                Ok((self.control[0], self.control[2]))
            }
            fn end_curvatures(&self) -> Result<(f64, f64)> {
                let ends: fn(&$ty) -> Result<(f64, f64)> = $ends;
                ends(self)
            }
            fn arc_length(&self) -> Result<f64> {
                let length: fn(&$ty) -> Result<f64> = $length;
                length(self)
            }
            fn curve_points(&self, n: usize) -> Result<Vec<CurvePoint>> {
                check_n(n)?;
                Ok(turning_points(&self.control, self.theta_d, self.sample(n)?))
            }
            fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
                <$ty>::to_bezpath(self, accuracy)
            }
            fn domain(&self) -> Result<(f64, f64)> {
                Ok((0.0, Curve::arc_length(self)?))
            }
            fn at(&self, u: f64) -> Result<CurveEval> {
                let s = parameter(u, (0.0, f64::INFINITY))?;
                Ok(arc_eval(self.at_arc_length(s)?))
            }
            fn to_nurbs(&self, accuracy: f64) -> Result<Nurbs> {
                let opts = crate::approx::ApproxOptions::default();
                Ok($spline(self, accuracy, MAX_NURBS_PIECES, &opts)?.nurbs)
            }
        }
    };
}

lac_curve!(
    LacSegment,
    LacSegment::end_curvatures,
    LacSegment::arc_length,
    crate::approx::fit_rational_spline
);
// 0 at the inflection end.
lac_curve!(
    LacInflectionSegment,
    |s| Ok((0.0, s.end_curvature())),
    |s| Ok(LacInflectionSegment::arc_length(s)),
    crate::approx::fit_inflection_spline
);

/// The [`Curve`] answers of consecutive pieces.
fn pieces_points<C: Curve>(pieces: &[C], n: usize) -> Result<Vec<CurvePoint>> {
    check_n(n)?;
    let mut out = Vec::with_capacity(pieces.len() * (n - 1) + 1);
    for (i, c) in pieces.iter().enumerate() {
        let pts = c.curve_points(n)?;
        out.extend(pts.into_iter().skip(usize::from(i > 0)));
    }
    Ok(out)
}

/// The first and the last piece (an error when there is none).
fn first_last<C>(pieces: &[C]) -> Result<(&C, &C)> {
    match (pieces.first(), pieces.last()) {
        (Some(a), Some(b)) => Ok((a, b)),
        _ => Err(Error::Degenerate("the curve has no pieces".into())),
    }
}

fn pieces_length<C: Curve>(pieces: &[C]) -> Result<f64> {
    pieces.iter().map(|c| c.arc_length()).sum()
}

fn pieces_path<C: Curve>(pieces: &[C], accuracy: f64) -> Result<BezPath> {
    let mut path = BezPath::new();
    for (i, c) in pieces.iter().enumerate() {
        for (j, el) in c.to_bezpath(accuracy)?.elements().iter().enumerate() {
            if i > 0 && j == 0 {
                continue; // the piece's move-to: the previous piece ended there
            }
            path.push(*el);
        }
    }
    Ok(path)
}

/// A curve made of pieces of one type (the spans of a NURBS, the Hermite spans of a spline,
/// the rational cubics of a sketch), in order, each starting where the previous one ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Pieces<C>(pub Vec<C>);

impl<C: Curve> Curve for Pieces<C> {
    fn ends(&self) -> Result<(Point, Point)> {
        let (a, b) = first_last(&self.0)?;
        Ok((a.ends()?.0, b.ends()?.1))
    }
    fn end_curvatures(&self) -> Result<(f64, f64)> {
        let (a, b) = first_last(&self.0)?;
        Ok((a.end_curvatures()?.0, b.end_curvatures()?.1))
    }
    fn arc_length(&self) -> Result<f64> {
        pieces_length(&self.0)
    }
    fn curve_points(&self, n: usize) -> Result<Vec<CurvePoint>> {
        pieces_points(&self.0, n)
    }
    fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
        pieces_path(&self.0, accuracy)
    }
    fn domain(&self) -> Result<(f64, f64)> {
        first_last(&self.0)?;
        Ok((0.0, self.0.len() as f64))
    }
    /// Piece `i = floor(u)` (the last for u = n) at its own parameter `a + (u - i)(b - a)`
    /// over its domain [a, b]; the derivatives scaled by `b - a` to the unit interval.
    fn at(&self, u: f64) -> Result<CurveEval> {
        let u = parameter(u, self.domain()?)?;
        let i = (u.floor() as usize).min(self.0.len() - 1);
        let piece = &self.0[i];
        let (a, b) = piece.domain()?;
        let w = b - a;
        let e = piece.at(a + (u - i as f64) * w)?;
        Ok(CurveEval {
            d1: e.d1 * w,
            d2: e.d2 * (w * w),
            ..e
        })
    }
    /// Every piece's rational Bézier spans joined into one NURBS ([`Nurbs::from_beziers`]:
    /// span i on [i, i + 1]), the one join of pieces in the library.
    fn to_nurbs(&self, accuracy: f64) -> Result<Nurbs> {
        let mut spans: Vec<RationalBezier> = Vec::with_capacity(self.0.len());
        for piece in &self.0 {
            spans.extend(piece.to_nurbs(accuracy)?.as_curve()?.0);
        }
        Nurbs::from_beziers(&spans)
    }
}

impl Nurbs {
    /// The curve's Bézier spans as [`Pieces`] (span i on [i, i + 1]); an error when it has
    /// none (a knot vector without interior spans). Its [`Curve`] impl answers in the knot
    /// parameter instead.
    pub fn as_curve(&self) -> Result<Pieces<RationalBezier>> {
        match self.bezier_spans() {
            Some(s) if !s.is_empty() => Ok(Pieces(s)),
            _ => Err(Error::Degenerate("the NURBS has no Bézier spans".into())),
        }
    }

    /// The distinct knots of the curve's domain, in order: Bézier span i of
    /// [`Nurbs::as_curve`] lies over `[breaks[i], breaks[i + 1]]`.
    pub fn span_breaks(&self) -> Vec<f64> {
        let (lo, hi) = (
            self.knots[self.degree],
            self.knots[self.control_points.len()],
        );
        let mut breaks: Vec<f64> = Vec::new();
        for &k in &self.knots {
            if (lo..=hi).contains(&k) && breaks.last() != Some(&k) {
                breaks.push(k);
            }
        }
        breaks
    }

    /// [`Curve::at`] at many knot parameters, the Bézier spans computed once (one call of
    /// `at` computes them for its one parameter).
    pub fn at_many(&self, us: &[f64]) -> Result<Vec<CurveEval>> {
        let spans = self.as_curve()?;
        let breaks = self.span_breaks();
        if breaks.len() != spans.0.len() + 1 {
            return Err(Error::Degenerate(
                "the NURBS's spans do not match its knots".into(),
            ));
        }
        let domain = (breaks[0], breaks[breaks.len() - 1]);
        us.iter()
            .map(|&u| {
                let u = parameter(u, domain)?;
                // The span with breaks[i] <= u < breaks[i + 1] (the last for u at the end).
                let i = breaks[1..breaks.len() - 1].partition_point(|&b| b <= u);
                let w = breaks[i + 1] - breaks[i];
                let e = spans.0[i].at((u - breaks[i]) / w)?;
                Ok(CurveEval {
                    d1: e.d1 / w,
                    d2: e.d2 / (w * w),
                    ..e
                })
            })
            .collect()
    }
}

/// A NURBS in its knot parameter: [`Curve::domain`] is the knots' interval
/// `[knots[p], knots[n]]`; [`Curve::at`] evaluates the Bézier span under `u`.
impl Curve for Nurbs {
    fn ends(&self) -> Result<(Point, Point)> {
        self.as_curve()?.ends()
    }
    fn end_curvatures(&self) -> Result<(f64, f64)> {
        self.as_curve()?.end_curvatures()
    }
    fn arc_length(&self) -> Result<f64> {
        self.as_curve()?.arc_length()
    }
    fn curve_points(&self, n: usize) -> Result<Vec<CurvePoint>> {
        self.as_curve()?.curve_points(n)
    }
    fn to_bezpath(&self, accuracy: f64) -> Result<BezPath> {
        self.as_curve()?.to_bezpath(accuracy)
    }
    fn domain(&self) -> Result<(f64, f64)> {
        let b = self.span_breaks();
        match (b.first(), b.last()) {
            (Some(&lo), Some(&hi)) if hi > lo => Ok((lo, hi)),
            _ => Err(Error::Degenerate("the NURBS has no Bézier spans".into())),
        }
    }
    fn at(&self, u: f64) -> Result<CurveEval> {
        Ok(self.at_many(&[u])?[0])
    }
    fn to_nurbs(&self, _accuracy: f64) -> Result<Nurbs> {
        Ok(self.clone())
    }
}

impl PseudoSpline {
    /// The spline's Hermite spans as cubic Béziers ([`Pieces`], its [`Curve`]).
    pub fn as_curve(&self) -> Result<Pieces<Bezier>> {
        let spans: Result<Vec<Bezier>> = self.segments.iter().map(|s| s.to_bezier()).collect();
        Ok(Pieces(spans?))
    }
}

impl Sketch {
    /// The fitted curve's rational cubics ([`Pieces`], its [`Curve`]).
    pub fn as_curve(&self) -> Pieces<RationalBezier> {
        Pieces(self.pieces.iter().map(|p| p.rational.clone()).collect())
    }
}

impl crate::sketch::contour::SketchContour {
    /// The contour as one curve of rational cubics in order ([`Pieces`], its [`Curve`]): a
    /// line run as the cubic with its inner control points at its thirds (straight, zero
    /// curvature), a curve run as its pieces' cubics.
    pub fn as_curve(&self) -> Result<Pieces<RationalBezier>> {
        use crate::sketch::contour::Run;
        let mut out = Vec::new();
        for run in &self.runs {
            match run {
                Run::Line { start, end } => {
                    let d = *end - *start;
                    let pts = vec![*start, *start + d / 3.0, *start + d * (2.0 / 3.0), *end];
                    out.push(RationalBezier::new(pts, vec![1.0; 4])?);
                }
                Run::Curve(s) => out.extend(s.pieces.iter().map(|p| p.rational.clone())),
            }
        }
        Ok(Pieces(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nurbs_answers_in_its_knot_parameter() {
        // Two rational cubic spans over uneven knots [2, 2.5] and [2.5, 5].
        let a = RationalBezier::new(
            vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0), p(3.0, 0.0)],
            vec![1.0, 0.8, 1.3, 1.0],
        )
        .unwrap();
        let b = RationalBezier::new(
            vec![p(3.0, 0.0), p(4.0, -1.0), p(5.0, 0.5), p(6.0, 2.0)],
            vec![1.0, 1.2, 0.9, 1.0],
        )
        .unwrap();
        let mut n = Nurbs::from_beziers(&[a, b]).unwrap();
        for k in &mut n.knots {
            *k = 2.0
                + if *k <= 1.0 {
                    0.5 * *k
                } else {
                    0.5 + 2.5 * (*k - 1.0)
                };
        }
        assert_eq!(n.span_breaks(), vec![2.0, 2.5, 5.0]);
        assert_eq!(Curve::domain(&n).unwrap(), (2.0, 5.0));
        let h = 1e-5;
        for u in [2.0, 2.1, 2.4999, 2.5, 3.7, 5.0] {
            let e = n.at(u).unwrap();
            // The point is de Boor's, independently of the spans.
            assert!((e.p - n.eval(u)).hypot() < 1e-12, "u = {u}");
            // The derivatives are the knot parameter's (central differences inside a span).
            let (lo, hi) = if u < 2.5 { (2.0, 2.5) } else { (2.5, 5.0) };
            let (u0, u1) = ((u - h).max(lo), (u + h).min(hi));
            let d = (n.at(u1).unwrap().p - n.at(u0).unwrap().p) / (u1 - u0);
            assert!(
                (d - e.d1).hypot() < 1e-4 * e.d1.hypot(),
                "u = {u}: {d:?} {:?}",
                e.d1
            );
            let d2 = (n.at(u1).unwrap().d1 - n.at(u0).unwrap().d1) / (u1 - u0);
            assert!(
                (d2 - e.d2).hypot() < 1e-4 * e.d2.hypot().max(1.0),
                "u = {u}"
            );
            // Curvature does not depend on the parameter.
            let k = e.d1.cross(e.d2) / e.d1.hypot().powi(3);
            assert!((k - e.kappa).abs() < 1e-9 * k.abs().max(1.0));
        }
        assert_eq!(n.to_nurbs(0.0).unwrap(), n);
        assert!(n.at(f64::NAN).is_err());
    }

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// The pseudo-elastic spline through four points, as its three cubic pieces.
    fn four_point_spline() -> Pieces<Bezier> {
        crate::pseudo_spline::pseudo_elastic(
            &[p(0.0, 0.0), p(2.0, 1.0), p(4.0, 0.0), p(6.0, 2.0)],
            false,
            crate::pseudo_spline::Mode::Table,
        )
        .unwrap()
        .as_curve()
        .unwrap()
    }

    /// The quarter circle of radius 2 about the origin from (2, 0) to (0, 2), as a rational
    /// quadratic and as a LAC segment (α = 0 in the isosceles triangle: Λ = 0, an arc).
    fn quarter_circle() -> (RationalBezier, LacSegment) {
        let arc = RationalBezier::new(
            vec![p(2.0, 0.0), p(2.0, 2.0), p(0.0, 2.0)],
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
        )
        .unwrap();
        let lac = LacSegment::new(0.0, [p(2.0, 0.0), p(2.0, 2.0), p(0.0, 2.0)]).unwrap();
        (arc, lac)
    }

    #[test]
    fn every_type_answers_alike_on_a_circle() {
        // The same quarter circle of radius 2 as a rational quadratic, its NURBS, and a LAC
        // segment with α = 0 in the isosceles triangle (Λ = 0: a circular arc): curvature
        // 1/2 everywhere, length π, tangents along the circle.
        let (arc, lac) = quarter_circle();
        let nurbs = Nurbs::from_beziers(std::slice::from_ref(&arc))
            .unwrap()
            .as_curve()
            .unwrap();
        let curves: [&dyn Curve; 3] = [&arc, &lac, &nurbs];
        for c in curves {
            let (a, b) = c.ends().unwrap();
            assert!((a - p(2.0, 0.0)).hypot() < 1e-12 && (b - p(0.0, 2.0)).hypot() < 1e-12);
            let (k0, k1) = c.end_curvatures().unwrap();
            assert!(
                (k0 - 0.5).abs() < 1e-12 && (k1 - 0.5).abs() < 1e-12,
                "{k0} {k1}"
            );
            let len = c.arc_length().unwrap();
            assert!((len - std::f64::consts::PI).abs() < 1e-12, "{len}");
            for q in c.curve_points(17).unwrap() {
                let r = q.p.to_vec2();
                assert!((r.hypot() - 2.0).abs() < 1e-12);
                assert!((q.kappa - 0.5).abs() < 1e-10, "{}", q.kappa);
                // Counter-clockwise: the tangent is the radius turned by +90°, the normal
                // points at the centre.
                assert!((q.tangent - r.turn_90() / 2.0).hypot() < 1e-9, "{q:?}");
                assert!((q.normal() + r / 2.0).hypot() < 1e-9);
            }
        }
    }

    #[test]
    fn every_type_answers_at_a_parameter() {
        // The quarter circle of radius 2 again: at every parameter the point is on the
        // circle, κ = 1/2, dκ/ds = 0, the first derivative along the tangent, and the
        // second derivative's normal part |d1|² κ.
        let (arc, lac) = quarter_circle();
        let next = RationalBezier::new(
            vec![p(0.0, 2.0), p(-2.0, 2.0), p(-2.0, 0.0)],
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
        )
        .unwrap();
        let two = Pieces(vec![arc.clone(), next]);
        let curves: [&dyn Curve; 3] = [&arc, &lac, &two];
        for c in curves {
            let (lo, hi) = c.domain().unwrap();
            for k in 0..=12 {
                let u = lo + (hi - lo) * k as f64 / 12.0;
                let e = c.at(u).unwrap();
                let r = e.p.to_vec2();
                assert!((r.hypot() - 2.0).abs() < 1e-12, "{u}: {e:?}");
                assert!(
                    (e.kappa - 0.5).abs() < 1e-10 && e.dkappa_ds.abs() < 1e-9,
                    "{e:?}"
                );
                assert!(r.dot(e.d1).abs() < 1e-9 * e.d1.hypot(), "{e:?}");
                let normal = e.d1.turn_90() / e.d1.hypot();
                assert!(
                    (e.d2.dot(normal) - e.d1.hypot2() * 0.5).abs() < 1e-9,
                    "{e:?}"
                );
            }
            assert!(c.at(f64::NAN).is_err());
            assert_eq!(c.at(hi + 5.0).unwrap(), c.at(hi).unwrap());
        }
        // The arc length is the LAC's parameter: unit first derivative.
        assert!((lac.at(1.0).unwrap().d1.hypot() - 1.0).abs() < 1e-14);
        // Pieces: the first derivative in the scaled parameter, against differences.
        let spline = four_point_spline();
        for u in [0.4, 1.5, 2.9] {
            let e = spline.at(u).unwrap();
            let h = 1e-6;
            let fd = (spline.at(u + h).unwrap().p - spline.at(u - h).unwrap().p) / (2.0 * h);
            assert!((fd - e.d1).hypot() < 1e-6 * e.d1.hypot(), "{u}");
            let fd2 = (spline.at(u + h).unwrap().d1 - spline.at(u - h).unwrap().d1) / (2.0 * h);
            assert!((fd2 - e.d2).hypot() < 1e-5 * e.d2.hypot().max(1.0), "{u}");
        }
    }

    #[test]
    fn every_type_becomes_one_nurbs() {
        // Exact types: the NURBS traces the same points (at the same parameter for one
        // piece; span i on [i, i + 1] for pieces).
        let quartic = Bezier::new(vec![
            p(0.0, 0.0),
            p(1.0, 2.0),
            p(3.0, 2.5),
            p(4.0, 0.5),
            p(6.0, 1.0),
        ])
        .unwrap();
        let n = quartic.to_nurbs(0.0).unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((n.eval(t) - quartic.eval(t)).hypot() < 1e-12, "{t}");
        }
        let spline = four_point_spline();
        let joined = spline.to_nurbs(0.0).unwrap();
        assert_eq!(joined.domain(), (0.0, 3.0));
        for (i, piece) in spline.0.iter().enumerate() {
            for t in [0.0, 0.3, 0.8] {
                let d = (joined.eval(i as f64 + t) - piece.eval(t)).hypot();
                assert!(d < 1e-12, "piece {i} at {t}: {d:e}");
            }
        }
        // A LAC segment: rational cubics within the accuracy (the distance from each NURBS
        // point to a dense polyline of the segment, whose chords sag less than 1e-7).
        let seg = LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)]).unwrap();
        let dense: Vec<Point> = seg.sample(20_001).unwrap().points;
        let near = |q: Point| {
            dense
                .windows(2)
                .map(|w| {
                    use kurbo::ParamCurveNearest;
                    kurbo::Line::new(w[0], w[1])
                        .nearest(q, 1e-12)
                        .distance_sq
                        .sqrt()
                })
                .fold(f64::INFINITY, f64::min)
        };
        for accuracy in [1e-2, 1e-5] {
            let nurbs = seg.to_nurbs(accuracy).unwrap();
            let (lo, hi) = nurbs.domain();
            let worst = (0..=400)
                .map(|i| near(nurbs.eval(lo + (hi - lo) * i as f64 / 400.0)))
                .fold(0.0, f64::max);
            assert!(worst <= accuracy + 1e-7, "{accuracy:e}: {worst:e}");
        }
        assert!(seg.to_nurbs(0.0).is_err() && seg.to_nurbs(f64::NAN).is_err());
    }

    #[test]
    fn pieces_share_their_joins_and_add_their_lengths() {
        let a = Bezier::new(vec![p(0.0, 0.0), p(1.0, 0.0), p(2.0, 1.0)]).unwrap();
        let b = Bezier::new(vec![p(2.0, 1.0), p(3.0, 2.0), p(5.0, 2.0), p(6.0, 2.0)]).unwrap();
        let both = Pieces(vec![a.clone(), b.clone()]);
        let pts = both.curve_points(11).unwrap();
        assert_eq!(pts.len(), 21);
        assert_eq!(pts[10].p, p(2.0, 1.0));
        let len = both.arc_length().unwrap();
        assert!((len - a.arc_length().unwrap() - b.arc_length().unwrap()).abs() < 1e-14);
        // A straight quadratic's length is its chord's: an independent check of the
        // quadrature.
        let line = Bezier::new(vec![p(0.0, 0.0), p(1.0, 1.0), p(3.0, 3.0)]).unwrap();
        assert!((line.arc_length().unwrap() - 18f64.sqrt()).abs() < 1e-14);
        // The path: one move-to, then the pieces' segments, exactly.
        let path = both.to_bezpath(1e-9).unwrap();
        assert_eq!(path.segments().count(), 2);
        assert!(Pieces::<Bezier>(vec![]).end_curvatures().is_err());
        assert!(Pieces::<Bezier>(vec![]).ends().is_err());
    }

    #[test]
    fn stationary_ends_take_the_limit_and_bad_counts_are_refused() {
        // P0 = P1: x'(0) = 0; the tangent and curvature at t = 0 come from just inside.
        let c = Bezier::new(vec![p(0.0, 0.0), p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0)]).unwrap();
        let pts = c.curve_points(5).unwrap();
        assert!(pts
            .iter()
            .all(|q| q.kappa.is_finite() && q.tangent.is_finite()));
        assert!((pts[0].tangent.hypot() - 1.0).abs() < 1e-12);
        assert!(c.curve_points(1).is_err());
        let lac = LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)]).unwrap();
        assert!(lac.curve_points(0).is_err());
        // The LAC's tangents follow its turning: first along the first leg, last along the
        // second.
        let pts = lac.curve_points(9).unwrap();
        assert!((pts[0].tangent - Vec2::new(1.0, 0.0)).hypot() < 1e-12);
        let last = Vec2::new(6.0, 9.0) / 117f64.sqrt();
        assert!((pts[8].tangent - last).hypot() < 1e-12);
    }
}
