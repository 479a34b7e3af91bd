//! One piece of a sketch, a contour or a spline as every op sends it.

use super::xy;
use aesthetic_curves::{Point, RationalBezier};
use schemars::JsonSchema;
use serde::Serialize;

/// A rational Bézier curve: control points and weights.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct RationalJson {
    /// Its control points.
    pub control_points: Vec<[f64; 2]>,
    /// One positive weight per control point.
    pub weights: Vec<f64>,
}

impl From<&RationalBezier> for RationalJson {
    fn from(r: &RationalBezier) -> Self {
        RationalJson {
            control_points: xy(r.points()),
            weights: r.weights().to_vec(),
        }
    }
}

/// A LAC piece: its kind, control triangle, end curvatures, rational cubic and monotone
/// verdict (each op adds its own fields).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct PieceJson {
    /// `lac`, `lac_inflection` or `line` (a spline's straight span).
    pub kind: &'static str,
    /// The control triangle: start, tangent intersection, end.
    pub control: Vec<[f64; 2]>,
    /// Curvature at the start and at the end.
    pub end_curvatures: [f64; 2],
    /// The rational cubic that stands for it.
    pub rational: RationalJson,
    /// Whether the cubic's curvature is proven monotone.
    pub monotone: bool,
}

impl PieceJson {
    /// The common fields of a piece.
    pub fn new(
        kind: &'static str,
        control: &[Point; 3],
        ends: (f64, f64),
        rational: &RationalBezier,
        monotone: bool,
    ) -> Self {
        PieceJson {
            kind,
            control: xy(control),
            end_curvatures: [ends.0, ends.1],
            rational: rational.into(),
            monotone,
        }
    }
}
