//! The outline check and the harmonize repair for Python: plain lists and dicts,
//! so that a fontTools pen (`aesthetic_curves.pens`) can feed them glyph by glyph.

use crate::{err, points_arg};
use ac::outline::{check_contour, findings};
use ac::Point;
use aesthetic_curves as ac;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// `(segments, closed)` pairs: each segment a sequence of 2 to 21 points.
fn contours_arg(obj: &Bound<'_, PyAny>) -> PyResult<Vec<(Vec<Vec<Point>>, bool)>> {
    let mut out = Vec::new();
    for (ci, item) in obj.try_iter()?.enumerate() {
        let item = item?;
        let (segs, closed): (Bound<'_, PyAny>, bool) = item.extract().map_err(|_| {
            PyValueError::new_err(format!(
                "contours[{ci}]: expected a (segments, closed) pair"
            ))
        })?;
        let mut segments = Vec::new();
        for (si, s) in segs.try_iter()?.enumerate() {
            let pts = points_arg(&format!("contours[{ci}] segment {si}"), &s?)?;
            if !(2..=21).contains(&pts.len()) {
                return Err(PyValueError::new_err(format!(
                    "contours[{ci}] segment {si}: {} points (2 to 21)",
                    pts.len()
                )));
            }
            segments.push(pts);
        }
        out.push((segments, closed));
    }
    Ok(out)
}

fn xy(py: Python<'_>, p: Point) -> PyResult<Bound<'_, PyAny>> {
    Ok((p.x, p.y).into_pyobject(py)?.into_any())
}

/// The exact check of an outline: `contours` is a sequence of `(segments, closed)`, each
/// segment its control points (a line 2, a quadratic 3, a cubic 4; each starting where the
/// previous one ends). Returns `{"contours": [{"segments": [...], "joins": [...]}],
/// "findings": [...]}`: per segment `degree`, `monotone`, `extrema` (parameters), `bump`;
/// per join `after_segment`, `angle_degrees`, `g1`, `g2`, `curvature_jump`; findings worst
/// first with `contour`, `segment`, `kind`, `point`, `severity`, `message`.
#[pyfunction]
#[pyo3(signature = (contours, grid = 0.0, g1_angle = 0.05, g2_jump = 0.05, near_break = 3.0, min_bump = 0.05))]
pub(crate) fn check_outline<'py>(
    py: Python<'py>,
    contours: &Bound<'py, PyAny>,
    grid: f64,
    g1_angle: f64,
    g2_jump: f64,
    near_break: f64,
    min_bump: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let input = contours_arg(contours)?;
    let opts = ac::outline::Thresholds {
        g1_angle_degrees: g1_angle,
        g2_jump,
        near_break_degrees: near_break,
        min_bump,
    }
    .options(grid)
    .map_err(err)?;
    let mut beziers = Vec::with_capacity(input.len());
    for (segs, closed) in &input {
        let mut row = Vec::with_capacity(segs.len());
        for s in segs {
            row.push(ac::Bezier::new(s.clone()).map_err(err)?.to_rational());
        }
        beziers.push((row, *closed));
    }
    let checks: Vec<_> = py.detach(|| {
        beziers
            .iter()
            .map(|(s, c)| check_contour(s, *c, &opts))
            .collect()
    });
    let found = findings(&checks, &opts);
    let out = PyDict::new(py);
    let list = PyList::empty(py);
    for c in &checks {
        let d = PyDict::new(py);
        let segs = PyList::empty(py);
        for s in &c.segments {
            let e = PyDict::new(py);
            e.set_item("degree", s.degree)?;
            e.set_item("monotone", s.monotone)?;
            e.set_item("extrema", s.extrema.iter().map(|x| x.0).collect::<Vec<_>>())?;
            e.set_item("bump", s.bump)?;
            e.set_item("flag", s.flag.clone())?;
            segs.append(e)?;
        }
        let joins = PyList::empty(py);
        for j in &c.joins {
            let e = PyDict::new(py);
            e.set_item("after_segment", j.after_segment)?;
            e.set_item("angle_degrees", j.angle_break.to_degrees())?;
            e.set_item("g1", j.g1)?;
            e.set_item("g2", j.g2)?;
            e.set_item("curvature_jump", j.curvature_jump)?;
            joins.append(e)?;
        }
        d.set_item("segments", segs)?;
        d.set_item("joins", joins)?;
        list.append(d)?;
    }
    out.set_item("contours", list)?;
    let fl = PyList::empty(py);
    for f in &found {
        let e = PyDict::new(py);
        e.set_item("contour", f.contour)?;
        e.set_item("segment", f.segment)?;
        e.set_item("kind", f.kind)?;
        e.set_item("point", xy(py, f.point)?)?;
        e.set_item("severity", f.score)?;
        e.set_item("message", &f.message)?;
        fl.append(e)?;
    }
    out.set_item("findings", fl)?;
    Ok(out)
}

