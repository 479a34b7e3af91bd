//! The splines through points: `spline.pseudo_elastic` (S2's, G1) and `spline.lac` (G2,
//! log-aesthetic).

use super::drawing::{drawing_budget, pieces_drawing, WithDrawing};
use super::fields::{count_message, Draw, Points};
use super::piece::PieceJson;
use super::{Op, ProtoError, Request};
use aesthetic_curves::lac_spline::{LacSpline, LacSplineOptions};
use aesthetic_curves::pseudo_spline::{Mode, PseudoSpline};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest number of points `spline.pseudo_elastic` accepts in table mode (microseconds
/// per point, but about 3.5 KB of memory per point for the request and its answer: 20,000
/// points keep a request near 70 MB; the library itself has no limit).
pub const MAX_SPLINE_POINTS: usize = 20_000;

/// Largest number of points in exact mode: a minimisation per point, 1.2 to 2 s each on a
/// shared 2-core machine (measured: 16 closed points 22 s, 32 past the batch's 60 s
/// deadline), so that a request within the limit ends inside `batch`'s default deadline.
pub const MAX_EXACT_SPLINE_POINTS: usize = 16;

/// Largest number of points `spline.lac` accepts: its Newton steps solve a dense system
/// in the smooth points (500 points: some 40 ms a step) and fit one or two cubics per span
/// (about half a millisecond each).
pub const MAX_LAC_SPLINE_POINTS: usize = 500;

/// How the pseudo-elastic spline finds its tangents.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SplineMode {
    /// S2's tables (fast; default).
    #[default]
    Table,
    /// A minimisation per point (slow).
    Exact,
}

impl SplineMode {
    /// The library's mode.
    pub fn mode(self) -> Mode {
        match self {
            SplineMode::Table => Mode::Table,
            SplineMode::Exact => Mode::Exact,
        }
    }
}

impl From<Mode> for SplineMode {
    fn from(m: Mode) -> Self {
        match m {
            Mode::Table => SplineMode::Table,
            Mode::Exact => SplineMode::Exact,
        }
    }
}

/// Points for the pseudo-elastic spline.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PseudoElasticRequest {
    /// The points it passes through (at least 3 when closed; at most 16 in exact mode).
    pub points: Points<2, MAX_SPLINE_POINTS>,
    /// A closed curve (default false).
    #[serde(default)]
    pub closed: Option<bool>,
    /// `table` (default) or `exact`.
    #[serde(default)]
    pub mode: Option<SplineMode>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

/// The points' count within `least..=most` (`least` 3 when closed).
fn check_count(n: usize, closed: bool, most: usize) -> Result<(), ProtoError> {
    let least = if closed { 3 } else { 2 };
    if n < least || n > most {
        return Err(ProtoError::invalid("points", count_message(least, most, n)));
    }
    Ok(())
}

impl Request for PseudoElasticRequest {
    fn check(&self) -> Result<(), ProtoError> {
        let most = match self.mode.unwrap_or_default() {
            SplineMode::Exact => MAX_EXACT_SPLINE_POINTS,
            SplineMode::Table => MAX_SPLINE_POINTS,
        };
        let n = self.points.0.len();
        check_count(n, self.closed == Some(true), most)?;
        match self.draw {
            Some(d) => drawing_budget(n, d.0 as usize),
            None => Ok(()),
        }
    }
}

/// One G1 segment of the pseudo-elastic spline: its ends and their unit tangents.
#[derive(Debug, Serialize, JsonSchema)]
pub struct PseudoSegmentJson {
    /// Start.
    pub p0: [f64; 2],
    /// End.
    pub p1: [f64; 2],
    /// Unit tangent at the start.
    pub d0: [f64; 2],
    /// Unit tangent at the end.
    pub d1: [f64; 2],
}

/// The pseudo-elastic spline.
#[derive(Debug, Serialize, JsonSchema)]
pub struct PseudoSplineResult {
    /// The tangent angle at each point (radians).
    pub tangent_angles: Vec<f64>,
    /// Its segments.
    pub segments: Vec<PseudoSegmentJson>,
    /// Its length.
    pub length: f64,
    /// The area under it.
    pub area: f64,
    /// Its bending energy.
    pub energy: f64,
    /// The mode used.
    pub mode: SplineMode,
}

/// The result object of `spline.pseudo_elastic` (also `aecurve spline --json`).
pub fn spline_json(s: &PseudoSpline, mode: SplineMode) -> PseudoSplineResult {
    let p = |v: kurbo::Point| [v.x, v.y];
    let d = |v: kurbo::Vec2| [v.x, v.y];
    PseudoSplineResult {
        tangent_angles: s.tangent_angles.clone(),
        segments: s
            .segments
            .iter()
            .map(|g| PseudoSegmentJson {
                p0: p(g.p0),
                p1: p(g.p1),
                d0: d(g.d0),
                d1: d(g.d1),
            })
            .collect(),
        length: s.length,
        area: s.area,
        energy: s.energy,
        mode,
    }
}

/// `spline.pseudo_elastic`.
pub struct PseudoElastic;

impl Op for PseudoElastic {
    const NAME: &'static str = "spline.pseudo_elastic";
    type Request = PseudoElasticRequest;
    type Response = WithDrawing<PseudoSplineResult>;

