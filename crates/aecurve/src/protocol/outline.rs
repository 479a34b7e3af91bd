//! Outlines: `outline.check` (the exact check of one outline, `aecurve check` for one
//! shape) and `outline.fix` (one contour repaired as `aecurve fix` repairs an SVG path).

use super::drawing::{drawing_budget, drawing_json, Drawing, MAX_DRAWING_POINTS};
use super::fields::{
    check_weight_count, weights, Draw, List, NonNegative, Points, Positive, Weights,
};
use super::piece::RationalJson;
use super::{xy, Op, ProtoError, Request};
use crate::check_json::{shape_json, FindingJson, ShapeJson};
use crate::outline_io::{check_shapes, options_for, Outlines};
use aesthetic_curves::{Point, RationalBezier};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Longest SVG path data `outline.check` accepts (characters).
pub const MAX_PATH_DATA: usize = 1 << 20;

/// Most segments `outline.check` checks and answers for in one request (as `segments`, or in
/// the shapes it checks of a path, an SVG or a file): each costs about 2 KB of answer and up
/// to 15 KB of memory while the answer is built, so an answer stays near 150 MB.
pub const MAX_OUTLINE_SEGMENTS: usize = 10_000;

/// Most points an `outline.check` drawing holds (segments times `draw`).
pub const MAX_OUTLINE_DRAWING: usize = MAX_DRAWING_POINTS;

/// Largest file `outline.check` takes in `svg` or `file` (bytes).
pub const MAX_OUTLINE_FILE: usize = 3 << 20;

/// One segment of an outline to check: a Bézier curve, polynomial or rational.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CheckSegment {
    /// Control points (a line, a quadratic, a cubic, ... up to degree 20).
    pub control_points: Points<2, 21>,
    /// Positive weights, one per control point.
    #[serde(default)]
    pub weights: Option<Weights>,
}

/// A file's name and bytes.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FileJson {
    /// Its name: the extension says what it is (.ttf, .otf, .ttc, .otc, .svg, .dxf).
    #[serde(default)]
    pub name: String,
    /// Its bytes, base64.
    pub base64: String,
}

/// An outline to check: one of `path`, `segments`, `svg` or `file`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutlineCheckRequest {
    /// SVG path data (arcs become cubics, as usvg writes them).
    #[serde(default)]
    pub path: Option<String>,
    /// Consecutive segments of one contour.
    #[serde(default)]
    pub segments: Option<List<CheckSegment, 1, MAX_OUTLINE_SEGMENTS>>,
    /// With `segments`: a closed contour (default false).
    #[serde(default)]
    pub closed: Option<bool>,
    /// An SVG document's text.
    #[serde(default)]
    pub svg: Option<String>,
    /// A font, an SVG or a DXF file.
    #[serde(default)]
    pub file: Option<FileJson>,
    /// Check only this shape (an index into `shape_names`).
    #[serde(default)]
    pub shape: Option<usize>,
    /// Suggest monotone cubics within this distance for the cubics that are not.
    #[serde(default)]
    pub suggest: Option<Positive>,
    /// Points per segment of a `drawing` of the (first) shape.
    #[serde(default)]
    pub draw: Option<Draw>,
}

/// `segments[i]` starts where `segments[i - 1]` ends (to 1e-9 of its size).
fn check_consecutive<'a>(
    ends: impl Iterator<Item = (&'a [Point], &'a [Point])>,
) -> Result<(), ProtoError> {
    for (i, (a, b)) in ends.enumerate() {
        let gap = (a[a.len() - 1] - b[0]).hypot();
        let size = (b[0] - b[b.len() - 1]).hypot().max(1.0);
        if gap > 1e-9 * size {
            return Err(ProtoError::invalid(
                &format!("segments[{}]", i + 1),
                "must start where the previous segment ends",
            ));
        }
    }
    Ok(())
}

