//! Pen input: the G2 sketch of one stroke, and the contour of runs and corners.

use crate::args::*;
use crate::curves::*;
use crate::exports::*;
use aesthetic_curves as ac;
use numpy::PyArray2;
use pyo3::prelude::*;

/// One piece of a sketch, with the fields of the protocol's `segments` entries.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct SketchSegment {
    /// "lac" or "lac_inflection".
    pub(crate) kind: &'static str,
    /// Its α.
    pub(crate) alpha: f64,
    /// α sits on the bound of its fit (the data do not pin it down).
    pub(crate) alpha_at_bound: bool,
    /// For a "lac" piece, the α values that fit its points as closely as their noise lets
    /// one tell (within the tolerance); None for an inflection piece.
    pub(crate) alpha_range: Option<(f64, f64)>,
    /// The points determine α (alpha_range at most 0.1 wide).
    pub(crate) alpha_determined: bool,
    /// α estimated from the piece's curvature graph (None for inflection pieces and
    /// pieces of nearly constant curvature).
    pub(crate) alpha_estimate: Option<f64>,
    /// Its control triangle in curve order, a (3, 2) array.
    pub(crate) control: Py<PyArray2<f64>>,
    /// Signed curvature at its start and end.
    pub(crate) end_curvatures: (f64, f64),
    /// Its rational cubic.
    pub(crate) rational: RationalBezier,
    /// Largest distance of the cubic from the segment.
    pub(crate) rational_error: f64,
    /// The cubic's curvature is proven monotone.
    pub(crate) monotone: bool,
}

/// What the sketch's G2 fairing did (the protocol's `fairing`).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct FairingReport {
    /// It reached its target.
    pub(crate) converged: bool,
    /// Newton iterations.
    pub(crate) iterations: usize,
    /// Largest relative curvature jump before.
    pub(crate) initial_jump: f64,
    /// Largest relative curvature jump after.
    pub(crate) final_jump: f64,
}

/// The smoothing B-spline a sketch's pieces were fitted to (the protocol's `bspline`).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct BSpline {
    /// Its degree.
    pub(crate) degree: usize,
    /// Its knots.
    pub(crate) knots: Vec<f64>,
    /// Its control points, an (n, 2) array.
    pub(crate) control_points: Py<PyArray2<f64>>,
}

/// A corner of a contour (the protocol's `corners` entries).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct Corner {
    /// The stroke point at the corner.
    pub(crate) index: usize,
    /// Where it is, (x, y).
    pub(crate) point: (f64, f64),
    /// The turn there (degrees).
    pub(crate) angle_degrees: f64,
    /// The run that ends there (the next run, or a closed contour's first, starts there).
    pub(crate) run: usize,
}

#[pymethods]
impl Corner {
    fn __repr__(&self) -> String {
        format!(
            "Corner(index={}, point=({}, {}), angle_degrees={}, run={})",
            self.index, self.point.0, self.point.1, self.angle_degrees, self.run
        )
    }
}

/// A smooth join between a line and a curve of a contour (the protocol's `smooth_joins`
/// entries).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct SmoothJoin {
    /// The run that ends there (the next run, or a closed contour's first, starts there).
    pub(crate) run: usize,
    /// Where it is, (x, y).
    pub(crate) point: (f64, f64),
    /// The tangent break (degrees).
    pub(crate) angle_degrees: f64,
    /// The relative curvature jump.
    pub(crate) curvature_jump: f64,
}

#[pymethods]
impl SmoothJoin {
    fn __repr__(&self) -> String {
        format!(
            "SmoothJoin(run={}, point=({}, {}), angle_degrees={}, curvature_jump={})",
            self.run, self.point.0, self.point.1, self.angle_degrees, self.curvature_jump
        )
    }
}

/// The seam of a closed contour that is one curve (the protocol's `seam`).
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct Seam {
    /// The tangent break (degrees).
    pub(crate) angle_degrees: f64,
    /// The relative curvature jump.
    pub(crate) curvature_jump: f64,
}

#[pymethods]
impl Seam {
    fn __repr__(&self) -> String {
        format!(
            "Seam(angle_degrees={}, curvature_jump={})",
            self.angle_degrees, self.curvature_jump
        )
    }
}

/// Pen input to a G2 curve of LAC pieces, each delivered as a rational cubic.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct Sketch {
    /// The delivered curve, one NURBS of the pieces' rational cubics.
    pub(crate) nurbs: Nurbs,
    /// Each piece's rational cubic.
    pub(crate) pieces: Vec<RationalBezier>,
    /// Each piece's α.
    pub(crate) alphas: Vec<f64>,
    /// Each piece with the protocol's fields, in order.
    pub(crate) segments: Vec<Py<SketchSegment>>,
    /// The fairing's report.
    pub(crate) fairing: Py<FairingReport>,
    /// The intermediate smoothing B-spline.
    pub(crate) bspline: Py<BSpline>,
    /// Largest distance from an input point to the delivered curve.
    pub(crate) max_deviation: f64,
    /// Root mean square of those distances.
    pub(crate) rms_deviation: f64,
    /// Largest relative curvature jump at a joint.
    pub(crate) max_curvature_jump: f64,
    /// Every joint is G2 to the fairing's tolerance.
    pub(crate) g2: bool,
    /// Every piece's rational cubic is proven curvature-monotone.
    pub(crate) all_monotone: bool,
    /// The fairing reached its tolerance.
    pub(crate) converged: bool,
    /// The tolerance used.
    pub(crate) tolerance: f64,
    /// Inflections.
    pub(crate) inflections: usize,
    /// Curvature extrema.
    pub(crate) curvature_extrema: usize,
}

