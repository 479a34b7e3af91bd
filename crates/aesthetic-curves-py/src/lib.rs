//! Python bindings of the `aesthetic-curves` library: the extension module
//! `aesthetic_curves._native`, re-exported by the Python package `aesthetic_curves`.
//!
//! Every class wraps a library type and calls it directly (no JSON protocol, no process).
//! Points go in as an `(n, 2)` float64 NumPy array (or a sequence of pairs) and come out as
//! NumPy arrays; the library's errors become exceptions under one base class,
//! `AestheticCurvesError`, with the library's messages. Long fits release the GIL.

mod outline;

use ac::approx::ApproxOptions;
use ac::monotone::CurvatureMonotone;
use ac::{Curve, PlanarCurve, Point};
use aesthetic_curves as ac;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyTypeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _native,
    AestheticCurvesError,
    PyException,
    "Base class of every error the library reports."
);
create_exception!(
    _native,
    InvalidInputError,
    AestheticCurvesError,
    "An argument is out of range or malformed (the message names it)."
);
create_exception!(
    _native,
    DegenerateError,
    AestheticCurvesError,
    "Degenerate geometry: coincident points, a vanishing derivative, a zero-length chord."
);
create_exception!(
    _native,
    NoSegmentError,
    AestheticCurvesError,
    "No curve of the requested kind exists for this input."
);
create_exception!(
    _native,
    NoConvergenceError,
    AestheticCurvesError,
    "A solver did not converge, or a result overflows float64."
);
create_exception!(
    _native,
    DeadlineError,
    AestheticCurvesError,
    "The work ran past its deadline."
);

/// The library's error as the matching Python exception (same message).
fn err(e: ac::Error) -> PyErr {
    let msg = e.to_string();
    match e {
        ac::Error::InvalidInput { .. } => InvalidInputError::new_err(msg),
        ac::Error::Degenerate(_) => DegenerateError::new_err(msg),
        ac::Error::NoSegment(_) => NoSegmentError::new_err(msg),
        ac::Error::NoConvergence(_) => NoConvergenceError::new_err(msg),
        ac::Error::Timeout(_) => DeadlineError::new_err(msg),
    }
}

/// Points from an `(n, 2)` float64 array or a sequence of pairs; anything else is refused
/// with a message that names the argument, the expected shape and what was given.
fn points_arg(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Point>> {
    if let Ok(a) = obj.extract::<PyReadonlyArray2<'_, f64>>() {
        let shape = a.shape();
        if shape[1] != 2 {
            return Err(PyValueError::new_err(format!(
                "{name}: expected an array of shape (n, 2), got ({}, {})",
                shape[0], shape[1]
            )));
        }
        let v = a.as_array();
        return Ok(v
            .rows()
            .into_iter()
            .map(|r| Point::new(r[0], r[1]))
            .collect());
    }
    if obj.hasattr("dtype")? && obj.hasattr("shape")? {
        let dtype = obj.getattr("dtype")?.str()?.to_string();
        let shape = obj.getattr("shape")?.str()?.to_string();
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a float64 array of shape (n, 2), got dtype {dtype} and shape {shape} \
             (convert with numpy.asarray(x, dtype=float))"
        )));
    }
    match obj.extract::<Vec<(f64, f64)>>() {
        Ok(v) => Ok(v.into_iter().map(|(x, y)| Point::new(x, y)).collect()),
        Err(_) => Err(PyTypeError::new_err(format!(
            "{name}: expected a float64 array of shape (n, 2) or a sequence of (x, y) pairs"
        ))),
    }
}

/// A 1-D float64 array or sequence of numbers.
fn numbers_arg(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().to_vec());
    }
    if obj.hasattr("dtype")? && obj.hasattr("shape")? {
        let dtype = obj.getattr("dtype")?.str()?.to_string();
        let shape = obj.getattr("shape")?.str()?.to_string();
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a 1-D float64 array, got dtype {dtype} and shape {shape}"
        )));
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{name}: expected a 1-D float64 array or a sequence of numbers"
        ))
    })
}

fn three(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<[Point; 3]> {
    let p = points_arg(name, obj)?;
    p.try_into().map_err(|p: Vec<Point>| {
        PyValueError::new_err(format!("{name}: expected 3 points, got {}", p.len()))
    })
}

/// An (n, 2) array of x, y pairs.
fn xy_array<'py>(
    py: Python<'py>,
    xy: impl ExactSizeIterator<Item = [f64; 2]>,
) -> Bound<'py, PyArray2<f64>> {
    let n = xy.len();
    let flat: Vec<f64> = xy.flatten().collect();
    Array2::from_shape_vec((n, 2), flat)
        .expect("n x 2")
        .into_pyarray(py)
}

fn points_array<'py>(py: Python<'py>, pts: &[Point]) -> Bound<'py, PyArray2<f64>> {
    xy_array(py, pts.iter().map(|p| [p.x, p.y]))
}

fn vecs_array<'py>(py: Python<'py>, v: &[ac::Vec2]) -> Bound<'py, PyArray2<f64>> {
    xy_array(py, v.iter().map(|p| [p.x, p.y]))
}

