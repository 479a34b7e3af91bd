//! The sketch's public types: its options, its pieces and its result.

use crate::approx::ApproxOptions;
use crate::bezier::{PlanarCurve, RationalBezier};
use crate::bspline::BSpline;
use crate::error::Result;
use crate::lac::{LacInflectionSegment, LacSegment};
use kurbo::{Point, Vec2};

/// Options of [`fit_sketch`](super::fit_sketch).
#[derive(Clone, Debug)]
pub struct SketchOptions {
    /// Largest allowed distance from an input point to the result (input units, > 0).
    pub tolerance: f64,
    /// Most pieces before giving up on the tolerance; never more than the points and 4
    /// (a stroke that needs more turns back or wiggles between its points, and is refused
    /// as degenerate).
    pub max_pieces: usize,
    /// Pieces turning more than this (radians) are split.
    pub max_turn: f64,
    /// Inflection pairs with less turning between them are noise (radians).
    pub min_turn: f64,
    /// Fairing target: largest curvature jump over the largest curvature.
    pub g2_tolerance: f64,
    /// Iteration limit of the fairing.
    pub max_fairing_iterations: usize,
    /// Options of the rational cubic per piece.
    pub approx: ApproxOptions,
    /// The points form a closed loop (the last is the first): the curve ends where it
    /// starts with the same tangent, and the seam is faired G2 like every joint.
    pub closed: bool,
    /// Ends that join a straight line G2, `[start, end]`: the curve leaves its first point
    /// (reaches its last) along this direction, in curve order, with zero curvature there,
    /// so a line along it continues the curve with no break and no curvature jump. The end
    /// piece is then an inflection-end segment. `None`: a free end. Open curves only.
    pub line_ends: [Option<Vec2>; 2],
}

impl SketchOptions {
    /// Defaults with the given tolerance.
    pub fn with_tolerance(tolerance: f64) -> Self {
        SketchOptions {
            tolerance,
            max_pieces: 64,
            max_turn: std::f64::consts::FRAC_PI_2,
            min_turn: 0.25f64.to_radians(),
            g2_tolerance: 1e-10,
            max_fairing_iterations: 60,
            approx: ApproxOptions::default(),
            closed: false,
            line_ends: [None, None],
        }
    }
}

/// Kind of a piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PieceKind {
    /// A LAC segment in its control triangle (docs/math.md §3.1).
    Lac,
    /// A segment with an inflection (zero curvature) at one end (docs/math.md §3.2).
    LacInflection,
}

impl PieceKind {
    /// `"lac"` or `"lac_inflection"` (the protocol's names).
    pub fn as_str(&self) -> &'static str {
        match self {
            PieceKind::Lac => "lac",
            PieceKind::LacInflection => "lac_inflection",
        }
    }
}

/// The curve of a piece.
#[derive(Clone, Debug)]
pub enum PieceCurve {
    /// A LAC segment; its `control[0]` is the piece's start.
    Lac(LacSegment),
    /// An inflection-end segment; its `control[0]` (the inflection) is the piece's start when
    /// `inflection_at_start`, else its end.
    Inflection {
        /// The segment.
        segment: LacInflectionSegment,
        /// Whether the inflection is at the piece's start.
        inflection_at_start: bool,
    },
}

/// What the sketch's stages ask of a piece's curve, whatever its family: the family, its
/// points in curve order, where its curvature is zero by construction, and whether its α
/// is free (a LAC's is; an inflection piece's α its triangle fixes). A new family (a line,
/// an arc) is a variant of [`PieceCurve`] and its arms here, plus its rational cubic
/// (`cubics`); the stages only call these.
pub trait PieceShape {
    /// The family.
    fn kind(&self) -> PieceKind;
    /// `n >= 2` points from the piece's start to its end.
    fn polyline(&self, n: usize) -> Result<Vec<Point>>;
    /// Whether the curvature is zero by construction at its start and at its end.
    fn zero_curvature_ends(&self) -> [bool; 2];
    /// Whether its α may move with the fairing's unknowns.
    fn alpha_is_free(&self) -> bool;
}

impl PieceShape for PieceCurve {
    fn kind(&self) -> PieceKind {
        match self {
            PieceCurve::Lac(_) => PieceKind::Lac,
            PieceCurve::Inflection { .. } => PieceKind::LacInflection,
        }
    }

