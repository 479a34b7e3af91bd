//! The JSON of a check (`aecurve check --json` and the protocol's `outline.check`): one type
//! per record, so that both write the same fields and the protocol's schema describes them.

use crate::json_out::{finite, EndCurvatureJson};
use crate::outline_io::ShapeCheck;
use aesthetic_curves::outline::{Finding, JoinCheck, SegmentCheck};
use aesthetic_curves::Point;
use schemars::JsonSchema;
use serde::Serialize;

/// One finding.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FindingJson {
    /// The shape's name.
    pub shape: String,
    /// The contour's index.
    pub contour: usize,
    /// The segment's index in its contour.
    pub segment: usize,
    /// What was found (`not-monotone`, `near-break`, `g2-jump`, ...).
    pub kind: String,
    /// Where.
    pub point: [f64; 2],
    /// For a person.
    pub message: String,
}

impl FindingJson {
    /// A finding of shape `name`.
    pub fn new(name: &str, f: &Finding) -> Self {
        FindingJson {
            shape: name.to_string(),
            contour: f.contour,
            segment: f.segment,
            kind: f.kind.to_string(),
            point: [f.point.x, f.point.y],
            message: f.message.clone(),
        }
    }
}

/// A place on a segment: its parameter and point.
#[derive(Debug, Serialize, JsonSchema)]
pub struct PlaceJson {
    /// The parameter.
    pub t: f64,
    /// The point.
    pub point: [f64; 2],
}

fn places(v: &[(f64, Point)]) -> Vec<PlaceJson> {
    v.iter()
        .map(|(t, p)| PlaceJson {
            t: *t,
            point: [p.x, p.y],
        })
        .collect()
}

/// Handles that make a cubic monotone within the asked distance.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SuggestionJson {
    /// The suggested cubic's control points.
    pub control_points: Vec<[f64; 2]>,
    /// Its handle lengths over the original's.
    pub handle_scale: [f64; 2],
    /// How far it lies from the original.
    pub deviation: f64,
}

/// One segment's check.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SegmentCheckJson {
    /// Its degree.
    pub degree: usize,
    /// Whether it is rational.
    pub rational: bool,
    /// Its interior curvature extrema.
    pub extrema: Vec<PlaceJson>,
    /// Its inflections.
    pub inflections: Vec<PlaceJson>,
    /// Whether exact arithmetic decided a sign floating point could not.
    pub exact_arithmetic: bool,
    /// Its largest |curvature|; null where it grows without bound (see `ends`).
    pub max_abs_curvature: Option<f64>,
    /// The curvature's detour relative to its largest (a non-monotone segment).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bump: Option<f64>,
    /// The curvature at each end, where a handle is retracted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ends: Option<Vec<EndCurvatureJson>>,
    /// Remarks.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// Whether its curvature is monotone (absent for a line).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub monotone: Option<bool>,
    /// `increasing`, `decreasing` or `constant`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trend: Option<&'static str>,
    /// Curvature at the start and the end (null where unbounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end_curvatures: Option<[Option<f64>; 2]>,
    /// Why it was not checked, where it was not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flag: Option<String>,
    /// With `suggest`: a monotone cubic close to it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub suggestion: Option<SuggestionJson>,
}

impl From<&SegmentCheck> for SegmentCheckJson {
    fn from(s: &SegmentCheck) -> Self {
        SegmentCheckJson {
            degree: s.degree,
            rational: s.rational,
            extrema: places(&s.extrema),
            inflections: places(&s.inflections),
            exact_arithmetic: s.exact,
            max_abs_curvature: finite(s.max_abs_curvature),
            bump: (s.bump > 0.0).then_some(s.bump),
            ends: s
                .ends
                .as_ref()
                .map(|e| e.iter().map(EndCurvatureJson::from).collect()),
            notes: s.notes.clone(),
            monotone: s.monotone,
            trend: s.trend.map(|t| t.as_str()),
            end_curvatures: s.end_curvatures.map(|(a, b)| [finite(a), finite(b)]),
            flag: s.flag.clone(),
            suggestion: s.suggestion.as_ref().map(|g| SuggestionJson {
                control_points: g.curve.points().iter().map(|p| [p.x, p.y]).collect(),
                handle_scale: [g.scale.0, g.scale.1],
                deviation: g.deviation,
            }),
        }
    }
}

/// One join's check.
#[derive(Debug, Serialize, JsonSchema)]
pub struct JoinCheckJson {
    /// The segment it follows.
    pub after_segment: usize,
    /// Where.
    pub point: [f64; 2],
    /// The tangent break (degrees); null where a tangent is undefined.
    pub angle_break_degrees: Option<f64>,
    /// Whether the tangents agree.
    pub g1: bool,
    /// Whether the curvatures agree too.
    pub g2: bool,
    /// A small break: probably meant smooth.
    pub near_break: bool,
    /// The relative curvature jump, where both curvatures are finite.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature_jump: Option<f64>,
    /// A curvature grows without bound at the join.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub unbounded_curvature: bool,
    /// Whether the source marks the point smooth (UFO); absent where it marks none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub smooth_mark: Option<bool>,
}

