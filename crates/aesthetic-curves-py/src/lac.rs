//! Log-aesthetic segments (ordinary and inflection-end), their rational cubic fits, and the
//! single-LAC fit to points.

use crate::args::*;
use crate::curves::*;
use crate::exports::*;
use ac::approx::ApproxOptions;
use ac::Curve;
use aesthetic_curves as ac;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// The best curvature-monotone rational cubic of a LAC segment (G2 at both ends).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct RationalCubicFit {
    /// The rational cubic.
    pub(crate) curve: RationalBezier,
    /// Handle length at the start over the triangle's first side.
    pub(crate) f0: f64,
    /// Handle length at the end over the triangle's second side.
    pub(crate) f1: f64,
    /// Root mean square distance to the segment over its arc length.
    pub(crate) rms: f64,
    /// Largest distance over the arc length.
    pub(crate) max_error: f64,
    /// Proven curvature-monotone by the exact test.
    pub(crate) monotone: bool,
    /// The final local refinement met its stopping test.
    pub(crate) converged: bool,
    /// Objective evaluations spent.
    pub(crate) evaluations: usize,
    /// The cubic's control points, a (4, 2) array (the protocol's `control_points`).
    pub(crate) control_points: Py<PyArray2<f64>>,
    /// The cubic's weights (the protocol's `weights`).
    pub(crate) weights: Py<PyArray1<f64>>,
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

pub(crate) fn fit_of(py: Python<'_>, f: ac::approx::RationalCubicFit) -> RationalCubicFit {
    RationalCubicFit {
        control_points: points_array(py, f.curve.points()).unbind(),
        weights: f.curve.weights().to_vec().into_pyarray(py).unbind(),
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
pub(crate) struct RationalSpline {
    /// The spline as one NURBS.
    pub(crate) nurbs: Nurbs,
    /// The pieces, each with its own fit report.
    pub(crate) pieces: Vec<Py<RationalCubicFit>>,
    /// Largest distance to the segment over all pieces, in input units.
    pub(crate) max_error: f64,
}

pub(crate) fn spline_of(py: Python<'_>, s: ac::approx::RationalSpline) -> PyResult<RationalSpline> {
    Ok(RationalSpline {
        nurbs: Nurbs { inner: s.nurbs },
        pieces: s
            .pieces
            .into_iter()
            .map(|f| Py::new(py, fit_of(py, f)))
            .collect::<PyResult<_>>()?,
        max_error: s.max_error,
    })
}

/// Points, unit tangents and radii of curvature.
pub(crate) type TurningArrays<'py> = (
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
                Ok(fit_of(py, f))
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
pub(crate) struct LacSegment {
    pub(crate) inner: ac::LacSegment,
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
pub(crate) struct LacInflectionSegment {
    pub(crate) inner: ac::LacInflectionSegment,
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

/// One LAC segment fitted to a point sequence.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct LacFit {
    /// The segment.
    pub(crate) segment: LacSegment,
    /// Its α.
    pub(crate) alpha: f64,
    /// Root mean square distance from the points to the segment.
    pub(crate) rms_deviation: f64,
    /// Largest distance.
    pub(crate) max_deviation: f64,
    /// The fit met its stopping test.
    pub(crate) converged: bool,
    /// The segment's control triangle, a (3, 2) array.
    pub(crate) control: Py<PyArray2<f64>>,
    /// Root mean square distance at arc-length correspondence (the paper's measure).
    pub(crate) rms_correspondence: f64,
    /// The objective minimised: "band", "distance" or "arc_length".
    pub(crate) objective: &'static str,
    /// The segment's largest curvature.
    pub(crate) max_curvature: f64,
    /// α stopped at the library's bound.
    pub(crate) alpha_at_bound: bool,
    /// The curvature cap the fit held, where it held one.
    pub(crate) curvature_cap: Option<f64>,
    /// The paper start's guess of α, where there is one.
    pub(crate) alpha_guess: Option<f64>,
}

/// The LAC segment nearest to `points` (an ordered sequence of at least 6), with α fitted
/// or fixed.
#[pyfunction]
#[pyo3(signature = (points, alpha=None, objective="band", start="scan"))]
pub(crate) fn fit_lac(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    alpha: Option<f64>,
    objective: &str,
    start: &str,
) -> PyResult<LacFit> {
    let p = points_arg("points", points)?;
    let opts = ac::lac_fit::LacFitOptions {
        alpha,
        objective: ac::lac_fit::LacFitObjective::from_name(objective).map_err(err)?,
        start: ac::lac_fit::LacFitStart::from_name(start).map_err(err)?,
    };
    let f = py
        .detach(move || ac::lac_fit::fit_lac(&p, opts))
        .map_err(err)?;
    Ok(LacFit {
        control: points_array(py, &f.segment.control()).unbind(),
        rms_correspondence: f.rms_correspondence,
        objective: opts.objective.as_str(),
        max_curvature: f.max_curvature,
        alpha_at_bound: f.alpha_at_bound,
        curvature_cap: f.curvature_cap,
        alpha_guess: f.alpha_guess,
        segment: LacSegment { inner: f.segment },
        alpha: f.alpha,
        rms_deviation: f.rms_deviation,
        max_deviation: f.max_deviation,
        converged: f.converged,
    })
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

pymethods_with_exports!(RationalSpline {});