/// Repair one contour of lines (2 points) and cubics (4 points) as `aecurve fix` does:
/// `smooth[j]` says whether the join after segment j is meant smooth; with `bumps`, cubics
/// with a curvature hook near an end or several extrema get monotone handle lengths first
/// where some exist within the tolerance. Returns `{"segments": [...], "joins": [...],
/// "moved": [...], "bumps": [...], "bumps_undecided": [...]}`: the new control points (only
/// handles move, along their tangents, at most `tolerance`, on the `grid`), per join
/// `after_segment`, `outcome`, `jump` and `angle_degrees` (each a (before, after) pair), the
/// segments whose bump was removed, and those whose repair search ran out of its budget for
/// exact arithmetic (coordinates spanning hundreds of orders of magnitude).
#[pyfunction]
#[pyo3(signature = (segments, closed, smooth, tolerance = 2.0, grid = 0.0, bumps = true))]
pub(crate) fn harmonize<'py>(
    py: Python<'py>,
    segments: &Bound<'py, PyAny>,
    closed: bool,
    smooth: Vec<bool>,
    tolerance: f64,
    grid: f64,
    bumps: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let mut segs = Vec::new();
    for (i, s) in segments.try_iter()?.enumerate() {
        segs.push(points_arg(&format!("segments[{i}]"), &s?)?);
    }
    let opts = ac::harmonize::HarmonizeOptions {
        tolerance,
        grid,
        ..Default::default()
    };
    let what = ac::harmonize::Repairs {
        bumps,
        ..Default::default()
    };
    let h = py
        .detach(|| ac::harmonize::repair(&segs, closed, &smooth, &opts, &what))
        .map_err(err)?;
    let out = PyDict::new(py);
    let pts: Vec<Vec<(f64, f64)>> = h
        .segments
        .iter()
        .map(|s| s.iter().map(|p| (p.x, p.y)).collect())
        .collect();
    out.set_item("segments", pts)?;
    out.set_item("moved", h.moved.clone())?;
    let joins = PyList::empty(py);
    for j in &h.joins {
        let e = PyDict::new(py);
        e.set_item("after_segment", j.after_segment)?;
        e.set_item("outcome", format!("{:?}", j.outcome).to_lowercase())?;
        e.set_item("jump", j.jump)?;
        e.set_item(
            "angle_degrees",
            (j.angle.0.to_degrees(), j.angle.1.to_degrees()),
        )?;
        joins.append(e)?;
    }
    out.set_item("joins", joins)?;
    let fixed: Vec<usize> = h.bumps.iter().map(|b| b.segment).collect();
    out.set_item("bumps", fixed)?;
    out.set_item("bumps_undecided", h.bumps_undecided.clone())?;
    Ok(out)
}

/// The segments of a UFO-style point list (`points`: `(x, y, type, smooth)` with `type` one
/// of "move", "line", "curve", "qcurve" or None for an off-curve point) with the indices of
/// their points: `(segments, indices, closed, smooth)`, or `(None, reason)` when the contour
/// is not one of lines and cubics (the same reader as `aecurve fix`).
#[pyfunction]
pub(crate) fn index_contour<'py>(
    py: Python<'py>,
    points: Vec<(f64, f64, Option<String>, bool)>,
) -> PyResult<Bound<'py, PyAny>> {
    use ac::contour_points::{ListPoint, PointKind as K};
    let mut list = Vec::with_capacity(points.len());
    for (i, (x, y, t, smooth)) in points.into_iter().enumerate() {
        let kind = match t.as_deref() {
            None => K::OffCurve,
            Some("move") => K::Move,
            Some("line") => K::Line,
            Some("curve") => K::Curve,
            Some("qcurve") => K::QCurve,
            Some(other) => {
                return Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "points[{i}]: type {other:?} is not move, line, curve, qcurve or None"
                )))
            }
        };
        list.push(ListPoint {
            at: ac::Point::new(x, y),
            kind,
            smooth,
        });
    }
    let out = match ac::contour_points::index_contour(&list) {
        Ok(c) => {
            let segs: Vec<Vec<(f64, f64)>> = c
                .segments
                .iter()
                .map(|s| s.iter().map(|p| (p.x, p.y)).collect())
                .collect();
            (segs, c.indices, c.closed, c.smooth)
                .into_pyobject(py)?
                .into_any()
        }
        Err(ac::Error::InvalidInput { message, .. }) => {
            (py.None(), message).into_pyobject(py)?.into_any()
        }
        Err(e) => return Err(err(e)),
    };
    Ok(out)
}
