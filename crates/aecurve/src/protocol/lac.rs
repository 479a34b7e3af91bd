//! The LAC ops: `lac.point`, `lac.segment`, `lac.inflection_segment`,
//! `lac.rational_approx` and `lac.fit`.

use super::drawing::{drawing_json, Drawing, NurbsJson, WithDrawing};
use super::fields::{bounded_seq, Draw, IntIn, Points, Positive};
use super::{xy, Op, ProtoError, Request};
use aesthetic_curves::approx::{self, ApproxOptions};
use aesthetic_curves::curve::MAX_NURBS_PIECES;
use aesthetic_curves::lac::{LacInflectionSegment, LacSegment, LacStandard};
use aesthetic_curves::nurbs::Nurbs;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::fmt;

/// Largest number of parameters in one request.
pub const MAX_THETAS: usize = 100_000;

/// Largest number of samples of a segment.
pub const MAX_SEGMENT_SAMPLES: u64 = 100_000;

/// Largest point sequence `lac.fit` accepts.
pub const MAX_FIT_POINTS: usize = 20_000;

/// Tangent angles: one number or an array of at most [`MAX_THETAS`].
#[derive(Debug, Clone)]
pub struct Thetas(pub Vec<f64>);

impl<'de> Deserialize<'de> for Thetas {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Thetas;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "a number or an array of at most {MAX_THETAS} numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Thetas, E> {
                Ok(Thetas(vec![v]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Thetas, E> {
                Ok(Thetas(vec![v as f64]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Thetas, E> {
                Ok(Thetas(vec![v as f64]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Thetas, A::Error> {
                let too = |n: usize| format!("at most {MAX_THETAS} values, got {n}");
                Ok(Thetas(bounded_seq(seq, (0, MAX_THETAS), too)?))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for Thetas {
    fn inline_schema() -> bool {
        true
    }
    fn schema_name() -> Cow<'static, str> {
        "Thetas".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({"oneOf": [{"type": "number"},
            {"type": "array", "items": {"type": "number"}, "maxItems": MAX_THETAS}]})
    }
}

/// Points of the standard LAC (ρ = 1 at θ = 0) at tangent angles.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LacPointRequest {
    /// The shape parameter α.
    pub alpha: f64,
    /// The parameter Λ.
    pub lambda: f64,
    /// Tangent angles θ (radians).
    pub theta: Thetas,
}

impl Request for LacPointRequest {}

/// Points, arc lengths and curvatures at the asked angles.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacPointResult {
    /// The point at each θ.
    pub points: Vec<[f64; 2]>,
    /// The arc length from θ = 0 to each θ.
    pub arc_length: Vec<f64>,
    /// The curvature at each θ.
    pub curvature: Vec<f64>,
}

/// `lac.point`.
pub struct LacPoint;

impl Op for LacPoint {
    const NAME: &'static str = "lac.point";
    type Request = LacPointRequest;
    type Response = LacPointResult;

    fn answer(req: LacPointRequest) -> Result<LacPointResult, ProtoError> {
        let c = LacStandard::new(req.alpha, req.lambda)?;
        let thetas = req.theta.0;
        Ok(LacPointResult {
            points: xy(&c.eval_many(&thetas)?),
            arc_length: thetas
                .iter()
                .map(|t| c.arc_length(*t))
                .collect::<Result<_, _>>()?,
            curvature: thetas
                .iter()
                .map(|t| c.kappa(*t))
                .collect::<Result<_, _>>()?,
        })
    }
}

/// A LAC segment by its control triangle.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LacSegmentRequest {
    /// The shape parameter α.
    pub alpha: f64,
    /// The control triangle: start, tangent intersection, end.
    pub control: Points<3, 3>,
    /// Points sampled along it (default 65).
    #[serde(default)]
    pub samples: Option<IntIn<2, MAX_SEGMENT_SAMPLES>>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for LacSegmentRequest {}

/// A segment's numbers and its samples with their curvature.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacSegmentResult {
    /// Λ.
    pub lambda: f64,
    /// The turning angle θ_d.
    pub theta_d: f64,
    /// The segment's length.
    pub arc_length: f64,
    /// Curvature at the start.
    pub curvature_start: f64,
    /// Curvature at the end.
    pub curvature_end: f64,
    /// Points along the segment.
    pub points: Vec<[f64; 2]>,
    /// Curvature at each point.
    pub curvature: Vec<f64>,
}

/// The result of `lac.segment` (also `aecurve lac --json`).
pub fn lac_segment_json(
    seg: &LacSegment,
    samples: usize,
) -> Result<LacSegmentResult, aesthetic_curves::Error> {
    let (k0, k1) = seg.end_curvatures()?;
    let s = seg.sample(samples)?;
    Ok(LacSegmentResult {
        lambda: seg.lambda(),
        theta_d: seg.theta_d(),
        arc_length: seg.arc_length()?,
        curvature_start: k0,
        curvature_end: k1,
        points: xy(&s.points),
        curvature: s.kappa,
    })
}

fn control3(p: &Points<3, 3>) -> [aesthetic_curves::Point; 3] {
    [p.0[0], p.0[1], p.0[2]]
}

/// `lac.segment`.
pub struct LacSegmentOp;

impl Op for LacSegmentOp {
    const NAME: &'static str = "lac.segment";
    type Request = LacSegmentRequest;
    type Response = WithDrawing<LacSegmentResult>;

    fn answer(req: LacSegmentRequest) -> Result<Self::Response, ProtoError> {
        let seg = LacSegment::new(req.alpha, control3(&req.control))?;
        let samples = req.samples.map_or(65, |s| s.0) as usize;
        Ok(WithDrawing {
            result: lac_segment_json(&seg, samples)?,
            // No NURBS: a LAC segment has no exact rational form (lac.rational_approx
            // gives one).
            drawing: req
                .draw
                .map(|n| drawing_json(&seg, n.0 as usize, None))
                .transpose()?,
        })
    }
}

/// An inflection-end LAC segment (α = -1 from κ = 0) by its control triangle.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LacInflectionRequest {
    /// The control triangle: the inflection end, tangent intersection, end.
    pub control: Points<3, 3>,
    /// Points sampled along it (default 65).
    #[serde(default)]
    pub samples: Option<IntIn<2, MAX_SEGMENT_SAMPLES>>,
    /// With a tolerance: rational cubics within it, G2, as one NURBS (`spline`).
    #[serde(default)]
    pub tolerance: Option<Positive>,
    /// Also its one rational cubic (`rational`).
    #[serde(default)]
    pub rational: Option<bool>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for LacInflectionRequest {}

/// An inflection-end segment's numbers and samples.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacInflectionResult {
    /// Its α (-1).
    pub alpha: f64,
    /// The turning angle θ_d.
    pub theta_d: f64,
    /// The segment's length.
    pub arc_length: f64,
    /// Curvature at the end (zero at the start).
    pub curvature_end: f64,
    /// Points along the segment.
    pub points: Vec<[f64; 2]>,
    /// Curvature at each point.
    pub curvature: Vec<f64>,
}

/// The base result of `lac.inflection_segment` (also `aecurve lac --inflection --json`).
pub fn lac_inflection_json(
    seg: &LacInflectionSegment,
    samples: usize,
) -> Result<LacInflectionResult, aesthetic_curves::Error> {
    let s = seg.sample(samples)?;
    Ok(LacInflectionResult {
        alpha: seg.alpha(),
        theta_d: seg.theta_d(),
        arc_length: seg.arc_length(),
        curvature_end: seg.end_curvature(),
        points: xy(&s.points),
        curvature: s.kappa,
    })
}

/// One rational cubic standing for a segment.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RationalCubicJson {
    /// Its four control points.
    pub control_points: Vec<[f64; 2]>,
    /// Its weights.
    pub weights: Vec<f64>,
    /// Largest distance from the segment.
    pub max_error: f64,
    /// Whether its curvature is proven monotone.
    pub monotone: bool,
    /// With `draw`: its picture.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drawing: Option<Drawing>,
}

/// Rational cubics within a tolerance, G2, as one NURBS.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RationalSplineJson {
    /// 3.
    pub degree: usize,
    /// Its knots.
    pub knots: Vec<f64>,
    /// Its control points.
    pub control_points: Vec<[f64; 2]>,
    /// Its weights.
    pub weights: Vec<f64>,
    /// How many cubics.
    pub pieces: usize,
    /// Largest distance from the segment.
    pub max_error: f64,
    /// Whether every cubic's curvature is proven monotone.
    pub monotone: bool,
}

impl From<&approx::RationalSpline> for RationalSplineJson {
    fn from(sp: &approx::RationalSpline) -> Self {
        let n = NurbsJson::from(&sp.nurbs);
        RationalSplineJson {
            degree: n.degree,
            knots: n.knots,
            control_points: n.control_points,
            weights: n.weights,
            pieces: sp.pieces.len(),
            max_error: sp.max_error,
            monotone: sp.pieces.iter().all(|p| p.monotone),
        }
    }
}

/// `lac.inflection_segment`'s result: the segment, and optionally its rational forms.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacInflectionResponse {
    /// The segment and its drawing.
    #[serde(flatten)]
    pub segment: WithDrawing<LacInflectionResult>,
    /// With `rational: true`: its one rational cubic (κ = 0 at its start, G2 at its end,
    /// curvature proven monotone).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rational: Option<RationalCubicJson>,
    /// With `tolerance`: rational cubics within it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spline: Option<RationalSplineJson>,
}

/// `lac.inflection_segment`.
pub struct LacInflectionSegmentOp;

impl Op for LacInflectionSegmentOp {
    const NAME: &'static str = "lac.inflection_segment";
    type Request = LacInflectionRequest;
    type Response = LacInflectionResponse;

    fn answer(req: LacInflectionRequest) -> Result<LacInflectionResponse, ProtoError> {
        let seg = LacInflectionSegment::new(control3(&req.control))?;
        let samples = req.samples.map_or(65, |s| s.0) as usize;
        let draw = req.draw.map(|n| n.0 as usize);
        let drawing = draw.map(|n| drawing_json(&seg, n, None)).transpose()?;
        let opts = ApproxOptions::default();
        let rational = if req.rational == Some(true) {
            let fit = approx::fit_inflection_cubic(&seg, &opts)?;
            let drawing = draw
                .map(|n| drawing_json(&fit.curve, n, Some(&Nurbs::from_bezier(&fit.curve))))
                .transpose()?;
            Some(RationalCubicJson {
                control_points: xy(fit.curve.points()),
                weights: fit.curve.weights().to_vec(),
                max_error: fit.max_error,
                monotone: fit.monotone,
                drawing,
            })
        } else {
            None
        };
        let spline = req
            .tolerance
            .map(|t| approx::fit_inflection_spline(&seg, t.0, MAX_NURBS_PIECES, &opts))
            .transpose()?;
        Ok(LacInflectionResponse {
            segment: WithDrawing {
                result: lac_inflection_json(&seg, samples)?,
                drawing,
            },
            rational,
            spline: spline.as_ref().map(RationalSplineJson::from),
        })
    }
}

/// A LAC segment to stand for by one rational cubic (and by a spline within a tolerance).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RationalApproxRequest {
    /// The shape parameter α.
    pub alpha: f64,
    /// The control triangle: start, tangent intersection, end.
    pub control: Points<3, 3>,
    /// With a tolerance: rational cubics within it, G2, as one NURBS (`spline`).
    #[serde(default)]
    pub tolerance: Option<Positive>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for RationalApproxRequest {}

/// The one rational cubic (global optimum) of a LAC segment.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RationalApproxResult {
    /// Its four control points.
    pub control_points: Vec<[f64; 2]>,
    /// Its weights.
    pub weights: Vec<f64>,
    /// The handle-length factor at the start.
    pub f0: f64,
    /// The handle-length factor at the end.
    pub f1: f64,
    /// Root-mean-square distance from the segment.
    pub rms: f64,
    /// Largest distance from the segment.
    pub max_error: f64,
    /// Whether its curvature is proven monotone.
    pub monotone: bool,
    /// Whether the search converged.
    pub converged: bool,
    /// Objective evaluations used.
    pub evaluations: usize,
    /// The segment's length.
    pub arc_length: f64,
    /// With `tolerance`: rational cubics within it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spline: Option<RationalSplineJson>,
}

/// The result object of `lac.rational_approx` (the `spline` member only with a spline).
pub fn rational_approx_json(
    seg: &LacSegment,
    fit: &approx::RationalCubicFit,
    spline: Option<&approx::RationalSpline>,
) -> Result<RationalApproxResult, aesthetic_curves::Error> {
    Ok(RationalApproxResult {
        control_points: xy(fit.curve.points()),
        weights: fit.curve.weights().to_vec(),
        f0: fit.f0,
        f1: fit.f1,
        rms: fit.rms,
        max_error: fit.max_error,
        monotone: fit.monotone,
        converged: fit.converged,
        evaluations: fit.evaluations,
        arc_length: seg.arc_length()?,
        spline: spline.map(RationalSplineJson::from),
    })
}

/// `lac.rational_approx`.
pub struct LacRationalApprox;

impl Op for LacRationalApprox {
    const NAME: &'static str = "lac.rational_approx";
    type Request = RationalApproxRequest;
    type Response = WithDrawing<RationalApproxResult>;