impl Request for OutlineCheckRequest {
    fn check(&self) -> Result<(), ProtoError> {
        let given = [
            self.path.is_some(),
            self.segments.is_some(),
            self.svg.is_some(),
            self.file.is_some(),
        ];
        if given.iter().filter(|g| **g).count() != 1 {
            return Err(ProtoError::invalid(
                "path",
                "give one of path (SVG path data), segments, svg (an SVG document) or file",
            ));
        }
        if self.path.as_ref().is_some_and(|d| d.len() > MAX_PATH_DATA) {
            return Err(ProtoError::invalid(
                "path",
                format!("longer than {MAX_PATH_DATA} characters"),
            ));
        }
        if let Some(s) = &self.segments {
            for (i, s) in s.0.iter().enumerate() {
                if let Some(w) = &s.weights {
                    let field = format!("segments[{i}].weights");
                    check_weight_count(&field, s.control_points.0.len(), w.len())?;
                }
            }
            let pts: Vec<&[Point]> = s.0.iter().map(|s| s.control_points.0.as_slice()).collect();
            check_consecutive(pts.windows(2).map(|w| (w[0], w[1])))?;
        }
        Ok(())
    }
}

impl OutlineCheckRequest {
    /// The outlines the request gives.
    fn outlines(self) -> Result<Outlines, ProtoError> {
        if let Some(d) = &self.path {
            return path_outlines(d);
        }
        if let Some(segs) = self.segments {
            let segments = segs
                .0
                .into_iter()
                .map(|s| {
                    let n = s.control_points.0.len();
                    let w = s.weights.map_or_else(|| vec![1.0; n], |w| weights(&w));
                    RationalBezier::new(s.control_points.0, w)
                })
                .collect::<Result<Vec<_>, _>>()?;
            return Ok(Outlines {
                kind: "segments",
                shapes: vec![crate::outline_io::Shape {
                    name: "outline".into(),
                    unicodes: Vec::new(),
                    contours: vec![crate::outline_io::Contour {
                        segments,
                        closed: self.closed == Some(true),
                        smooth: None,
                    }],
                }],
                unreadable: Vec::new(),
            });
        }
        match (self.svg, self.file) {
            (Some(t), None) => file_outlines("drawing.svg", t.into_bytes()),
            (None, Some(f)) => {
                use base64::Engine;
                if f.base64.len() > MAX_OUTLINE_FILE / 3 * 4 + 4 {
                    return Err(too_large());
                }
                let bytes = base64::engine::general_purpose::STANDARD
                    .decode(&f.base64)
                    .map_err(|e| ProtoError::invalid("file", format!("base64: {e}")))?;
                file_outlines(&f.name.to_lowercase(), bytes)
            }
            _ => Err(ProtoError::invalid(
                "svg",
                "give svg (text) or file, not both",
            )),
        }
    }
}

fn too_large() -> ProtoError {
    ProtoError::invalid("file", format!("larger than {MAX_OUTLINE_FILE} bytes"))
}

/// The outline of SVG path data.
fn path_outlines(d: &str) -> Result<Outlines, ProtoError> {
    let esc = d
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('"', "&quot;");
    let doc =
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg"><path id="path" d="{esc}"/></svg>"#);
    let o = crate::outline_io::read_svg(doc.as_bytes())
        .map_err(|e| ProtoError::invalid("path", format!("{e:#} (SVG path data expected)")))?;
    if o.shapes.is_empty() {
        let why = o
            .unreadable
            .first()
            .map_or("it draws nothing", |u| u.1.as_str());
        return Err(ProtoError::invalid(
            "path",
            format!("the path data cannot be read: {why} (SVG path data expected)"),
        ));
    }
    Ok(o)
}

/// The outlines of a file (a font, an SVG or a DXF by the name's extension).
fn file_outlines(name: &str, bytes: Vec<u8>) -> Result<Outlines, ProtoError> {
    if bytes.len() > MAX_OUTLINE_FILE {
        return Err(too_large());
    }
    let ext = name.rsplit_once('.').map_or("", |(_, e)| e);
    let read = match ext {
        "ttf" | "otf" | "ttc" | "otc" => crate::outline_io::read_font(&bytes),
        "dxf" => crate::outline_io::read_dxf(&bytes),
        "svg" => crate::outline_io::read_svg(&bytes),
        _ => {
            return Err(ProtoError::invalid(
                "file",
                format!(
                    "{name:?}: not a file outline.check reads (by its name's extension: .ttf, \
                     .otf, .ttc, .otc, .svg or .dxf)"
                ),
            ))
        }
    };
    read.map_err(|e| ProtoError::invalid("file", format!("{e:#}")))
}