/// Fit a pen stroke (`points`, in drawing order) with LAC pieces joined G2, within
/// `tolerance` (input units; None: the default from the points, as the protocol's).
#[pyfunction]
#[pyo3(signature = (points, tolerance=None))]
pub(crate) fn fit_sketch(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    tolerance: Option<f64>,
) -> PyResult<Sketch> {
    let p = points_arg("points", points)?;
    let (s, tolerance) = py
        .detach(move || ac::sketch::fit_sketch_within(&p, tolerance))
        .map_err(err)?;
    let (nurbs, pieces) = joined(s.as_curve())?;
    let segments = s
        .pieces
        .iter()
        .map(|q| {
            Py::new(
                py,
                SketchSegment {
                    kind: q.kind.as_str(),
                    alpha: q.alpha,
                    alpha_at_bound: q.alpha_at_bound,
                    alpha_range: q.alpha_range,
                    alpha_determined: q.alpha_determined(),
                    alpha_estimate: q.alpha_estimate,
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
    let f = &s.fairing;
    let fairing = Py::new(
        py,
        FairingReport {
            converged: f.converged,
            iterations: f.iterations,
            initial_jump: f.initial_jump,
            final_jump: f.final_jump,
        },
    )?;
    let bspline = Py::new(
        py,
        BSpline {
            degree: s.bspline.degree,
            knots: s.bspline.knots.clone(),
            control_points: points_array(py, &s.bspline.control_points).unbind(),
        },
    )?;
    Ok(Sketch {
        nurbs,
        pieces,
        alphas: s.pieces.iter().map(|p| p.alpha).collect(),
        segments,
        fairing,
        bspline,
        max_deviation: s.max_deviation,
        rms_deviation: s.rms_deviation,
        max_curvature_jump: s.max_curvature_jump,
        g2: s.g2,
        all_monotone: s.all_monotone,
        converged: s.fairing.converged,
        tolerance,
        inflections: s.inflections,
        curvature_extrema: s.curvature_extrema,
    })
}

/// A pen stroke as a contour: runs (lines and G2 curves of LAC pieces) joined at corners.
#[pyclass(module = "aesthetic_curves._native", frozen, get_all)]
pub(crate) struct SketchContour {
    /// The whole contour, one NURBS of its rational cubics (a line as a straight cubic).
    pub(crate) nurbs: Nurbs,
    /// Each piece's rational cubic, in order.
    pub(crate) pieces: Vec<RationalBezier>,
    /// Each run's kind, in order: "line" or "curve".
    pub(crate) runs: Vec<&'static str>,
    /// Each run's pieces (a line: 1).
    pub(crate) run_pieces: Vec<usize>,
    /// Each curve run's α per piece (a line: empty).
    pub(crate) alphas: Vec<Vec<f64>>,
    /// The corners in order.
    pub(crate) corners: Vec<Py<Corner>>,
    /// The smooth joins in order, where a straight stretch inside a curved part of the
    /// stroke meets a curve (G2: the curve leaves the line along it with zero curvature).
    pub(crate) smooth_joins: Vec<Py<SmoothJoin>>,
    /// Closed.
    pub(crate) closed: bool,
    /// A closed contour that is one curve (no corners, no straight stretch): where its one
    /// run ends at its start.
    pub(crate) seam: Option<Py<Seam>>,
    /// The tolerance used.
    pub(crate) tolerance: f64,
    /// Largest distance from an input point to the result.
    pub(crate) max_deviation: f64,
    /// Points of a closed stroke's overshoot past its start, left out.
    pub(crate) trimmed: usize,
    /// Every curve run is G2 inside.
    pub(crate) g2: bool,
    /// Every piece is proven curvature-monotone.
    pub(crate) all_monotone: bool,
}

/// A pen stroke (`points`, in drawing order) as a contour: corners found, straight runs
/// as lines, a stroke that ends at its start closed (`closed`: None decides from the
/// stroke); `tolerance` None for the default from the points' size and noise;
/// `corner_angle` the least turn of a corner (degrees); `resolution` the size of one
/// device pixel in the points' units (None: read from the points), the default tolerance
/// at least three of them.
#[pyfunction]
#[pyo3(signature = (points, tolerance=None, closed=None, corner_angle=35.0, resolution=None))]
pub(crate) fn fit_contour(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    tolerance: Option<f64>,
    closed: Option<bool>,
    corner_angle: f64,
    resolution: Option<f64>,
) -> PyResult<SketchContour> {
    use ac::sketch::contour::{fit_contour, ContourOptions, Run};
    let p = points_arg("points", points)?;
    let opts = ContourOptions {
        tolerance,
        closed,
        corner_angle: corner_angle.to_radians(),
        resolution,
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
            .map(|k| {
                let corner = Corner {
                    index: k.index,
                    point: (k.point.x, k.point.y),
                    angle_degrees: k.angle.to_degrees(),
                    run: k.run,
                };
                Py::new(py, corner)
            })
            .collect::<PyResult<_>>()?,
        smooth_joins: c
            .smooth_joins
            .iter()
            .map(|j| {
                let join = SmoothJoin {
                    run: j.run,
                    point: (j.point.x, j.point.y),
                    angle_degrees: j.angle.to_degrees(),
                    curvature_jump: j.curvature_jump,
                };
                Py::new(py, join)
            })
            .collect::<PyResult<_>>()?,
        closed: c.closed,
        seam: c
            .seam
            .map(|s| {
                let seam = Seam {
                    angle_degrees: s.angle.to_degrees(),
                    curvature_jump: s.curvature_jump,
                };
                Py::new(py, seam)
            })
            .transpose()?,
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

impl Sketch {
    fn nurbs_of(&self) -> PyResult<ac::Nurbs> {
        Ok(self.nurbs.inner.clone())
    }
}

pieces_methods!(Sketch {});