    fn answer(req: PseudoElasticRequest) -> Result<Self::Response, ProtoError> {
        let mode = req.mode.unwrap_or_default();
        let closed = req.closed == Some(true);
        let s =
            aesthetic_curves::pseudo_spline::pseudo_elastic(&req.points.0, closed, mode.mode())?;
        let drawing = req
            .draw
            .map(|n| pieces_drawing(&s.as_curve()?, n.0 as usize))
            .transpose()?;
        Ok(WithDrawing {
            result: spline_json(&s, mode),
            drawing,
        })
    }
}

/// Points for the G2 log-aesthetic spline.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SplineLacRequest {
    /// The points it passes through (at least 3 when closed).
    pub points: Points<2, MAX_LAC_SPLINE_POINTS>,
    /// A closed curve (default false).
    #[serde(default)]
    pub closed: Option<bool>,
    /// Indices of corner points (G0 there; G2 everywhere else).
    #[serde(default)]
    pub corners: Option<Vec<usize>>,
    /// α of every span (default -1: clothoids).
    #[serde(default)]
    pub alpha: Option<f64>,
    /// α of each span, instead of `alpha`.
    #[serde(default)]
    pub alphas: Option<Vec<f64>>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl SplineLacRequest {
    /// The library's options of this request (also `aecurve spline --kind lac`).
    pub fn options(&self) -> LacSplineOptions {
        LacSplineOptions {
            alpha: self.alpha.unwrap_or(-1.0),
            span_alphas: self.alphas.clone(),
            closed: self.closed == Some(true),
            corners: self.corners.clone().unwrap_or_default(),
            ..Default::default()
        }
    }
}

impl Request for SplineLacRequest {
    fn check(&self) -> Result<(), ProtoError> {
        let closed = self.closed == Some(true);
        check_count(self.points.0.len(), closed, MAX_LAC_SPLINE_POINTS)
    }
}

/// One piece of the spline: a sketch piece with the span it belongs to.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SplinePieceJson {
    /// The piece.
    #[serde(flatten)]
    pub piece: PieceJson,
    /// The span (from point `span` to the next) it belongs to.
    pub span: usize,
    /// Largest distance of its cubic from it.
    pub rational_error: f64,
    /// Its α (absent for a line).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
}

/// The G2 log-aesthetic spline.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacSplineResult {
    /// Its pieces, span by span.
    pub segments: Vec<SplinePieceJson>,
    /// The unit tangent at each point.
    pub tangents: Vec<[f64; 2]>,
    /// Whether it is closed.
    pub closed: bool,
    /// Newton iterations.
    pub iterations: usize,
    /// Whether the solve converged.
    pub converged: bool,
    /// Converged with the cubics' curvature jumps below 1e-8.
    pub g2: bool,
    /// Largest relative curvature jump at a smooth point (of the LAC pieces).
    pub max_curvature_jump: f64,
    /// Largest relative curvature jump between the cubics.
    pub max_cubic_jump: f64,
    /// Largest tangent angle between the cubics (radians).
    pub max_cubic_angle: f64,
    /// Whether every cubic's curvature is proven monotone.
    pub all_monotone: bool,
    /// Largest distance of a cubic from its piece.
    pub max_rational_error: f64,
    /// Inflections.
    pub inflections: usize,
    /// Curvature extrema.
    pub curvature_extrema: usize,
    /// The α each span was solved with: the requested one, or where no G2 spline through
    /// the points holds it in every span, the nearest one that span could hold.
    pub span_alphas: Vec<f64>,
    /// The spans (by their first point) whose α is not the requested one; empty when every
    /// span has it.
    pub relaxed_spans: Vec<usize>,
}

/// The result of `spline.lac` (also `aecurve spline --kind lac --json`).
pub fn lac_spline_json(s: &LacSpline) -> LacSplineResult {
    let segments = s
        .pieces
        .iter()
        .map(|p| SplinePieceJson {
            piece: PieceJson::new(
                p.kind.as_str(),
                &p.control,
                p.end_curvatures,
                &p.rational,
                p.monotone,
            ),
            span: p.span,
            rational_error: p.rational_error,
            alpha: p.alpha,
        })
        .collect();
    LacSplineResult {
        segments,
        tangents: s.tangents.iter().map(|t| [t.x, t.y]).collect(),
        closed: s.closed,
        iterations: s.iterations,
        converged: s.converged,
        g2: s.g2(),
        max_curvature_jump: s.max_curvature_jump,
        max_cubic_jump: s.max_cubic_jump,
        max_cubic_angle: s.max_cubic_angle,
        all_monotone: s.all_monotone,
        max_rational_error: s.max_rational_error,
        inflections: s.inflections,
        curvature_extrema: s.curvature_extrema,
        span_alphas: s.span_alphas.clone(),
        relaxed_spans: s.relaxed_spans.clone(),
    }
}

/// `spline.lac`.
pub struct SplineLac;

impl Op for SplineLac {
    const NAME: &'static str = "spline.lac";
    type Request = SplineLacRequest;
    type Response = WithDrawing<LacSplineResult>;

    fn answer(req: SplineLacRequest) -> Result<Self::Response, ProtoError> {
        let s = aesthetic_curves::lac_spline::lac_spline(&req.points.0, &req.options())?;
        let drawing = req
            .draw
            .map(|n| pieces_drawing(&s.rationals(), n.0 as usize))
            .transpose()?;
        Ok(WithDrawing {
            result: lac_spline_json(&s),
            drawing,
        })
    }
}