/// One contour of the drawn shape.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ContourDrawing {
    /// Whether it is closed.
    pub closed: bool,
    /// Its segments (what an editor drags).
    pub segments: Vec<RationalJson>,
    /// Its picture.
    pub drawing: Drawing,
}

/// The (first) checked shape's contours for a picture.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ShapeDrawing {
    /// The shape's name.
    pub name: String,
    /// Its contours.
    pub contours: Vec<ContourDrawing>,
}

/// The check of an outline.
#[derive(Debug, Serialize, JsonSchema)]
pub struct OutlineCheckResult {
    /// Every shape's name (the index is what `shape` takes).
    pub shape_names: Vec<String>,
    /// Every shape's number of segments.
    pub shape_segments: Vec<usize>,
    /// The checked shapes: per contour its segments and joins, as `aecurve check --json`
    /// writes them.
    pub shapes: Vec<ShapeJson>,
    /// What the check found.
    pub findings: Vec<FindingJson>,
    /// With `draw`: the (first) checked shape.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drawing: Option<ShapeDrawing>,
}

/// `outline.check`.
pub struct OutlineCheck;

/// `invalid_input` when the picked shapes hold more than [`MAX_OUTLINE_SEGMENTS`].
fn check_budget(
    shapes: &[&crate::outline_io::Shape],
    pick: Option<usize>,
    field: &str,
) -> Result<(), ProtoError> {
    let total: usize = shapes
        .iter()
        .flat_map(|s| s.contours.iter())
        .map(|c| c.segments.len())
        .sum();
    if total <= MAX_OUTLINE_SEGMENTS {
        return Ok(());
    }
    let what = match pick {
        Some(i) => format!("shape {i} holds {total} segments"),
        None => format!("the {} shapes hold {total} segments", shapes.len()),
    };
    Err(ProtoError::invalid(
        field,
        format!(
            "{what}, over the {MAX_OUTLINE_SEGMENTS} one outline.check answers for: pick \
             one shape with `shape` (an index into `shape_names`, which every answer \
             holds), or check the whole file with `aecurve check --json`"
        ),
    ))
}

/// The drawing of one shape at `n` points per segment.
fn shape_drawing(shape: &crate::outline_io::Shape, n: usize) -> Result<ShapeDrawing, ProtoError> {
    let mut contours = Vec::new();
    for c in shape.contours.iter().filter(|c| !c.segments.is_empty()) {
        let pieces = aesthetic_curves::curve::Pieces(c.segments.clone());
        contours.push(ContourDrawing {
            closed: c.closed,
            segments: c.segments.iter().map(RationalJson::from).collect(),
            drawing: drawing_json(&pieces, n, None)?,
        });
    }
    Ok(ShapeDrawing {
        name: shape.name.clone(),
        contours,
    })
}

impl Op for OutlineCheck {
    const NAME: &'static str = "outline.check";
    type Request = OutlineCheckRequest;
    type Response = OutlineCheckResult;