/// A float or a 1-D array of parameters: the values of `f` at them, as a float or an array
/// (points: a (2,) or (n, 2) array).
enum Params {
    One(f64),
    Many(Vec<f64>),
}

fn params_arg(obj: &Bound<'_, PyAny>) -> PyResult<Params> {
    if let Ok(t) = obj.extract::<f64>() {
        return Ok(Params::One(t));
    }
    numbers_arg("t", obj).map(Params::Many)
}

fn eval_points<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    f: impl Fn(f64) -> Point,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match params_arg(t)? {
        Params::One(t) => {
            let p = f(t);
            vec![p.x, p.y].into_pyarray(py).into_any()
        }
        Params::Many(ts) => {
            let pts: Vec<Point> = ts.iter().map(|&t| f(t)).collect();
            points_array(py, &pts).into_any()
        }
    })
}

fn eval_numbers<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match params_arg(t)? {
        Params::One(t) => f(t).into_pyobject(py)?.into_any(),
        Params::Many(ts) => ts
            .iter()
            .map(|&t| f(t))
            .collect::<Vec<_>>()
            .into_pyarray(py)
            .into_any(),
    })
}

/// Samples of a curve: points, unit tangents and signed curvature, as arrays.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct Samples {
    /// The points, an (n, 2) array.
    points: Py<PyArray2<f64>>,
    /// Unit tangents, an (n, 2) array.
    tangents: Py<PyArray2<f64>>,
    /// Signed curvature (positive turning left), an (n,) array.
    kappa: Py<PyArray1<f64>>,
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

fn samples_of(py: Python<'_>, c: &dyn Curve, n: usize) -> PyResult<Samples> {
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
struct CurveAt {
    /// The points, an (n, 2) array.
    points: Py<PyArray2<f64>>,
    /// First derivatives with respect to the parameter, an (n, 2) array.
    d1: Py<PyArray2<f64>>,
    /// Second derivatives, an (n, 2) array.
    d2: Py<PyArray2<f64>>,
    /// Signed curvature, an (n,) array.
    kappa: Py<PyArray1<f64>>,
    /// dκ/ds, an (n,) array.
    dkappa_ds: Py<PyArray1<f64>>,
}

#[pymethods]
impl CurveAt {
    fn __len__(&self, py: Python<'_>) -> usize {
        self.kappa.bind(py).len()
    }
}

/// A float or an array of parameters, as a list.
fn params_list(u: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    Ok(match params_arg(u)? {
        Params::One(u) => vec![u],
        Params::Many(us) => us,
    })
}

/// [`Curve::at`] at a float or an array of parameters.
fn curve_at(py: Python<'_>, c: &dyn Curve, u: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
    let at: Vec<ac::CurveEval> = params_list(u)?
        .iter()
        .map(|&u| c.at(u))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    curve_at_of(py, at)
}

/// The rows of a [`CurveAt`].
fn curve_at_of(py: Python<'_>, at: Vec<ac::CurveEval>) -> PyResult<CurveAt> {
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
struct MonotoneReport {
    /// Curvature monotone along the whole curve (proven).
    monotone: bool,
    /// "increasing", "decreasing", "constant", or None when not monotone.
    trend: Option<String>,
    /// Parameters of the curvature extrema inside (0, 1), an (m,) array.
    extrema: Py<PyArray1<f64>>,
    /// Degree of the Bernstein polynomial the test examines.
    test_degree: usize,
    /// The floating-point filter could not decide: exact integer arithmetic did.
    exact: bool,
    /// How the curvature behaves at t = 0 and at t = 1.
    ends: (EndCurvature, EndCurvature),
}

/// The curvature at one end of a curve.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
#[derive(Clone)]
struct EndCurvature {
    /// "regular" (the speed does not vanish), "finite" (a retracted handle, the curvature
    /// tends to a limit) or "unbounded" (a retracted handle, the curvature grows without
    /// bound).
    kind: String,
    /// The curvature at the end (its limit at a retracted one); None where unbounded.
    curvature: Option<f64>,
    /// How many handles are retracted onto the end point (0 at a regular end).
    retracted_handles: usize,
    /// Where unbounded: the curvature grows like 1/t**growth_rate.
    growth_rate: Option<usize>,
    /// Where unbounded: the sign of the curvature near the end (+1 or -1).
    sign: Option<i8>,
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
            sign,
        }
    }
}

