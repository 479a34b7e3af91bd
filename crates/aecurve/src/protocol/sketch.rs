//! Pen strokes: `sketch.fit` (one G2 run of LAC pieces) and `sketch.contour` (runs, lines
//! and corners, open or closed).

use super::drawing::{pieces_drawing, WithDrawing};
use super::fields::{Draw, Points, Positive};
use super::piece::PieceJson;
use super::{xy, Op, ProtoError, Request};
use crate::json_out::finite;
use aesthetic_curves::sketch::contour::{fit_contour, ContourOptions, Run, SketchContour};
use aesthetic_curves::sketch::Sketch;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest point sequence `sketch.fit` accepts.
pub const MAX_SKETCH_POINTS: usize = 20_000;

/// A pen stroke to fit with one G2 run.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SketchFitRequest {
    /// The stroke's points, in drawing order.
    pub points: Points<4, MAX_SKETCH_POINTS>,
    /// Largest distance of the curve from the points (default: from the stroke's size).
    #[serde(default)]
    pub tolerance: Option<Positive>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for SketchFitRequest {}

/// One piece of a sketch.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SketchPieceJson {
    /// The piece.
    #[serde(flatten)]
    pub piece: PieceJson,
    /// Its α.
    pub alpha: f64,
    /// Whether α stopped at the library's bound.
    pub alpha_at_bound: bool,
    /// For a `lac` piece, the α values whose segment in its triangle fits its points as
    /// closely as their noise lets one tell (within the tolerance): how far the points pin
    /// α down.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha_range: Option<[f64; 2]>,
    /// Whether the points determine α (`alpha_range` at most 0.1 wide): false for a nearly
    /// circular or straight piece, or too few points for the tolerance.
    pub alpha_determined: bool,
    /// α estimated from the stroke's curvature graph, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha_estimate: Option<f64>,
    /// Largest distance of its cubic from it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rational_error: Option<f64>,
}

/// The smoothing B-spline the pieces were fitted to.
#[derive(Debug, Serialize, JsonSchema)]
pub struct BSplineJson {
    /// Its degree.
    pub degree: usize,
    /// Its knots.
    pub knots: Vec<f64>,
    /// Its control points.
    pub control_points: Vec<[f64; 2]>,
}

/// How the joints were faired to G2.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FairingJson {
    /// Iterations.
    pub iterations: usize,
    /// Whether it converged.
    pub converged: bool,
    /// Largest relative curvature jump before.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_jump: Option<f64>,
    /// Largest relative curvature jump after.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub final_jump: Option<f64>,
}

/// A sketch: G2 LAC pieces through a stroke.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SketchResult {
    /// The pieces, in order.
    pub segments: Vec<SketchPieceJson>,
    /// The smoothing B-spline.
    pub bspline: BSplineJson,
    /// The tolerance used.
    pub tolerance: f64,
    /// Largest distance of a point from the curve.
    pub max_deviation: f64,
    /// Root-mean-square distance of the points from the curve.
    pub rms_deviation: f64,
    /// Whether every joint is G2.
    pub g2: bool,
    /// Whether every cubic's curvature is proven monotone.
    pub all_monotone: bool,
    /// Inflections.
    pub inflections: usize,
    /// Curvature extrema.
    pub curvature_extrema: usize,
    /// The fairing's report.
    pub fairing: FairingJson,
    /// Largest relative curvature jump at a joint.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_curvature_jump: Option<f64>,
}

/// The `sketch.fit` result of a sketch (shared with `aecurve sketch --json`).
pub fn sketch_json(sk: &Sketch, tolerance: f64) -> SketchResult {
    let segments = sk
        .pieces
        .iter()
        .map(|p| SketchPieceJson {
            piece: PieceJson::new(
                p.kind.as_str(),
                &p.control,
                p.end_curvatures,
                &p.rational,
                p.monotone,
            ),
            alpha: p.alpha,
            alpha_at_bound: p.alpha_at_bound,
            alpha_range: p.alpha_range.map(|(lo, hi)| [lo, hi]),
            alpha_determined: p.alpha_determined(),
            alpha_estimate: p.alpha_estimate.and_then(finite),
            rational_error: finite(p.rational_error),
        })
        .collect();
    SketchResult {
        segments,
        bspline: BSplineJson {
            degree: sk.bspline.degree,
            knots: sk.bspline.knots.clone(),
            control_points: xy(&sk.bspline.control_points),
        },
        tolerance,
        max_deviation: sk.max_deviation,
        rms_deviation: sk.rms_deviation,
        g2: sk.g2,
        all_monotone: sk.all_monotone,
        inflections: sk.inflections,
        curvature_extrema: sk.curvature_extrema,
        fairing: FairingJson {
            iterations: sk.fairing.iterations,
            converged: sk.fairing.converged,
            initial_jump: finite(sk.fairing.initial_jump),
            final_jump: finite(sk.fairing.final_jump),
        },
        max_curvature_jump: finite(sk.max_curvature_jump),
    }
}

/// `sketch.fit`.
pub struct SketchFit;

impl Op for SketchFit {
    const NAME: &'static str = "sketch.fit";
    type Request = SketchFitRequest;
    type Response = WithDrawing<SketchResult>;

    fn answer(req: SketchFitRequest) -> Result<Self::Response, ProtoError> {
        let points = req.points.0;
        let (sk, tolerance) =
            aesthetic_curves::sketch::fit_sketch_within(&points, req.tolerance.map(|t| t.0))?;
        let drawing = req
            .draw
            .map(|n| pieces_drawing(&sk.as_curve(), n.0 as usize))
            .transpose()?;
        Ok(WithDrawing {
            result: sketch_json(&sk, tolerance),
            drawing,
        })
    }
}

