//! # aesthetic-curves
//!
//! Curves whose curvature varies monotonically, and the tools to design, check and export
//! them. The mathematics follows `shared/spec/math.md` (the five seed papers, corrected).
//!
//! - [`approx`]: one rational cubic per LAC segment (G2 ends, proven monotone curvature,
//!   global optimum), and rational cubic B-splines for longer segments.
//! - [`bernstein`]: polynomials in Bernstein form (products, subdivision, degree elevation,
//!   sign analysis with rounding bounds, root isolation).
//! - [`bezier`]: polynomial and rational Bézier curves of degree 1 to 20: evaluation,
//!   derivatives, curvature, dkappa/ds, subdivision, elevation, power basis.
//! - [`bspline`]: cubic B-splines, least-squares fitting of point sequences, Bézier
//!   extraction.
//! - [`lac`]: log-aesthetic curves: standard form, segments from three control points,
//!   segments with an inflection end.
//! - [`lcg`]: the logarithmic curvature graph and alpha estimation.
//! - [`nurbs`]: rational B-splines, the exchange form of CAD systems.
//! - [`quadrature`]: adaptive Gauss–Kronrod quadrature.
//! - [`region`]: where a control point may go and keep a property (LAC existence,
//!   curvature monotonicity), on a grid: the shaded regions of an editor.
//! - [`sketch`]: pen input to a G2 curve of log-aesthetic pieces (as rational cubics).
//! - [`monotone`]: the exact curvature-monotonicity test (Bernstein form of dkappa/ds plus
//!   subdivision) and the sampling test.
//!
//! Points and vectors are [`kurbo::Point`] and [`kurbo::Vec2`]; angles are radians; signed
//! curvature is positive where the curve turns counter-clockwise.

#![warn(missing_docs)]

pub mod approx;
pub mod bernstein;
pub mod bezier;
pub mod bspline;
pub mod error;
pub mod lac;
pub mod lac_fit;
pub mod lcg;
pub mod monotone;
pub mod nurbs;
pub mod pseudo_spline;
pub mod pseudo_table;
pub mod quadrature;
pub mod region;
pub mod roots;
pub mod samples;
pub mod sketch;

pub use bezier::{Bezier, PlanarCurve, RationalBezier};
pub use error::{Error, Result};
pub use kurbo::{Point, Vec2};
pub use monotone::{MonotoneReport, SampledReport, Trend};