#[pymethods]
impl MonotoneReport {
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

fn report(py: Python<'_>, r: ac::MonotoneReport) -> MonotoneReport {
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
struct Bezier {
    inner: ac::Bezier,
}

/// A rational Bézier curve (positive weights).
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
struct RationalBezier {
    inner: ac::RationalBezier,
}

/// The file formats of [`export`].
#[derive(Clone, Copy, PartialEq)]
enum Format {
    Dxf,
    Step,
    Iges,
    Svg,
}

/// The NURBS written in `format` (DXF: bytes; STEP, IGES, SVG: text), into the file `path`
/// (then None) or returned.
fn export(
    py: Python<'_>,
    c: &ac::Nurbs,
    format: Format,
    path: Option<std::path::PathBuf>,
    name: &str,
    tolerance: f64,
) -> PyResult<Option<Py<PyAny>>> {
    use aesthetic_curves_export as ex;
    ex::check_exportable(c).map_err(|e| InvalidInputError::new_err(format!("{e:#}")))?;
    let bytes: Vec<u8> = match format {
        Format::Dxf => {
            ex::dxf_bytes(c).map_err(|e| NoConvergenceError::new_err(format!("{e:#}")))?
        }
        Format::Step => ex::step_text(c, name).into_bytes(),
        Format::Iges => ex::iges_text(c, name).into_bytes(),
        Format::Svg => {
            if !(tolerance.is_finite() && tolerance > 0.0) {
                return Err(InvalidInputError::new_err(
                    "invalid input: tolerance: must be a positive number",
                ));
            }
            let spans = c.as_curve().map_err(err)?;
            let comb = ex::curve_samples(&spans, 40).map_err(err)?;
            ex::svg_document(c, tolerance, &comb, name)
                .ok_or_else(|| DegenerateError::new_err("degenerate: the curve has no spans"))?
                .into_bytes()
        }
    };
    match path {
        Some(p) => {
            std::fs::write(&p, &bytes).map_err(|e| {
                pyo3::exceptions::PyOSError::new_err(format!("writing {}: {e}", p.display()))
            })?;
            Ok(None)
        }
        None if format == Format::Dxf => Ok(Some(
            pyo3::types::PyBytes::new(py, &bytes).into_any().unbind(),
        )),
        None => Ok(Some(
            String::from_utf8(bytes)
                .expect("text formats are UTF-8")
                .into_pyobject(py)?
                .into_any()
                .unbind(),
        )),
    }
}

/// A `#[pymethods]` block with `to_dxf`, `to_step`, `to_iges` and `to_svg` added (the class's
/// `nurbs_of(&self)` gives its NURBS; pyo3 expands no macro inside the block itself).
macro_rules! pymethods_with_exports {
    ($ty:ident { $($items:tt)* }) => {
        #[pymethods]
        impl $ty {
            $($items)*

        /// A DXF drawing (R2000) with the curve as one rational SPLINE: bytes, or None
        /// when written to `path`.
        #[pyo3(signature = (path=None))]
        fn to_dxf(
            &self,
            py: Python<'_>,
            path: Option<std::path::PathBuf>,
        ) -> PyResult<Option<Py<PyAny>>> {
            export(py, &self.nurbs_of()?, Format::Dxf, path, "", 0.0)
        }
        /// A STEP file (AP214 geometry: a rational B-spline curve) named `name`: text, or
        /// None when written to `path`.
        #[pyo3(signature = (path=None, name="curve"))]
        fn to_step(
            &self,
            py: Python<'_>,
            path: Option<std::path::PathBuf>,
            name: &str,
        ) -> PyResult<Option<Py<PyAny>>> {
            export(py, &self.nurbs_of()?, Format::Step, path, name, 0.0)
        }
        /// An IGES file (entity 126, rational B-spline curve): text, or None when written.
        #[pyo3(signature = (path=None, name="curve"))]
        fn to_iges(
            &self,
            py: Python<'_>,
            path: Option<std::path::PathBuf>,
            name: &str,
        ) -> PyResult<Option<Py<PyAny>>> {
            export(py, &self.nurbs_of()?, Format::Iges, path, name, 0.0)
        }
        /// An SVG picture of the curve (cubic Béziers within `tolerance`) with its
        /// curvature comb: text, or None when written to `path`.
        #[pyo3(signature = (path=None, tolerance=1e-3, caption="curve"))]
        fn to_svg(
            &self,
            py: Python<'_>,
            path: Option<std::path::PathBuf>,
            tolerance: f64,
            caption: &str,
        ) -> PyResult<Option<Py<PyAny>>> {
            export(py, &self.nurbs_of()?, Format::Svg, path, caption, tolerance)
        }
        }
    };
}

/// The methods every Bézier type shares (same names as the Rust API).
/// The methods of a curve made of rational cubic pieces held in `pieces` (a sketch, a
/// contour, a spline): `domain` and `at` over the pieces, the exports, and `extra`.
macro_rules! pieces_methods {
    ($ty:ident { $($extra:tt)* }) => {
        pymethods_with_exports!($ty {
    /// The parameter interval of `at`: (0, n) for n pieces (piece i on [i, i + 1]).
    fn domain(&self) -> (f64, f64) {
        (0.0, self.pieces.len() as f64)
    }
    /// Point, first and second derivatives, curvature and dκ/ds at `u` (a float or an
    /// array; piece `floor(u)` at its own t = u - floor(u); clamped into the domain).
    fn at(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
        let pieces = ac::Pieces(self.pieces.iter().map(|p| p.inner.clone()).collect());
        curve_at(py, &pieces, u)
    }
            $($extra)*
        });
    };
}

macro_rules! bezier_methods {
    ($ty:ident, { $($extra:tt)* }) => {
        pymethods_with_exports!($ty {
            $($extra)*
            /// The control points, an (n + 1, 2) array.
            #[getter]
            fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
                points_array(py, self.inner.points())
            }
            /// The degree.
            #[getter]
            fn degree(&self) -> usize {
                self.inner.degree()
            }
            /// The parameter interval of `at`: (0, 1).
            fn domain(&self) -> PyResult<(f64, f64)> {
                Curve::domain(&self.inner).map_err(err)
            }
            /// Point, first and second derivatives, curvature and dκ/ds at `t` (a float or
            /// an array; clamped into the domain).
            fn at(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
                curve_at(py, &self.inner, t)
            }
            /// The point at `t` (a float: a (2,) array; an array of n: an (n, 2) array).
            fn eval<'py>(
                &self,
                py: Python<'py>,
                t: &Bound<'py, PyAny>,
            ) -> PyResult<Bound<'py, PyAny>> {
                eval_points(py, t, |t| self.inner.eval(t))
            }
            /// Signed curvature at `t` (a float or an array).
            fn kappa<'py>(
                &self,
                py: Python<'py>,
                t: &Bound<'py, PyAny>,
            ) -> PyResult<Bound<'py, PyAny>> {
                eval_numbers(py, t, |t| self.inner.kappa(t))
            }
            /// dκ/ds at `t` (a float or an array).
            fn dkappa_ds<'py>(
                &self,
                py: Python<'py>,
                t: &Bound<'py, PyAny>,
            ) -> PyResult<Bound<'py, PyAny>> {
                eval_numbers(py, t, |t| self.inner.dkappa_ds(t))
            }
            /// The exact test's verdict alone (fast: stops at the first proof).
            fn is_curvature_monotone(&self) -> PyResult<bool> {
                self.inner.is_curvature_monotone().map_err(err)
            }
            /// The exact test with the curvature extrema located.
            fn curvature_monotone(&self, py: Python<'_>) -> PyResult<MonotoneReport> {
                Ok(report(py, self.inner.curvature_monotone().map_err(err)?))
            }
            /// The sampling test with `samples` divisions: (monotone, trend or None).
            fn curvature_monotone_sampled(
                &self,
                samples: usize,
            ) -> PyResult<(bool, Option<String>)> {
                let r = self
                    .inner
                    .curvature_monotone_sampled(samples)
                    .map_err(err)?;
                Ok((r.monotone, r.trend.map(|t| t.as_str().to_string())))
            }
            /// `n >= 2` samples (points, unit tangents, signed curvature) at uniform t.
            fn sample(&self, py: Python<'_>, n: usize) -> PyResult<Samples> {
                samples_of(py, &self.inner, n)
            }
            /// Arc length.
            fn arc_length(&self) -> PyResult<f64> {
                Curve::arc_length(&self.inner).map_err(err)
            }
            /// Signed curvature at both ends.
            fn end_curvatures(&self) -> PyResult<(f64, f64)> {
                Curve::end_curvatures(&self.inner).map_err(err)
            }
            /// SVG path data of the curve (cubic Béziers within `accuracy`).
            #[pyo3(signature = (accuracy=1e-3))]
            fn to_svg_path(&self, accuracy: f64) -> PyResult<String> {
                Ok(Curve::to_bezpath(&self.inner, accuracy)
                    .map_err(err)?
                    .to_svg())
            }
            /// The curve as a one-span NURBS.
            fn to_nurbs(&self) -> Nurbs {
                Nurbs {
                    inner: ac::Nurbs::from_bezier(&rational_of(&self.inner)),
                }
            }

            fn __repr__(&self) -> String {
                format!(
                    "{}(degree={}, points={:?})",
                    stringify!($ty),
                    self.inner.degree(),
                    self.inner
                        .points()
                        .iter()
                        .map(|p| (p.x, p.y))
                        .collect::<Vec<_>>()
                )
            }
        });
    };
}

