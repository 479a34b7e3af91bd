//! # aesthetic-curves
//!
//! Curves whose curvature varies monotonically, and the tools to design, check and export
//! them: the exact curvature-monotonicity test of Bézier curves, log-aesthetic curves (LAC),
//! their approximation by one rational cubic with proven monotone curvature, the
//! pseudo-elastic spline, the G2 log-aesthetic spline through points, and pen input to a G2
//! curve of LAC pieces. The mathematics of
//! every module, with the accuracy of each result and the test that checks it, is in
//! `docs/math.md` of the repository; the papers (cited as S0-S4) in `docs/bibliography.md`.
//!
//! ## Quick start
//!
//! ```
//! use aesthetic_curves::{Bezier, CurvatureMonotone, LacSegment, Point};
//! use aesthetic_curves::approx::{fit_rational_cubic, ApproxOptions};
//! use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
//! use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
//!
//! # fn main() -> aesthetic_curves::Result<()> {
//! let p = Point::new;
//!
//! // Is the curvature of this cubic monotone? No: it peaks in the middle.
//! let cubic = Bezier::new(vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0), p(3.0, 0.0)])?;
//! let report = cubic.curvature_monotone()?;
//! assert!(!report.monotone);
//! assert!((report.extrema[0] - 0.5).abs() < 1e-12);
//!
//! // A log-aesthetic segment (alpha = -1: a clothoid arc) in a control triangle.
//! let seg = LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)])?;
//! let (k0, k1) = seg.end_curvatures()?;
//! assert!(k0 > k1 && k1 > 0.0); // curvature falls along it
//!
//! // One rational cubic for it: G2 at both ends, curvature proven monotone.
//! let fit = fit_rational_cubic(&seg, &ApproxOptions::default())?;
//! assert!(fit.monotone && fit.max_error < 1e-6);
//!
//! // The pseudo-elastic spline through points, from the shipped tables.
//! let pts = [p(0.0, 0.0), p(2.0, 1.5), p(4.0, 1.0), p(6.0, 3.0)];
//! let spline = pseudo_elastic(&pts, false, Mode::Table)?;
//! assert_eq!(spline.segments.len(), 3);
//! assert!(spline.length > 7.0);
//!
//! // The G2 log-aesthetic spline through the same points (clothoid pieces, alpha = -1):
//! // through every point, G2 at each, every piece one rational cubic proven monotone.
//! use aesthetic_curves::lac_spline::{lac_spline, LacSplineOptions};
//! let g2 = lac_spline(&pts, &LacSplineOptions::default())?;
//! assert!(g2.all_monotone && g2.max_curvature_jump < 1e-10);
//!
//! // Pen input to a G2 curve of LAC pieces, each one rational cubic.
//! let stroke: Vec<Point> = (0..=40)
//!     .map(|i| {
//!         let t = i as f64 / 40.0;
//!         p(100.0 * t, 60.0 * t * t)
//!     })
//!     .collect();
//! let sketch = fit_sketch(&stroke, &SketchOptions::with_tolerance(0.5))?;
//! assert!(sketch.g2 && sketch.all_monotone);
//! assert!(sketch.max_deviation <= 0.5);
//! # Ok(())
//! # }
//! ```
//!
//! Bad input is an [`Error`] with a kind, never a panic or a NaN:
//!
//! ```
//! use aesthetic_curves::{LacSegment, Point};
//! let p = Point::new;
//! // Turning 45 degrees with the base angle at the far end too large for a clothoid.
//! let err = LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(11.0, 1.0)]).unwrap_err();
//! assert_eq!(err.kind(), "no_segment");
//! ```
//!
//! More: runnable programs in `examples/` of this crate (`cargo run --example NAME -p
//! aesthetic-curves`).
//!
//! ## Modules
//!
//! - [`approx`]: one rational cubic per LAC segment (G2 ends, proven monotone curvature,
//!   global optimum), and rational cubic B-splines for longer segments.
//! - [`approx_table`]: the shipped table of the rational-cubic error surface's local optima
//!   that starts [`approx`]'s fit.
//! - [`curve`]: the one interface of every curve type ([`curve::Curve`]: ends, end
//!   curvatures, arc length, points with tangent and curvature, cubic Bézier paths).
//! - [`bezpath`]: cubic Bézier paths (kurbo's `BezPath`) within an accuracy of the curves
//!   that are not polynomial: LAC segments, inflection-end segments, rational Béziers.
//! - [`bernstein`]: polynomials in Bernstein form (products, subdivision, degree elevation,
//!   sign analysis with rounding bounds, root isolation).
//! - [`bezier`]: polynomial and rational Bézier curves of degree 1 to 20: evaluation,
//!   derivatives, curvature, dkappa/ds, subdivision, elevation, power basis.
//! - [`bspline`]: cubic B-splines, least-squares fitting of point sequences, Bézier
//!   extraction.
//! - [`deadline`]: cooperative cancellation: work run under a deadline stops with a
//!   `timeout` error once it has passed.
//! - [`error`]: the one error type, [`Error`], whose kinds are the JSON protocol's.
//! - [`harmonize`]: the repair of existing outlines: curvature hooks and extra extrema
//!   removed by handle lengths, then smooth joins of cubic contours made G2 by sliding
//!   handles along their tangents (or the join's point along its handles' line), within a
//!   tolerance and on a grid, never making a join or a segment worse.
//! - [`lac`]: log-aesthetic curves: standard form, segments from three control points,
//!   segments with an inflection end.
//! - [`lac_fit`]: the single least-squares LAC segment through points.
//! - [`lcg`]: the logarithmic curvature graph and alpha estimation.
//! - [`monotone`]: the exact curvature-monotonicity test (Bernstein form of dkappa/ds plus
//!   subdivision) and the sampling test.
//! - [`outline`]: the exact curvature check of existing outlines (fonts, SVG, DXF): per
//!   segment (monotone, extrema, inflections, largest curvature) and per join (tangent
//!   break, curvature jump), and the places most worth a look.
//! - [`nurbs`]: rational B-splines, the exchange form of CAD systems.
//! - [`pseudo_segment`]: one pseudo-elastic Hermite segment on the unit chord (its energy,
//!   every local minimum of J = E L², the single-angle function).
//! - [`pseudo_spline`]: the pseudo-elastic spline (interpolation by Hermite cubics of
//!   least pseudo-energy), open or closed, with length, area and energy.
//! - [`pseudo_table`]: the shipped tables of the pseudo-elastic segment behind its fast mode.
//! - [`quadrature`]: adaptive Gauss–Kronrod quadrature.
//! - [`region`]: where a control point may go and keep a property (LAC existence,
//!   curvature monotonicity), on a grid: the shaded regions of an editor.
//! - [`samples`]: reproducible random curve sets for benchmarks and tests.
//! - [`sketch`]: pen input to a G2 curve of log-aesthetic pieces (as rational cubics).
//! - [`solve`]: the solver layer, every solver with its own options and a report of how it
//!   ended, one file per kind: minimisers of a few variables (`solve::minimize`), of one
//!   variable (`solve::line_search`), roots (`solve::roots`), systems and fixed points
//!   (`solve::systems`), least squares (`solve::least_squares`).
//!
//! Points and vectors are [`kurbo::Point`] and [`kurbo::Vec2`]; angles are radians; signed
//! curvature is positive where the curve turns counter-clockwise (kurbo's curvature has
//! the opposite sign). [`Bezier`] converts from and to kurbo's `Line`, `QuadBez`,
//! `CubicBez`, `PathSeg` and `BezPath`, and Bézier curves take kurbo's `Affine` maps.

#![warn(missing_docs)]

pub mod approx;
pub mod approx_table;
pub mod bernstein;
pub mod bezier;
pub mod bezpath;
pub mod bspline;
pub mod contour_points;
pub mod curve;
pub mod deadline;
pub mod error;
pub mod exact;
pub mod harmonize;
pub mod lac;
pub mod lac_fit;
pub mod lac_spline;
pub mod lcg;
pub mod monotone;
pub mod nurbs;
pub mod outline;
pub mod pseudo_segment;
pub mod pseudo_spline;
pub mod pseudo_table;
pub mod quadrature;
pub mod region;
pub mod samples;
pub mod sketch;
pub mod solve;
pub mod space;

pub use bezier::{Bezier, PlanarCurve, RationalBezier};
pub use curve::{Curve, CurveEval, CurvePoint, Pieces};
pub use error::{Error, Result};
pub use kurbo::{Point, Vec2};
pub use lac::{ArcPoint, LacInflectionSegment, LacSegment, LacStandard, Polyline, TurningSamples};
pub use monotone::{CurvatureMonotone, MonotoneReport, SampledReport, Trend};
pub use nurbs::Nurbs;