impl From<&JoinCheck> for JoinCheckJson {
    fn from(j: &JoinCheck) -> Self {
        JoinCheckJson {
            after_segment: j.after_segment,
            point: [j.point.x, j.point.y],
            angle_break_degrees: finite(j.angle_break.to_degrees()),
            g1: j.g1,
            g2: j.g2,
            near_break: j.near_break,
            curvature_jump: j.curvature_jump,
            unbounded_curvature: j.unbounded_curvature,
            smooth_mark: j.smooth_mark,
        }
    }
}

/// One contour's check.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ContourCheckJson {
    /// Whether it is closed.
    pub closed: bool,
    /// Its segments.
    pub segments: Vec<SegmentCheckJson>,
    /// Its joins.
    pub joins: Vec<JoinCheckJson>,
}

/// A shape's check: per contour its segments and joins.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ShapeJson {
    /// The shape's name.
    pub name: String,
    /// Its contours.
    pub contours: Vec<ContourCheckJson>,
}

/// A shape's check as JSON.
pub fn shape_json(c: &ShapeCheck) -> ShapeJson {
    ShapeJson {
        name: c.name.to_string(),
        contours: c
            .contours
            .iter()
            .map(|k| ContourCheckJson {
                closed: k.closed,
                segments: k.segments.iter().map(SegmentCheckJson::from).collect(),
                joins: k.joins.iter().map(JoinCheckJson::from).collect(),
            })
            .collect(),
    }
}

/// What `aecurve check --json` prints: one document (`x-cli.check` of the schema), its
/// shapes streamed as they are checked, then the rest ([`CheckTailJson`]).
#[derive(Debug, Serialize, JsonSchema)]
pub struct CheckFileJson {
    /// The file checked.
    pub file: String,
    /// What it held: `font`, `ufo`, `svg`, `dxf`, ...
    pub kind: String,
    /// Every shape's check, in the file's order.
    pub shapes: Vec<ShapeJson>,
    /// The totals, the ranked findings, the times and what could not be read.
    #[serde(flatten)]
    pub tail: CheckTailJson,
}

/// The part of [`CheckFileJson`] written after the shapes.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CheckTailJson {
    /// Totals over every shape.
    pub counts: CheckCountsJson,
    /// The findings, each place once, worst (by [`RankedFindingJson::rank`]) first.
    pub findings: Vec<RankedFindingJson>,
    /// Where the time went.
    pub milliseconds: CheckMillisJson,
    /// The shapes that could not be read, each with why.
    pub unreadable: Vec<UnreadableJson>,
}

/// Totals of a check.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CheckCountsJson {
    pub shapes: usize,
    pub segments: usize,
    /// Segments of degree 2 or more.
    pub curved_segments: usize,
    /// Segments proven monotone.
    pub monotone_segments: usize,
    pub inflections: usize,
    pub joins: usize,
    pub g1_joins: usize,
    pub g2_joins: usize,
    /// Joins whose tangents break by a hair (less than the near-break angle).
    pub near_breaks: usize,
    /// Segments given suggested handles.
    pub suggestions: usize,
    /// Segments whose verdict needed exact arithmetic.
    pub exact_arithmetic: usize,
    /// Segments with a retracted handle.
    pub retracted_handles: usize,
    /// The findings that are defects.
    pub defects: DefectCountsJson,
    /// Segments with one curvature extremum inside: the design, not a defect.
    pub one_extremum_inside: usize,
    /// Curvature steps where a line meets a curve at a point not marked smooth: the design.
    pub line_curve_steps: usize,
}

/// The defects of a check, by kind.
#[derive(Debug, Serialize, JsonSchema)]
pub struct DefectCountsJson {
    /// Curvature extrema within the hook zone of an end.
    pub hooks: usize,
    /// Segments with several curvature extrema.
    pub several_extrema: usize,
    /// Curvature jumps at smooth joins.
    pub curvature_jumps: usize,
    pub near_breaks: usize,
    /// Degenerate segments.
    pub degenerate: usize,
}

/// A finding in `check --json`'s ranked list.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RankedFindingJson {
    /// The finding, in the first shape that has it.
    #[serde(flatten)]
    pub finding: FindingJson,
    /// How bad it is, from 0 up.
    pub severity: f64,
    /// The largest use weight of the shapes that have it (basic Latin 1, symbols less).
    pub use_weight: f64,
    /// Severity times use weight, raised by 5 % for each other shape with it (up to ten).
    pub rank: f64,
    /// The other shapes that draw the same place (components, copies).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub also_in: Vec<String>,
}

/// How long reading and checking took.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CheckMillisJson {
    pub read: f64,
    pub check: f64,
}

/// A shape that could not be read.
#[derive(Debug, Serialize, JsonSchema)]
pub struct UnreadableJson {
    pub name: String,
    pub error: String,
}