trait AsRational {
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
fn rational_of(c: &impl AsRational) -> ac::RationalBezier {
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
fn are_curvature_monotone<'py>(
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
struct Nurbs {
    inner: ac::Nurbs,
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

/// The best curvature-monotone rational cubic of a LAC segment (G2 at both ends).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct RationalCubicFit {
    /// The rational cubic.
    curve: RationalBezier,
    /// Handle length at the start over the triangle's first side.
    f0: f64,
    /// Handle length at the end over the triangle's second side.
    f1: f64,
    /// Root mean square distance to the segment over its arc length.
    rms: f64,
    /// Largest distance over the arc length.
    max_error: f64,
    /// Proven curvature-monotone by the exact test.
    monotone: bool,
    /// The final local refinement met its stopping test.
    converged: bool,
    /// Objective evaluations spent.
    evaluations: usize,
}

pymethods_with_exports!(RationalCubicFit {


    fn __repr__(&self) -> String {
        format!(
            "RationalCubicFit(f0={}, f1={}, rms={:e}, max_error={:e}, converged={})",
            self.f0,
            self.f1,
            self.rms,
            self.max_error,
            if self.converged { "True" } else { "False" }
        )
    }
});

fn fit_of(f: ac::approx::RationalCubicFit) -> RationalCubicFit {
    RationalCubicFit {
        curve: RationalBezier { inner: f.curve },
        f0: f.f0,
        f1: f.f1,
        rms: f.rms,
        max_error: f.max_error,
        monotone: f.monotone,
        converged: f.converged,
        evaluations: f.evaluations,
    }
}

/// A rational cubic spline (pieces joined G2) approximating a segment within a tolerance.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct RationalSpline {
    /// The spline as one NURBS.
    nurbs: Nurbs,
    /// The pieces, each with its own fit report.
    pieces: Vec<Py<RationalCubicFit>>,
    /// Largest distance to the segment over all pieces, in input units.
    max_error: f64,
}

fn spline_of(py: Python<'_>, s: ac::approx::RationalSpline) -> PyResult<RationalSpline> {
    Ok(RationalSpline {
        nurbs: Nurbs { inner: s.nurbs },
        pieces: s
            .pieces
            .into_iter()
            .map(|f| Py::new(py, fit_of(f)))
            .collect::<PyResult<_>>()?,
        max_error: s.max_error,
    })
}

/// Points, unit tangents and radii of curvature.
type TurningArrays<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
);

