//! Bézier curves (polynomial and rational), NURBS, their samples and evaluations, and the
//! exact curvature-monotonicity verdict.

use crate::args::*;
use crate::exports::*;
use ac::monotone::CurvatureMonotone;
use ac::{Curve, PlanarCurve, Point};
use aesthetic_curves as ac;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Samples of a curve: points, unit tangents and signed curvature, as arrays.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct Samples {
    /// The points, an (n, 2) array.
    pub(crate) points: Py<PyArray2<f64>>,
    /// Unit tangents, an (n, 2) array.
    pub(crate) tangents: Py<PyArray2<f64>>,
    /// Signed curvature (positive turning left), an (n,) array.
    pub(crate) kappa: Py<PyArray1<f64>>,
}

#[pymethods]
impl Samples {
    /// The curvature comb: the points and the tips of the comb's teeth, which stand on the
    /// curve's normal with length `scale * kappa` (on the side the curve turns to).
    #[pyo3(signature = (scale))]
    fn comb<'py>(
        &self,
        py: Python<'py>,
        scale: f64,
    ) -> (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>) {
        let p = self.points.bind(py).readonly();
        let t = self.tangents.bind(py).readonly();
        let k = self.kappa.bind(py).readonly();
        let (p, t, k) = (p.as_array(), t.as_array(), k.as_array());
        let n = k.len();
        let mut tips = Vec::with_capacity(2 * n);
        for i in 0..n {
            // The left normal (-ty, tx) times kappa points to the centre of curvature.
            let s = scale * k[i];
            tips.push(p[[i, 0]] - t[[i, 1]] * s);
            tips.push(p[[i, 1]] + t[[i, 0]] * s);
        }
        (
            self.points.bind(py).clone(),
            Array2::from_shape_vec((n, 2), tips)
                .expect("n x 2")
                .into_pyarray(py),
        )
    }

    fn __len__(&self, py: Python<'_>) -> usize {
        self.kappa.bind(py).len()
    }
}

pub(crate) fn samples_of(py: Python<'_>, c: &dyn Curve, n: usize) -> PyResult<Samples> {
    let pts = c.curve_points(n).map_err(err)?;
    Ok(Samples {
        points: xy_array(py, pts.iter().map(|q| [q.p.x, q.p.y])).unbind(),
        tangents: xy_array(py, pts.iter().map(|q| [q.tangent.x, q.tangent.y])).unbind(),
        kappa: pts
            .iter()
            .map(|q| q.kappa)
            .collect::<Vec<_>>()
            .into_pyarray(py)
            .unbind(),
    })
}

/// A curve at values of its parameter ([`Curve::at`]): one row per parameter.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct CurveAt {
    /// The points, an (n, 2) array.
    pub(crate) points: Py<PyArray2<f64>>,
    /// First derivatives with respect to the parameter, an (n, 2) array.
    pub(crate) d1: Py<PyArray2<f64>>,
    /// Second derivatives, an (n, 2) array.
    pub(crate) d2: Py<PyArray2<f64>>,
    /// Signed curvature, an (n,) array.
    pub(crate) kappa: Py<PyArray1<f64>>,
    /// dκ/ds, an (n,) array.
    pub(crate) dkappa_ds: Py<PyArray1<f64>>,
}

#[pymethods]
impl CurveAt {
    fn __len__(&self, py: Python<'_>) -> usize {
        self.kappa.bind(py).len()
    }
}

/// A float or an array of parameters, as a list.
pub(crate) fn params_list(u: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    Ok(match params_arg(u)? {
        Params::One(u) => vec![u],
        Params::Many(us) => us,
    })
}

/// [`Curve::at`] at a float or an array of parameters.
pub(crate) fn curve_at(py: Python<'_>, c: &dyn Curve, u: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
    let at: Vec<ac::CurveEval> = params_list(u)?
        .iter()
        .map(|&u| c.at(u))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    curve_at_of(py, at)
}

/// The rows of a [`CurveAt`].
pub(crate) fn curve_at_of(py: Python<'_>, at: Vec<ac::CurveEval>) -> PyResult<CurveAt> {
    let xy = |f: fn(&ac::CurveEval) -> [f64; 2]| xy_array(py, at.iter().map(f)).unbind();
    let nums = |f: fn(&ac::CurveEval) -> f64| {
        at.iter()
            .map(f)
            .collect::<Vec<_>>()
            .into_pyarray(py)
            .unbind()
    };
    Ok(CurveAt {
        points: xy(|e| [e.p.x, e.p.y]),
        d1: xy(|e| [e.d1.x, e.d1.y]),
        d2: xy(|e| [e.d2.x, e.d2.y]),
        kappa: nums(|e| e.kappa),
        dkappa_ds: nums(|e| e.dkappa_ds),
    })
}

