//! The `drawing` member (with `draw`): what a picture of a result needs, computed here so
//! that a client draws without evaluating curves itself.

use super::ProtoError;
use aesthetic_curves::nurbs::Nurbs;
use aesthetic_curves::{Curve as _, Error};
use schemars::JsonSchema;
use serde::Serialize;

/// Largest `draw` (points per piece).
pub const MAX_DRAW_SAMPLES: u64 = 2000;

/// Most points one `drawing` member holds (pieces times points per piece): about 110 bytes
/// of JSON and up to 1 KB of memory each while the answer is built (measured), so a drawing
/// stays under about 200 MB. A screen is a few thousand pixels wide: no picture needs more.
pub const MAX_DRAWING_POINTS: usize = 200_000;

/// A NURBS as the protocol writes it (what an export writes).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NurbsJson {
    /// Its degree.
    pub degree: usize,
    /// Its knot vector (clamped).
    pub knots: Vec<f64>,
    /// Its control points.
    pub control_points: Vec<[f64; 2]>,
    /// One weight per control point.
    pub weights: Vec<f64>,
}

impl From<&Nurbs> for NurbsJson {
    fn from(c: &Nurbs) -> Self {
        NurbsJson {
            degree: c.degree,
            knots: c.knots.clone(),
            control_points: super::xy(&c.control_points),
            weights: c.weights.clone(),
        }
    }
}

/// `n` points per piece with the curve's unit left normal and signed curvature (consecutive
/// pieces share their joint), the number of pieces, and the curve as one NURBS.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct Drawing {
    /// Points along the curve.
    pub points: Vec<[f64; 2]>,
    /// The unit left normal at each point.
    pub normals: Vec<[f64; 2]>,
    /// The signed curvature at each point.
    pub curvature: Vec<f64>,
    /// Points per piece.
    pub per_piece: usize,
    /// Pieces drawn.
    pub pieces: usize,
    /// The curve as one NURBS, where it has an exact one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nurbs: Option<NurbsJson>,
    /// Places to circle (the interior curvature extrema of `bezier.curvature_monotone`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub marks: Option<Vec<[f64; 2]>>,
}

/// The drawing of `curve` at `n` points per piece, with its NURBS if given.
pub fn drawing_json(
    curve: &dyn aesthetic_curves::Curve,
    n: usize,
    nurbs: Option<&Nurbs>,
) -> Result<Drawing, Error> {
    let pts = curve.curve_points(n)?;
    let pieces = (pts.len() - 1) / (n - 1);
    Ok(Drawing {
        points: pts.iter().map(|q| [q.p.x, q.p.y]).collect(),
        normals: pts
            .iter()
            .map(|q| {
                let v = q.normal();
                [v.x, v.y]
            })
            .collect(),
        curvature: pts.iter().map(|q| q.kappa).collect(),
        per_piece: n,
        pieces,
        nurbs: nurbs.map(NurbsJson::from),
        marks: None,
    })
}

/// `invalid_input` on `draw` when `pieces` pieces at `n` points each are over
/// [`MAX_DRAWING_POINTS`]: checked before any work where the pieces are known from the
/// request (a spline's points, an outline's segments), and for `sketch.fit`, whose pieces
/// the fit decides, after the fit and before the drawing.
pub fn drawing_budget(pieces: usize, n: usize) -> Result<(), ProtoError> {
    if pieces.saturating_mul(n) > MAX_DRAWING_POINTS {
        let most = (MAX_DRAWING_POINTS / pieces.max(1)).max(1);
        return Err(ProtoError::invalid(
            "draw",
            format!(
                "{pieces} pieces at {n} points each is over the drawing budget of \
                 {MAX_DRAWING_POINTS} points: ask for at most {most} points per piece"
            ),
        ));
    }
    Ok(())
}

/// The drawing of a curve of Bézier pieces (a sketch, a contour, a spline), within the
/// drawing budget for its pieces, with its exact NURBS.
pub fn pieces_drawing<C: aesthetic_curves::Curve>(
    curve: &aesthetic_curves::Pieces<C>,
    n: usize,
) -> Result<Drawing, ProtoError> {
    drawing_budget(curve.0.len(), n)?;
    let nurbs = curve.to_exact_nurbs()?;
    Ok(drawing_json(curve, n, Some(&nurbs))?)
}

/// A result with its optional drawing.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(rename = "{T}Drawn")]
pub struct WithDrawing<T> {
    /// The result's own fields.
    #[serde(flatten)]
    pub result: T,
    /// With `draw`: the picture of the result.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drawing: Option<Drawing>,
}
