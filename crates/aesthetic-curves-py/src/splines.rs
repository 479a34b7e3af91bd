//! Splines through points: S2's pseudo-elastic spline (G1) and the G2 log-aesthetic spline.

use crate::args::*;
use crate::curves::*;
use crate::exports::*;
use ac::Curve;
use aesthetic_curves as ac;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// The pseudo-elastic spline through points (Hermite cubics minimising the pseudo-energy).
#[pyclass(module = "aesthetic_curves._native", frozen)]
pub(crate) struct PseudoSpline {
    pub(crate) inner: ac::pseudo_spline::PseudoSpline,
}

pymethods_with_exports!(PseudoSpline {
    /// Tangent angle at each input point (radians), an array.
    #[getter]
    fn tangent_angles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.tangent_angles.clone().into_pyarray(py)
    }
    /// Total length.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length
    }
    /// Signed area between the curve and its chords (closed: the enclosed area).
    #[getter]
    fn area(&self) -> f64 {
        self.inner.area
    }
    /// The pseudo-energy.
    #[getter]
    fn energy(&self) -> f64 {
        self.inner.energy
    }
    /// The parameter interval of `at`: (0, n) for n spans (span i on [i, i + 1]).
    fn domain(&self) -> PyResult<(f64, f64)> {
        self.inner.as_curve().and_then(|c| c.domain()).map_err(err)
    }
    /// Point, first and second derivatives, curvature and dκ/ds at `u` (a float or an
    /// array; span `floor(u)` at its own t = u - floor(u); clamped into the domain).
    fn at(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
        curve_at(py, &self.inner.as_curve().map_err(err)?, u)
    }
    /// The spans as cubic Béziers.
    fn beziers(&self) -> PyResult<Vec<Bezier>> {
        Ok(self
            .inner
            .as_curve()
            .map_err(err)?
            .0
            .into_iter()
            .map(|inner| Bezier { inner })
            .collect())
    }
    /// `n >= 2` samples per span (points, unit tangents, signed curvature), the spans'
    /// shared ends once.
    fn sample(&self, py: Python<'_>, n: usize) -> PyResult<Samples> {
        samples_of(py, &self.inner.as_curve().map_err(err)?, n)
    }
    /// The spline as one NURBS (cubic spans joined at the input points).
    fn to_nurbs(&self) -> PyResult<Nurbs> {
        Ok(Nurbs {
            inner: self.nurbs_of()?,
        })
    }

    fn __len__(&self) -> usize {
        self.inner.segments.len()
    }
    fn __repr__(&self) -> String {
        format!(
            "PseudoSpline(spans={}, length={}, energy={})",
            self.inner.segments.len(),
            self.inner.length,
            self.inner.energy
        )
    }
});

/// The pseudo-elastic spline through `points` (open, or `closed`); `mode` "table" (fast,
/// from the shipped tables) or "exact" (minimised per span, about a second per point).
#[pyfunction]
#[pyo3(signature = (points, closed=false, mode="table"))]
pub(crate) fn pseudo_elastic(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    closed: bool,
    mode: &str,
) -> PyResult<PseudoSpline> {
    let p = points_arg("points", points)?;
    let mode = ac::pseudo_spline::Mode::from_name(mode).map_err(err)?;
    let inner = py
        .detach(move || ac::pseudo_spline::pseudo_elastic(&p, closed, mode))
        .map_err(err)?;
    Ok(PseudoSpline { inner })
}

/// The G2 log-aesthetic spline through points: LAC pieces of one α, G2 at every smooth
/// point, each delivered as a rational cubic proven curvature-monotone.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct LacSpline {
    /// The delivered curve, one NURBS of the pieces' rational cubics.
    pub(crate) nurbs: Nurbs,
    /// Each piece's rational cubic, in order.
    pub(crate) pieces: Vec<RationalBezier>,
    /// Each piece with the protocol's fields, in order.
    pub(crate) segments: Vec<Py<SplineSegment>>,
    /// Each piece's kind: "line", "lac" or "lac_inflection".
    pub(crate) kinds: Vec<&'static str>,
    /// Each piece's span (the index of the point it starts from).
    pub(crate) spans: Vec<usize>,
    /// Each piece's α (None for a line).
    pub(crate) alphas: Vec<Option<f64>>,
    /// The unit tangent at each point (at a corner, the outgoing one).
    pub(crate) tangents: Vec<(f64, f64)>,
    /// Largest relative curvature jump at a smooth point, of the LAC pieces.
    pub(crate) max_curvature_jump: f64,
    /// The same on the delivered cubics.
    pub(crate) max_cubic_jump: f64,
    /// Every piece's rational cubic is proven curvature-monotone.
    pub(crate) all_monotone: bool,
    /// The G2 solve reached its target.
    pub(crate) converged: bool,
    /// Newton steps.
    pub(crate) iterations: usize,
    /// Closed.
    pub(crate) closed: bool,
    /// G2 as delivered: converged, and the cubics' curvature jumps below 1e-8.
    pub(crate) g2: bool,
    /// Largest tangent angle between the delivered cubics at a smooth point (radians).
    pub(crate) max_cubic_angle: f64,
    /// Largest distance of a cubic from its LAC piece.
    pub(crate) max_rational_error: f64,
    /// Inflections.
    pub(crate) inflections: usize,
    /// Curvature extrema.
    pub(crate) curvature_extrema: usize,
    /// The α each span was solved with (the requested one, or the nearest one it holds
    /// where the requested α has no G2 spline through the points).
    pub(crate) span_alphas: Vec<f64>,
    /// The spans whose α is not the requested one.
    pub(crate) relaxed_spans: Vec<usize>,
}