/// A pen stroke to fit as a contour: fair runs, straight runs and corners.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SketchContourRequest {
    /// The stroke's points, in drawing order.
    pub points: Points<2, MAX_SKETCH_POINTS>,
    /// Largest distance of the curve from the points (default: from the stroke's size).
    #[serde(default)]
    pub tolerance: Option<Positive>,
    /// Closed (true), open (false), or decided from the stroke (absent or null).
    #[serde(default)]
    pub closed: Option<bool>,
    /// The smallest turn that is a corner, in degrees, in (0, 180) (at a point of a sparse
    /// stroke, between its two chords, at least 80).
    #[serde(default)]
    pub corner_angle_degrees: Option<f64>,
    /// The size of one device pixel in the points' units (the editor sends its view's):
    /// the default tolerance is at least three of them. Absent: read from the points (a
    /// mouse's whole pixels).
    #[serde(default)]
    pub resolution: Option<Positive>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for SketchContourRequest {
    fn check(&self) -> Result<(), ProtoError> {
        match self.corner_angle_degrees {
            Some(a) if !(a > 0.0 && a < 180.0) => Err(ProtoError::invalid(
                "corner_angle_degrees",
                "must lie in (0, 180)",
            )),
            _ => Ok(()),
        }
    }
}

/// One run of a contour.
#[derive(Debug, Serialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RunJson {
    /// A straight run.
    Line {
        /// Its start.
        start: [f64; 2],
        /// Its end.
        end: [f64; 2],
    },
    /// A fair run: a sketch.
    Curve(Box<SketchResult>),
}

/// A corner between two runs.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CornerJson {
    /// The stroke point at the corner.
    pub index: usize,
    /// Where it is.
    pub point: [f64; 2],
    /// The turn there (degrees).
    pub angle_degrees: f64,
    /// The run that ends there (the next run, or a closed contour's first, starts there).
    pub run: usize,
}

/// A smooth join between two runs (a line and a curve).
#[derive(Debug, Serialize, JsonSchema)]
pub struct SmoothJoinJson {
    /// The run that ends there (the next run, or a closed contour's first, starts there).
    pub run: usize,
    /// Where it is.
    pub point: [f64; 2],
    /// The tangent break (degrees).
    pub angle_degrees: f64,
    /// The relative curvature jump.
    pub curvature_jump: f64,
}

/// The seam of a closed contour.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SeamJson {
    /// The tangent break (degrees).
    pub angle_degrees: f64,
    /// The relative curvature jump.
    pub curvature_jump: f64,
}

/// A contour.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ContourResult {
    /// Its runs, in order.
    pub runs: Vec<RunJson>,
    /// Its corners.
    pub corners: Vec<CornerJson>,
    /// Its smooth joins between runs.
    pub smooth_joins: Vec<SmoothJoinJson>,
    /// Whether it is closed.
    pub closed: bool,
    /// Pieces in all runs.
    pub pieces: usize,
    /// The tolerance used.
    pub tolerance: f64,
    /// Largest distance of a point from the contour.
    pub max_deviation: f64,
    /// Stroke points trimmed at the ends.
    pub trimmed: usize,
    /// The seam of a closed contour without a corner there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seam: Option<SeamJson>,
}

/// The `sketch.contour` result of a contour (shared with `aecurve sketch --contour --json`).
pub fn contour_json(c: &SketchContour) -> ContourResult {
    let p = |p: aesthetic_curves::Point| [p.x, p.y];
    let runs = c
        .runs
        .iter()
        .map(|r| match r {
            Run::Line { start, end } => RunJson::Line {
                start: p(*start),
                end: p(*end),
            },
            Run::Curve(sk) => RunJson::Curve(Box::new(sketch_json(sk, c.tolerance))),
        })
        .collect();
    ContourResult {
        runs,
        corners: c
            .corners
            .iter()
            .map(|k| CornerJson {
                index: k.index,
                point: p(k.point),
                angle_degrees: k.angle.to_degrees(),
                run: k.run,
            })
            .collect(),
        smooth_joins: c
            .smooth_joins
            .iter()
            .map(|j| SmoothJoinJson {
                run: j.run,
                point: p(j.point),
                angle_degrees: j.angle.to_degrees(),
                curvature_jump: j.curvature_jump,
            })
            .collect(),
        closed: c.closed,
        pieces: c.pieces(),
        tolerance: c.tolerance,
        max_deviation: c.max_deviation,
        trimmed: c.trimmed,
        seam: c.seam.map(|s| SeamJson {
            angle_degrees: s.angle.to_degrees(),
            curvature_jump: s.curvature_jump,
        }),
    }
}

/// `sketch.contour`.
pub struct SketchContourOp;

impl Op for SketchContourOp {
    const NAME: &'static str = "sketch.contour";
    type Request = SketchContourRequest;
    type Response = WithDrawing<ContourResult>;

    fn answer(req: SketchContourRequest) -> Result<Self::Response, ProtoError> {
        let mut opts = ContourOptions {
            tolerance: req.tolerance.map(|t| t.0),
            closed: req.closed,
            resolution: req.resolution.map(|r| r.0),
            ..Default::default()
        };
        if let Some(a) = req.corner_angle_degrees {
            opts.corner_angle = a.to_radians();
        }
        let c = fit_contour(&req.points.0, &opts)?;
        let drawing = req
            .draw
            .map(|n| pieces_drawing(&c.as_curve()?, n.0 as usize))
            .transpose()?;
        Ok(WithDrawing {
            result: contour_json(&c),
            drawing,
        })
    }
}