/// The methods both LAC segment types share (`$cubic` and `$spline`: their fits in
/// `approx`), plus `$extra`.
macro_rules! lac_methods {
    ($ty:ident, $cubic:ident, $spline:ident, { $($extra:tt)* }) => {
        impl $ty {
            fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
                let f = ac::approx::$cubic(&self.inner, &ApproxOptions::default()).map_err(err)?;
                Ok(ac::Nurbs::from_bezier(&f.curve))
            }
        }

        pymethods_with_exports!($ty {
            $($extra)*
            /// The shape parameter α.
            #[getter]
            fn alpha(&self) -> f64 {
                self.inner.alpha()
            }
            /// The turning angle (radians).
            #[getter]
            fn theta_d(&self) -> f64 {
                self.inner.theta_d()
            }
            /// The control triangle, a (3, 2) array.
            #[getter]
            fn control<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
                points_array(py, &self.inner.control())
            }
            /// The parameter interval of `at`: the arc length, (0, length).
            fn domain(&self) -> PyResult<(f64, f64)> {
                Curve::domain(&self.inner).map_err(err)
            }
            /// Point, unit tangent (the first derivative in arc length), second derivative,
            /// curvature and dκ/ds (closed form) at arc length `s` from the first control
            /// point (a float or an array; clamped into the domain).
            fn at(&self, py: Python<'_>, s: &Bound<'_, PyAny>) -> PyResult<CurveAt> {
                curve_at(py, &self.inner, s)
            }
            /// Arc length.
            fn arc_length(&self) -> PyResult<f64> {
                Curve::arc_length(&self.inner).map_err(err)
            }
            /// Signed curvature at both ends (0 at an inflection end).
            fn end_curvatures(&self) -> PyResult<(f64, f64)> {
                Curve::end_curvatures(&self.inner).map_err(err)
            }
            /// `n >= 2` samples evenly spaced in tangent angle: points, unit tangents,
            /// curvature.
            fn sample(&self, py: Python<'_>, n: usize) -> PyResult<Samples> {
                samples_of(py, &self.inner, n)
            }
            /// The best curvature-monotone rational cubic (G2 at both ends, zero curvature
            /// at an inflection end; global optimisation).
            fn rational_approx(&self, py: Python<'_>) -> PyResult<RationalCubicFit> {
                let seg = self.inner.clone();
                let f = py
                    .detach(move || ac::approx::$cubic(&seg, &ApproxOptions::default()))
                    .map_err(err)?;
                Ok(fit_of(f))
            }
            /// Rational cubics (G2 joints) within `tolerance` (input units).
            #[pyo3(signature = (tolerance, max_pieces=64))]
            fn rational_spline(
                &self,
                py: Python<'_>,
                tolerance: f64,
                max_pieces: usize,
            ) -> PyResult<RationalSpline> {
                let seg = self.inner.clone();
                let s = py
                    .detach(move || {
                        ac::approx::$spline(&seg, tolerance, max_pieces, &ApproxOptions::default())
                    })
                    .map_err(err)?;
                spline_of(py, s)
            }
            /// SVG path data (cubic Béziers within `accuracy`, input units).
            #[pyo3(signature = (accuracy=1e-3))]
            fn to_svg_path(&self, accuracy: f64) -> PyResult<String> {
                Ok(self.inner.to_bezpath(accuracy).map_err(err)?.to_svg())
            }
            /// The segment as a NURBS: its best rational cubic, or with `tolerance` (input
            /// units) rational cubics within it. The exports (`to_dxf`, `to_step`,
            /// `to_iges`, `to_svg`) write the best rational cubic.
            #[pyo3(signature = (tolerance=None))]
            fn to_nurbs(&self, py: Python<'_>, tolerance: Option<f64>) -> PyResult<Nurbs> {
                match tolerance {
                    None => Ok(Nurbs {
                        inner: self.nurbs_of()?,
                    }),
                    Some(t) => Ok(self.rational_spline(py, t, 64)?.nurbs),
                }
            }
            fn __repr__(&self) -> String {
                format!(
                    "{}(alpha={}, theta_d={})",
                    stringify!($ty),
                    self.inner.alpha(),
                    self.inner.theta_d()
                )
            }
        });
    };
}