    fn answer(req: OutlineCheckRequest) -> Result<OutlineCheckResult, ProtoError> {
        let (pick, suggest, draw) = (req.shape, req.suggest.map(|s| s.0), req.draw);
        let field = if req.path.is_some() { "path" } else { "shape" };
        let outlines = req.outlines()?;
        if let Some(i) = pick.filter(|i| *i >= outlines.shapes.len()) {
            let _ = i;
            return Err(ProtoError::invalid(
                "shape",
                format!("must be a shape index below {}", outlines.shapes.len()),
            ));
        }
        let opts = aesthetic_curves::outline::OutlineOptions {
            suggest,
            ..options_for(&outlines)
        };
        // One shape (`shape`), or every shape.
        let shapes: Vec<_> = match pick {
            Some(i) => vec![&outlines.shapes[i]],
            None => outlines.shapes.iter().collect(),
        };
        // The answer's budget and the drawing's, before any work.
        check_budget(&shapes, pick, field)?;
        if let (Some(n), Some(first)) = (draw, shapes.first()) {
            let segments: usize = first.contours.iter().map(|c| c.segments.len()).sum();
            drawing_budget(segments, n.0 as usize)?;
        }
        let checked = check_shapes(&shapes, &opts, &|| {});
        // Past the deadline the rest was flagged, not checked: no answer from half a check.
        aesthetic_curves::deadline::check()?;
        let findings = checked
            .iter()
            .flat_map(|c| c.findings.iter().map(move |f| FindingJson::new(c.name, f)))
            .collect();
        let drawing = match (draw, shapes.first()) {
            (Some(n), Some(first)) => Some(shape_drawing(first, n.0 as usize)?),
            _ => None,
        };
        Ok(OutlineCheckResult {
            shape_names: outlines.shapes.iter().map(|s| s.name.clone()).collect(),
            shape_segments: outlines
                .shapes
                .iter()
                .map(|s| s.contours.iter().map(|c| c.segments.len()).sum())
                .collect(),
            shapes: checked.iter().map(shape_json).collect(),
            findings,
            drawing,
        })
    }
}

/// One segment to repair: a line (2 points) or a polynomial cubic (4).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FixSegment {
    /// Its control points.
    pub control_points: Points<2, 4>,
    /// Weights, all 1 if given (a polynomial curve).
    #[serde(default)]
    pub weights: Option<Vec<f64>>,
}

/// One contour to repair.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutlineFixRequest {
    /// Its consecutive segments.
    pub segments: List<FixSegment, 1, MAX_OUTLINE_SEGMENTS>,
    /// A closed contour (default false).
    #[serde(default)]
    pub closed: Option<bool>,
    /// How far the outline may move from the input's shape (its units): every point of
    /// each segment within this of the other.
    pub tolerance: Positive,
    /// Round moved coordinates to this step (0 or absent: none).
    #[serde(default)]
    pub grid: Option<NonNegative>,
    /// Also move on-curve points along their tangent (default false).
    #[serde(default)]
    pub move_points: Option<bool>,
    /// Remove curvature bumps inside cubics (default true).
    #[serde(default)]
    pub bumps: Option<bool>,
}

impl Request for OutlineFixRequest {
    fn check(&self) -> Result<(), ProtoError> {
        let segs = &self.segments.0;
        for (i, s) in segs.iter().enumerate() {
            let n = s.control_points.0.len();
            if n == 3 {
                return Err(ProtoError::invalid(
                    &format!("segments[{i}].control_points"),
                    "a quadratic: outline.fix repairs lines (2 points) and cubics (4)",
                ));
            }
            if s.weights
                .as_ref()
                .is_some_and(|w| w.len() != n || w.iter().any(|x| *x != 1.0))
            {
                return Err(ProtoError::invalid(
                    &format!("segments[{i}].weights"),
                    "outline.fix repairs lines and polynomial cubics: weights must be 1",
                ));
            }
        }
        let pts: Vec<&[Point]> = segs.iter().map(|s| s.control_points.0.as_slice()).collect();
        check_consecutive(pts.windows(2).map(|w| (w[0], w[1])))
    }
}

/// What the repair did at a join (the library's `JoinOutcome`, in lower case).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum FixOutcome {
    /// Not a smooth join: left alone.
    Corner,
    /// A line (or a retracted handle) on one side: G2 needs zero curvature on the other.
    NotBetweenCubics,
    /// The curvature changes sign at the join: no handle lengths make it continuous.
    SignChange,
    /// Already G2 within rounding, or zero curvature on both sides.
    AlreadyG2,
    /// Made G2: the jump under 1 % (on the grid).
    Harmonized,
    /// G2 needs more than the tolerance: moved as far towards it as allowed.
    Limited,
    /// Moved part of the way (the whole move would add an extremum or worsen a join, or
    /// the grid allows no closer).
    Partly,
    /// Moved, then given back its handles because the result was worse.
    Reverted,
    /// Held as it was (a designspace's masters held together).
    Held,
}