    fn answer(req: RationalApproxRequest) -> Result<Self::Response, ProtoError> {
        let seg = LacSegment::new(req.alpha, control3(&req.control))?;
        let opts = ApproxOptions::default();
        let fit = approx::fit_rational_cubic(&seg, &opts)?;
        let spline = req
            .tolerance
            .map(|t| approx::fit_rational_spline(&seg, t.0, MAX_NURBS_PIECES, &opts))
            .transpose()?;
        let drawing = req
            .draw
            .map(|n| {
                let nurbs = Nurbs::from_bezier(&fit.curve);
                drawing_json(&fit.curve, n.0 as usize, Some(&nurbs))
            })
            .transpose()?;
        Ok(WithDrawing {
            result: rational_approx_json(&seg, &fit, spline.as_ref())?,
            drawing,
        })
    }
}

/// What `lac.fit` minimises.
#[derive(Debug, Clone, Copy, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// The narrowest band around the curve (default).
    #[default]
    Band,
    /// Least squares.
    Distance,
    /// The paper's arc-length correspondence.
    ArcLength,
}

/// Where `lac.fit` starts.
#[derive(Debug, Clone, Copy, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// Least squares over all α (default).
    #[default]
    Scan,
    /// α guessed from the curvature graph, kept within 10 %.
    Paper,
}

