//! Arguments in and results out: the library's errors as Python exceptions, points and
//! numbers from NumPy arrays or sequences, arrays back, curve parameters.

use ac::Point;
use aesthetic_curves as ac;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
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
pub(crate) fn err(e: ac::Error) -> PyErr {
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
pub(crate) fn points_arg(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Point>> {
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
    if let Ok(v) = obj.extract::<Vec<(f64, f64)>>() {
        return Ok(v.into_iter().map(|(x, y)| Point::new(x, y)).collect());
    }
    // Lists of lists, `[[0, 0], [1, 2]]`, numbers int or float: each pair checked.
    let Ok(rows) = obj.extract::<Vec<Vec<f64>>>() else {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected a float64 array of shape (n, 2) or a sequence of (x, y) pairs"
        )));
    };
    rows.into_iter()
        .enumerate()
        .map(|(i, r)| match r[..] {
            [x, y] => Ok(Point::new(x, y)),
            _ => Err(PyValueError::new_err(format!(
                "{name}[{i}]: expected an (x, y) pair, got {} numbers",
                r.len()
            ))),
        })
        .collect()
}

/// A 1-D float64 array or sequence of numbers.
pub(crate) fn numbers_arg(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
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

pub(crate) fn three(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<[Point; 3]> {
    let p = points_arg(name, obj)?;
    p.try_into().map_err(|p: Vec<Point>| {
        PyValueError::new_err(format!("{name}: expected 3 points, got {}", p.len()))
    })
}

/// An (n, 2) array of x, y pairs.
pub(crate) fn xy_array<'py>(
    py: Python<'py>,
    xy: impl ExactSizeIterator<Item = [f64; 2]>,
) -> Bound<'py, PyArray2<f64>> {
    let n = xy.len();
    let flat: Vec<f64> = xy.flatten().collect();
    Array2::from_shape_vec((n, 2), flat)
        .expect("n x 2")
        .into_pyarray(py)
}

pub(crate) fn points_array<'py>(py: Python<'py>, pts: &[Point]) -> Bound<'py, PyArray2<f64>> {
    xy_array(py, pts.iter().map(|p| [p.x, p.y]))
}

pub(crate) fn vecs_array<'py>(py: Python<'py>, v: &[ac::Vec2]) -> Bound<'py, PyArray2<f64>> {
    xy_array(py, v.iter().map(|p| [p.x, p.y]))
}

/// A float or a 1-D array of parameters: the values of `f` at them, as a float or an array
/// (points: a (2,) or (n, 2) array).
pub(crate) enum Params {
    One(f64),
    Many(Vec<f64>),
}

pub(crate) fn params_arg(obj: &Bound<'_, PyAny>) -> PyResult<Params> {
    if let Ok(t) = obj.extract::<f64>() {
        return Ok(Params::One(t));
    }
    numbers_arg("t", obj).map(Params::Many)
}

pub(crate) fn eval_points<'py>(
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

pub(crate) fn eval_numbers<'py>(
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