impl From<aesthetic_curves::harmonize::JoinOutcome> for FixOutcome {
    fn from(o: aesthetic_curves::harmonize::JoinOutcome) -> Self {
        use aesthetic_curves::harmonize::JoinOutcome as J;
        match o {
            J::Corner => FixOutcome::Corner,
            J::NotBetweenCubics => FixOutcome::NotBetweenCubics,
            J::SignChange => FixOutcome::SignChange,
            J::AlreadyG2 => FixOutcome::AlreadyG2,
            J::Harmonized => FixOutcome::Harmonized,
            J::Limited => FixOutcome::Limited,
            J::Partly => FixOutcome::Partly,
            J::Reverted => FixOutcome::Reverted,
            J::Held => FixOutcome::Held,
        }
    }
}

/// One join after the repair.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixJoinJson {
    /// The segment it follows.
    pub after_segment: usize,
    /// Whether it is a smooth join (G1 within 0.5°).
    pub smooth: bool,
    /// What was done.
    pub outcome: FixOutcome,
    /// The tangent break before and after (degrees).
    pub angle_degrees: [f64; 2],
    /// The relative curvature jump before and after (absent at a retracted handle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jump: Option<[f64; 2]>,
}

impl FixJoinJson {
    /// A join of the repair's result, `smooth` as the input marked it.
    pub fn of(j: &aesthetic_curves::harmonize::JoinReport, smooth: bool) -> Self {
        FixJoinJson {
            after_segment: j.after_segment,
            smooth,
            outcome: FixOutcome::from(j.outcome),
            angle_degrees: [j.angle.0.to_degrees(), j.angle.1.to_degrees()],
            // Undefined at a retracted handle: left out rather than null.
            jump: (j.jump.0.is_finite() && j.jump.1.is_finite()).then_some([j.jump.0, j.jump.1]),
        }
    }
}

/// A moved segment.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixedSegment {
    /// Its control points.
    pub control_points: Vec<[f64; 2]>,
}

/// The repaired contour and what changed.
#[derive(Debug, Serialize, JsonSchema)]
pub struct OutlineFixResult {
    /// The segments, same count and kinds, coordinates moved.
    pub segments: Vec<FixedSegment>,
    /// Whether it is closed.
    pub closed: bool,
    /// Every join.
    pub joins: Vec<FixJoinJson>,
    /// Segments that moved.
    pub changed_segments: usize,
    /// The largest distance moved.
    pub max_moved: f64,
    /// Curvature bumps removed.
    pub bumps_removed: usize,
    /// Segments with a curvature bump whose repair search stopped at its budget for exact
    /// arithmetic (coordinates spanning hundreds of orders of magnitude): left as they are.
    pub bumps_undecided: Vec<usize>,
}

/// `outline.fix`.
pub struct OutlineFix;

impl Op for OutlineFix {
    const NAME: &'static str = "outline.fix";
    type Request = OutlineFixRequest;
    type Response = OutlineFixResult;

    fn answer(req: OutlineFixRequest) -> Result<OutlineFixResult, ProtoError> {
        let segments: Vec<Vec<Point>> = req
            .segments
            .0
            .into_iter()
            .map(|s| s.control_points.0)
            .collect();
        let closed = req.closed == Some(true);
        let opts = crate::fix::FixOptions {
            tolerance: req.tolerance.0,
            grid: req.grid.unwrap_or_default().0,
            move_points: req.move_points == Some(true),
            repairs: aesthetic_curves::harmonize::Repairs {
                bumps: req.bumps != Some(false),
                ..Default::default()
            },
            deadline: None,
        };
        let (h, smooth) = crate::fix::fix_segments(&segments, closed, &opts)?;
        let joins = h
            .joins
            .iter()
            .map(|j| FixJoinJson::of(j, smooth[j.after_segment]))
            .collect();
        Ok(OutlineFixResult {
            changed_segments: h
                .segments
                .iter()
                .zip(&segments)
                .filter(|(a, b)| a != b)
                .count(),
            segments: h
                .segments
                .iter()
                .map(|s| FixedSegment {
                    control_points: xy(s),
                })
                .collect(),
            closed,
            joins,
            max_moved: h.moved.iter().copied().fold(0.0, f64::max),
            bumps_removed: h.bumps.len(),
            bumps_undecided: h.bumps_undecided.clone(),
        })
    }
}