/// Points to fit one LAC segment to.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LacFitRequest {
    /// The points, in order along the curve.
    pub points: Points<6, MAX_FIT_POINTS>,
    /// α held fixed (absent: fitted).
    #[serde(default)]
    pub alpha: Option<f64>,
    /// What is minimised.
    #[serde(default)]
    pub objective: Option<Objective>,
    /// Where the search starts.
    #[serde(default)]
    pub start: Option<Start>,
}

impl Request for LacFitRequest {}

/// The fitted segment.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LacFitResult {
    /// Its α.
    pub alpha: f64,
    /// Its control triangle.
    pub control: Vec<[f64; 2]>,
    /// Root-mean-square distance of the points from it.
    pub rms_deviation: f64,
    /// Largest distance of a point from it.
    pub max_deviation: f64,
    /// Root-mean-square distance at arc-length correspondence.
    pub rms_correspondence: f64,
    /// Whether the search converged.
    pub converged: bool,
    /// The objective minimised.
    pub objective: &'static str,
    /// Its largest curvature.
    pub max_curvature: f64,
    /// Whether α stopped at the library's bound.
    pub alpha_at_bound: bool,
    /// The curvature cap the fit held, where it held one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature_cap: Option<f64>,
    /// The paper start's guess of α, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha_guess: Option<f64>,
}