    fn polyline(&self, n: usize) -> Result<Vec<Point>> {
        match self {
            PieceCurve::Lac(seg) => Ok(seg.sample(n)?.points),
            PieceCurve::Inflection {
                segment,
                inflection_at_start,
            } => {
                let mut pts = segment.sample(n)?.points;
                if !inflection_at_start {
                    pts.reverse();
                }
                Ok(pts)
            }
        }
    }

    fn zero_curvature_ends(&self) -> [bool; 2] {
        match self {
            PieceCurve::Lac(_) => [false, false],
            PieceCurve::Inflection {
                inflection_at_start,
                ..
            } => [*inflection_at_start, !inflection_at_start],
        }
    }

    fn alpha_is_free(&self) -> bool {
        self.kind() == PieceKind::Lac
    }
}

/// The widest [`SketchPiece::alpha_range`] of a piece whose α the points determine: α is
/// then within ±0.05 of every α that fits them.
pub const ALPHA_DETERMINED_WIDTH: f64 = 0.1;

impl SketchPiece {
    /// Whether the points determine this piece's α ([`SketchPiece::alpha_range`] at most
    /// [`ALPHA_DETERMINED_WIDTH`] wide); an inflection piece's α is its triangle's.
    pub fn alpha_determined(&self) -> bool {
        self.alpha_range
            .is_none_or(|(lo, hi)| hi - lo <= ALPHA_DETERMINED_WIDTH)
    }
}

/// One piece of the result, in curve order.
#[derive(Clone, Debug)]
pub struct SketchPiece {
    /// Which family.
    pub kind: PieceKind,
    /// Shape parameter of the segment.
    pub alpha: f64,
    /// α estimated from the piece's curvature graph (before any adaptation); `None` for
    /// inflection pieces and pieces of (nearly) constant curvature.
    pub alpha_estimate: Option<f64>,
    /// Control triangle in curve order: start, tangent intersection, end.
    pub control: [Point; 3],
    /// The segment itself.
    pub curve: PieceCurve,
    /// Signed curvature at the start and at the end.
    pub end_curvatures: (f64, f64),
    /// The rational cubic, in curve order.
    pub rational: RationalBezier,
    /// Largest distance of the rational cubic from the segment over its arc length.
    pub rational_error: f64,
    /// Curvature monotonicity of the rational cubic, proven by the exact test.
    pub monotone: bool,
    /// α sits on a bound of its least-squares fit ([`ALPHA_RANGE`](crate::lac::ALPHA_RANGE)): the data do not pin
    /// it down (a shallow piece) or want a steeper curvature graph than allowed; for an
    /// inflection piece, whose α its control triangle fixes, α on the range's lower end (no
    /// piece beyond it is built: the fit turns the tangents or splits the piece instead).
    pub alpha_at_bound: bool,
    /// For a LAC piece, the α values whose segment in this piece's triangle keeps every
    /// input point of the piece within the fit's tolerance: how far the points pin α down.
    /// A wide range (see [`SketchPiece::alpha_determined`]) means that the points, at this
    /// tolerance, do not tell α: a nearly circular or nearly straight piece, or few points.
    /// `None` for an inflection piece, whose triangle fixes α.
    pub alpha_range: Option<(f64, f64)>,
    /// Parameter range on the intermediate B-spline.
    pub u_range: (f64, f64),
}

/// What the G2 fairing did.
#[derive(Clone, Debug, PartialEq)]
pub struct FairingReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Largest relative curvature jump before.
    pub initial_jump: f64,
    /// Largest relative curvature jump after.
    pub final_jump: f64,
    /// Reached [`SketchOptions::g2_tolerance`].
    pub converged: bool,
}

/// The result of [`fit_sketch`](super::fit_sketch).
#[derive(Clone, Debug)]
pub struct Sketch {
    /// The intermediate least-squares B-spline.
    pub bspline: BSpline,
    /// Its largest distance from the input points.
    pub bspline_deviation: f64,
    /// The pieces in order.
    pub pieces: Vec<SketchPiece>,
    /// Largest distance from an input point to the rational result.
    pub max_deviation: f64,
    /// Root mean square of those distances.
    pub rms_deviation: f64,
    /// Largest |κ_left - κ_right| at a joint of the rational cubics over their largest |κ|.
    pub max_curvature_jump: f64,
    /// `max_curvature_jump` below 1e-6.
    pub g2: bool,
    /// The fairing's report (of the last round).
    pub fairing: FairingReport,
    /// Every rational piece proven curvature-monotone.
    pub all_monotone: bool,
    /// Inflections of the result (sign changes of its curvature).
    pub inflections: usize,
    /// Interior curvature extrema of the result (the pieces are monotone, so these sit at
    /// joints where the curvature turns back).
    pub curvature_extrema: usize,
}