/// The exact test's report.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct MonotoneReport {
    /// Curvature monotone along the whole curve (proven).
    pub(crate) monotone: bool,
    /// "increasing", "decreasing", "constant", or None when not monotone.
    pub(crate) trend: Option<String>,
    /// Parameters of the curvature extrema inside (0, 1), an (m,) array.
    pub(crate) extrema: Py<PyArray1<f64>>,
    /// Degree of the Bernstein polynomial the test examines.
    pub(crate) test_degree: usize,
    /// The floating-point filter could not decide: exact integer arithmetic did.
    pub(crate) exact: bool,
    /// How the curvature behaves at t = 0 and at t = 1.
    pub(crate) ends: (EndCurvature, EndCurvature),
}

/// The curvature at one end of a curve.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
#[derive(Clone)]
pub(crate) struct EndCurvature {
    /// "regular" (the speed does not vanish), "finite" (a retracted handle, the curvature
    /// tends to a limit) or "unbounded" (a retracted handle, the curvature grows without
    /// bound).
    pub(crate) kind: String,
    /// The curvature at the end (its limit at a retracted one); None where unbounded.
    pub(crate) curvature: Option<f64>,
    /// How many handles are retracted onto the end point (0 at a regular end).
    pub(crate) retracted_handles: usize,
    /// Where unbounded: the curvature grows like 1/t**growth_rate.
    pub(crate) growth_rate: Option<usize>,
    /// Where unbounded: the growth as the protocol writes it, "1/t" or "1/t^k".
    pub(crate) growth: Option<String>,
    /// Where unbounded: the sign of the curvature near the end (+1 or -1).
    pub(crate) sign: Option<i8>,
}

#[pymethods]
impl EndCurvature {
    fn __repr__(&self) -> String {
        let opt = |v: Option<String>| v.unwrap_or_else(|| "None".into());
        format!(
            "EndCurvature(kind='{}', curvature={}, retracted_handles={}, growth_rate={}, sign={})",
            self.kind,
            opt(self.curvature.map(|k| k.to_string())),
            self.retracted_handles,
            opt(self.growth_rate.map(|r| r.to_string())),
            opt(self.sign.map(|s| s.to_string())),
        )
    }
}

impl From<ac::monotone::EndCurvature> for EndCurvature {
    fn from(e: ac::monotone::EndCurvature) -> Self {
        use ac::monotone::EndCurvature as E;
        let (kind, retracted_handles, growth_rate, sign) = match e {
            E::Regular(_) => ("regular", 0, None, None),
            E::Finite { order, .. } => ("finite", order, None, None),
            E::Unbounded {
                positive,
                order,
                rate,
            } => (
                "unbounded",
                order,
                Some(rate),
                Some(if positive { 1 } else { -1 }),
            ),
        };
        EndCurvature {
            kind: kind.into(),
            curvature: e.value(),
            retracted_handles,
            growth_rate,
            growth: e.growth(),
            sign,
        }
    }
}

#[pymethods]
impl MonotoneReport {
    /// `exact` under the protocol's name.
    #[getter]
    fn exact_arithmetic(&self) -> bool {
        self.exact
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "MonotoneReport(monotone={}, trend={}, extrema={}, test_degree={}, exact={})",
            if self.monotone { "True" } else { "False" },
            self.trend
                .as_ref()
                .map_or("None".to_string(), |t| format!("'{t}'")),
            self.extrema.bind(py).len(),
            self.test_degree,
            if self.exact { "True" } else { "False" }
        )
    }
}

pub(crate) fn report(py: Python<'_>, r: ac::MonotoneReport) -> MonotoneReport {
    MonotoneReport {
        monotone: r.monotone,
        trend: r.trend.map(|t| t.as_str().to_string()),
        extrema: r.extrema.into_pyarray(py).unbind(),
        test_degree: r.test_degree,
        exact: r.exact,
        ends: (r.ends[0].into(), r.ends[1].into()),
    }
}

/// A polynomial Bézier curve of any degree.
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
pub(crate) struct Bezier {
    pub(crate) inner: ac::Bezier,
}

/// A rational Bézier curve (positive weights).
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
pub(crate) struct RationalBezier {
    pub(crate) inner: ac::RationalBezier,
}