/// One piece of the G2 spline, with the fields of the protocol's `segments` entries.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct SplineSegment {
    /// "line", "lac" or "lac_inflection".
    pub(crate) kind: &'static str,
    /// The span (from point `span` to the next) it belongs to.
    pub(crate) span: usize,
    /// Its α (None for a line).
    pub(crate) alpha: Option<f64>,
    /// Its control triangle in curve order, a (3, 2) array (a line's middle point is its
    /// midpoint).
    pub(crate) control: Py<PyArray2<f64>>,
    /// Signed curvature at its start and end.
    pub(crate) end_curvatures: (f64, f64),
    /// Its rational cubic.
    pub(crate) rational: RationalBezier,
    /// Largest distance of the cubic from the piece.
    pub(crate) rational_error: f64,
    /// The cubic's curvature is proven monotone.
    pub(crate) monotone: bool,
}

/// The G2 log-aesthetic spline through `points`: `alpha` for every span (-1: clothoids) or
/// `alphas` one per span; `closed`; `corners` the indices of corner points.
#[pyfunction]
#[pyo3(signature = (points, alpha=-1.0, closed=false, corners=Vec::new(), alphas=None))]
pub(crate) fn lac_spline(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    alpha: f64,
    closed: bool,
    corners: Vec<usize>,
    alphas: Option<Vec<f64>>,
) -> PyResult<LacSpline> {
    let p = points_arg("points", points)?;
    let opts = ac::lac_spline::LacSplineOptions {
        alpha,
        span_alphas: alphas,
        closed,
        corners,
        ..Default::default()
    };
    let s = py
        .detach(move || ac::lac_spline::lac_spline(&p, &opts))
        .map_err(err)?;
    let (nurbs, pieces) = joined(s.rationals())?;
    let segments = s
        .pieces
        .iter()
        .map(|q| {
            Py::new(
                py,
                SplineSegment {
                    kind: q.kind.as_str(),
                    span: q.span,
                    alpha: q.alpha,
                    control: points_array(py, &q.control).unbind(),
                    end_curvatures: q.end_curvatures,
                    rational: RationalBezier {
                        inner: q.rational.clone(),
                    },
                    rational_error: q.rational_error,
                    monotone: q.monotone,
                },
            )
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok(LacSpline {
        nurbs,
        pieces,
        segments,
        kinds: s.pieces.iter().map(|p| p.kind.as_str()).collect(),
        spans: s.pieces.iter().map(|p| p.span).collect(),
        alphas: s.pieces.iter().map(|p| p.alpha).collect(),
        tangents: s.tangents.iter().map(|t| (t.x, t.y)).collect(),
        max_curvature_jump: s.max_curvature_jump,
        max_cubic_jump: s.max_cubic_jump,
        all_monotone: s.all_monotone,
        converged: s.converged,
        iterations: s.iterations,
        closed: s.closed,
        g2: s.g2(),
        max_cubic_angle: s.max_cubic_angle,
        max_rational_error: s.max_rational_error,
        inflections: s.inflections,
        curvature_extrema: s.curvature_extrema,
        span_alphas: s.span_alphas.clone(),
        relaxed_spans: s.relaxed_spans.clone(),
    })
}

impl LacSpline {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.nurbs.inner.clone())
    }
}

pieces_methods!(LacSpline {
    fn __len__(&self) -> usize {
        self.pieces.len()
    }
});

impl PseudoSpline {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        self.inner
            .as_curve()
            .and_then(|c| c.to_exact_nurbs())
            .map_err(err)
    }
}