/// Inflections and interior curvature extrema of a curve made of curvature-monotone pieces
/// with signed end curvatures `ends` (curve order): the curvature between two ends is
/// monotone, so the sign changes and turns of the sequence of end values are all of them.
pub fn count_events(ends: &[(f64, f64)]) -> (usize, usize) {
    let mut ks: Vec<f64> = Vec::with_capacity(ends.len() + 1);
    for (i, e) in ends.iter().enumerate() {
        if i == 0 {
            ks.push(e.0);
        }
        ks.push(e.1);
    }
    let scale = ks.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    let tiny = 1e-9 * scale;
    let signs: Vec<f64> = ks
        .iter()
        .filter(|k| k.abs() > tiny)
        .map(|k| k.signum())
        .collect();
    let inflections = signs.windows(2).filter(|w| w[0] != w[1]).count();
    let steps: Vec<f64> = ks
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| d.abs() > tiny)
        .map(|d| d.signum())
        .collect();
    let extrema = steps.windows(2).filter(|w| w[0] != w[1]).count();
    (inflections, extrema)
}

impl Sketch {
    /// The joints in order: the start of every piece and the end of the last.
    pub fn joints(&self) -> Vec<Point> {
        self.pieces
            .iter()
            .map(|p| p.control[0])
            .chain(self.pieces.last().map(|p| p.control[2]))
            .collect()
    }

    /// A point of the rational result at `t` in [0, pieces] (piece index + local parameter).
    pub fn eval(&self, t: f64) -> Point {
        let n = self.pieces.len();
        let t = t.clamp(0.0, n as f64);
        let i = (t.floor() as usize).min(n - 1);
        self.pieces[i].rational.eval(t - i as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A piece's points run in curve order whatever its segment's own order, and its zero
    /// curvature sits at the inflection end.
    #[test]
    fn piece_shapes_in_curve_order() {
        let ctrl = [
            Point::new(0.0, 0.0),
            Point::new(5.0, 0.0),
            Point::new(7.0, 3.0),
        ];
        let segment = LacInflectionSegment::new(ctrl).unwrap();
        for at_start in [true, false] {
            let c = PieceCurve::Inflection {
                segment: segment.clone(),
                inflection_at_start: at_start,
            };
            let pts = c.polyline(9).unwrap();
            let (first, last) = (pts[0], pts[8]);
            let want = if at_start {
                (ctrl[0], ctrl[2])
            } else {
                (ctrl[2], ctrl[0])
            };
            assert_eq!((first, last), want);
            assert_eq!(c.zero_curvature_ends(), [at_start, !at_start]);
            assert_eq!(c.kind(), PieceKind::LacInflection);
            assert!(!c.alpha_is_free());
        }
        let lac = PieceCurve::Lac(LacSegment::new(0.5, ctrl).unwrap());
        assert_eq!(lac.polyline(5).unwrap()[0], ctrl[0]);
        assert_eq!(lac.zero_curvature_ends(), [false, false]);
        assert!(lac.alpha_is_free());
    }

    #[test]
    fn events_of_monotone_pieces() {
        // One bump: up then down, one sign: one extremum, no inflection.
        assert_eq!(count_events(&[(0.1, 0.3), (0.3, 0.2)]), (0, 1));
        // An S through an inflection joint (zero at the joint), monotone across it.
        assert_eq!(count_events(&[(0.2, 0.0), (0.0, -0.3)]), (1, 0));
        // A piece crossing zero inside, then turning back.
        assert_eq!(count_events(&[(0.2, -0.1), (-0.1, 0.05)]), (2, 1));
        // Constant curvature: nothing.
        assert_eq!(count_events(&[(0.5, 0.5), (0.5, 0.5)]), (0, 0));
    }
}
