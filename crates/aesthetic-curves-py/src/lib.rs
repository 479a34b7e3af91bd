//! Python bindings of the `aesthetic-curves` library: the extension module
//! `aesthetic_curves._native`, re-exported by the Python package `aesthetic_curves`.
//!
//! Every class wraps a library type and calls it directly (no JSON protocol, no process).
//! Points go in as an `(n, 2)` float64 NumPy array (or a sequence of pairs) and come out as
//! NumPy arrays; the library's errors become exceptions under one base class,
//! `AestheticCurvesError`, with the library's messages. Long fits release the GIL.

#[macro_use]
mod exports;
mod args;
mod curves;
mod lac;
mod outline;
mod sketch;
mod splines;

use args::*;
use curves::*;
use lac::*;
use pyo3::prelude::*;
use sketch::*;
use splines::*;

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
    m.add_class::<SplineSegment>()?;
    m.add_class::<LacFit>()?;
    m.add_class::<Sketch>()?;
    m.add_class::<SketchSegment>()?;
    m.add_class::<FairingReport>()?;
    m.add_class::<BSpline>()?;
    m.add_class::<SketchContour>()?;
    m.add_class::<Corner>()?;
    m.add_class::<SmoothJoin>()?;
    m.add_class::<Seam>()?;
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