pub(crate) trait AsRational {
    fn as_rational(&self) -> ac::RationalBezier;
}
impl AsRational for ac::Bezier {
    fn as_rational(&self) -> ac::RationalBezier {
        self.to_rational()
    }
}
impl AsRational for ac::RationalBezier {
    fn as_rational(&self) -> ac::RationalBezier {
        self.clone()
    }
}
pub(crate) fn rational_of(c: &impl AsRational) -> ac::RationalBezier {
    c.as_rational()
}

bezier_methods!(Bezier, {
    #[new]
    fn new(points: &Bound<'_, PyAny>) -> PyResult<Self> {
        let p = points_arg("points", points)?;
        Ok(Bezier {
            inner: ac::Bezier::new(p).map_err(err)?,
        })
    }
});

bezier_methods!(RationalBezier, {
    #[new]
    fn new(points: &Bound<'_, PyAny>, weights: &Bound<'_, PyAny>) -> PyResult<Self> {
        let p = points_arg("points", points)?;
        let w = numbers_arg("weights", weights)?;
        Ok(RationalBezier {
            inner: ac::RationalBezier::new(p, w).map_err(err)?,
        })
    }
    /// The weights, an (n + 1,) array.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.weights().to_vec().into_pyarray(py)
    }
});

/// The exact verdicts of many polynomial Bézier curves of one degree: `control` is an
/// (m, n + 1, 2) float64 array; returns an (m,) bool array (a degenerate curve: False).
#[pyfunction]
pub(crate) fn are_curvature_monotone<'py>(
    py: Python<'py>,
    control: numpy::PyReadonlyArray3<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let a = control.as_array();
    let s = a.shape();
    if s[1] < 2 || s[2] != 2 {
        return Err(PyValueError::new_err(format!(
            "control: expected an array of shape (m, n + 1, 2) with n >= 1, got ({}, {}, {})",
            s[0], s[1], s[2]
        )));
    }
    let curves: Vec<Vec<Point>> = a
        .outer_iter()
        .map(|c| {
            c.rows()
                .into_iter()
                .map(|r| Point::new(r[0], r[1]))
                .collect()
        })
        .collect();
    let out: Vec<bool> = py.detach(|| {
        curves
            .into_iter()
            .map(|p| {
                ac::Bezier::new(p)
                    .and_then(|b| b.is_curvature_monotone())
                    .unwrap_or(false)
            })
            .collect()
    });
    Ok(out.into_pyarray(py))
}

/// A NURBS curve (the form every exporter writes).
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
pub(crate) struct Nurbs {
    pub(crate) inner: ac::Nurbs,
}

pymethods_with_exports!(Nurbs {
    /// The degree.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree
    }
    /// The knot vector, an array.
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.knots.clone().into_pyarray(py)
    }
    /// The control points, an (m, 2) array.
    #[getter]
    fn control_points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &self.inner.control_points)
    }
    /// The weights, an (m,) array.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.weights.clone().into_pyarray(py)
    }
    /// The parameter domain (first and last knot of the curve).
    fn domain(&self) -> (f64, f64) {
        self.inner.domain()
    }
    /// Point, first and second derivatives (in the knot parameter), curvature and dκ/ds at
    /// `u` (a float or an array; clamped into the domain).
    fn at(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
        let us = params_list(u)?;
        curve_at_of(py, self.inner.at_many(&us).map_err(err)?)
    }
    /// The point at `u` (a float or an array) in the domain.
    fn eval<'py>(&self, py: Python<'py>, u: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        eval_points(py, u, |u| self.inner.eval(u))
    }


    /// The rational Bézier spans.
    fn bezier_spans(&self) -> Vec<RationalBezier> {
        self.inner
            .bezier_spans()
            .unwrap_or_default()
            .into_iter()
            .map(|inner| RationalBezier { inner })
            .collect()
    }
    fn __repr__(&self) -> String {
        format!(
            "Nurbs(degree={}, control_points={}, knots={})",
            self.inner.degree,
            self.inner.control_points.len(),
            self.inner.knots.len()
        )
    }
});

impl Bezier {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(ac::Nurbs::from_bezier(&self.inner.to_rational()))
    }
}
impl RationalBezier {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(ac::Nurbs::from_bezier(&self.inner))
    }
}
impl Nurbs {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.inner.clone())
    }
}

/// A curve of rational cubic pieces as the Python classes hold it: one NURBS of all the
/// pieces, and each piece.
pub(crate) fn joined(
    curve: ac::Pieces<ac::RationalBezier>,
) -> PyResult<(Nurbs, Vec<RationalBezier>)> {
    let nurbs = Nurbs {
        inner: curve.to_exact_nurbs().map_err(err)?,
    };
    let pieces = curve
        .0
        .into_iter()
        .map(|inner| RationalBezier { inner })
        .collect();
    Ok((nurbs, pieces))
}
