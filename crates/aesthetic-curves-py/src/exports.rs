//! The CAD and SVG exports every curve class shares, and the macros that add them (and the
//! methods of Bézier curves and of curves made of pieces) to a class.

use crate::args::*;
use aesthetic_curves as ac;
use pyo3::prelude::*;

/// The file formats of [`export`].
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Format {
    Dxf,
    Step,
    Iges,
    Svg,
}

/// The NURBS written in `format` (DXF: bytes; STEP, IGES, SVG: text), into the file `path`
/// (then None) or returned.
pub(crate) fn export(
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
            ac::Error::check_positive("tolerance", tolerance).map_err(err)?;
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