/// A log-aesthetic curve segment of shape `alpha` in a control triangle (its ends and the
/// intersection of its end tangents).
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
struct LacSegment {
    inner: ac::LacSegment,
}

lac_methods!(LacSegment, fit_rational_cubic, fit_rational_spline, {
    #[new]
    fn new(alpha: f64, control: &Bound<'_, PyAny>) -> PyResult<Self> {
        let c = three("control", control)?;
        Ok(LacSegment {
            inner: ac::LacSegment::new(alpha, c).map_err(err)?,
        })
    }
    /// Whether a segment of shape `alpha` exists in the triangle `control`.
    #[staticmethod]
    fn exists(alpha: f64, control: &Bound<'_, PyAny>) -> PyResult<bool> {
        ac::LacSegment::exists(alpha, three("control", control)?).map_err(err)
    }
    /// The largest base angle at the high-curvature end for which a segment of shape
    /// `alpha` turning by `theta_d` exists.
    #[staticmethod]
    fn theta_lim(alpha: f64, theta_d: f64) -> PyResult<f64> {
        ac::LacSegment::theta_lim(alpha, theta_d).map_err(err)
    }
    /// Points, unit tangents and radii of curvature at turning angles `taus` from the start.
    fn eval_turning<'py>(
        &self,
        py: Python<'py>,
        taus: &Bound<'py, PyAny>,
    ) -> PyResult<TurningArrays<'py>> {
        let t = numbers_arg("taus", taus)?;
        let s = self.inner.eval_turning(&t).map_err(err)?;
        Ok((
            points_array(py, &s.points),
            vecs_array(py, &s.tangents),
            s.radii.into_pyarray(py),
        ))
    }
});

/// A log-aesthetic segment with an inflection end (zero curvature at `control[0]`).
#[pyclass(module = "aesthetic_curves._native", frozen)]
#[derive(Clone)]
struct LacInflectionSegment {
    inner: ac::LacInflectionSegment,
}

lac_methods!(
    LacInflectionSegment,
    fit_inflection_cubic,
    fit_inflection_spline,
    {
        #[new]
        fn new(control: &Bound<'_, PyAny>) -> PyResult<Self> {
            Ok(LacInflectionSegment {
                inner: ac::LacInflectionSegment::new(three("control", control)?).map_err(err)?,
            })
        }
    }
);

/// The pseudo-elastic spline through points (Hermite cubics minimising the pseudo-energy).
#[pyclass(module = "aesthetic_curves._native", frozen)]
struct PseudoSpline {
    inner: ac::pseudo_spline::PseudoSpline,
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
fn pseudo_elastic(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    closed: bool,
    mode: &str,
) -> PyResult<PseudoSpline> {
    let p = points_arg("points", points)?;
    let mode = match mode {
        "table" => ac::pseudo_spline::Mode::Table,
        "exact" => ac::pseudo_spline::Mode::Exact,
        _ => {
            return Err(InvalidInputError::new_err(format!(
                "invalid input: mode: must be \"table\" or \"exact\", got {mode:?}"
            )))
        }
    };
    let inner = py
        .detach(move || ac::pseudo_spline::pseudo_elastic(&p, closed, mode))
        .map_err(err)?;
    Ok(PseudoSpline { inner })
}

/// A curve of rational cubic pieces as the Python classes hold it: one NURBS of all the
/// pieces, and each piece.
fn joined(curve: ac::Pieces<ac::RationalBezier>) -> PyResult<(Nurbs, Vec<RationalBezier>)> {
    let nurbs = Nurbs {
        inner: curve.to_nurbs(0.0).map_err(err)?,
    };
    let pieces = curve
        .0
        .into_iter()
        .map(|inner| RationalBezier { inner })
        .collect();
    Ok((nurbs, pieces))
}

/// The G2 log-aesthetic spline through points: LAC pieces of one α, G2 at every smooth
/// point, each delivered as a rational cubic proven curvature-monotone.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct LacSpline {
    /// The delivered curve, one NURBS of the pieces' rational cubics.
    nurbs: Nurbs,
    /// Each piece's rational cubic, in order.
    pieces: Vec<RationalBezier>,
    /// Each piece's kind: "line", "lac" or "lac_inflection".
    kinds: Vec<&'static str>,
    /// Each piece's span (the index of the point it starts from).
    spans: Vec<usize>,
    /// Each piece's α (None for a line).
    alphas: Vec<Option<f64>>,
    /// The unit tangent at each point (at a corner, the outgoing one).
    tangents: Vec<(f64, f64)>,
    /// Largest relative curvature jump at a smooth point, of the LAC pieces.
    max_curvature_jump: f64,
    /// The same on the delivered cubics.
    max_cubic_jump: f64,
    /// Every piece's rational cubic is proven curvature-monotone.
    all_monotone: bool,
    /// The G2 solve reached its target.
    converged: bool,
    /// Newton steps.
    iterations: usize,
    /// Closed.
    closed: bool,
}