/// `lac.fit`.
pub struct LacFitOp;

impl Op for LacFitOp {
    const NAME: &'static str = "lac.fit";
    type Request = LacFitRequest;
    type Response = LacFitResult;

    fn answer(req: LacFitRequest) -> Result<LacFitResult, ProtoError> {
        use aesthetic_curves::lac_fit::{self, LacFitObjective, LacFitStart};
        let objective = match req.objective.unwrap_or_default() {
            Objective::Band => LacFitObjective::Band,
            Objective::Distance => LacFitObjective::Distance,
            Objective::ArcLength => LacFitObjective::ArcLength,
        };
        let start = match req.start.unwrap_or_default() {
            Start::Scan => LacFitStart::Scan,
            Start::Paper => LacFitStart::Paper,
        };
        let f = lac_fit::fit_lac(
            &req.points.0,
            lac_fit::LacFitOptions {
                alpha: req.alpha,
                objective,
                start,
            },
        )?;
        Ok(LacFitResult {
            alpha: f.alpha,
            control: xy(&f.segment.control()),
            rms_deviation: f.rms_deviation,
            max_deviation: f.max_deviation,
            rms_correspondence: f.rms_correspondence,
            converged: f.converged,
            objective: objective.as_str(),
            max_curvature: f.max_curvature,
            alpha_at_bound: f.alpha_at_bound,
            curvature_cap: f.curvature_cap,
            alpha_guess: f.alpha_guess,
        })
    }
}