/// The G2 log-aesthetic spline through `points`: `alpha` for every span (-1: clothoids) or
/// `alphas` one per span; `closed`; `corners` the indices of corner points.
#[pyfunction]
#[pyo3(signature = (points, alpha=-1.0, closed=false, corners=Vec::new(), alphas=None))]
fn lac_spline(
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
    Ok(LacSpline {
        nurbs,
        pieces,
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

/// One LAC segment fitted to a point sequence.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct LacFit {
    /// The segment.
    segment: LacSegment,
    /// Its α.
    alpha: f64,
    /// Root mean square distance from the points to the segment.
    rms_deviation: f64,
    /// Largest distance.
    max_deviation: f64,
    /// The fit met its stopping test.
    converged: bool,
}

/// The LAC segment nearest to `points` (an ordered sequence of at least 6), with α fitted
/// or fixed.
#[pyfunction]
#[pyo3(signature = (points, alpha=None))]
fn fit_lac(py: Python<'_>, points: &Bound<'_, PyAny>, alpha: Option<f64>) -> PyResult<LacFit> {
    let p = points_arg("points", points)?;
    let opts = ac::lac_fit::LacFitOptions {
        alpha,
        ..Default::default()
    };
    let f = py
        .detach(move || ac::lac_fit::fit_lac(&p, opts))
        .map_err(err)?;
    Ok(LacFit {
        segment: LacSegment { inner: f.segment },
        alpha: f.alpha,
        rms_deviation: f.rms_deviation,
        max_deviation: f.max_deviation,
        converged: f.converged,
    })
}

/// Pen input to a G2 curve of LAC pieces, each delivered as a rational cubic.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct Sketch {
    /// The delivered curve, one NURBS of the pieces' rational cubics.
    nurbs: Nurbs,
    /// Each piece's rational cubic.
    pieces: Vec<RationalBezier>,
    /// Each piece's α.
    alphas: Vec<f64>,
    /// Largest distance from an input point to the delivered curve.
    max_deviation: f64,
    /// Root mean square of those distances.
    rms_deviation: f64,
    /// Largest relative curvature jump at a joint.
    max_curvature_jump: f64,
    /// Every joint is G2 to the fairing's tolerance.
    g2: bool,
    /// Every piece's rational cubic is proven curvature-monotone.
    all_monotone: bool,
    /// The fairing reached its tolerance.
    converged: bool,
}

/// Fit a pen stroke (`points`, in drawing order) with LAC pieces joined G2, within
/// `tolerance` (input units).
#[pyfunction]
#[pyo3(signature = (points, tolerance))]
fn fit_sketch(py: Python<'_>, points: &Bound<'_, PyAny>, tolerance: f64) -> PyResult<Sketch> {
    let p = points_arg("points", points)?;
    let opts = ac::sketch::SketchOptions::with_tolerance(tolerance);
    let s = py
        .detach(move || ac::sketch::fit_sketch(&p, &opts))
        .map_err(err)?;
    let (nurbs, pieces) = joined(s.as_curve())?;
    Ok(Sketch {
        nurbs,
        pieces,
        alphas: s.pieces.iter().map(|p| p.alpha).collect(),
        max_deviation: s.max_deviation,
        rms_deviation: s.rms_deviation,
        max_curvature_jump: s.max_curvature_jump,
        g2: s.g2,
        all_monotone: s.all_monotone,
        converged: s.fairing.converged,
    })
}

/// A pen stroke as a contour: runs (lines and G2 curves of LAC pieces) joined at corners.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
struct SketchContour {
    /// The whole contour, one NURBS of its rational cubics (a line as a straight cubic).
    nurbs: Nurbs,
    /// Each piece's rational cubic, in order.
    pieces: Vec<RationalBezier>,
    /// Each run's kind, in order: "line" or "curve".
    runs: Vec<&'static str>,
    /// Each run's pieces (a line: 1).
    run_pieces: Vec<usize>,
    /// Each curve run's α per piece (a line: empty).
    alphas: Vec<Vec<f64>>,
    /// The corners in order, as (x, y, turn in degrees, index of the input point).
    corners: Vec<(f64, f64, f64, usize)>,
    /// The run each corner follows (the next run starts there; closed: the last may follow
    /// the last run).
    corner_runs: Vec<usize>,
    /// The smooth joins in order, where a straight stretch inside a curved part of the
    /// stroke meets a curve (G2: the curve leaves the line along it with zero curvature),
    /// as (x, y, angle in degrees, relative curvature jump, the run it follows).
    smooth_joins: Vec<(f64, f64, f64, f64, usize)>,
    /// Closed.
    closed: bool,
    /// A closed contour that is one curve (no corners, no straight stretch): (angle in
    /// degrees, relative curvature jump) where its one run ends at its start.
    seam: Option<(f64, f64)>,
    /// The tolerance used.
    tolerance: f64,
    /// Largest distance from an input point to the result.
    max_deviation: f64,
    /// Points of a closed stroke's overshoot past its start, left out.
    trimmed: usize,
    /// Every curve run is G2 inside.
    g2: bool,
    /// Every piece is proven curvature-monotone.
    all_monotone: bool,
}

/// A pen stroke (`points`, in drawing order) as a contour: corners found, straight runs
/// as lines, a stroke that ends at its start closed (`closed`: None decides from the
/// stroke); `tolerance` None for the default from the points' size and noise;
/// `corner_angle` the least turn of a corner (degrees).
#[pyfunction]
#[pyo3(signature = (points, tolerance=None, closed=None, corner_angle=35.0))]
fn fit_contour(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    tolerance: Option<f64>,
    closed: Option<bool>,
    corner_angle: f64,
) -> PyResult<SketchContour> {
    use ac::sketch::contour::{fit_contour, ContourOptions, Run};
    let p = points_arg("points", points)?;
    let opts = ContourOptions {
        tolerance,
        closed,
        corner_angle: corner_angle.to_radians(),
    };
    let c = py.detach(move || fit_contour(&p, &opts)).map_err(err)?;
    let (nurbs, pieces) = joined(c.as_curve().map_err(err)?)?;
    let curves = || {
        c.runs.iter().filter_map(|r| match r {
            Run::Curve(s) => Some(s),
            Run::Line { .. } => None,
        })
    };
    Ok(SketchContour {
        nurbs,
        pieces,
        runs: c.runs.iter().map(Run::kind).collect(),
        run_pieces: c
            .runs
            .iter()
            .map(|r| match r {
                Run::Line { .. } => 1,
                Run::Curve(s) => s.pieces.len(),
            })
            .collect(),
        alphas: c
            .runs
            .iter()
            .map(|r| match r {
                Run::Line { .. } => Vec::new(),
                Run::Curve(s) => s.pieces.iter().map(|p| p.alpha).collect(),
            })
            .collect(),
        corners: c
            .corners
            .iter()
            .map(|k| (k.point.x, k.point.y, k.angle.to_degrees(), k.index))
            .collect(),
        corner_runs: c.corners.iter().map(|k| k.run).collect(),
        smooth_joins: c
            .smooth_joins
            .iter()
            .map(|j| {
                let (x, y) = (j.point.x, j.point.y);
                (x, y, j.angle.to_degrees(), j.curvature_jump, j.run)
            })
            .collect(),
        closed: c.closed,
        seam: c.seam.map(|s| (s.angle.to_degrees(), s.curvature_jump)),
        tolerance: c.tolerance,
        max_deviation: c.max_deviation,
        trimmed: c.trimmed,
        g2: curves().all(|s| s.g2),
        all_monotone: curves().all(|s| s.all_monotone),
    })
}

impl SketchContour {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.nurbs.inner.clone())
    }
}

pieces_methods!(SketchContour {});

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
impl RationalCubicFit {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(ac::Nurbs::from_bezier(&self.curve.inner))
    }
}
impl RationalSpline {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.nurbs.inner.clone())
    }
}
impl Sketch {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.nurbs.inner.clone())
    }
}
impl PseudoSpline {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        self.inner
            .as_curve()
            .and_then(|c| c.to_nurbs(0.0))
            .map_err(err)
    }
}

pymethods_with_exports!(RationalSpline {});

pieces_methods!(Sketch {});

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add(
        "AestheticCurvesError",
        py.get_type::<AestheticCurvesError>(),
    )?;
    m.add("InvalidInputError", py.get_type::<InvalidInputError>())?;
    m.add("DegenerateError", py.get_type::<DegenerateError>())?;
    m.add("NoSegmentError", py.get_type::<NoSegmentError>())?;
    m.add("NoConvergenceError", py.get_type::<NoConvergenceError>())?;
    m.add("DeadlineError", py.get_type::<DeadlineError>())?;
    m.add_class::<Samples>()?;
    m.add_class::<MonotoneReport>()?;
    m.add_class::<EndCurvature>()?;
    m.add_class::<CurveAt>()?;
    m.add_class::<Bezier>()?;
    m.add_class::<RationalBezier>()?;
    m.add_class::<Nurbs>()?;
    m.add_class::<RationalCubicFit>()?;
    m.add_class::<RationalSpline>()?;
    m.add_class::<LacSegment>()?;
    m.add_class::<LacInflectionSegment>()?;
    m.add_class::<PseudoSpline>()?;
    m.add_class::<LacSpline>()?;
    m.add_class::<LacFit>()?;
    m.add_class::<Sketch>()?;
    m.add_class::<SketchContour>()?;
    m.add_function(wrap_pyfunction!(are_curvature_monotone, m)?)?;
    m.add_function(wrap_pyfunction!(pseudo_elastic, m)?)?;
    m.add_function(wrap_pyfunction!(lac_spline, m)?)?;
    m.add_function(wrap_pyfunction!(fit_lac, m)?)?;
    m.add_function(wrap_pyfunction!(fit_sketch, m)?)?;
    m.add_function(wrap_pyfunction!(fit_contour, m)?)?;
    m.add_function(wrap_pyfunction!(outline::check_outline, m)?)?;
    m.add_function(wrap_pyfunction!(outline::harmonize, m)?)?;
    m.add_function(wrap_pyfunction!(outline::index_contour, m)?)?;
    Ok(())
}
